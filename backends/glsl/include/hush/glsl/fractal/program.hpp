// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::glsl::noise_program<fractal<perlin<D>>>: fractal sums of Perlin noise
// (include/hush/fractal.hpp) on the GPU as a banded program (noise_program.hpp); its
// GLSL functions are the library's (hush/glsl/fractal/glsl.hpp, hush/glsl/perlin/glsl.hpp).
#ifndef HUSH_GLSL_FRACTAL_PROGRAM_HPP
#define HUSH_GLSL_FRACTAL_PROGRAM_HPP

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "hush/core/hash.hpp"
#include "hush/fractal.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"
#include "hush/perlin.hpp"

namespace hush {
namespace glsl {

// Fractal sums (fBm, turbulence) of Perlin noise, include/hush/fractal.hpp.
// Band b has its own key (seed_key of the band's seed) and period; its
// coordinate f_b x + o_b is formed and split on the CPU in double
// (fractal::band_position), so the GPU sees the CPU's cells and fractions bit
// for bit. Uniforms: hush_key[], hush_weight[] (float bits of float(w_b)),
// hush_chain[] (float bits of float(w_b f_b), the gradient's chain factor),
// hush_scale (float bits of float(scale())) and hush_turbulence; the arrays
// have fractal::kMaxOctaves entries, the first band_count() set.
template <int D>
struct noise_program<fractal<perlin<D>>> {
  using noise_type = fractal<perlin<D>>;
  static constexpr int dimension = D;
  static constexpr const char* name = D == 2 ? "fractal_perlin2" : "fractal_perlin3";
  static constexpr bool banded = true;

  static std::string uniforms() {
    const std::string n = "[" + std::to_string(noise_type::kMaxOctaves) + "]";
    return "uniform uint hush_key" + n + ";     // seed_key of each band's seed\n" +
           "uniform uint hush_weight" + n + ";  // floatBitsToUint(float(w_b))\n" +
           "uniform uint hush_chain" + n + ";   // floatBitsToUint(float(w_b * f_b))\n" +
           "uniform uint hush_scale;        // floatBitsToUint(float(scale()))\n"
           "uniform uint hush_turbulence;   // 1u: sum |n_b| (turbulence), 0u: fBm\n";
  }
  static int band_count(const noise_type& fr) { return fr.band_count(); }
  static std::uint32_t band_period(const noise_type& fr, int band, int axis) {
    return static_cast<std::uint32_t>(
        fr.band_noise(band).parameters().period[static_cast<std::size_t>(axis)]);
  }
  static vec<double, D> band_position(const noise_type& fr, int band, const vec<double, D>& p) {
    return fr.band_position(band, p);
  }
  static std::string band_begin(bool gradient) {
    return gradient ? "  vec" + std::to_string(D + 1) + " acc = vec" + std::to_string(D + 1) +
                          "(0.0);\n  bool bad = false;\n"
                    : "  float acc = 0.0;\n  bool bad = false;\n";
  }
  static std::string band_step(bool gradient) {
    const std::string cells = std::string("hush_perlin") + std::to_string(D) +
                              (gradient ? "_cells_gradient" : "_cells") +
                              "(i0, i1, f, hush_key[b])";
    std::string s = "    bad = bad || hush_any_nonfinite(f);\n";
    if (gradient)
      s += "    acc = hush_fractal_add_gradient(acc, " + cells +
           ", uintBitsToFloat(hush_weight[b]), uintBitsToFloat(hush_chain[b]), "
           "hush_turbulence != 0u);\n";
    else
      s += "    acc = hush_fractal_add(acc, " + cells +
           ", uintBitsToFloat(hush_weight[b]), hush_turbulence != 0u);\n";
    return s;
  }
  static std::string band_result(bool gradient) {
    const std::string t = gradient ? "vec" + std::to_string(D + 1) : std::string("float");
    return "bad ? " + t + "(hush_nan()) : uintBitsToFloat(hush_scale) * acc";
  }
  static void set_uniforms(const detail::gl_api& gl, detail::gl_uint program,
                           const noise_type& fr) {
    const int nb = fr.band_count();
    std::uint32_t key[noise_type::kMaxOctaves] = {}, weight[noise_type::kMaxOctaves] = {},
                  chain[noise_type::kMaxOctaves] = {};
    for (int b = 0; b < nb; ++b) {
      const std::size_t i = static_cast<std::size_t>(b);
      key[i] = seed_key(fr.band_noise(b).parameters().seed);
      // The CPU's float constants: T(w) and T(w * f) (fractal::value_and_gradient).
      weight[i] = bits(static_cast<float>(fr.band_raw_weight(b)));
      chain[i] = bits(static_cast<float>(fr.band_raw_weight(b) * fr.band_frequency(b)));
    }
    const auto n = static_cast<detail::gl_sizei>(nb);
    gl.Uniform1uiv(gl.GetUniformLocation(program, "hush_key"), n, key);
    gl.Uniform1uiv(gl.GetUniformLocation(program, "hush_weight"), n, weight);
    gl.Uniform1uiv(gl.GetUniformLocation(program, "hush_chain"), n, chain);
    gl.Uniform1ui(gl.GetUniformLocation(program, "hush_scale"),
                  bits(static_cast<float>(fr.scale())));
    gl.Uniform1ui(gl.GetUniformLocation(program, "hush_turbulence"),
                  fr.parameters().kind == fractal_kind::turbulence ? 1u : 0u);
  }

 private:
  static std::uint32_t bits(float f) {
    std::uint32_t u = 0;
    std::memcpy(&u, &f, sizeof u);
    return u;
  }
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_FRACTAL_PROGRAM_HPP
