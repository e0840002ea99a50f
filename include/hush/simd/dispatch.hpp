// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The SIMD backend's target-independent face: the entry points exec::simd
// calls, which SIMD targets were compiled and which one runs.
//
// Three ways to build, chosen by macro (config.hpp normalises them into
// HUSH_CONFIG_SIMD and HUSH_CONFIG_SIMD_STATIC):
//  - HUSH_SIMD_DYNAMIC: kernels for every target Highway compiles (SSE4,
//    AVX2, AVX-512 on x86), the best one the CPU supports chosen at run time.
//    Exactly one .cpp of the program includes hush/simd/dispatch_impl.hpp;
//    the CMake target hush::simd is that file, defines the macro and links
//    Highway. This is the route for portable binaries.
//  - HUSH_SIMD_STATIC: kernels for the compiler's baseline target only
//    (HWY_STATIC_TARGET; AVX2 under -march=haswell or -march=native), inlined
//    where called; no extra translation unit. The route for -march=native
//    builds and for the single header.
//  - neither (or HUSH_NO_SIMD): exec::simd runs the scalar loop, and nothing
//    needs Highway.
#ifndef HUSH_SIMD_DISPATCH_HPP
#define HUSH_SIMD_DISPATCH_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hush/anisotropic.hpp"
#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/coherent_kernel.hpp"
#include "hush/detail/npr_gabor_splat.hpp"
#include "hush/fractal.hpp"
#include "hush/gabor.hpp"
#include "hush/perlin.hpp"
#include "hush/wavelet.hpp"

namespace hush {
namespace detail {

// The SIMD kernels of a noise type (used by exec.hpp). Noises with kernels
// specialise it below; the primary template says "none", and exec::simd then
// runs the scalar loop.
template <class Noise>
struct simd_kernel {
  static constexpr bool available = false;
};

}  // namespace detail
}  // namespace hush

#if HUSH_CONFIG_SIMD

#if HUSH_CONFIG_SIMD_STATIC
// Highway 1.0.3 leaves AVX3_DL out of its target list even when it is the
// compiler's baseline (-march=native on Ice Lake or Zen 4), then stops with
// "best baseline should be included in dynamic targets". Opting in fixes it.
#ifndef HWY_WANT_AVX3_DL
#define HWY_WANT_AVX3_DL
#endif
#include <hwy/highway.h>

#include "hush/simd/anisotropic-inl.h"
#include "hush/simd/coherent-inl.h"
#include "hush/simd/gabor-inl.h"
#include "hush/simd/npr_gabor-inl.h"
#include "hush/simd/perlin-inl.h"
#include "hush/simd/wavelet-inl.h"
#endif

namespace hush {
namespace simd {

// Kernel entry points. Points are interleaved floats (x0, y0[, z0], x1, ...),
// gradients are written interleaved the same way unless `grad` is null.
// `period` has one entry per axis (0 = not periodic). Results follow
// hush::perlin's contract; see hush/simd/perlin-inl.h for the agreement with
// scalar evaluation. Grid entries evaluate the slab of slowest-axis indices
// (j in 2D, k in 3D) [first, first + count) into value (and grad), which
// start at that slab's first sample; (0, g.size[D - 1]) is the whole grid.
#if HUSH_CONFIG_SIMD_STATIC
#define HUSH_SIMD_ENTRY inline
#else
#define HUSH_SIMD_ENTRY
#endif
HUSH_SIMD_ENTRY void perlin2_points(std::uint32_t key, const std::uint32_t* period, const float* xy,
                                    std::size_t n, float* value, float* grad);
HUSH_SIMD_ENTRY void perlin3_points(std::uint32_t key, const std::uint32_t* period,
                                    const float* xyz, std::size_t n, float* value, float* grad);
HUSH_SIMD_ENTRY void perlin2_grid(std::uint32_t key, const std::uint32_t* period, const grid<2>& g,
                                  std::size_t first, std::size_t count, float* value, float* grad);
HUSH_SIMD_ENTRY void perlin3_grid(std::uint32_t key, const std::uint32_t* period, const grid<3>& g,
                                  std::size_t first, std::size_t count, float* value, float* grad);
HUSH_SIMD_ENTRY void fractal2_points(const fractal<perlin<2>>& fr, const float* xy, std::size_t n,
                                     float* value, float* grad);
HUSH_SIMD_ENTRY void fractal3_points(const fractal<perlin<3>>& fr, const float* xyz, std::size_t n,
                                     float* value, float* grad);
// Wavelet noise (hush/simd/wavelet-inl.h): points and gradients interleaved as above;
// samples as hush::samples (footprints, normals).
HUSH_SIMD_ENTRY void wavelet2_points(const wavelet<2>& w, const float* xy, std::size_t n,
                                     float* value, float* grad);
HUSH_SIMD_ENTRY void wavelet3_points(const wavelet<3>& w, const float* xyz, std::size_t n,
                                     float* value, float* grad);
HUSH_SIMD_ENTRY void wavelet2_grid(const wavelet<2>& w, const grid<2>& g, float* value,
                                   float* grad);
HUSH_SIMD_ENTRY void wavelet3_grid(const wavelet<3>& w, const grid<3>& g, float* value,
                                   float* grad);
HUSH_SIMD_ENTRY void wavelet2_samples(const wavelet<2>& w, const samples<2>& s, float* value,
                                      float* grad);
HUSH_SIMD_ENTRY void wavelet3_samples(const wavelet<3>& w, const samples<3>& s, float* value,
                                      float* grad);
HUSH_SIMD_ENTRY void fractal2_grid(const fractal<perlin<2>>& fr, const grid<2>& g,
                                   std::size_t first, std::size_t count, float* value, float* grad);
HUSH_SIMD_ENTRY void fractal3_grid(const fractal<perlin<3>>& fr, const grid<3>& g,
                                   std::size_t first, std::size_t count, float* value, float* grad);
// Coherent noise: one recursive-filter pass over a frame (hush/simd/coherent-inl.h;
// the same result as detail::coherent_pass_scalar, bit for bit under HUSH_STRICT_FP).
HUSH_SIMD_ENTRY void coherent_pass(const detail::coherent_pass_job<float>& job);
// Gabor noise (hush/gabor.hpp): points (interleaved), grid slabs (as Perlin's), and
// points with footprints (filtered samples); same conventions. hush/simd/gabor-inl.h states
// the agreement with scalar evaluation.
HUSH_SIMD_ENTRY void gabor2_points(const gabor<2>& g, const float* xy, std::size_t n, float* value,
                                   float* grad);
HUSH_SIMD_ENTRY void gabor3_points(const gabor<3>& g, const float* xyz, std::size_t n, float* value,
                                   float* grad);
HUSH_SIMD_ENTRY void gabor2_grid(const gabor<2>& g, const grid<2>& gr, std::size_t first,
                                 std::size_t count, float* value, float* grad);
HUSH_SIMD_ENTRY void gabor2_filtered(const gabor<2>& g, const float* xy, const footprint<2>* fps,
                                     std::size_t n, float* value, float* grad);
HUSH_SIMD_ENTRY void gabor3_filtered(const gabor<3>& g, const float* xyz, const footprint<3>* fps,
                                     std::size_t n, float* value, float* grad);
HUSH_SIMD_ENTRY void gabor3_grid(const gabor<3>& g, const grid<3>& gr, std::size_t first,
                                 std::size_t count, float* value, float* grad);
// Samples with normals (surface noise), interleaved normals; fps null: point footprints.
HUSH_SIMD_ENTRY void gabor3_surface(const gabor<3>& g, const float* xyz, const float* normals,
                                    const footprint<3>* fps, std::size_t n, float* value,
                                    float* grad);

// Anisotropic noise (hush/simd/anisotropic-inl.h): n samples at interleaved
// positions xy, with footprints fp (3 floats each, null = points) and surface
// maps (4 floats each, null = none); or a uniform grid. Gradients
// (interleaved x, y) into grad unless null.
HUSH_SIMD_ENTRY void anisotropic_samples(const anisotropic& a, const float* xy, const float* fp,
                                         const float* map, std::size_t n, float* value,
                                         float* grad);
HUSH_SIMD_ENTRY void anisotropic_grid(const anisotropic& a, const grid<2>& g, float* value,
                                      float* grad);

// NPR Gabor noise's stage 2 (hush/simd/npr_gabor-inl.h): the job's records added into
// out (frame-sized, zeroed by the caller), per pixel in record order; bit for bit
// detail::npr_gabor_splat_scalar<float> under HUSH_STRICT_FP.
HUSH_SIMD_ENTRY void npr_gabor_splat(const detail::npr_gabor_splat_job& job,
                                     const image_view<float>& out);

// Names of the targets compiled into this program ("AVX2", "SSE4", ...),
// best first, and of the one the kernels run on, on this CPU.
HUSH_SIMD_ENTRY std::vector<std::string> compiled_targets();
HUSH_SIMD_ENTRY std::string chosen_target();
// "dynamic" or "static".
inline const char* dispatch_mode() { return HUSH_CONFIG_SIMD_STATIC ? "static" : "dynamic"; }

#if HUSH_CONFIG_SIMD_STATIC
inline void perlin2_points(std::uint32_t key, const std::uint32_t* period, const float* xy,
                           std::size_t n, float* value, float* grad) {
  HWY_STATIC_DISPATCH(perlin2_points)(key, period, xy, n, value, grad);
}
inline void perlin3_points(std::uint32_t key, const std::uint32_t* period, const float* xyz,
                           std::size_t n, float* value, float* grad) {
  HWY_STATIC_DISPATCH(perlin3_points)(key, period, xyz, n, value, grad);
}
inline void perlin2_grid(std::uint32_t key, const std::uint32_t* period, const grid<2>& g,
                         std::size_t first, std::size_t count, float* value, float* grad) {
  HWY_STATIC_DISPATCH(perlin2_grid)(key, period, g, first, count, value, grad);
}
inline void perlin3_grid(std::uint32_t key, const std::uint32_t* period, const grid<3>& g,
                         std::size_t first, std::size_t count, float* value, float* grad) {
  HWY_STATIC_DISPATCH(perlin3_grid)(key, period, g, first, count, value, grad);
}
inline void fractal2_points(const fractal<perlin<2>>& fr, const float* xy, std::size_t n,
                            float* value, float* grad) {
  HWY_STATIC_DISPATCH(fractal2_points)(fr, xy, n, value, grad);
}
inline void fractal3_points(const fractal<perlin<3>>& fr, const float* xyz, std::size_t n,
                            float* value, float* grad) {
  HWY_STATIC_DISPATCH(fractal3_points)(fr, xyz, n, value, grad);
}
inline void fractal2_grid(const fractal<perlin<2>>& fr, const grid<2>& g, std::size_t first,
                          std::size_t count, float* value, float* grad) {
  HWY_STATIC_DISPATCH(fractal2_grid)(fr, g, first, count, value, grad);
}
inline void fractal3_grid(const fractal<perlin<3>>& fr, const grid<3>& g, std::size_t first,
                          std::size_t count, float* value, float* grad) {
  HWY_STATIC_DISPATCH(fractal3_grid)(fr, g, first, count, value, grad);
}
inline void coherent_pass(const detail::coherent_pass_job<float>& job) {
  HWY_STATIC_DISPATCH(coherent_pass)(job);
}
inline void wavelet2_points(const wavelet<2>& w, const float* xy, std::size_t n, float* value,
                            float* grad) {
  HWY_STATIC_DISPATCH(wavelet2_points)(w, xy, n, value, grad);
}
inline void wavelet3_points(const wavelet<3>& w, const float* xyz, std::size_t n, float* value,
                            float* grad) {
  HWY_STATIC_DISPATCH(wavelet3_points)(w, xyz, n, value, grad);
}
inline void wavelet2_grid(const wavelet<2>& w, const grid<2>& g, float* value, float* grad) {
  HWY_STATIC_DISPATCH(wavelet2_grid)(w, g, value, grad);
}
inline void wavelet3_grid(const wavelet<3>& w, const grid<3>& g, float* value, float* grad) {
  HWY_STATIC_DISPATCH(wavelet3_grid)(w, g, value, grad);
}
inline void wavelet2_samples(const wavelet<2>& w, const samples<2>& s, float* value, float* grad) {
  HWY_STATIC_DISPATCH(wavelet2_samples)(w, s, value, grad);
}
inline void wavelet3_samples(const wavelet<3>& w, const samples<3>& s, float* value, float* grad) {
  HWY_STATIC_DISPATCH(wavelet3_samples)(w, s, value, grad);
}
inline void anisotropic_samples(const anisotropic& a, const float* xy, const float* fp,
                                const float* map, std::size_t n, float* value, float* grad) {
  HWY_STATIC_DISPATCH(anisotropic_samples)(a, xy, fp, map, n, value, grad);
}
inline void anisotropic_grid(const anisotropic& a, const grid<2>& g, float* value, float* grad) {
  HWY_STATIC_DISPATCH(anisotropic_grid)(a, g, value, grad);
}
inline void gabor2_points(const gabor<2>& g, const float* xy, std::size_t n, float* value,
                          float* grad) {
  HWY_STATIC_DISPATCH(gabor2_points)(g, xy, n, value, grad);
}
inline void gabor3_points(const gabor<3>& g, const float* xyz, std::size_t n, float* value,
                          float* grad) {
  HWY_STATIC_DISPATCH(gabor3_points)(g, xyz, n, value, grad);
}
inline void gabor2_grid(const gabor<2>& g, const grid<2>& gr, std::size_t first,
                        std::size_t count, float* value, float* grad) {
  HWY_STATIC_DISPATCH(gabor2_grid)(g, gr, first, count, value, grad);
}
inline void gabor2_filtered(const gabor<2>& g, const float* xy, const footprint<2>* fps,
                            std::size_t n, float* value, float* grad) {
  HWY_STATIC_DISPATCH(gabor2_filtered)(g, xy, fps, n, value, grad);
}
inline void gabor3_filtered(const gabor<3>& g, const float* xyz, const footprint<3>* fps,
                            std::size_t n, float* value, float* grad) {
  HWY_STATIC_DISPATCH(gabor3_filtered)(g, xyz, fps, n, value, grad);
}
inline void gabor3_grid(const gabor<3>& g, const grid<3>& gr, std::size_t first,
                        std::size_t count, float* value, float* grad) {
  HWY_STATIC_DISPATCH(gabor3_grid)(g, gr, first, count, value, grad);
}
inline void gabor3_surface(const gabor<3>& g, const float* xyz, const float* normals,
                           const footprint<3>* fps, std::size_t n, float* value, float* grad) {
  HWY_STATIC_DISPATCH(gabor3_surface)(g, xyz, normals, fps, n, value, grad);
}
inline void npr_gabor_splat(const detail::npr_gabor_splat_job& job, const image_view<float>& out) {
  HWY_STATIC_DISPATCH(npr_gabor_splat)(job, out);
}
inline std::vector<std::string> compiled_targets() { return {hwy::TargetName(HWY_STATIC_TARGET)}; }
inline std::string chosen_target() { return hwy::TargetName(HWY_STATIC_TARGET); }
#endif
#undef HUSH_SIMD_ENTRY

}  // namespace simd

namespace detail {

template <int D>
struct simd_kernel<perlin<D>> {
  static constexpr bool available = true;
  static_assert(sizeof(vec<float, D>) == D * sizeof(float),
                "vec<float, D> must be D packed floats");

  static void config(const perlin<D>& n, std::uint32_t& key, std::uint32_t (&period)[3]) {
    key = seed_key(n.parameters().seed);
    for (int a = 0; a < 3; ++a)
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

// Wavelet noise: points, grids and samples (footprints, normals) have kernels.
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

// Anisotropic noise: samples (footprints, surface maps), points and grids,
// values and gradients in SIMD (gradients: the bilinear lookups' slopes).
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

// Gabor noise: points, grids, and samples with footprints and (3D) normals.
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

#endif  // HUSH_SIMD_DISPATCH_HPP
