// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// This header forwards to hush/gabor/kernel.hpp, the Gabor kernel and its filtered form.
#include "hush/gabor/kernel.hpp"  // IWYU pragma: export
