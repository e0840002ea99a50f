// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise's SIMD entry points (kernels: hush/gabor/simd-inl.h, which
// states the agreement with scalar evaluation) and detail::simd_kernel<gabor<D>>,
// which exec::simd calls: points (interleaved), grid slabs (as Perlin's,
// hush/perlin/simd_kernel.hpp), points with footprints (filtered samples) and,
// in 3D, samples with normals (surface noise; interleaved normals, fps null:
// point footprints). Included at the end of hush/gabor.hpp, after the class its
// kernels use; not on its own.
#ifndef HUSH_GABOR_SIMD_KERNEL_HPP
#define HUSH_GABOR_SIMD_KERNEL_HPP

#include <cstddef>

#include "hush/config.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/dispatch.hpp"

#if HUSH_CONFIG_SIMD_STATIC
#include "hush/gabor/simd-inl.h"
#endif

#define HUSH_SIMD_ENTRIES_GABOR(X)                                                                 \
  X(gabor2_points, (const gabor<2>& g, const float* xy, std::size_t n, float* value, float* grad), \
    (g, xy, n, value, grad))                                                                       \
  X(gabor3_points,                                                                                 \
    (const gabor<3>& g, const float* xyz, std::size_t n, float* value, float* grad),               \
    (g, xyz, n, value, grad))                                                                      \
  X(gabor2_grid,                                                                                   \
    (const gabor<2>& g, const grid<2>& gr, std::size_t first, std::size_t count, float* value,     \
     float* grad),                                                                                 \
    (g, gr, first, count, value, grad))                                                            \
  X(gabor3_grid,                                                                                   \
    (const gabor<3>& g, const grid<3>& gr, std::size_t first, std::size_t count, float* value,     \
     float* grad),                                                                                 \
    (g, gr, first, count, value, grad))                                                            \
  X(gabor2_filtered,                                                                               \
    (const gabor<2>& g, const float* xy, const footprint<2>* fps, std::size_t n, float* value,     \
     float* grad),                                                                                 \
    (g, xy, fps, n, value, grad))                                                                  \
  X(gabor3_filtered,                                                                               \
    (const gabor<3>& g, const float* xyz, const footprint<3>* fps, std::size_t n, float* value,    \
     float* grad),                                                                                 \
    (g, xyz, fps, n, value, grad))                                                                 \
  X(gabor3_surface,                                                                                \
    (const gabor<3>& g, const float* xyz, const float* normals, const footprint<3>* fps,           \
     std::size_t n, float* value, float* grad),                                                    \
    (g, xyz, normals, fps, n, value, grad))

HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_GABOR)

#if HUSH_CONFIG_SIMD
namespace hush {
namespace detail {

template <int D>
struct simd_kernel<gabor<D>> {
  static constexpr bool available = true;
  static constexpr bool has_samples = true;

  static void samples(const gabor<D>& g, const hush::samples<D>& s, float* out,
                      vec<float, D>* grad) {
    const auto* p = reinterpret_cast<const float*>(s.positions.data());
    auto* gr = reinterpret_cast<float*>(grad);
    if constexpr (D == 3) {
      if (s.has_normals()) {  // surface noise
        simd::gabor3_surface(g, p, reinterpret_cast<const float*>(s.normals.data()),
                             s.has_footprints() ? s.footprints.data() : nullptr, s.size(), out, gr);
        return;
      }
    }
    if constexpr (D == 2)
      simd::gabor2_filtered(g, p, s.footprints.data(), s.size(), out, gr);
    else
      simd::gabor3_filtered(g, p, s.footprints.data(), s.size(), out, gr);
  }

  static void points(const gabor<D>& g, const vec<float, D>* pts, std::size_t count, float* out,
                     vec<float, D>* grad) {
    const auto* p = reinterpret_cast<const float*>(pts);
    auto* gr = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::gabor2_points(g, p, count, out, gr);
    else
      simd::gabor3_points(g, p, count, out, gr);
  }
  // Slabs along the slowest axis (exec::parallel; exec.hpp).
  static constexpr bool has_grid_slab = true;
  static void grid_slab(const gabor<D>& g, const hush::grid<D>& gr, std::size_t first,
                        std::size_t count, float* out, vec<float, D>* grad) {
    auto* gp = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::gabor2_grid(g, gr, first, count, out, gp);
    else
      simd::gabor3_grid(g, gr, first, count, out, gp);
  }
  static void grid(const gabor<D>& g, const hush::grid<D>& gr, float* out, vec<float, D>* grad) {
    grid_slab(g, gr, 0, gr.size[D - 1], out, grad);
  }
};

}  // namespace detail
}  // namespace hush
#endif  // HUSH_CONFIG_SIMD

#endif  // HUSH_GABOR_SIMD_KERNEL_HPP
