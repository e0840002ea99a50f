// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Anisotropic noise's SIMD entry points (kernels: hush/anisotropic/simd-inl.h)
// and detail::simd_kernel<anisotropic>, which exec::simd calls: n samples at
// interleaved positions xy, with footprints fp (3 floats each, null = points)
// and surface maps (4 floats each, null = none), or a uniform grid; gradients
// (interleaved x, y: the bilinear lookups' slopes) into grad unless null.
// Included at the end of hush/anisotropic.hpp, after the class its kernels
// use; not on its own.
#ifndef HUSH_ANISOTROPIC_SIMD_KERNEL_HPP
#define HUSH_ANISOTROPIC_SIMD_KERNEL_HPP

#include <cstddef>

#include "hush/config.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/surface_map.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/dispatch.hpp"

#if HUSH_CONFIG_SIMD_STATIC
#include "hush/anisotropic/simd-inl.h"
#endif

#define HUSH_SIMD_ENTRIES_ANISOTROPIC(X)                                                      \
  X(anisotropic_samples,                                                                      \
    (const anisotropic& a, const float* xy, const float* fp, const float* map, std::size_t n, \
     float* value, float* grad),                                                              \
    (a, xy, fp, map, n, value, grad))                                                         \
  X(anisotropic_grid, (const anisotropic& a, const grid<2>& g, float* value, float* grad),    \
    (a, g, value, grad))

HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_ANISOTROPIC)

#if HUSH_CONFIG_SIMD
namespace hush {
namespace detail {

template <>
struct simd_kernel<anisotropic> {
  static constexpr bool available = true;
  static constexpr bool has_samples = true;

  static void points(const anisotropic& a, const vec<float, 2>* pts, std::size_t count, float* out,
                     vec<float, 2>* grad) {
    simd::anisotropic_samples(a, reinterpret_cast<const float*>(pts), nullptr, nullptr, count, out,
                              reinterpret_cast<float*>(grad));
  }
  static void grid(const anisotropic& a, const hush::grid<2>& g, float* out, vec<float, 2>* grad) {
    simd::anisotropic_grid(a, g, out, reinterpret_cast<float*>(grad));
  }
  static void samples(const anisotropic& a, const hush::samples<2>& s, float* out,
                      vec<float, 2>* grad) {
    static_assert(sizeof(footprint<2>) == 3 * sizeof(float), "footprint<2> is 3 packed floats");
    static_assert(sizeof(surface_map) == 4 * sizeof(float), "surface_map is 4 packed floats");
    static_assert(sizeof(vec<float, 2>) == 2 * sizeof(float), "vec<float, 2> is 2 packed floats");
    simd::anisotropic_samples(
        a, reinterpret_cast<const float*>(s.positions.data()),
        s.has_footprints() ? reinterpret_cast<const float*>(s.footprints.data()) : nullptr,
        s.has_surface_maps() ? reinterpret_cast<const float*>(s.surface_maps.data()) : nullptr,
        s.size(), out, reinterpret_cast<float*>(grad));
  }
};

}  // namespace detail
}  // namespace hush
#endif  // HUSH_CONFIG_SIMD

#endif  // HUSH_ANISOTROPIC_SIMD_KERNEL_HPP
