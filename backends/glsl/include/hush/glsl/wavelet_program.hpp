// hush — procedural noise for rendering. MIT License, see LICENSE.
// Wavelet noise's GLSL program: this header includes hush/glsl/wavelet/program.hpp.
#include "hush/glsl/wavelet/program.hpp"
