// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Fractal sums of Perlin noise (include/hush/fractal.hpp: fBm, turbulence) in the user's own
// shader (hush/glsl/shader.hpp). shader_for(fractal<perlin<D>>) returns a kit whose
// functions sum every band in the shader from the position alone:
//
//   float hush_fractal_perlin2(vec2 p)            K sum_i w_i n_i(f_i p + o_i) (or |n_i|)
//   vec3  hush_fractal_perlin2_gradient(vec2 p)   (value, d/dx, d/dy)
//   float hush_fractal_perlin3(vec3 p),  vec4 hush_fractal_perlin3_gradient(vec3 p)
//
// with hush's normalisation K = scale(), the raw weights w_i (gain^i or explicit), the
// frequencies f_i = frequency lacunarity^i, each band's key seed_key(hash32(seed, i)),
// lattice offset o_i and period, all in the std140 block hush_fractal_perlinD_params
// (binding 22 / 23):
//   uvec4 config;      band count, 1 = turbulence (0 = fBm)
//   vec4  scalars;     K
//   vec4  band[32];    float(f_i), float(w_i), float(w_i f_i) (the gradient's chain factor)
//   vec4  offset[32];  o_i (24-bit fractions: exact in float)
//   uvec4 lattice[32]; seed_key of band i's seed, its period per axis (0: not periodic)
// Each band is the library's hush_perlinD[_gradient](q, key, period), summed with the
// library's hush_fractal_add[_gradient] in the CPU's order (hush/glsl/fractal/glsl.hpp), the
// bodies hush's own runner runs. fractal has no footprint on the CPU (no sample()), so the
// kit has none either. One fractal<perlin<D>> instance per program; it may share the
// shader with the Perlin and wavelet kits. GLSL: 430 core, Vulkan 450, 300 es.
//
// Precision. The runner forms band coordinates f_i x + o_i in double on the CPU; the kit
// forms them in float: float(f_i) (exact for power-of-two frequencies and integer
// lacunarity up to 2^24), the product and the sum each round once, so a coordinate is off
// by delta_i <= 2^-24 (3 |p| f_i + 1). With L the Perlin Lipschitz bound (7.3 in 2D, 10.0
// in 3D) and H its Hessian bound (perlin_hessian_bound below), for |p_a| <= pmax:
//   values    within K sum_i |w_i| (2 (2^-16 + (nb + 4) 2^-24) + L sqrt(D) delta_i)
//   gradients within K sum_i |w_i| f_i (2 (2^-16 + (nb + 4) 2^-24) (1 + L) + H sqrt(D) delta_i)
// of the CPU float path (shader_budget, shader_gradient_budget). At |p| <= 2^8 the default
// fBm (5 octaves) is within 6.9e-3, 8 octaves of lacunarity 2 within 1.1e-2 (f_7 = 128:
// band coordinates near 2^15 keep 9 fraction bits); measured on llvmpipe over a 40^2 grid
// at |p| <= 2^8 (tests/fractal/glsl_fractal_shader_test.cpp): 8 octaves 1.4e-4 (2D),
// 6 octaves 1.2e-4 (3D); near the origin 5e-6. Turbulence's gradient follows the
// band's sign, undetermined where a band is within its error of 0. For larger coordinates
// hush::evaluate with exec::glsl{device} splits band coordinates in double on the CPU.
#ifndef HUSH_GLSL_FRACTAL_SHADER_HPP
#define HUSH_GLSL_FRACTAL_SHADER_HPP

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hush/core/hash.hpp"
#include "hush/fractal.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/perlin/shader.hpp"
#include "hush/glsl/shader.hpp"
#include "hush/perlin.hpp"

namespace hush {
namespace glsl {

namespace detail {

constexpr unsigned kFractalShaderBinding[2] = {22u, 23u};  // 2D, 3D params blocks

template <int D>
std::string fractal_shader_source() {
  const std::string d = std::to_string(D), w = "hush_fractal_perlin" + d, P = w + "_p";
  const std::string v = "vec" + d, g = "vec" + std::to_string(D + 1);
  const std::string n = std::to_string(fractal<perlin<D>>::kMaxOctaves);
  const std::string sw = D == 2 ? ".xy" : ".xyz";
  std::string s = std::string(kShaderPrelude) +
                  resource_layout("HUSH_FRACTAL_PERLIN" + d + "_PARAMS_BINDING",
                                  kFractalShaderBinding[D - 2], "std140") +
                  "uniform " + w + "_params {\n  uvec4 config;      // band count, turbulence\n" +
                  "  vec4 scalars;     // K\n  vec4 band[" + n + "];    // f_i, w_i, w_i f_i\n" +
                  "  vec4 offset[" + n + "];  // o_i\n  uvec4 lattice[" + n +
                  "]; // key, period per axis\n} " + P + ";\n" + library_once();
  s += "// ---- Fractal sums of Perlin noise of the " + w +
       "_params block (hush/glsl/fractal/shader.hpp).\n"
       "// Band i's coordinate f_i p + o_i in float; one that overflows is 0, as on the CPU.\n" +
       v + " " + w + "_band_position(" + v + " p, uint i) {\n  " + v + " q = p * " + P +
       ".band[i].x + " + P + ".offset[i]" + sw + ";\n  for (int a = 0; a < " + d +
       "; ++a)\n    if (hush_is_nonfinite(q[a])) q[a] = 0.0;\n  return q;\n}\n";
  s += "float " + w + "(" + v + " p) {\n  if (hush_any_nonfinite(p)) return hush_nan();\n" +
       "  bool turbulence = " + P + ".config.y != 0u;\n  float acc = 0.0;\n" +
       "  for (uint i = 0u; i < " + P + ".config.x; ++i)\n    acc = hush_fractal_add(acc, " +
       "hush_perlin" + d + "(" + w + "_band_position(p, i), " + P + ".lattice[i].x, " + P +
       ".lattice[i].yzw" + (D == 2 ? ".xy" : "") + "), " + P +
       ".band[i].y, turbulence);\n  return " + P + ".scalars.x * acc;\n}\n";
  s += g + " " + w + "_gradient(" + v + " p) {\n  if (hush_any_nonfinite(p)) return " + g +
       "(hush_nan());\n  bool turbulence = " + P + ".config.y != 0u;\n  " + g + " acc = " + g +
       "(0.0);\n  for (uint i = 0u; i < " + P + ".config.x; ++i)\n" +
       "    acc = hush_fractal_add_gradient(acc, hush_perlin" + d + "_gradient(" + w +
       "_band_position(p, i), " + P + ".lattice[i].x, " + P + ".lattice[i].yzw" +
       (D == 2 ? ".xy" : "") + "), " + P + ".band[i].y, " + P +
       ".band[i].z, turbulence);\n  return " + P + ".scalars.x * acc;\n}\n";
  return s;
}

// The Perlin Lipschitz bound L (|grad n| <= L): sqrt(D) S (g + F1 g sqrt(D)), S the
// output scale, g the largest gradient-vector length (1 in 2D, sqrt 2 in 3D), F1 = 15/8
// the fade's largest slope.
template <int D>
double perlin_lipschitz_bound() {
  const double f1 = 15.0 / 8.0, g = D == 2 ? 1.0 : std::sqrt(2.0);
  const double s = D == 2 ? hush::detail::constants::kPerlin2Scale
                          : hush::detail::constants::kPerlin3Scale;
  return std::sqrt(double(D)) * s * (g + f1 * g * std::sqrt(double(D)));
}
// A bound on Perlin noise's Hessian (spectral norm <= D times the largest entry): an entry
// of the blend of corner dot products d (|d| <= g sqrt(D)) with fades u(t) is at most
// F2 |d1 - d0| + 2 F1 |g1 - g0| (diagonal) or F1^2 |second difference of d| + 2 F1 |g1 - g0|
// (mixed), F2 = 10 / sqrt(3) the fade's largest curvature.
template <int D>
double perlin_hessian_bound() {
  const double f1 = 15.0 / 8.0, f2 = 10.0 / std::sqrt(3.0), g = D == 2 ? 1.0 : std::sqrt(2.0);
  const double s = D == 2 ? hush::detail::constants::kPerlin2Scale
                          : hush::detail::constants::kPerlin3Scale;
  const double rd = std::sqrt(double(D));
  const double diagonal = f2 * 2 * g * rd + 2 * f1 * 2 * g;
  const double mixed = f1 * f1 * 4 * g * rd + 2 * f1 * 2 * g;
  return D * s * std::max(diagonal, mixed);
}

template <int D>
double fractal_kit_budget(const fractal<perlin<D>>& fr, double pmax, bool gradient) {
  const double u = std::ldexp(1.0, -24);
  const double band_eval = 2 * (std::ldexp(1.0, -16) + (fr.band_count() + 4) * u);
  const double l = perlin_lipschitz_bound<D>(), h = perlin_hessian_bound<D>();
  double sum = 0;
  for (int i = 0; i < fr.band_count(); ++i) {
    const double f = fr.band_frequency(i), wi = std::fabs(fr.band_raw_weight(i));
    const double delta = u * (3 * pmax * f + 1);
    sum += gradient ? wi * f * (band_eval * (1 + l) + h * std::sqrt(double(D)) * delta)
                    : wi * (band_eval + l * std::sqrt(double(D)) * delta);
  }
  return fr.scale() * sum;
}

}  // namespace detail

// |kit value - CPU float value| at |p_a| <= pmax (file comment).
template <int D>
double shader_budget(const fractal<perlin<D>>& fr, double pmax) {
  return detail::fractal_kit_budget(fr, pmax, false);
}
// The same for each gradient component.
template <int D>
double shader_gradient_budget(const fractal<perlin<D>>& fr, double pmax) {
  return detail::fractal_kit_budget(fr, pmax, true);
}

// The kit of a fractal sum of Perlin noise (file comment).
template <int D>
shader_kit shader_for(const fractal<perlin<D>>& fr) {
  constexpr int kMax = fractal<perlin<D>>::kMaxOctaves;
  const std::string d = std::to_string(D);
  const int nb = fr.band_count();
  std140_writer b;
  b.uvec4(static_cast<std::uint32_t>(nb),
          fr.parameters().kind == fractal_kind::turbulence ? 1u : 0u, 0u, 0u);
  b.vec4(static_cast<float>(fr.scale()), 0.0f, 0.0f, 0.0f);
  for (int i = 0; i < kMax; ++i) {
    if (i >= nb) {
      b.vec4(0.0f, 0.0f, 0.0f, 0.0f);
      continue;
    }
    // The CPU's float constants: T(w) and T(w f) (fractal::value_and_gradient).
    b.vec4(static_cast<float>(fr.band_frequency(i)), static_cast<float>(fr.band_raw_weight(i)),
           static_cast<float>(fr.band_raw_weight(i) * fr.band_frequency(i)), 0.0f);
  }
  for (int i = 0; i < kMax; ++i) {
    float o[3] = {0, 0, 0};
    if (i < nb) {
      const vec<double, D> q = fr.band_position(i, vec<double, D>{});  // o_i
      for (int a = 0; a < D; ++a) o[a] = static_cast<float>(q[a]);
    }
    b.vec4(o[0], o[1], o[2], 0.0f);
  }
  for (int i = 0; i < kMax; ++i) {
    std::uint32_t l[4] = {0, 0, 0, 0};
    if (i < nb) {
      const auto& np = fr.band_noise(i).parameters();
      l[0] = seed_key(np.seed);
      for (int a = 0; a < D; ++a)
        l[a + 1] = static_cast<std::uint32_t>(np.period[static_cast<std::size_t>(a)]);
    }
    b.uvec4(l[0], l[1], l[2], l[3]);
  }
  shader_resource block;
  block.name = "hush_fractal_perlin" + d + "_params";
  block.kind = resource_kind::uniform_block;
  block.binding = detail::kFractalShaderBinding[D - 2];
  block.binding_macro = "HUSH_FRACTAL_PERLIN" + d + "_PARAMS_BINDING";
  block.layout = "std140: uvec4 config at 0, vec4 scalars at 16, vec4 band[" +
                 std::to_string(kMax) + "] at 32, vec4 offset[" + std::to_string(kMax) +
                 "], uvec4 lattice[" + std::to_string(kMax) + "] (16-byte stride)";
  block.words = b.words();
  shader_kit kit;
  kit.source = detail::fractal_shader_source<D>();
  kit.resources = {block};
  kit.versions = "430 core, Vulkan 450, 300 es";
  const std::string n = "hush_fractal_perlin" + d, v = "vec" + d;
  kit.usage = "// float " + n + "(" + v + " p): the fBm or turbulence sum, hush's normalisation\n" +
              "// vec" + std::to_string(D + 1) + " " + n + "_gradient(" + v +
              " p): (value, gradient)\n// Error against hush's float path at |p| <= pmax: "
              "hush::glsl::shader_budget(noise, pmax).\n";
  return kit;
}

// The fractal kits' sources for `hush glsl-export`: hush_fractal_perlin2_shader.glsl,
// hush_fractal_perlin3_shader.glsl.
inline std::vector<std::pair<std::string, std::string>> fractal_shader_exports() {
  return {{"hush_fractal_perlin2_shader.glsl", detail::fractal_shader_source<2>()},
          {"hush_fractal_perlin3_shader.glsl", detail::fractal_shader_source<3>()}};
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_FRACTAL_SHADER_HPP
