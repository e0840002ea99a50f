// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Wavelet noise's SIMD entry points (kernels: hush/wavelet/simd-inl.h) and
// detail::simd_kernel<wavelet<D>>, which exec::simd calls: points, grids and
// samples (footprints, normals). Included at the end of hush/wavelet.hpp, after
// the class its kernels use; not on its own. Points and gradients are
// interleaved floats as Perlin's (hush/perlin/simd_kernel.hpp).
#ifndef HUSH_WAVELET_SIMD_KERNEL_HPP
#define HUSH_WAVELET_SIMD_KERNEL_HPP

#include <cstddef>

#include "hush/config.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/dispatch.hpp"

#if HUSH_CONFIG_SIMD_STATIC
#include "hush/wavelet/simd-inl.h"
#endif

#define HUSH_SIMD_ENTRIES_WAVELET(X)                                                         \
  X(wavelet2_points,                                                                         \
    (const wavelet<2>& w, const float* xy, std::size_t n, float* value, float* grad),        \
    (w, xy, n, value, grad))                                                                 \
  X(wavelet3_points,                                                                         \
    (const wavelet<3>& w, const float* xyz, std::size_t n, float* value, float* grad),       \
    (w, xyz, n, value, grad))                                                                \
  X(wavelet2_grid, (const wavelet<2>& w, const grid<2>& g, float* value, float* grad),       \
    (w, g, value, grad))                                                                     \
  X(wavelet3_grid, (const wavelet<3>& w, const grid<3>& g, float* value, float* grad),       \
    (w, g, value, grad))                                                                     \
  X(wavelet2_samples, (const wavelet<2>& w, const samples<2>& s, float* value, float* grad), \
    (w, s, value, grad))                                                                     \
  X(wavelet3_samples, (const wavelet<3>& w, const samples<3>& s, float* value, float* grad), \
    (w, s, value, grad))

HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_WAVELET)

#if HUSH_CONFIG_SIMD
namespace hush {
namespace detail {

template <int D>
struct simd_kernel<wavelet<D>> {
  static constexpr bool available = true;
  static constexpr bool has_samples = true;

  static void points(const wavelet<D>& w, const vec<float, D>* pts, std::size_t count, float* out,
                     vec<float, D>* grad) {
    const auto* p = reinterpret_cast<const float*>(pts);
    auto* g = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::wavelet2_points(w, p, count, out, g);
    else
      simd::wavelet3_points(w, p, count, out, g);
  }
  static void grid(const wavelet<D>& w, const hush::grid<D>& gr, float* out, vec<float, D>* grad) {
    auto* g = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::wavelet2_grid(w, gr, out, g);
    else
      simd::wavelet3_grid(w, gr, out, g);
  }
  static void samples(const wavelet<D>& w, const hush::samples<D>& s, float* out,
                      vec<float, D>* grad) {
    auto* g = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::wavelet2_samples(w, s, out, g);
    else
      simd::wavelet3_samples(w, s, out, g);
  }
};

}  // namespace detail
}  // namespace hush
#endif  // HUSH_CONFIG_SIMD

#endif  // HUSH_WAVELET_SIMD_KERNEL_HPP
