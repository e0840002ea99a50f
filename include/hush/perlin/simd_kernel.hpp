// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Perlin noise's SIMD entry points (kernels: hush/perlin/simd-inl.h) and
// detail::simd_kernel<perlin<D>>, which exec::simd calls. Included at the end
// of hush/perlin.hpp, after the class its kernels use; not on its own.
//
// Points are interleaved floats (x0, y0[, z0], x1, ...), gradients are
// written interleaved the same way unless `grad` is null. `period` has one
// entry per axis (0 = not periodic). Grid entries evaluate the slab of
// slowest-axis indices (j in 2D, k in 3D) [first, first + count) into value
// (and grad), which start at that slab's first sample; (0, g.size[D - 1]) is
// the whole grid. Results follow hush::perlin's contract; perlin/simd-inl.h states
// the agreement with scalar evaluation.
#ifndef HUSH_PERLIN_SIMD_KERNEL_HPP
#define HUSH_PERLIN_SIMD_KERNEL_HPP

#include <cstddef>
#include <cstdint>

#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/dispatch.hpp"

#if HUSH_CONFIG_SIMD_STATIC
#include "hush/perlin/simd-inl.h"
#endif

#define HUSH_SIMD_ENTRIES_PERLIN(X)                                                                \
  X(perlin2_points,                                                                                \
    (std::uint32_t key, const std::uint32_t* period, const float* xy, std::size_t n, float* value, \
     float* grad),                                                                                 \
    (key, period, xy, n, value, grad))                                                             \
  X(perlin3_points,                                                                                \
    (std::uint32_t key, const std::uint32_t* period, const float* xyz, std::size_t n,              \
     float* value, float* grad),                                                                   \
    (key, period, xyz, n, value, grad))                                                            \
  X(perlin2_grid,                                                                                  \
    (std::uint32_t key, const std::uint32_t* period, const grid<2>& g, std::size_t first,          \
     std::size_t count, float* value, float* grad),                                                \
    (key, period, g, first, count, value, grad))                                                   \
  X(perlin3_grid,                                                                                  \
    (std::uint32_t key, const std::uint32_t* period, const grid<3>& g, std::size_t first,          \
     std::size_t count, float* value, float* grad),                                                \
    (key, period, g, first, count, value, grad))

HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_PERLIN)

#if HUSH_CONFIG_SIMD
namespace hush {
namespace detail {

template <int D>
struct simd_kernel<perlin<D>> {
  static constexpr bool available = true;
  static_assert(sizeof(vec<float, D>) == D * sizeof(float),
                "vec<float, D> must be D packed floats");

  static void config(const perlin<D>& n, std::uint32_t& key, std::uint32_t (&period)[3]) {
    key = seed_key(n.parameters().seed);
    for (std::size_t a = 0; a < 3; ++a)
      period[a] = a < D ? static_cast<std::uint32_t>(n.parameters().period[a]) : 0u;
  }
  static void points(const perlin<D>& n, const vec<float, D>* pts, std::size_t count, float* out,
                     vec<float, D>* grad) {
    std::uint32_t key, period[3];
    config(n, key, period);
    const auto* p = reinterpret_cast<const float*>(pts);
    auto* g = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::perlin2_points(key, period, p, count, out, g);
    else
      simd::perlin3_points(key, period, p, count, out, g);
  }
  // Slabs along the slowest axis (exec::parallel; exec.hpp).
  static constexpr bool has_grid_slab = true;
  static void grid_slab(const perlin<D>& n, const hush::grid<D>& gr, std::size_t first,
                        std::size_t count, float* out, vec<float, D>* grad) {
    std::uint32_t key, period[3];
    config(n, key, period);
    auto* g = reinterpret_cast<float*>(grad);
    if constexpr (D == 2)
      simd::perlin2_grid(key, period, gr, first, count, out, g);
    else
      simd::perlin3_grid(key, period, gr, first, count, out, g);
  }
  static void grid(const perlin<D>& n, const hush::grid<D>& gr, float* out, vec<float, D>* grad) {
    grid_slab(n, gr, 0, gr.size[D - 1], out, grad);
  }
};

}  // namespace detail
}  // namespace hush
#endif  // HUSH_CONFIG_SIMD

#endif  // HUSH_PERLIN_SIMD_KERNEL_HPP
