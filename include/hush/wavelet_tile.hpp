// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// This header forwards to hush/wavelet/tile.hpp, wavelet noise's tile of coefficients.
#include "hush/wavelet/tile.hpp"  // IWYU pragma: export
