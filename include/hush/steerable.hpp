// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// This header forwards to hush/anisotropic/steerable.hpp, anisotropic noise's steerable filters.
#include "hush/anisotropic/steerable.hpp"  // IWYU pragma: export
