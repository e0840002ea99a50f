// hush — procedural noise for rendering. MIT License, see LICENSE.
// NPR Gabor noise on the GPU: this header includes hush/glsl/npr_gabor/renderer.hpp.
#include "hush/glsl/npr_gabor/renderer.hpp"
