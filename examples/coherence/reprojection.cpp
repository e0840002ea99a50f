// hush — temporal-coherence metrics: backward reprojection (see reprojection.hpp).
#include "coherence/reprojection.hpp"

#include <algorithm>
#include <cmath>

namespace hush_tools {
namespace coherence {

reprojection reproject(const scene::gbuffer& previous, const scene::gbuffer& current, int x, int y,
                       double depth_epsilon) {
  reprojection r;
  const std::size_t w = static_cast<std::size_t>(current.width);
  const std::size_t pixel = static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
  const std::uint32_t id = current.object_id[pixel];
  if (id == 0) return r;
  // q - (0.5, 0.5): position in "pixel index" units, where pixel (i, j) has its centre at (i, j).
  const double u = x + 0.5 - current.velocity[3 * pixel] - 0.5;
  const double v = y + 0.5 - current.velocity[3 * pixel + 1] - 0.5;
  const double max_u = previous.width - 1, max_v = previous.height - 1;
  // NaN velocity: the point had no previous screen position (behind frame i-1's camera);
  // gbuffer.hpp says to treat it as disoccluded.
  if (!std::isfinite(u) || !std::isfinite(v) || !std::isfinite(current.velocity[3 * pixel + 2])) {
    r.status = visibility::disoccluded;
    return r;
  }
  if (!(u >= 0 && u <= max_u && v >= 0 && v <= max_v)) {
    r.status = visibility::offscreen;
    return r;
  }
  // The cell's lower corner; on the last row/column the cell is the one before it, with the
  // upper taps weighted 1 (so every pixel centre, the last included, is reachable).
  const int i0 = std::min(static_cast<int>(std::floor(u)), std::max(previous.width - 2, 0));
  const int j0 = std::min(static_cast<int>(std::floor(v)), std::max(previous.height - 2, 0));
  const int i1 = std::min(i0 + 1, previous.width - 1), j1 = std::min(j0 + 1, previous.height - 1);
  const double tu = i1 == i0 ? 0 : u - i0, tv = j1 == j0 ? 0 : v - j0;
  const std::size_t pw = static_cast<std::size_t>(previous.width);
  auto index = [pw](int i, int j) {
    return static_cast<std::size_t>(j) * pw + static_cast<std::size_t>(i);
  };
  r.taps = {index(i0, j0), index(i1, j0), index(i0, j1), index(i1, j1)};
  r.weights = {(1 - tu) * (1 - tv), tu * (1 - tv), (1 - tu) * tv, tu * tv};

  const double expected =
      static_cast<double>(current.depth[pixel]) - current.velocity[3 * pixel + 2];
  double depth = 0;
  for (int k = 0; k < 4; ++k) {
    if (r.weights[k] == 0) continue;  // never read: background depth is +inf, 0 * inf is NaN
    if (previous.object_id[r.taps[k]] != id) {
      r.status = visibility::disoccluded;
      return r;
    }
    depth += r.weights[k] * static_cast<double>(previous.depth[r.taps[k]]);
  }
  const bool consistent =
      expected > 0 && std::abs(depth - expected) <= depth_epsilon * expected;  // NaN: false
  r.status = consistent ? visibility::visible : visibility::disoccluded;
  return r;
}

}  // namespace coherence
}  // namespace hush_tools
