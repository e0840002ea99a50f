// Wavelet noise on a receding plane in an engine's own fragment shader, band-limited per
// pixel from the shader's own dFdx/dFdy (Cook & DeRose's footprint fade): the kit's tile is
// an R32F texture and its parameters a std140 block, uploaded and bound with plain GL calls
// (examples/shader_gl_calls.hpp). The pixels are compared with the CPU's
// sample(p, footprint) at the same position and derivatives, read back from a second
// colour attachment.
#include <hush/hush.hpp>
#include <hush/glsl/osmesa_context.hpp>
#include <hush/glsl/wavelet/shader.hpp>

#include <cmath>
#include <cstdio>

#include "shader_gl_calls.hpp"

int main() {
  hush::glsl::osmesa_context context;  // any current GL >= 4.3 context
  const example_gl::gl gl{context.loader()};
  hush::wavelet<2>::params prm;
  prm.tile_size = 64;
  prm.weights = {1.0, 0.5, 0.25, 0.125};  // bands of frequency 1, 2, 4, 8
  const hush::wavelet<2> noise{prm};
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
  const std::string fs =
      "#version 430 core\n" + kit.source +
      "layout(location = 0) out vec4 colour;\n"
      "layout(location = 1) out vec4 derivatives;\n"
      "void main() {\n"
      "  // A ground plane seen from above it: depth grows towards the top of the image.\n"
      "  vec2 s = gl_FragCoord.xy / 64.0;\n"
      "  float depth = 1.0 / (1.1 - s.y);\n"
      "  vec2 p = vec2((s.x - 0.5) * depth * 4.0, depth * 4.0);\n"
      "  vec2 dx = dFdx(p), dy = dFdy(p);\n"
      "  colour = vec4(hush_wavelet2_filtered(p, dx, dy), p, 0.0);\n"
      "  derivatives = vec4(dx, dy);\n"
      "}\n";
  gl.bind_kit(kit);  // block, tile, variant tile and table textures at their bindings
  const int size = 64;
  const auto out = gl.draw(gl.program(fs), size, 2);
  double worst = 0, pmax = 0;
  for (int k = 0; k < size * size; ++k) {
    const float* c = &out[0][4 * std::size_t(k)];
    const float* d = &out[1][4 * std::size_t(k)];
    const hush::vec2 p{c[1], c[2]};
    const auto fp = hush::footprint<2>::from_derivatives(hush::vec2{d[0], d[1]}, hush::vec2{d[2], d[3]});
    pmax = std::fmax(pmax, std::fmax(std::fabs(p[0]), std::fabs(p[1])));
    worst = std::fmax(worst, std::fabs(c[0] - noise.sample(p, fp)));
  }
  const double budget = hush::glsl::shader_budget(noise, pmax, /*footprint=*/true);
  std::printf("hush_wavelet2_filtered on a receding plane (dFdx/dFdy footprints): largest "
              "|gpu - cpu| = %.3g (bound %.3g)\n", worst, budget);
  return worst <= budget ? 0 : 1;
}
