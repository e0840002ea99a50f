// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// This header forwards to hush/npr_gabor/style.hpp, the styles that turn noise into drawings.
#include "hush/npr_gabor/style.hpp"  // IWYU pragma: export
