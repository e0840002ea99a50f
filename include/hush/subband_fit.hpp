// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// This header forwards to hush/anisotropic/subband_fit.hpp, the sub-band fit of anisotropic noise.
#include "hush/anisotropic/subband_fit.hpp"  // IWYU pragma: export
