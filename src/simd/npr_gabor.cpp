// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The SIMD kernels of NPR Gabor noise for every target Highway compiles, with
// run-time dispatch: one translation unit of the CMake target hush::simd.
#include "hush/npr_gabor.hpp"
#define HUSH_SIMD_UNIT_INL "hush/npr_gabor/simd-inl.h"
#define HUSH_SIMD_UNIT_ENTRIES HUSH_SIMD_ENTRIES_NPR_GABOR
#include "hush/simd/dispatch_unit.hpp"
