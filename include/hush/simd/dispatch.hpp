// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The SIMD backend's target-independent machinery: what turns a noise's list
// of SIMD entry points into dispatch code, the kernel trait exec.hpp asks,
// and which SIMD targets were compiled and which one runs. It names no noise:
// each noise declares its entry points and specialises detail::simd_kernel in
// its own hush/<noise>/simd_kernel.hpp.
//
// Three ways to build, chosen by macro (config.hpp normalises them into
// HUSH_CONFIG_SIMD and HUSH_CONFIG_SIMD_STATIC):
//  - HUSH_SIMD_DYNAMIC: kernels for every target Highway compiles (SSE4,
//    AVX2, AVX-512 on x86), the best one the CPU supports chosen at run time.
//    The CMake target hush::simd is one translation unit per noise
//    (src/simd/<noise>.cpp, hush/simd/dispatch_unit.hpp) and defines the
//    macro; without CMake, exactly one .cpp of the program includes
//    hush/simd/dispatch_impl.hpp (every noise in one unit) and links Highway.
//    This is the route for portable binaries.
//  - HUSH_SIMD_STATIC: kernels for the compiler's baseline target only
//    (HWY_STATIC_TARGET; AVX2 under -march=haswell or -march=native), inlined
//    where called; no extra translation unit. The route for -march=native
//    builds and for the single header.
//  - neither (or HUSH_NO_SIMD): exec::simd runs the scalar loop, and nothing
//    needs Highway.
//
// A noise's entry points are one X-macro list (Highway's HWY_EXPORT needs a
// name per function, so the list is a macro, as FastNoise2's build list is):
//   #define HUSH_SIMD_ENTRIES_PERLIN(X)
//     X(perlin2_points, (std::uint32_t key, ..., float* grad), (key, ..., grad)) ...
//   HUSH_SIMD_DECLARE(HUSH_SIMD_ENTRIES_PERLIN)
// Each entry returns void; its kernel is hush::HWY_NAMESPACE::<name> in the
// noise's -inl.h, and hush::simd::<name> calls it. HUSH_SIMD_DECLARE gives the
// declarations (dynamic) or the inline wrappers (static); the dispatch unit
// gives HWY_EXPORT and the dynamic wrappers from the same list.
#ifndef HUSH_SIMD_DISPATCH_HPP
#define HUSH_SIMD_DISPATCH_HPP

#include <string>
#include <vector>

#include "hush/config.hpp"

namespace hush {
namespace detail {

// The SIMD kernels of a noise type (used by exec.hpp). Noises with kernels
// specialise it in their hush/<noise>/simd_kernel.hpp with
//   static constexpr bool available = true;
//   static void points(noise, const vec<float, D>* pts, size_t n, float* out, vec<float, D>* grad);
//   static void grid(noise, const grid<D>&, float* out, vec<float, D>* grad);
// and optionally has_grid_slab + grid_slab(noise, grid, first, count, out, grad) (slabs along
// the slowest axis, for exec::parallel) and has_samples + samples(noise, samples, out, grad).
// The primary template says "none", and exec::simd then runs the scalar loop.
template <class Noise>
struct simd_kernel {
  static constexpr bool available = false;
};

}  // namespace detail
}  // namespace hush

#if HUSH_CONFIG_SIMD

#if HUSH_CONFIG_SIMD_STATIC
#include <hwy/highway.h>  // after hush/config.hpp: see HWY_WANT_AVX3_DL there

// Static route: hush::simd::<name> calls the baseline target's kernel inline.
#define HUSH_SIMD_DECLARE_ONE(name, params, args) \
  inline void name params { HWY_STATIC_DISPATCH(name) args; }
#else
// Dynamic route: declared here, defined once by the noise's dispatch unit.
#define HUSH_SIMD_DECLARE_ONE(name, params, args) void name params;
#endif

// The entry points of `list` (an X-macro list, above) in namespace hush::simd.
#define HUSH_SIMD_DECLARE(list) \
  namespace hush {              \
  namespace simd {              \
  list(HUSH_SIMD_DECLARE_ONE)   \
  } /* namespace simd */        \
  } /* namespace hush */

namespace hush {
namespace simd {

// Names of the targets compiled into this program ("AVX2", "SSE4", ...),
// best first, and of the one the kernels run on, on this CPU. Without SIMD
// (below): none, and "scalar (no SIMD compiled in)".
#if HUSH_CONFIG_SIMD_STATIC
inline std::vector<std::string> compiled_targets() { return {hwy::TargetName(HWY_STATIC_TARGET)}; }
inline std::string chosen_target() { return hwy::TargetName(HWY_STATIC_TARGET); }
#else
std::vector<std::string> compiled_targets();  // defined by hush/simd/dispatch_targets.hpp
std::string chosen_target();
#endif
// "dynamic" or "static" ("none" without SIMD).
inline const char* dispatch_mode() { return HUSH_CONFIG_SIMD_STATIC ? "static" : "dynamic"; }

}  // namespace simd
}  // namespace hush

#else  // no SIMD: the lists declare nothing, simd_kernel stays "none"

#define HUSH_SIMD_DECLARE(list)

// What the SIMD build has (above), so that code printing it compiles in every build:
// exec::simd runs the scalar loop here.
namespace hush {
namespace simd {
inline std::vector<std::string> compiled_targets() { return {}; }
inline std::string chosen_target() { return "scalar (no SIMD compiled in)"; }
inline const char* dispatch_mode() { return "none"; }
}  // namespace simd
}  // namespace hush

#endif  // HUSH_CONFIG_SIMD

#endif  // HUSH_SIMD_DISPATCH_HPP
