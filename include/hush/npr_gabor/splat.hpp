// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The splat list of NPR Gabor noise (hush/npr_gabor.hpp) and its second
// stage, the splatting. npr_gabor::render runs in two stages:
//  1. npr_gabor::make_splats: per triangle, its points (paper sec. 3.3) become
//     records, one per point, in triangle order then point order, each with
//     everything the kernel and the visibility tests need (its own frequency
//     vector and radius, so parameters may differ per splat);
//  2. splatting: every record's kernel is added at the pixel centres of its
//     range that pass the tests (sec. 3.4), per pixel in record order.
// Stage 2 is here once for the scalar backends (npr_gabor_splat_scalar, float
// or double) and once in lanes (hush/npr_gabor/simd-inl.h, float), which
// repeats it operation by operation.
#ifndef HUSH_NPR_GABOR_SPLAT_HPP
#define HUSH_NPR_GABOR_SPLAT_HPP

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hush/config.hpp"
#include "hush/core/views.hpp"
#include "hush/gabor/kernel.hpp"

namespace hush {

// One point's kernel, ready to splat (stage 1's output). The kernel is
// weight g_F(p - (x, y)) with g gabor_kernel<2>'s tapered kernel of radius
// `radius` (from the bandwidth a: r = sqrt(ln(1/t) / pi) / a) and frequency
// vector F = (fx, fy) = F0 (cos omega, sin omega); it covers the pixels
// x0 ... x1, y0 ... y1 (inclusive, clamped to the image, never empty): the
// centres within r of (x, y). The point's triangle's plane, 1/z = q0 + qx x +
// qy y in screen pixels, gives the depth test its reference depth at every
// pixel (the point's own depth is 1 / (q0 + qx x + qy y)). `index` is the
// point's J in its triangle's sequence (npr_gabor/tree.hpp): stage 2
// does not read it; it names the point (tests, GPU stage 1 comparisons).
struct npr_gabor_splat {
  double x = 0, y = 0;            // position, pixels (x right, y down)
  double fx = 0, fy = 0;          // F, cycles per pixel
  double bandwidth = 0;           // a, 1/pixel
  double radius = 0;              // r, pixels
  double weight = 0;              // w_i v_i scale (paper eq. 1, LOD weight eq. 4)
  double q0 = 0, qx = 0, qy = 0;  // the triangle's plane of 1/z
  std::uint32_t object = 0, triangle = 0;
  std::int32_t x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // pixel range, inclusive
  std::uint64_t index = 0;  // J: the point's index in its triangle's sequence
};

namespace detail {

// Everything stage 2 reads: the records, the frame's views the enabled tests
// need (the others may be empty), the tests, and the output.
struct npr_gabor_splat_job {
  const npr_gabor_splat* splats = nullptr;
  std::size_t count = 0;
  image_view<const float> depth;
  image_view<const std::uint32_t> object_id, triangle_id;
  bool object_test = true, triangle_test = false, depth_test = true, soft_depth = false;
  double depth_tolerance = 0;
  double envelope_exponent = 0;  // A = ln(1/t): the envelope is e^{-A d^2}, d in radii
};

// The visibility factor of a fragment at pixel (x, y) of splat s (sec. 3.4):
// 0 where a test fails, 1 where all pass, 2 - rel / tol in the soft band.
template <class T>
HUSH_INLINE T npr_gabor_visibility(const npr_gabor_splat_job& j, const npr_gabor_splat& s,
                                   std::size_t x, std::size_t y) {
  if (j.object_test && j.object_id(x, y) != s.object) return T(0);
  if (j.triangle_test && j.triangle_id(x, y) != s.triangle) return T(0);
  if (!j.depth_test) return T(1);
  const double zp = static_cast<double>(j.depth(x, y));
  if (!(zp > 0.0) || !std::isfinite(zp)) return T(0);
  // Relative difference of the pixel's depth and the plane's there.
  const double plane =
      s.q0 + s.qx * (static_cast<double>(x) + 0.5) + s.qy * (static_cast<double>(y) + 0.5);
  const double rel = std::fabs(zp * plane - 1.0);
  const double tol = j.depth_tolerance;
  if (!(rel <= (j.soft_depth ? 2.0 * tol : tol))) return T(0);
  return j.soft_depth && rel > tol ? T(2.0 - rel / tol) : T(1);
}

// Stage 2, scalar: adds every record's kernel to `out` (frame-sized), per
// pixel in record order. `columns` is scratch.
template <class T>
void npr_gabor_splat_scalar(const npr_gabor_splat_job& j, const image_view<T>& out,
                            std::vector<gabor_axis<T>>& columns) {
  namespace c = constants;
  const T neg_a = T(-j.envelope_exponent), taper_k = T(1.0 / (1.0 - c::kGaborTaperStart));
  for (std::size_t i = 0; i < j.count; ++i) {
    const npr_gabor_splat& s = j.splats[i];
    const double inv_r = 1.0 / s.radius;
    const T phi_x = T(s.fx * s.radius), phi_y = T(s.fy * s.radius);
    const std::size_t ix0 = static_cast<std::size_t>(s.x0), ix1 = static_cast<std::size_t>(s.x1);
    columns.resize(ix1 - ix0 + 1);
    for (std::size_t x = ix0; x <= ix1; ++x)
      columns[x - ix0] =
          gabor_axis_factors(T((static_cast<double>(x) + 0.5 - s.x) * inv_r), neg_a, phi_x);
    for (std::size_t y = static_cast<std::size_t>(s.y0); y <= static_cast<std::size_t>(s.y1); ++y) {
      const gabor_axis<T> ay =
          gabor_axis_factors(T((static_cast<double>(y) + 0.5 - s.y) * inv_r), neg_a, phi_y);
      const gabor_row<T> row = gabor_row_of(T(s.weight), ay);
      T* o = out.row(y);
      for (std::size_t x = ix0; x <= ix1; ++x) {
        const gabor_axis<T>& ax = columns[x - ix0];
        if (!(ax.d2 + row.d2 < T(1))) continue;
        const T vis = npr_gabor_visibility<T>(j, s, x, y);
        if (vis == T(0)) continue;  // adding vis * g = +-0 would change nothing
        o[x] += vis * gabor_pair(ax, row, taper_k);
      }
    }
  }
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_NPR_GABOR_SPLAT_HPP
