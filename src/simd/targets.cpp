// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::simd::compiled_targets() and chosen_target(): the translation unit of
// the CMake target hush::simd that names no noise.
#include "hush/simd/dispatch_targets.hpp"
