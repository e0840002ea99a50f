// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The kernels of every noise, and HUSH_SIMD_ENTRIES_ALL, the union of their
// entry lists: the one dispatch unit of hush/simd/dispatch_impl.hpp. The CMake
// target hush::simd compiles one unit per noise instead (src/simd/). The
// registry test (tests/registry) checks that both name every registered noise.
#if defined(HUSH_SIMD_ALL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_SIMD_ALL_INL_H_
#undef HUSH_SIMD_ALL_INL_H_
#else
#define HUSH_SIMD_ALL_INL_H_
#endif

#include "hush/anisotropic/simd-inl.h"
#include "hush/coherent/simd-inl.h"
#include "hush/fractal/simd-inl.h"
#include "hush/gabor/simd-inl.h"
#include "hush/npr_gabor/simd-inl.h"
#include "hush/perlin/simd-inl.h"
#include "hush/wavelet/simd-inl.h"

#endif  // HUSH_SIMD_ALL_INL_H_ toggle

#ifndef HUSH_SIMD_ENTRIES_ALL
#define HUSH_SIMD_ENTRIES_ALL(X)                                                        \
  HUSH_SIMD_ENTRIES_ANISOTROPIC(X)                                                      \
  HUSH_SIMD_ENTRIES_COHERENT(X) HUSH_SIMD_ENTRIES_FRACTAL(X) HUSH_SIMD_ENTRIES_GABOR(X) \
      HUSH_SIMD_ENTRIES_NPR_GABOR(X) HUSH_SIMD_ENTRIES_PERLIN(X) HUSH_SIMD_ENTRIES_WAVELET(X)
#endif
