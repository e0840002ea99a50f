// Perlin noise in an engine's own fragment shader: hush::glsl::shader_for(noise) gives the
// GLSL and the parameter block; the engine uploads and binds the block itself (plain GL
// calls, examples/shader_gl_calls.hpp), draws, and here compares with the CPU.
#include <hush/hush.hpp>
#include <hush/glsl/osmesa_context.hpp>
#include <hush/glsl/perlin/shader.hpp>

#include <cmath>
#include <cstdio>

#include "shader_gl_calls.hpp"

int main() {
  hush::glsl::osmesa_context context;  // any current GL >= 4.3 context
  const example_gl::gl gl{context.loader()};
  const hush::perlin<3> noise{/*seed=*/7};
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);
  // The engine's shader: kit.source, then its own code calling hush_perlin3(p).
  const std::string fs = "#version 430 core\n" + kit.source +
                         "layout(location = 0) out vec4 colour;\n"
                         "void main() {\n"
                         "  vec3 p = vec3(gl_FragCoord.xy * 0.0625, 2.5);\n"
                         "  colour = hush_perlin3_gradient(p);\n"
                         "}\n";
  gl.bind_kit(kit);  // the block at binding HUSH_PERLIN3_PARAMS_BINDING
  const int size = 64;
  const auto px = gl.draw(gl.program(fs), size, 1)[0];
  double worst = 0;
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const hush::vec3 p{(float(i) + 0.5f) * 0.0625f, (float(j) + 0.5f) * 0.0625f, 2.5f};
      worst = std::fmax(worst, std::fabs(px[4 * std::size_t(j * size + i)] - noise(p)));
    }
  std::printf("hush_perlin3 in a fragment shader, %dx%d: largest |gpu - cpu| = %.3g\n", size,
              size, worst);
  return worst <= 0x1p-15 ? 0 : 1;  // the kit's bound against the CPU float path
}
