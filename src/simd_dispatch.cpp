// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The one translation unit of the CMake target hush::simd: the SIMD kernels
// for every target Highway compiles, with run-time dispatch
// (hush/simd/dispatch.hpp says how to do the same without CMake).
#include "hush/simd/dispatch_impl.hpp"
