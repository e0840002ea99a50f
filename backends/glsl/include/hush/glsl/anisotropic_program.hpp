// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL program of anisotropic noise (hush/anisotropic.hpp): a banded
// program (noise_program.hpp) whose bands are the scales. Per sample and
// scale the runner reads the tile coordinate p f_s / band + offset split on
// the CPU in double (cell and fraction, exactly as the CPU splits it), and
// the shader
//  - computes the weights from the footprint fp and the surface map smap as
//    anisotropic.hpp does (the same polynomials, generated constants; the
//    quadratic forms and det T in double, GLSL 4.00's fp64),
//  - looks the scale's tiles up: value programs with texture() on the
//    RGBA32F tiles (hardware bilinear filtering, repeat wrapping; two
//    textures for K > 4), gradient programs with texelFetch and the CPU's
//    own bilinear blend and slopes,
//  - sums as the CPU does (per channel, scale by scale; the channels in the
//    CPU's tree order; turbulence per octave).
// The tiles are uploaded once per shared tile (device.hpp, noise textures).
// Least-squares weight rules are CPU-only: the program refuses them
// (hush::invalid_argument from textures(), before anything runs).
//
// Tolerance (tests/glsl/glsl_anisotropic_test.cpp): against the CPU float
// path, |gpu - cpu| <= sum over subbands of |w| (2^-8 t_i + 2^-20 m_i) +
// 2 float_budget(), with w the sample's weights, t_i the largest texel step
// and m_i the largest |texel| of orientation i (anisotropic_tile::max_step,
// max_abs): many GPUs quantise bilinear weights to 8 fractional bits (2^-9
// per axis; two axes), 2^-20 covers GLSL's 2.5 ulp division in log2 and the
// freedom to fuse multiply-adds, and the float budget the rest. Gradient
// programs (texelFetch, no filtering hardware) drop the 2^-8 term.
// Measured on llvmpipe: tests/glsl/glsl_anisotropic_test.cpp prints it.
//
// The functions need GLSL 4.00 (double), so they live in the runner, not in
// the #version 330 library (library.hpp); hush glsl-export writes them with
// the runners.
#ifndef HUSH_GLSL_ANISOTROPIC_PROGRAM_HPP
#define HUSH_GLSL_ANISOTROPIC_PROGRAM_HPP

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hush/anisotropic.hpp"
#include "hush/core/error.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/noise_program.hpp"

namespace hush {
namespace glsl {
namespace detail {

// The anisotropic noise's GLSL functions and uniforms (runner only: fp64).
constexpr const char* kAnisotropicBody = R"glsl(
// ---- Anisotropic noise (include/hush/anisotropic.hpp, hush/glsl/anisotropic_program.hpp).
uniform sampler2D hush_tile0;             // channels 0-3 of the subband tiles
uniform sampler2D hush_tile1;             // channels 4-7 (K > 4)
uniform uint hush_aniso_k;                // orientations K
uniform uint hush_aniso_kc;               // channels: 4 or 8
uniform uint hush_aniso_base;             // scale of octave 0
uniform uint hush_aniso_octaves;
uniform uint hush_aniso_turbulence;       // 1u: sum gain^k |n_k|, 0u: fbm
uniform uint hush_aniso_three_filter;     // 1u: three-point lambda, 0u: centre
uniform uint hush_aniso_three_map;        // 1u: three-point gamma, 0u: centre
uniform float hush_aniso_tile_size;       // N
uniform double hush_aniso_dxx[HUSH_ANISO_MAX_ORIENTATIONS];   // cos^2 theta_i
uniform double hush_aniso_dyy[HUSH_ANISO_MAX_ORIENTATIONS];   // sin^2 theta_i
uniform double hush_aniso_dxy2[HUSH_ANISO_MAX_ORIENTATIONS];  // 2 cos sin
uniform double hush_aniso_dx[HUSH_ANISO_MAX_ORIENTATIONS];    // cos theta_i
uniform double hush_aniso_dy[HUSH_ANISO_MAX_ORIENTATIONS];    // sin theta_i
uniform double hush_aniso_kappa[HUSH_ANISO_MAX_SCALES];       // 2 pi^2 sigma^2 f_s^2 log2 e
uniform float hush_aniso_tpu[HUSH_ANISO_MAX_SCALES];          // texels per unit, float
uniform float hush_aniso_ow[HUSH_ANISO_MAX_SCALES];           // octave weights (fbm)
uniform float hush_aniso_gain[HUSH_ANISO_MAX_SCALES];         // gain^k (turbulence)
uniform float hush_aniso_norm;            // 1 / sqrt(sum gain^2k)
uniform float hush_aniso_cap;             // heuristic gamma cap
uniform float hush_aniso_cut;             // lambda cutoff (powers of two)

// 2^y for y in [-126, 0] (approx_math.hpp exp2_nonpositive).
float hush_aniso_exp2(float y) {
  float n = floor(y + 1.0 / 2.0);
  float r = y - n;
  float p = HUSH_ANISO_EXP2[HUSH_ANISO_EXP2.length() - 1];
  for (int m = HUSH_ANISO_EXP2.length() - 2; m >= 0; --m) p = p * r + HUSH_ANISO_EXP2[m];
  return ldexp(p, int(n));
}
// log2 m (approx_math.hpp log2_positive): -inf below the smallest normal float.
float hush_aniso_log2(float m) {
  if (!(m >= HUSH_FLOAT_MIN_NORMAL))
    return m >= 0.0 ? uintBitsToFloat(HUSH_FLOAT_EXP_MASK | HUSH_FLOAT_SIGN_MASK) : hush_nan();
  if (hush_is_nonfinite(m)) return m;
  int e;
  float a = frexp(m, e) * 2.0;  // a in [1, 2), exact
  e -= 1;
  if (a > HUSH_ANISO_SQRT2) {
    a = a / 2.0;
    e += 1;
  }
  float z = (a - 1.0) / (a + 1.0);
  float z2 = z * z;
  float p = HUSH_ANISO_LOG2[HUSH_ANISO_LOG2.length() - 1];
  for (int j = HUSH_ANISO_LOG2.length() - 2; j >= 0; --j) p = p * z2 + HUSH_ANISO_LOG2[j];
  return float(e) + p * z;
}
// cos^2(pi x / 2) for |x| < 1, else 0 (approx_math.hpp band_profile).
float hush_aniso_profile(float x) {
  float ax = abs(x);
  if (!(ax < 1.0)) return 0.0;
  float z = ax - 1.0 / 2.0;
  float z2 = z * z;
  float p = HUSH_ANISO_SINPI[HUSH_ANISO_SINPI.length() - 1];
  for (int j = HUSH_ANISO_SINPI.length() - 2; j >= 0; --j) p = p * z2 + HUSH_ANISO_SINPI[j];
  return 1.0 / 2.0 - (p * z) / 2.0;
}
float hush_aniso_lambda1(float z) { return z > hush_aniso_cut ? 0.0 : hush_aniso_exp2(-z); }
float hush_aniso_lambda(float z) {
  if (hush_aniso_three_filter == 0u) return hush_aniso_lambda1(z);
  return (HUSH_ANISO_SIDE * hush_aniso_lambda1(z / 2.0) +
          HUSH_ANISO_CENTRE * hush_aniso_lambda1(z)) +
         HUSH_ANISO_SIDE * hush_aniso_lambda1(z * 2.0);
}
float hush_aniso_band(float x) {
  if (hush_aniso_three_map == 0u) return hush_aniso_profile(x);
  return (HUSH_ANISO_SIDE * hush_aniso_profile(x - HUSH_ANISO_OFFSET) +
          HUSH_ANISO_CENTRE * hush_aniso_profile(x)) +
         HUSH_ANISO_SIDE * hush_aniso_profile(x + HUSH_ANISO_OFFSET);
}
// The weight of channel i at scale s for octaves [k0, k1): anisotropic.hpp's
// combine (gamma from the map, or the identity) times lambda.
float hush_aniso_weight(uint i, uint s, int k0, int k1, double q, bool has_map, float half_log,
                        float sd) {
  if (i >= hush_aniso_k) return 0.0;
  float lam = hush_aniso_lambda(float(hush_aniso_kappa[s] * q));
  bool fbm = hush_aniso_turbulence == 0u;
  int rel = int(s) - int(hush_aniso_base);
  if (!has_map) {
    if (rel < k0 || rel >= k1) return 0.0;
    return (fbm ? hush_aniso_ow[rel] : hush_aniso_norm) * lam;
  }
  float acc = 0.0;
  for (int k = k0; k < k1; ++k) {
    float prof = hush_aniso_band(float(rel - k) + half_log);
    float g = prof > 0.0 ? min(ldexp(1.0, rel - k) * (sd * prof), hush_aniso_cap) : 0.0;
    acc = acc + (fbm ? hush_aniso_ow[k] : hush_aniso_norm) * g;
  }
  return acc * lam;
}
float hush_aniso_channel_sum(vec4 a, vec4 b) {
  float s4 = (a.x + a.y) + (a.z + a.w);
  return hush_aniso_kc == 4u ? s4 : s4 + ((b.x + b.y) + (b.z + b.w));
}
// Turbulence: sum over octave passes of gain^k |n_k| (and its gradient).
float hush_aniso_turbulence_sum(vec4 acc[2u * HUSH_ANISO_MAX_SCALES], uint passes) {
  float r = 0.0;
  for (uint p = 0u; p < passes; ++p)
    r = r + hush_aniso_gain[p] * abs(hush_aniso_channel_sum(acc[2u * p], acc[2u * p + 1u]));
  return r;
}
vec3 hush_aniso_turbulence_sum_gradient(vec4 acc[2u * HUSH_ANISO_MAX_SCALES],
                                        vec4 gx[2u * HUSH_ANISO_MAX_SCALES],
                                        vec4 gy[2u * HUSH_ANISO_MAX_SCALES], uint passes) {
  vec3 r = vec3(0.0);
  for (uint p = 0u; p < passes; ++p) {
    float v = hush_aniso_channel_sum(acc[2u * p], acc[2u * p + 1u]);
    float g = hush_aniso_gain[p], sign = v < 0.0 ? -1.0 : 1.0;
    r = vec3(r.x + g * abs(v), r.y + g * sign * hush_aniso_channel_sum(gx[2u * p], gx[2u * p + 1u]),
             r.z + g * sign * hush_aniso_channel_sum(gy[2u * p], gy[2u * p + 1u]));
  }
  return r;
}
)glsl";

}  // namespace detail

template <>
struct noise_program<anisotropic> {
  static constexpr int dimension = 2;
  static constexpr const char* name = "anisotropic";
  static constexpr bool banded = true;

  static std::string uniforms() { return detail::kAnisotropicBody; }
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
        "  double q[HUSH_ANISO_MAX_ORIENTATIONS];\n"
        "  float half_log[HUSH_ANISO_MAX_ORIENTATIONS];\n"
        "  float sd = 0.0;\n"
        "  // A map with a non-finite entry counts as the zero map.\n"
        "  mat2 tm = smap;\n"
        "  if (has_smap && (hush_is_nonfinite(tm[0][0]) || hush_is_nonfinite(tm[0][1]) ||\n"
        "                   hush_is_nonfinite(tm[1][0]) || hush_is_nonfinite(tm[1][1])))\n"
        "    tm = mat2(0.0);\n"
        "  double m00 = double(tm[0][0]), m01 = double(tm[1][0]);\n"
        "  double m10 = double(tm[0][1]), m11 = double(tm[1][1]);\n"
        "  if (has_smap) sd = sqrt(float(abs(m00 * m11 - m01 * m10)));\n"
        "  for (uint i = 0u; i < hush_aniso_k; ++i) {\n"
        "    q[i] = (double(fp[0][0]) * hush_aniso_dxx[i] + double(fp[1][0]) * "
        "hush_aniso_dxy2[i]) + double(fp[1][1]) * hush_aniso_dyy[i];\n"
        "    double tu = m00 * hush_aniso_dx[i] + m10 * hush_aniso_dy[i];\n"
        "    double tv = m01 * hush_aniso_dx[i] + m11 * hush_aniso_dy[i];\n"
        "    half_log[i] = has_smap ? hush_aniso_log2(float(tu * tu + tv * tv)) / 2.0 : 0.0;\n"
        "  }\n"
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
        "      for (uint i = 0u; i < HUSH_ANISO_MAX_ORIENTATIONS; ++i)\n"
        "        w[i] = hush_aniso_weight(i, b, k0, k1, q[i < hush_aniso_k ? i : 0u], has_smap,\n"
        "                                 half_log[i < hush_aniso_k ? i : 0u], sd);\n"
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
    if (p.filtering == weight_rule::least_squares || p.compensation == weight_rule::least_squares)
      throw hush::invalid_argument(
          "hush::glsl: anisotropic noise with least-squares weights runs on the CPU only (a "
          "least-squares fit per sample); valid on the GPU: filtering and compensation centre or "
          "three_point");
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
    constexpr int kO = hush::detail::constants::kAnisoMaxOrientations;
    constexpr int kS = hush::detail::constants::kAnisoMaxScales;
    double dxx[kO] = {}, dyy[kO] = {}, dxy2[kO] = {}, dx[kO] = {}, dy[kO] = {}, kappa[kS] = {};
    float tpu[kS] = {}, ow[kS] = {}, gain[kS] = {};
    for (int i = 0; i < p.orientations; ++i) {
      const dvec2 d = a.direction(i);
      dxx[i] = d.x * d.x;
      dyy[i] = d.y * d.y;
      dxy2[i] = 2.0 * d.x * d.y;
      dx[i] = d.x;
      dy[i] = d.y;
    }
    double g = 1.0;
    for (int s = 0; s < p.scales; ++s) {
      kappa[s] = a.kappa(s);
      tpu[s] = static_cast<float>(a.texels_per_unit(s));
    }
    for (int k = 0; k < p.octaves; ++k, g *= p.gain) {
      ow[k] = static_cast<float>(a.octave_weight(k));
      gain[k] = static_cast<float>(g);
    }
    gl.Uniform1dv(loc("hush_aniso_dxx"), kO, dxx);
    gl.Uniform1dv(loc("hush_aniso_dyy"), kO, dyy);
    gl.Uniform1dv(loc("hush_aniso_dxy2"), kO, dxy2);
    gl.Uniform1dv(loc("hush_aniso_dx"), kO, dx);
    gl.Uniform1dv(loc("hush_aniso_dy"), kO, dy);
    gl.Uniform1dv(loc("hush_aniso_kappa"), kS, kappa);
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
  static double tolerance(const anisotropic& a, const float* w, bool hardware_filter) {
    double t = 0;
    const int kc = a.channels();
    for (int s = 0; s < a.parameters().scales; ++s)
      for (int i = 0; i < a.parameters().orientations; ++i) {
        const double wi = std::fabs(static_cast<double>(w[i + kc * s]));
        t += wi * ((hardware_filter ? std::ldexp(a.tile().max_step(i), -8) : 0.0) +
                   std::ldexp(a.tile().max_abs(i), -20));
      }
    return t + 2 * a.float_budget();
  }
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_ANISOTROPIC_PROGRAM_HPP
