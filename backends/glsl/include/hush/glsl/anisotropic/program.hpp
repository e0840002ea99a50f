// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL program of anisotropic noise (hush/anisotropic.hpp): a banded
// program (noise_program.hpp) whose bands are the scales. Per sample and
// scale the runner reads the tile coordinate p f_s / band + offset split on
// the CPU in double (cell and fraction, exactly as the CPU splits it), and
// the shader
//  - computes the weights from per-sample data the runner forms on the CPU in
//    double and rounds to float once (sample_data: q_i = d_i^T S d_i, the
//    footprint's quadratic form per orientation, |T^T d_i|^2 and |det T|;
//    they cancel in float for grazing footprints and nearly singular maps),
//    then as anisotropic.hpp does, in float only (the same polynomials,
//    generated constants): no fp64, so GLES / WebGL-class GPUs and GPUs with
//    1/32-rate doubles run it; least-squares rules read the CPU's own weights
//    per sample instead (its fits cached per map there),
//  - looks the scale's tiles up: value programs with texture() on the
//    RGBA32F tiles (hardware bilinear filtering, repeat wrapping; two
//    textures for K > 4), gradient programs with texelFetch and the CPU's
//    own bilinear blend and slopes,
//  - sums as the CPU does (per channel, scale by scale; the channels in the
//    CPU's tree order; turbulence per octave).
// The tiles are uploaded once per shared tile (device.hpp, noise textures).
// Per-sample data travels in an SSBO at kFirstDataBinding (2K + 1 floats per
// sample; least squares: channels x scales x passes), batches split to the
// GL's SSBO size limit by the device.
//
// Tolerance (tests/anisotropic/glsl_anisotropic_test.cpp): against the CPU float
// path, |gpu - cpu| <= sum over subbands of |w| (2^-8 t_i + e_w m_i) +
// 2 float_budget(), with w the sample's weights, t_i the largest texel step
// and m_i the largest |texel| of orientation i (anisotropic_tile::max_step,
// max_abs): many GPUs quantise bilinear weights to 8 fractional bits (2^-9
// per axis; two axes); e_w = 2^-20 + 17 * 2^-22 bounds a weight's relative
// error: 2^-20 covers GLSL's 2.5 ulp division in log2 and the freedom to fuse
// multiply-adds, and 17 * 2^-22 the exponent: the CPU rounds z = kappa_s q_i
// once (from double), the GPU forms float(kappa_s) * float(q_i) (three
// roundings), so the two z differ by at most 4 u z (u = 2^-24), and
// lambda = 2^-z by at most ln2 * 4 u z = x 2^-22 relative, x = z ln2 <=
// kAnisoWeightCutoff = 17 below the cutoff (a z that straddles it gives 0
// against e^-17 times at most the cap: inside the float budget). The map's
// terms are the CPU's float inputs bit for bit, and least-squares weights are
// the CPU's own. The float budget covers the rest. Gradient programs
// (texelFetch, no filtering hardware) drop the 2^-8 term.
// Measured on llvmpipe: tests/anisotropic/glsl_anisotropic_test.cpp prints it.
//
// The functions (hush/glsl/anisotropic/glsl.hpp) read the runner's per-sample
// SSBO, so they live in the runner, not in the #version 330 library
// (library.hpp); hush glsl-export writes them with the runners.
#ifndef HUSH_GLSL_ANISOTROPIC_PROGRAM_HPP
#define HUSH_GLSL_ANISOTROPIC_PROGRAM_HPP

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hush/anisotropic.hpp"
#include "hush/core/error.hpp"
#include "hush/glsl/anisotropic/glsl.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"

namespace hush {
namespace glsl {

template <>
struct noise_program<anisotropic> {
  static constexpr int dimension = 2;
  static constexpr const char* name = "anisotropic";
  static constexpr bool banded = true;

  static constexpr unsigned sample_data_binding = kFirstDataBinding;
  // The body, then the per-sample data's SSBO (read in the samples layout only).
  static std::string uniforms() {
    return std::string(detail::kAnisotropicBody) +
           "layout(std430, binding = " + std::to_string(sample_data_binding) +
           ") readonly buffer hush_aniso_samples { float hush_aniso_sample[]; };\n";
  }
  static bool given_weights(const anisotropic& a) {
    const auto& p = a.parameters();
    return p.filtering == weight_rule::least_squares ||
           p.compensation == weight_rule::least_squares;
  }
  // Floats per sample: the heuristic rules' inputs q_i, |T^T d_i|^2 (K each)
  // and |det T|; least squares: the CPU's weights, channels() per scale per pass.
  static std::size_t sample_data_floats(const anisotropic& a) {
    const auto& p = a.parameters();
    if (!given_weights(a)) return 2 * static_cast<std::size_t>(p.orientations) + 1;
    const std::size_t passes =
        p.kind == fractal_kind::turbulence ? hush::detail::index(p.octaves) : 1;
    return passes * hush::detail::index(p.scales) * hush::detail::index(a.channels());
  }
  // The sample data carries all the program reads of footprints and maps: the device
  // uploads neither (has_smap still says whether maps were given).
  static constexpr bool reads_sample_inputs = false;
  // Sample in's data, formed in double as anisotropic.hpp forms it and rounded
  // to float once: q_i = d_i^T S d_i (filter_weights) and |T^T d_i|^2, |det T|
  // (combine; a map with a non-finite entry is the zero map), so the shader's
  // weights are float-only and no quadratic form cancels in float. Least
  // squares: the CPU's own weights (anisotropic::weights, octave_weights), its
  // per-map fits cached there.
  static void sample_data(const anisotropic& a, const sample_input<2>& in, float* out) {
    const auto& p = a.parameters();
    const int k = p.orientations;
    if (given_weights(a)) {
      const std::size_t per_pass =
          hush::detail::index(p.scales) * hush::detail::index(a.channels());
      if (p.kind == fractal_kind::fbm) {
        a.weights<float>(in, out);
      } else {
        for (int o = 0; o < p.octaves; ++o)
          a.octave_weights<float>(in, o, out + per_pass * hush::detail::index(o));
      }
      return;
    }
    const surface_map m = in.map.finite() ? in.map : surface_map::zero();
    const double m00 = m.m00, m01 = m.m01, m10 = m.m10, m11 = m.m11;
    for (int i = 0; i < k; ++i) {
      const dvec2 d = a.direction(i);
      const double q = a.filter_form(in.fp, i);
      const double tu = m00 * d.x + m10 * d.y, tv = m01 * d.x + m11 * d.y;
      out[hush::detail::index(i)] = static_cast<float>(q);
      out[hush::detail::index(k + i)] = static_cast<float>(tu * tu + tv * tv);
    }
    out[hush::detail::index(2 * k)] = static_cast<float>(std::fabs(m00 * m11 - m01 * m10));
  }
  static int band_count(const anisotropic& a) { return a.parameters().scales; }
  static std::uint32_t band_period(const anisotropic& a, int, int) {
    return static_cast<std::uint32_t>(a.parameters().tile_size);
  }
  static vec<double, 2> band_position(const anisotropic& a, int band, const vec<double, 2>& p) {
    return {a.band_coordinate(band, 0, p.x), a.band_coordinate(band, 1, p.y)};
  }

  // Per-sample state: the footprint's quadratic form per orientation, the
  // map's log-stretch per orientation and sqrt|det T|, and the accumulators
  // (value, and d/dx, d/dy with gradients) of every octave pass, two vec4
  // (channels 0-3, 4-7) each.
  static std::string band_begin(bool gradient) {
    std::string s =
        "  bool bad = false;\n"
        "  float q[HUSH_ANISO_MAX_ORIENTATIONS];\n"
        "  float half_log[HUSH_ANISO_MAX_ORIENTATIONS];\n"
        "  float sd = 0.0;\n"
        "#ifdef HUSH_SAMPLES\n"
        "  // Per-sample data formed on the CPU in double (sample_data): q_i, then\n"
        "  // |T^T d_i|^2, then |det T|.\n"
        "  // (Least squares: the weights themselves, read in band_step; nothing here.)\n"
        "  uint sbase = hush_aniso_stride * n;\n"
        "  bool own = hush_aniso_given == 0u;\n"
        "  if (own && has_smap) sd = sqrt(hush_aniso_sample[sbase + 2u * hush_aniso_k]);\n"
        "  for (uint i = 0u; i < hush_aniso_k; ++i) {\n"
        "    q[i] = own ? hush_aniso_sample[sbase + i] : 0.0;\n"
        "    float r = own && has_smap ? hush_aniso_sample[sbase + hush_aniso_k + i] : 1.0;\n"
        "    half_log[i] = own && has_smap ? hush_aniso_log2(r) / 2.0 : 0.0;\n"
        "  }\n"
        "#else\n"
        "  // Points and grids: a point footprint and no map.\n"
        "  for (uint i = 0u; i < hush_aniso_k; ++i) {\n"
        "    q[i] = 0.0;\n"
        "    half_log[i] = 0.0;\n"
        "  }\n"
        "#endif\n"
        "  uint passes = hush_aniso_turbulence != 0u ? hush_aniso_octaves : 1u;\n"
        "  vec4 acc[2u * HUSH_ANISO_MAX_SCALES];\n"
        "  for (uint a = 0u; a < 2u * passes; ++a) acc[a] = vec4(0.0);\n";
    if (gradient)
      s +=
          "  vec4 gxa[2u * HUSH_ANISO_MAX_SCALES], gya[2u * HUSH_ANISO_MAX_SCALES];\n"
          "  for (uint a = 0u; a < 2u * passes; ++a) { gxa[a] = vec4(0.0); gya[a] = vec4(0.0); }\n";
    return s;
  }
  // Band b = scale b: its weights per pass, the lookup, the accumulation.
  static std::string band_step(bool gradient) {
    std::string s =
        "    bad = bad || hush_any_nonfinite(f);\n"
        "    vec4 w0[HUSH_ANISO_MAX_SCALES], w1[HUSH_ANISO_MAX_SCALES];\n"
        "    bool used = false;\n"
        "    for (uint pass = 0u; pass < passes; ++pass) {\n"
        "      int k0 = hush_aniso_turbulence != 0u ? int(pass) : 0;\n"
        "      int k1 = hush_aniso_turbulence != 0u ? int(pass) + 1 : int(hush_aniso_octaves);\n"
        "      float w[HUSH_ANISO_MAX_ORIENTATIONS];\n"
        "#ifdef HUSH_SAMPLES\n"
        "      if (hush_aniso_given != 0u) {\n"
        "        // Least squares: the CPU's weights of this pass and scale, as given.\n"
        "        for (uint i = 0u; i < HUSH_ANISO_MAX_ORIENTATIONS; ++i)\n"
        "          w[i] = i < hush_aniso_kc\n"
        "                     ? hush_aniso_sample[sbase + hush_aniso_kc * (hush_bands * pass + b) "
        "+ i]\n"
        "                     : 0.0;\n"
        "      } else\n"
        "#endif\n"
        "        for (uint i = 0u; i < HUSH_ANISO_MAX_ORIENTATIONS; ++i)\n"
        "          w[i] = hush_aniso_weight(i, b, k0, k1, q[i < hush_aniso_k ? i : 0u], has_smap,\n"
        "                                   half_log[i < hush_aniso_k ? i : 0u], sd);\n"
        "      w0[pass] = vec4(w[0], w[1], w[2], w[3]);\n"
        "      w1[pass] = vec4(w[4], w[5], w[6], w[7]);\n"
        "      used = used || any(notEqual(w0[pass], vec4(0.0))) || any(notEqual(w1[pass], "
        "vec4(0.0)));\n"
        "    }\n"
        "    if (used) {\n";
    if (!gradient) {
      s += "      // Hardware bilinear: texel centres at (i + 1/2) / N.\n"
           "      vec2 uv = (vec2(i0) + vec2(1.0 / 2.0) + f) / hush_aniso_tile_size;\n"
           "      vec4 v0 = texture(hush_tile0, uv);\n"
           "      vec4 v1 = hush_aniso_kc > 4u ? texture(hush_tile1, uv) : vec4(0.0);\n"
           "      for (uint pass = 0u; pass < passes; ++pass) {\n"
           "        acc[2u * pass] = acc[2u * pass] + w0[pass] * v0;\n"
           "        acc[2u * pass + 1u] = acc[2u * pass + 1u] + w1[pass] * v1;\n"
           "      }\n";
    } else {
      s += "      // texelFetch and the CPU's blend (anisotropic.hpp accumulate).\n"
           "      float scale = hush_aniso_tpu[b];\n"
           "      for (uint t = 0u; t < hush_aniso_kc / 4u; ++t) {\n"
           "        vec4 c00 = t == 0u ? texelFetch(hush_tile0, ivec2(i0), 0) : "
           "texelFetch(hush_tile1, "
           "ivec2(i0), 0);\n"
           "        vec4 c10 = t == 0u ? texelFetch(hush_tile0, ivec2(i1.x, i0.y), 0) : "
           "texelFetch(hush_tile1, ivec2(i1.x, i0.y), 0);\n"
           "        vec4 c01 = t == 0u ? texelFetch(hush_tile0, ivec2(i0.x, i1.y), 0) : "
           "texelFetch(hush_tile1, ivec2(i0.x, i1.y), 0);\n"
           "        vec4 c11 = t == 0u ? texelFetch(hush_tile0, ivec2(i1), 0) : "
           "texelFetch(hush_tile1, "
           "ivec2(i1), 0);\n"
           "        vec4 r0 = c00 + f.y * (c01 - c00), r1 = c10 + f.y * (c11 - c10);\n"
           "        vec4 v = r0 + f.x * (r1 - r0);\n"
           "        vec4 dx = r1 - r0;\n"
           "        vec4 dy = (c01 - c00) + f.x * ((c11 - c10) - (c01 - c00));\n"
           "        for (uint pass = 0u; pass < passes; ++pass) {\n"
           "          vec4 wv = t == 0u ? w0[pass] : w1[pass];\n"
           "          uint a = 2u * pass + t;\n"
           "          acc[a] = acc[a] + wv * v;\n"
           "          gxa[a] = gxa[a] + wv * (scale * dx);\n"
           "          gya[a] = gya[a] + wv * (scale * dy);\n"
           "        }\n"
           "      }\n";
    }
    return s + "    }\n";
  }
  static std::string band_result(bool gradient) {
    if (!gradient)
      return "bad ? hush_nan() : (hush_aniso_turbulence == 0u ? hush_aniso_channel_sum(acc[0], "
             "acc[1]) : hush_aniso_turbulence_sum(acc, passes))";
    return "bad ? vec3(hush_nan()) : (hush_aniso_turbulence == 0u ? "
           "vec3(hush_aniso_channel_sum(acc[0], acc[1]), hush_aniso_channel_sum(gxa[0], gxa[1]), "
           "hush_aniso_channel_sum(gya[0], gya[1])) : hush_aniso_turbulence_sum_gradient(acc, gxa, "
           "gya, passes))";
  }

  static std::vector<noise_texture> textures(const anisotropic& a) {
    const auto& p = a.parameters();
    std::vector<noise_texture> list;
    const std::shared_ptr<const anisotropic_tile>& tile = a.tile_ptr();
    for (int t = 0; t < 2; ++t) {
      noise_texture tex;
      tex.sampler = t == 0 ? "hush_tile0" : "hush_tile1";
      tex.width = tex.height = static_cast<std::size_t>(p.tile_size);
      tex.owner = tile;
      // K <= 4 has one texture; the second sampler still needs a valid one.
      tex.index = a.channels() > 4 ? t : 0;
      tex.rgba = [tile, index = tex.index] { return tile->rgba(index); };
      list.push_back(tex);
    }
    return list;
  }

  static void set_uniforms(const detail::gl_api& gl, detail::gl_uint program,
                           const anisotropic& a) {
    const auto& p = a.parameters();
    auto loc = [&](const char* n) { return gl.GetUniformLocation(program, n); };
    gl.Uniform1ui(loc("hush_aniso_k"), static_cast<detail::gl_uint>(p.orientations));
    gl.Uniform1ui(loc("hush_aniso_kc"), static_cast<detail::gl_uint>(a.channels()));
    gl.Uniform1ui(loc("hush_aniso_base"), static_cast<detail::gl_uint>(p.base_scale));
    gl.Uniform1ui(loc("hush_aniso_octaves"), static_cast<detail::gl_uint>(p.octaves));
    gl.Uniform1ui(loc("hush_aniso_turbulence"), p.kind == fractal_kind::turbulence ? 1u : 0u);
    gl.Uniform1ui(loc("hush_aniso_three_filter"),
                  p.filtering == weight_rule::three_point ? 1u : 0u);
    gl.Uniform1ui(loc("hush_aniso_three_map"),
                  p.compensation == weight_rule::three_point ? 1u : 0u);
    gl.Uniform1f(loc("hush_aniso_tile_size"), static_cast<float>(p.tile_size));
    constexpr int kS = hush::detail::constants::kAnisoMaxScales;
    float kappa[kS] = {}, tpu[kS] = {}, ow[kS] = {}, gain[kS] = {};
    double g = 1.0;
    for (int s = 0; s < p.scales; ++s) {
      kappa[s] = static_cast<float>(a.kappa(s));
      tpu[s] = static_cast<float>(a.texels_per_unit(s));
    }
    for (int k = 0; k < p.octaves; ++k, g *= p.gain) {
      ow[k] = static_cast<float>(a.octave_weight(k));
      gain[k] = static_cast<float>(g);
    }
    gl.Uniform1ui(loc("hush_aniso_given"), given_weights(a) ? 1u : 0u);
    gl.Uniform1ui(loc("hush_aniso_stride"), static_cast<detail::gl_uint>(sample_data_floats(a)));
    gl.Uniform1fv(loc("hush_aniso_kappa"), kS, kappa);
    gl.Uniform1fv(loc("hush_aniso_tpu"), kS, tpu);
    gl.Uniform1fv(loc("hush_aniso_ow"), kS, ow);
    gl.Uniform1fv(loc("hush_aniso_gain"), kS, gain);
    gl.Uniform1f(loc("hush_aniso_norm"), static_cast<float>(a.normalization()));
    gl.Uniform1f(loc("hush_aniso_cap"), static_cast<float>(a.gamma_cap()));
    gl.Uniform1f(loc("hush_aniso_cut"),
                 static_cast<float>(hush::detail::constants::kAnisoWeightCutoff *
                                    hush::detail::constants::kLog2E));
  }

  // The GPU's agreement with the CPU float path for one sample whose
  // weights are w[i + channels() s] (anisotropic::weights; turbulence: the
  // sum of the octaves' weights times their gains), values from texture()
  // (hardware bilinear) or texelFetch (gradient programs): see the file comment.
  // Relative error of a GPU weight against the CPU's (file comment):
  // 2^-20 (log2's division, fused multiply-adds) plus x 2^-22 for
  // lambda = e^-x, x <= kAnisoWeightCutoff (z = kappa_s q_i in float).
  static constexpr double kWeightError =
      1.0 / (1 << 20) + hush::detail::constants::kAnisoWeightCutoff / (1 << 22);
  static double tolerance(const anisotropic& a, const float* w, bool hardware_filter) {
    double t = 0;
    const int kc = a.channels();
    for (int s = 0; s < a.parameters().scales; ++s)
      for (int i = 0; i < a.parameters().orientations; ++i) {
        const double wi = std::fabs(static_cast<double>(w[i + kc * s]));
        t += wi * ((hardware_filter ? std::ldexp(a.tile().max_step(i), -8) : 0.0) +
                   kWeightError * a.tile().max_abs(i));
      }
    return t + 2 * a.float_budget();
  }
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_ANISOTROPIC_PROGRAM_HPP
