// hush — the GLSL backend's include paths of 0.1.x that now forward to a noise's
// folder (hush/glsl/coherent.hpp, hush/glsl/wavelet_glsl.hpp, ...): each still
// compiles and declares what it declared. Only those headers are included, so a
// forward that lost its target fails to build.
#include <doctest/doctest.h>

#include <type_traits>

#include "hush/glsl/anisotropic_program.hpp"
#include "hush/glsl/coherent.hpp"
#include "hush/glsl/gabor_glsl.hpp"
#include "hush/glsl/npr_gabor.hpp"
#include "hush/glsl/wavelet_glsl.hpp"
#include "hush/glsl/wavelet_program.hpp"

TEST_CASE("include paths: the GLSL forwarding headers of 0.1.x declare their programs") {
  CHECK(sizeof(hush::glsl::noise_program<hush::anisotropic>) > 0);
  CHECK(sizeof(hush::glsl::noise_program<hush::gabor<2>>) > 0);
  CHECK(sizeof(hush::glsl::noise_program<hush::wavelet<3>>) > 0);
  CHECK(sizeof(hush::glsl::noise_program<hush::wavelet<2>>) > 0);
  CHECK(std::is_function<decltype(hush::glsl::coherent_glsl_step)>::value);
  CHECK(std::is_function<decltype(hush::glsl::npr_gabor_glsl_render)>::value);
}
