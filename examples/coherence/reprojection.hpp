// hush — temporal-coherence metrics: backward reprojection of a pixel into the previous frame.
//
// The point seen at pixel centre p = (x + 0.5, y + 0.5) in frame i was at p - (dx, dy) with
// linear depth depth - dz in frame i-1 (scene/gbuffer.hpp; Kass & Pesare 2011 sec. 3). The
// previous frame is sampled there bilinearly between pixel centres; a pixel is compared only
// when that point was visible in frame i-1 (Bénard et al. 2010 sec. 1, "coherent motion").
#ifndef HUSH_COHERENCE_REPROJECTION_HPP
#define HUSH_COHERENCE_REPROJECTION_HPP

#include <array>
#include <cstddef>

#include "scene/gbuffer.hpp"

namespace hush_tools {
namespace coherence {

enum class visibility {
  background,   // pixel not covered in frame i (object_id 0): not part of any metric
  visible,      // visible in both frames: compared
  offscreen,    // p - v leaves the area between the outer pixel centres
  disoccluded,  // a bilinear tap is background or another object, the depth disagrees, or
                // the velocity is NaN (no previous position, scene/gbuffer.hpp)
};

// Where pixel (x, y) of `current` was in `previous`: the four bilinear taps and weights
// (taps with weight 0 are never read, so an exact integer shift next to an edge is fine).
struct reprojection {
  visibility status = visibility::background;
  std::array<std::size_t, 4> taps{};  // pixel indices in the previous frame
  std::array<double, 4> weights{};    // bilinear weights, sum 1 (visible only)
};

// Classifies pixel (x, y) of `current` against `previous` (same size; not checked here, the
// sequence functions validate). Visible means: covered in frame i; q = p - (dx, dy) lies in
// [0.5, width - 0.5] x [0.5, height - 0.5]; every tap with a non-zero weight is covered by the
// same object_id; and the bilinearly interpolated previous depth d' satisfies
// |d' - (depth - dz)| <= depth_epsilon * (depth - dz), with depth - dz > 0.
reprojection reproject(const scene::gbuffer& previous, const scene::gbuffer& current, int x, int y,
                       double depth_epsilon);

// The bilinear value of `image` (previous frame's pixels) at the reprojection's taps.
inline double sample(const float* image, const reprojection& r) {
  double v = 0;
  for (int k = 0; k < 4; ++k)
    if (r.weights[k] != 0) v += r.weights[k] * static_cast<double>(image[r.taps[k]]);
  return v;
}

}  // namespace coherence
}  // namespace hush_tools

#endif  // HUSH_COHERENCE_REPROJECTION_HPP
