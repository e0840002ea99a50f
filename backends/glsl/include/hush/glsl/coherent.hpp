// hush — procedural noise for rendering. MIT License, see LICENSE.
// Coherent noise on the GPU: this header includes hush/glsl/coherent/renderer.hpp.
#include "hush/glsl/coherent/renderer.hpp"
