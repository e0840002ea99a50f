// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Dynamic dispatch of the SIMD backend without CMake: include this in exactly
// ONE .cpp of a program built with HUSH_SIMD_DYNAMIC, and link Highway
// (libhwy). It compiles the kernels of every noise once per SIMD target
// Highway builds for and defines the entry points their
// hush/<noise>/simd_kernel.hpp declare, which pick the best target the CPU
// supports on first use. The CMake target hush::simd does the same in one
// translation unit per noise (src/simd/), which builds in parallel.
//
// No include guard: included once per program, by one translation unit.
#if !defined(HUSH_SIMD_DYNAMIC)
#error "hush/simd/dispatch_impl.hpp needs HUSH_SIMD_DYNAMIC defined for the whole program"
#endif

#include "hush/hush.hpp"  // every noise: the kernels use their classes

#define HUSH_SIMD_UNIT_INL "hush/simd/all-inl.h"
#define HUSH_SIMD_UNIT_ENTRIES HUSH_SIMD_ENTRIES_ALL
#include "hush/simd/dispatch_unit.hpp"

#include "hush/simd/dispatch_targets.hpp"
