// fBm of Perlin noise summed in an engine's own fragment shader: the kit's block holds every
// band (keys, offsets, weights, hush's normalisation); plain GL calls bind it
// (examples/shader_gl_calls.hpp); the result is compared with the CPU.
#include <hush/hush.hpp>
#include <hush/glsl/fractal/shader.hpp>
#include <hush/glsl/osmesa_context.hpp>

#include <cmath>
#include <cstdio>

#include "shader_gl_calls.hpp"

int main() {
  hush::glsl::osmesa_context context;  // any current GL >= 4.3 context
  const example_gl::gl gl{context.loader()};
  hush::fractal<hush::perlin<2>>::params prm;
  prm.octaves = 6;
  prm.seed = 3;
  const hush::fractal<hush::perlin<2>> fbm{prm};
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(fbm);
  const std::string fs = "#version 430 core\n" + kit.source +
                         "layout(location = 0) out vec4 colour;\n"
                         "void main() {\n"
                         "  vec2 p = gl_FragCoord.xy * 0.125 - 4.0;\n"
                         "  colour = vec4(hush_fractal_perlin2(p), p, 0.0);\n"
                         "}\n";
  gl.bind_kit(kit);  // the block at binding HUSH_FRACTAL_PERLIN2_PARAMS_BINDING
  const int size = 64;
  const auto px = gl.draw(gl.program(fs), size, 1)[0];
  double worst = 0, pmax = 0;
  for (int k = 0; k < size * size; ++k) {
    const hush::vec2 p{px[4 * std::size_t(k) + 1], px[4 * std::size_t(k) + 2]};
    pmax = std::fmax(pmax, std::fmax(std::fabs(p[0]), std::fabs(p[1])));
    worst = std::fmax(worst, std::fabs(px[4 * std::size_t(k)] - fbm(p)));
  }
  const double budget = hush::glsl::shader_budget(fbm, pmax);
  std::printf("hush_fractal_perlin2 (6 octaves) in a fragment shader: largest |gpu - cpu| = %.3g "
              "(bound %.3g at |p| <= %g)\n", worst, budget, pmax);
  return worst <= budget ? 0 : 1;
}
