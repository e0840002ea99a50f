// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::noise_program<perlin<D>>: improved Perlin noise (include/hush/perlin.hpp)
// on the GPU, the runner's part (noise_program.hpp); its GLSL functions are the
// library's (hush/glsl/perlin/glsl.hpp, contract in hush/glsl/library.hpp).
#ifndef HUSH_GLSL_PERLIN_PROGRAM_HPP
#define HUSH_GLSL_PERLIN_PROGRAM_HPP

#include <cstddef>
#include <cstdint>
#include <string>

#include "hush/core/hash.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"
#include "hush/perlin.hpp"

namespace hush {
namespace glsl {

// Improved Perlin noise, 2D and 3D: uniforms hush_key = hush::seed_key(seed)
// and hush_period (uvecD; the CPU's params::period, 0 = not periodic).
template <int D>
struct noise_program<perlin<D>> {
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "perlin2" : "perlin3";

  static std::string uniforms() {
    return std::string("uniform uint hush_key;\nuniform uvec") + std::to_string(D) +
           " hush_period;\n";
  }
  static std::string point_call(bool gradient) {
    return std::string("hush_") + name + (gradient ? "_gradient" : "") +
           "(p, hush_key, hush_period)";
  }
  static std::string cells_call(bool gradient) {
    return std::string("hush_") + name + (gradient ? "_cells_gradient" : "_cells") +
           "(i0, i1, f, hush_key)";
  }
  static std::uint32_t period(const perlin<D>& noise, int axis) {
    return static_cast<std::uint32_t>(noise.parameters().period[static_cast<std::size_t>(axis)]);
  }
  static void set_uniforms(const detail::gl_api& gl, detail::gl_uint program,
                           const perlin<D>& noise) {
    gl.Uniform1ui(gl.GetUniformLocation(program, "hush_key"), seed_key(noise.parameters().seed));
    const detail::gl_int loc = gl.GetUniformLocation(program, "hush_period");
    if constexpr (D == 2)
      gl.Uniform2ui(loc, period(noise, 0), period(noise, 1));
    else
      gl.Uniform3ui(loc, period(noise, 0), period(noise, 1), period(noise, 2));
  }
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_PERLIN_PROGRAM_HPP
