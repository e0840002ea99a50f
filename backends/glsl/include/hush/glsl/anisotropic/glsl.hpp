// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL functions of anisotropic noise (include/hush/anisotropic.hpp): its uniforms, the
// per-sample SSBO they read and the per-scale sums. They read the runner's per-sample SSBO,
// so they are the runner's (hush/glsl/anisotropic/program.hpp states their contract), not the
// #version 330 library's (library.hpp).
#ifndef HUSH_GLSL_ANISOTROPIC_GLSL_HPP
#define HUSH_GLSL_ANISOTROPIC_GLSL_HPP

namespace hush {
namespace glsl {
namespace detail {

// The anisotropic noise's GLSL functions, uniforms and per-sample SSBO (runner only).
constexpr const char* kAnisotropicBody = R"glsl(
// ---- Anisotropic noise (include/hush/anisotropic.hpp, hush/glsl/anisotropic/glsl.hpp).
layout(binding = 0) uniform sampler2D hush_tile0;  // channels 0-3 of the subband tiles
layout(binding = 1) uniform sampler2D hush_tile1;  // channels 4-7 (K > 4)
uniform uint hush_aniso_k;                // orientations K
uniform uint hush_aniso_kc;               // channels: 4 or 8
uniform uint hush_aniso_base;             // scale of octave 0
uniform uint hush_aniso_octaves;
uniform uint hush_aniso_turbulence;       // 1u: sum gain^k |n_k|, 0u: fbm
uniform uint hush_aniso_three_filter;     // 1u: three-point lambda, 0u: centre
uniform uint hush_aniso_three_map;        // 1u: three-point gamma, 0u: centre
uniform float hush_aniso_tile_size;       // N
uniform uint hush_aniso_given;            // 1u: per-sample weights given (least squares)
uniform uint hush_aniso_stride;           // floats of per-sample data per sample
uniform float hush_aniso_kappa[HUSH_ANISO_MAX_SCALES];        // 2 pi^2 sigma^2 f_s^2 log2 e
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
float hush_aniso_weight(uint i, uint s, int k0, int k1, float q, bool has_map, float half_log,
                        float sd) {
  if (i >= hush_aniso_k) return 0.0;
  float lam = hush_aniso_lambda(hush_aniso_kappa[s] * q);
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
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_ANISOTROPIC_GLSL_HPP
