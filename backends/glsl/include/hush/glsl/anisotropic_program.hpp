// hush — procedural noise for rendering. MIT License, see LICENSE.
// Anisotropic noise's GLSL program: this header includes hush/glsl/anisotropic/program.hpp.
#include "hush/glsl/anisotropic/program.hpp"
