// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Improved Perlin noise (include/hush/perlin.hpp) in the user's own shader
// (hush/glsl/shader.hpp): shader_for(perlin<D>) returns a kit whose functions take only a
// position; the key and period come from a std140 block:
//
//   layout(std140, binding = HUSH_PERLIN<D>_PARAMS_BINDING) uniform hush_perlin<D>_params {
//     uint key;        // hush::seed_key(seed)
//     uvec<D> period;  // params::period per axis, 0 = not periodic
//   } hush_perlin<D>_p;
//   float hush_perlin2(vec2 p)            value in [-1, 1]
//   vec3  hush_perlin2_gradient(vec2 p)   (value, d/dx, d/dy)
//   float hush_perlin3(vec3 p)
//   vec4  hush_perlin3_gradient(vec3 p)   (value, d/dx, d/dy, d/dz)
//
// They call the library's hush_perlinD(p, key, period) (hush/glsl/perlin/glsl.hpp), whose
// overloads stay available. Default bindings: 20 (2D), 21 (3D); one perlin<D> instance per
// program (a second noise of the same type passes its own key and period to the library
// functions). The kit source holds hush's GLSL library once per shader (guarded by
// HUSH_GLSL_LIBRARY), so the Perlin and fractal kits can share a shader.
//
// Precision (hush/glsl/library.hpp): the position is split exactly on the GPU, as the CPU
// splits the same float, so at ANY finite float position values are within 2^-16 of the
// double reference and 2^-15 of the CPU float path, gradients within 2^-16 (1 + L),
// L = 7.3 (2D), 10.0 (3D), on GPUs with correctly rounded float ops (twice that with 2-ulp
// ops); tests/perlin/glsl_perlin_shader_test.cpp measures it on llvmpipe.
// GLSL: 430 core, Vulkan 450 (GL_KHR_vulkan_glsl), 300 es.
#ifndef HUSH_GLSL_PERLIN_SHADER_HPP
#define HUSH_GLSL_PERLIN_SHADER_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hush/core/hash.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/shader.hpp"
#include "hush/perlin.hpp"

namespace hush {
namespace glsl {

namespace detail {

constexpr unsigned kPerlinShaderBinding[2] = {20u, 21u};  // 2D, 3D params blocks

template <int D>
std::string perlin_shader_source() {
  const std::string d = std::to_string(D), name = "hush_perlin" + d;
  const std::string macro = "HUSH_PERLIN" + d + "_PARAMS_BINDING";
  const std::string vec = "vec" + d, grad = "vec" + std::to_string(D + 1);
  return std::string(kShaderPrelude) +
         resource_layout(macro, kPerlinShaderBinding[D - 2], "std140") + "uniform " + name +
         "_params {\n  uint key;\n  uvec" + d + " period;\n} " + name + "_p;\n" +
         library_once() + "// ---- Perlin noise of the " + name +
         "_params block (hush/glsl/perlin/shader.hpp).\n" + "float " + name + "(" + vec +
         " p) { return " + name + "(p, " + name + "_p.key, " + name + "_p.period); }\n" + grad +
         " " + name + "_gradient(" + vec + " p) {\n  return " + name + "_gradient(p, " + name +
         "_p.key, " + name + "_p.period);\n}\n";
}

}  // namespace detail

// The kit of improved Perlin noise, 2D or 3D (file comment): its source depends on D only;
// the block holds seed_key(seed) and the period.
template <int D>
shader_kit shader_for(const perlin<D>& noise) {
  const auto& prm = noise.parameters();
  shader_kit kit;
  kit.source = detail::perlin_shader_source<D>();
  shader_resource block;
  block.name = "hush_perlin" + std::to_string(D) + "_params";
  block.kind = resource_kind::uniform_block;
  block.binding = detail::kPerlinShaderBinding[D - 2];
  block.binding_macro = "HUSH_PERLIN" + std::to_string(D) + "_PARAMS_BINDING";
  block.layout = "std140: uint key at 0 (hush::seed_key(seed)); uvec" + std::to_string(D) +
                 " period at " + (D == 2 ? "8" : "16") + " (0 = not periodic)";
  std140_writer w;
  w.u(seed_key(prm.seed));
  const auto period = [&](int a) {
    return static_cast<std::uint32_t>(prm.period[static_cast<std::size_t>(a)]);
  };
  if constexpr (D == 2)
    w.uvec2(period(0), period(1));
  else
    w.uvec3(period(0), period(1), period(2));
  block.words = w.words();
  kit.resources = {block};
  kit.versions = "430 core, Vulkan 450, 300 es";
  const std::string n = "hush_perlin" + std::to_string(D);
  const std::string v = "vec" + std::to_string(D);
  kit.usage = "// float " + n + "(" + v + " p): improved Perlin noise, in [-1, 1]\n// vec" +
              std::to_string(D + 1) + " " + n + "_gradient(" + v +
              " p): (value, gradient)\n// Any finite float p: within 2^-16 of hush's double "
              "reference (2^-15 of its float path);\n// gradients within 2^-16 (1 + L), L = " +
              (D == 2 ? "7.3" : "10.0") + ". NaN or Inf in p: NaN.\n";
  return kit;
}

// The Perlin kits' sources for `hush glsl-export`: hush_perlin2_shader.glsl,
// hush_perlin3_shader.glsl.
inline std::vector<std::pair<std::string, std::string>> perlin_shader_exports() {
  return {{"hush_perlin2_shader.glsl", detail::perlin_shader_source<2>()},
          {"hush_perlin3_shader.glsl", detail::perlin_shader_source<3>()}};
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_PERLIN_SHADER_HPP
