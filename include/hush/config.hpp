// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Version and configuration. User-facing switches are HUSH_* macros that a
// program may define before including hush; they are normalised here, once,
// into HUSH_CONFIG_* macros that are always defined (0 or 1), so the rest of
// the library never asks `#ifdef` twice (the GLM `detail/setup.hpp` idea).
#ifndef HUSH_CONFIG_HPP
#define HUSH_CONFIG_HPP

// The version lives here and nowhere else; CMake reads it from this file.
#define HUSH_VERSION_MAJOR 0
#define HUSH_VERSION_MINOR 1
#define HUSH_VERSION_PATCH 0
#define HUSH_VERSION_STRING "0.1.0"

// HUSH_NO_GLM: define to keep hush from converting to and from glm vectors even
// when GLM's headers are reachable. Otherwise the conversions are enabled when
// <glm/vec2.hpp> can be found (libglm-dev), and can be forced with HUSH_FORCE_GLM.
#if defined(HUSH_NO_GLM)
#define HUSH_CONFIG_GLM 0
#elif defined(HUSH_FORCE_GLM)
#define HUSH_CONFIG_GLM 1
#elif defined(__has_include)
#if __has_include(<glm/vec2.hpp>)
#define HUSH_CONFIG_GLM 1
#else
#define HUSH_CONFIG_GLM 0
#endif
#else
#define HUSH_CONFIG_GLM 0
#endif

// HUSH_STRICT_FP: the build promises no floating-point contraction (the CMake
// option of the same name adds -ffp-contract=off). Code may rely on it to
// claim bit-identical results between evaluation paths.
#if defined(HUSH_STRICT_FP)
#define HUSH_CONFIG_STRICT_FP 1
#else
#define HUSH_CONFIG_STRICT_FP 0
#endif

// HUSH_CONFIG_SIMD: 1 when exec::simd runs the Highway kernels (hush/simd/),
// 0 when it runs the scalar loop. The user opts in with HUSH_SIMD_DYNAMIC
// (run-time dispatch: the CMake target hush::simd, or one .cpp including
// hush/simd/dispatch_impl.hpp) or HUSH_SIMD_STATIC (compile-time target,
// e.g. -march=native builds); HUSH_NO_SIMD overrides both. Opt-in, so that a
// header-only user never has to link Highway without asking for it.
// HUSH_CONFIG_SIMD_STATIC tells the two routes apart. Without SIMD, naming
// hush::exec::simd draws a deprecation warning (hush/exec.hpp) unless HUSH_NO_SIMD or
// HUSH_SIMD_ALLOW_SCALAR is defined.
#if defined(HUSH_NO_SIMD) || !(defined(HUSH_SIMD_DYNAMIC) || defined(HUSH_SIMD_STATIC))
#define HUSH_CONFIG_SIMD 0
#define HUSH_CONFIG_SIMD_STATIC 0
#elif defined(HUSH_SIMD_DYNAMIC) && defined(HUSH_SIMD_STATIC)
#error "hush: define one of HUSH_SIMD_DYNAMIC and HUSH_SIMD_STATIC, not both"
#elif defined(HUSH_SIMD_STATIC)
#define HUSH_CONFIG_SIMD 1
#define HUSH_CONFIG_SIMD_STATIC 1
#else
#define HUSH_CONFIG_SIMD 1
#define HUSH_CONFIG_SIMD_STATIC 0
#endif

// Highway 1.0.3 compiles AVX3_DL (AVX-512 with VNNI, VBMI2, BITALG, VAES... and AVX-VNNI) only
// when HWY_WANT_AVX3_DL is defined, even where that is the compiler's baseline target:
// -march=native on Sapphire Rapids or Zen 5, -march=sapphirerapids. Its detect_targets.h then
// stops every SIMD translation unit with "best baseline should be included in dynamic
// targets". hush defines HWY_WANT_AVX3_DL before any Highway header when the baseline has
// AVX3_DL's features (Highway's own test: detect_targets.h, HWY_BASELINE_AVX3_DL), so both SIMD
// routes build there; other builds compile the targets they did. A translation unit that
// includes Highway before hush must define HWY_WANT_AVX3_DL itself (or pass it to the compiler).
#if HUSH_CONFIG_SIMD && !defined(HWY_WANT_AVX3_DL) && defined(__AVX512F__) &&              \
    defined(__AVX512BW__) && defined(__AVX512DQ__) && defined(__AVX512VL__) &&             \
    defined(__AVXVNNI__) && defined(__VAES__) && defined(__VPCLMULQDQ__) &&                \
    defined(__AVX512VBMI__) && defined(__AVX512VBMI2__) && defined(__AVX512VPOPCNTDQ__) && \
    defined(__AVX512BITALG__)
#define HWY_WANT_AVX3_DL
#endif

// HUSH_NO_EXCEPTIONS: define to have hush report errors through its error handler
// (hush::set_error_handler, hush/core/error.hpp) instead of throwing. Builds without
// exceptions (-fno-exceptions) get the handler without asking. HUSH_CONFIG_CXX_EXCEPTIONS
// says whether the compiler accepts try and throw at all; HUSH_CONFIG_EXCEPTIONS whether
// hush throws. Define HUSH_NO_EXCEPTIONS alike in every translation unit of a program.
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND)
#define HUSH_CONFIG_CXX_EXCEPTIONS 1
#else
#define HUSH_CONFIG_CXX_EXCEPTIONS 0
#endif
#if defined(HUSH_NO_EXCEPTIONS) || !HUSH_CONFIG_CXX_EXCEPTIONS
#define HUSH_CONFIG_EXCEPTIONS 0
#else
#define HUSH_CONFIG_EXCEPTIONS 1
#endif

#if defined(__GNUC__) || defined(__clang__)
#define HUSH_INLINE inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define HUSH_INLINE __forceinline
#else
#define HUSH_INLINE inline
#endif

#endif  // HUSH_CONFIG_HPP
