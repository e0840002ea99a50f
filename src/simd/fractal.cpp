// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The SIMD kernels of fractal sums of Perlin noise for every target Highway compiles, with
// run-time dispatch: one translation unit of the CMake target hush::simd.
#include "hush/fractal.hpp"
#define HUSH_SIMD_UNIT_INL "hush/fractal/simd-inl.h"
#define HUSH_SIMD_UNIT_ENTRIES HUSH_SIMD_ENTRIES_FRACTAL
#include "hush/simd/dispatch_unit.hpp"
