// hush — procedural noise for rendering. MIT License, see LICENSE.
// Gabor noise's GLSL program: this header includes hush/glsl/gabor/program.hpp.
#include "hush/glsl/gabor/program.hpp"
