// hush — procedural noise for rendering. MIT License, see LICENSE.
// Wavelet noise's GLSL bodies: this header includes hush/glsl/wavelet/glsl.hpp.
#include "hush/glsl/wavelet/glsl.hpp"
