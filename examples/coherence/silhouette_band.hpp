// The silhouette band of a G-buffer: the covered pixels within `radius` pixels (Chebyshev
// distance) of a depth discontinuity, so that a temporal metric can be restricted to where
// occlusion changes (docs/npr-gabor.md, "Popping at silhouettes"). A discontinuity is a
// covered pixel whose 4-neighbour is background, has another object id, or a depth that
// differs by more than `relative_depth` times the larger of the two depths (the NPR Gabor
// depth test's measure, params::depth_tolerance).
#ifndef HUSH_EXAMPLES_COHERENCE_SILHOUETTE_BAND_HPP
#define HUSH_EXAMPLES_COHERENCE_SILHOUETTE_BAND_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "scene/gbuffer.hpp"

namespace hush_tools::coherence {

// `g` with object_id set to 0 (background) outside the band, so that the metrics
// (measure(), temporal.hpp) count only band pixels: a pixel enters a frame pair when it is
// in the band of both frames. radius >= 0; relative_depth >= 0.
inline hush_tools::scene::gbuffer silhouette_band(const hush_tools::scene::gbuffer& g, int radius,
                                                  double relative_depth) {
  const int w = g.width, h = g.height;
  const auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
  std::vector<char> edge(g.pixels(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = at(x, y);
      if (!g.covered(p)) continue;
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= w || ny[k] >= h) continue;
        const std::size_t q = at(nx[k], ny[k]);
        const double a = g.depth[p], b = g.depth[q];
        if (g.object_id[q] != g.object_id[p] ||
            std::abs(a - b) > relative_depth * std::max(std::abs(a), std::abs(b)))
          edge[p] = 1;
      }
    }
  hush_tools::scene::gbuffer band = g;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool near = false;
      for (int yy = std::max(0, y - radius); yy <= std::min(h - 1, y + radius) && !near; ++yy)
        for (int xx = std::max(0, x - radius); xx <= std::min(w - 1, x + radius); ++xx)
          if (edge[at(xx, yy)]) {
            near = true;
            break;
          }
      if (!near) band.object_id[at(x, y)] = 0;
    }
  return band;
}

}  // namespace hush_tools::coherence

#endif  // HUSH_EXAMPLES_COHERENCE_SILHOUETTE_BAND_HPP
