// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::noise_program<Noise>: what the GL runner needs to know about a
// noise type, so that later noises plug into hush::glsl::device without
// touching it. A specialisation provides
//   static constexpr int dimension;            D, the position's dimension
//   static constexpr const char* name;         program name, e.g. "perlin2"
//   static std::string uniforms();             GLSL uniform declarations of its params
//   static std::string point_call(bool grad);  expression of `p` (vecD): float, or
//                                              vec(D+1) (value, gradient) when grad
//   static std::string cells_call(bool grad);  the same of `i0`, `i1` (uvecD), `f` (vecD)
//   static std::uint32_t period(const Noise&, int axis);  lattice period (0 = none),
//                                              for the CPU-side split of grid axes
//   static void set_uniforms(const detail::gl_api&, detail::gl_uint program, const Noise&);
// The runner validates nothing about a noise: noise objects are valid by construction.
#ifndef HUSH_GLSL_NOISE_PROGRAM_HPP
#define HUSH_GLSL_NOISE_PROGRAM_HPP

#include <cstdint>
#include <string>
#include <type_traits>

#include "hush/core/hash.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/perlin.hpp"

namespace hush {
namespace glsl {

// Primary template: not a GLSL-capable noise (no specialisation).
template <class Noise>
struct noise_program;

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

// True when the GLSL backend has a program for Noise (noise_program is
// specialised for it), e.g. to pick a backend at compile time.
template <class Noise, class = void>
struct has_program : std::false_type {};
template <class Noise>
struct has_program<Noise, std::void_t<decltype(sizeof(noise_program<Noise>))>> : std::true_type {};
template <class Noise>
inline constexpr bool has_program_v = has_program<Noise>::value;

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_NOISE_PROGRAM_HPP
