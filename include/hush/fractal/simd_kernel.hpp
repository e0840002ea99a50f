// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The SIMD entry points of fractal sums of Perlin noise (kernels:
// hush/fractal/simd-inl.h) and detail::simd_kernel<fractal<perlin<D>>>, which
// exec::simd calls; other bases run the scalar loop. Included at the end of
// hush/fractal.hpp, after the class its kernels use; not on its own.
// Layout conventions as Perlin's (hush/perlin/simd_kernel.hpp).
#ifndef HUSH_FRACTAL_SIMD_KERNEL_HPP
#define HUSH_FRACTAL_SIMD_KERNEL_HPP

#include <cstddef>

#include "hush/config.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/perlin.hpp"  // the bands' noise, and its kernels
#include "hush/simd/dispatch.hpp"

#if HUSH_CONFIG_SIMD_STATIC
#include "hush/fractal/simd-inl.h"
#endif

#define HUSH_SIMD_ENTRIES_FRACTAL(X)                                                            \
  X(fractal2_points,                                                                            \
    (const fractal<perlin<2>>& fr, const float* xy, std::size_t n, float* value, float* grad),  \
    (fr, xy, n, value, grad))                                                                   \
  X(fractal3_points,                                                                            \
    (const fractal<perlin<3>>& fr, const float* xyz, std::size_t n, float* value, float* grad), \
    (fr, xyz, n, value, grad))                                                                  \
  X(fractal2_grid,                                                                              \
    (const fractal<perlin<2>>& fr, const grid<2>& g, std::size_t first, std::size_t count,      \
     float* value, float* grad),                                                                \
    (fr, g, first, count, value, grad))                                                         \
  X(fractal3_grid,                                                                              \
    (const fractal<perlin<3>>& fr, const grid<3>& g, std::size_t first, std::size_t count,      \
     float* value, float* grad),                                                                \
    (fr, g, first, count, value, grad))

HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_FRACTAL)

#if HUSH_CONFIG_SIMD
namespace hush {
namespace detail {

template <int D>
struct simd_kernel<fractal<perlin<D>>> {
  static constexpr bool available = true;

  static void points(const fractal<perlin<D>>& fr, const vec<float, D>* pts, std::size_t count,
                     float* out, vec<float, D>* grad) {
    const auto* p = reinterpret_cast<const float*>(pts);
    auto* g = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::fractal2_points(fr, p, count, out, g);
    else
      simd::fractal3_points(fr, p, count, out, g);
  }
  static constexpr bool has_grid_slab = true;
  static void grid_slab(const fractal<perlin<D>>& fr, const hush::grid<D>& gr, std::size_t first,
                        std::size_t count, float* out, vec<float, D>* grad) {
    auto* g = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::fractal2_grid(fr, gr, first, count, out, g);
    else
      simd::fractal3_grid(fr, gr, first, count, out, g);
  }
  static void grid(const fractal<perlin<D>>& fr, const hush::grid<D>& gr, float* out,
                   vec<float, D>* grad) {
    grid_slab(fr, gr, 0, gr.size[D - 1], out, grad);
  }
};

}  // namespace detail
}  // namespace hush
#endif  // HUSH_CONFIG_SIMD

#endif  // HUSH_FRACTAL_SIMD_KERNEL_HPP
