// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Anisotropic noise (include/hush/anisotropic.hpp; Goldberg, Zwicker & Durand 2008) inside the
// user's own shader (hush/glsl/shader.hpp): shader_for(noise) returns the GLSL functions and
// the resources they read, so a fragment shader evaluates the filtered, distortion-compensated
// noise per pixel from what it has: the texture position uv, its screen derivatives
// dFdx(uv), dFdy(uv) (or a given 2 x 2 Jacobian) and, for distortion compensation, the
// surface map. Everything per pixel happens in the shader:
//  - lambda_{i,s} (sec. 4, the pixel filter's weight of subband i at scale s): the centre or
//    three-point heuristic, 2^-(kappa_s q_i) with q_i = |J^T d_i|^2 formed from the Jacobian's
//    columns (a sum of squares: no cancelling quadratic form),
//  - gamma_{k,i,s} (sec. 3.1, octave k's target moved to texture space): from |T^T d_i|^2 and
//    sqrt|det T| of the map T, capped as the CPU caps it,
//  - the weights w_{i,s} = sum_k octave_weight_k gamma_{k,i,s} lambda_{i,s}, the bilinear
//    lookups of the subband tiles (texelFetch and the CPU's own blend) and the sums (fbm:
//    one; turbulence: one per octave, gain^k |n_k|), in the CPU's order.
// Only the heuristic rules (weight_rule::centre, three_point) run in a shader: least-squares
// weights are per-sample fits on the CPU (shader_for throws for them; hush::evaluate with
// exec::glsl{device} uploads the CPU's fits instead).
//
// Resources (one instance per shader program; #define a binding macro before the source to
// move a resource):
//   hush_anisotropic_params  std140 uniform block, binding HUSH_ANISOTROPIC_PARAMS_BINDING (0)
//   hush_anisotropic_tile0   sampler2D, RGBA32F N x N, unit HUSH_ANISOTROPIC_TILE0_BINDING (1):
//                            texel (x, y) = orientations 0-3 of the subband tiles
//                            (anisotropic_tile::rgba(0), the same call that fills the batch
//                            runner's hush_tile0)
//   hush_anisotropic_tile1   sampler2D, unit HUSH_ANISOTROPIC_TILE1_BINDING (2): orientations
//                            4-7 (K > 4, anisotropic_tile::rgba(1)); K <= 4: one texel of
//                            zeros (the source reads it only for K > 4)
// The source carries the generated constants (generator.hpp) under the guard
// HUSH_GLSL_CONSTANTS, so that kits share one copy; a shader that also pastes
// hush::glsl::library() (its own copy, unguarded) defines HUSH_GLSL_CONSTANTS before the kit.
// Both tiles are read with texelFetch, so their filtering does not matter (GL_NEAREST: RGBA32F
// is not filterable in GLSL ES 3.00) and the kit compiles for GL 4.30 core, Vulkan 450 and
// GLSL ES 3.00 (no SSBO, ldexp or frexp: powers of two and the exponent split by bits).
//
// Error bound (tests/anisotropic/glsl_anisotropic_shader_test.cpp): against the CPU's float
// sample(uv, footprint::from_derivatives(dFdx(uv), dFdy(uv))[, T]) at the same float inputs,
// |gpu - cpu| <= anisotropic_shader_tolerance(noise, uv, dx, dy[, T]), which is the batch
// runner's per-sample bound (hush/glsl/anisotropic/program.hpp, without its 2^-8 term: the
// blend is the CPU's) plus what the shader's own float inputs add:
//  - q_i: the shader forms |J^T d_i|^2 in float, the CPU d_i^T S d_i in double from S
//    rounded to float; both lie within 2^-20 Q_i of the exact value, Q_i = (|d_ix J_00| +
//    |d_iy J_10|)^2 + (|d_ix J_01| + |d_iy J_11|)^2 (the GPU: 3 roundings in each dot
//    product and 2 in the squares, 8.1 u Q_i; the CPU: u Q_i for S's rounding, u = 2^-24).
//    Grazing footprints (J nearly rank 1) make Q_i large against q_i: the weights then
//    differ by ln 2 kappa_s 2^-20 Q_i relative, as the CPU's own rounding of S does.
//  - the map's terms in float (|T^T d_i|^2: 3 roundings per component; det T: 3), which the
//    bound carries as intervals through log2, the band profile (slope <= pi / 2) and sqrt.
//  - the band coordinate uv f_s / band + offset in float: 2^-23 (|uv| tpu_s + N) texels
//    (tpu_s = anisotropic::texels_per_unit(s)), times the tile's largest texel step.
// The coordinate term makes the bound grow with |uv|: for |uv| tpu_s <= 2^12 texels it adds
// at most 2^-11 texel steps; beyond 2^24 texels the fraction is lost (use the batch path,
// whose split is exact in double). NaN or +-Inf in uv gives NaN; a non-finite derivative
// filters everything (0, the mean); a map with a non-finite entry is the zero map (0).
#ifndef HUSH_GLSL_ANISOTROPIC_SHADER_HPP
#define HUSH_GLSL_ANISOTROPIC_SHADER_HPP

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "hush/anisotropic.hpp"
#include "hush/core/error.hpp"
#include "hush/glsl/anisotropic/program.hpp"
#include "hush/glsl/generator.hpp"
#include "hush/glsl/library.hpp"
#include "hush/glsl/shader.hpp"

namespace hush {
namespace glsl {
namespace detail {

constexpr unsigned kAnisotropicParamsBinding = 0;
constexpr unsigned kAnisotropicTile0Binding = 1;
constexpr unsigned kAnisotropicTile1Binding = 2;

// The kit's functions (after the block and sampler declarations). Every number is a generated
// constant (generator.hpp) or a block member; literals are structural (0, 1, 2, halves).
constexpr const char* kAnisotropicShaderBody = R"glsl(
// 2^n for n in [-126, 127]: the exponent field by bits (GLSL ES 3.00 has no ldexp).
float hush_anisotropic_pow2(int n) {
  return uintBitsToFloat(uint(n + int(HUSH_FLOAT_EXP_BIAS)) << HUSH_FLOAT_MANTISSA_BITS);
}
bool hush_anisotropic_nonfinite(float x) {
  return (floatBitsToUint(x) & HUSH_FLOAT_EXP_MASK) == HUSH_FLOAT_EXP_MASK;
}
// 2^y for y <= 0, 0 below -126 (approx_math.hpp exp2_nonpositive, the same polynomial).
float hush_anisotropic_exp2(float y) {
  if (!(y >= -float(HUSH_FLOAT_EXP_BIAS - 1u))) return 0.0;
  float n = floor(y + 1.0 / 2.0);
  float r = y - n;
  float p = HUSH_ANISO_EXP2[HUSH_ANISO_EXP2.length() - 1];
  for (int m = HUSH_ANISO_EXP2.length() - 2; m >= 0; --m) p = p * r + HUSH_ANISO_EXP2[m];
  return p * hush_anisotropic_pow2(int(n));
}
// log2 m for m >= 0 (approx_math.hpp log2_positive): -inf below the smallest normal float.
float hush_anisotropic_log2(float m) {
  if (!(m >= HUSH_FLOAT_MIN_NORMAL)) return -uintBitsToFloat(HUSH_FLOAT_EXP_MASK);
  if (hush_anisotropic_nonfinite(m)) return m;
  uint b = floatBitsToUint(m);
  int e = int(b >> HUSH_FLOAT_MANTISSA_BITS) - int(HUSH_FLOAT_EXP_BIAS);
  float a = uintBitsToFloat((b & HUSH_FLOAT_MANTISSA_MASK) |
                            (HUSH_FLOAT_EXP_BIAS << HUSH_FLOAT_MANTISSA_BITS));  // [1, 2)
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
float hush_anisotropic_profile(float x) {
  float ax = abs(x);
  if (!(ax < 1.0)) return 0.0;
  float z = ax - 1.0 / 2.0;
  float z2 = z * z;
  float p = HUSH_ANISO_SINPI[HUSH_ANISO_SINPI.length() - 1];
  for (int j = HUSH_ANISO_SINPI.length() - 2; j >= 0; --j) p = p * z2 + HUSH_ANISO_SINPI[j];
  return 1.0 / 2.0 - (p * z) / 2.0;
}
// lambda = 2^-z, 0 beyond the cutoff; the three-point rule 1/4, 1/2, 1/4 at z/2, z, 2z.
float hush_anisotropic_lambda1(float z) {
  return z > hush_anisotropic_p.consts.z ? 0.0 : hush_anisotropic_exp2(-z);
}
float hush_anisotropic_lambda(float z) {
  if (hush_anisotropic_p.mode.z == 0u) return hush_anisotropic_lambda1(z);
  return (HUSH_ANISO_SIDE * hush_anisotropic_lambda1(z / 2.0) +
          HUSH_ANISO_CENTRE * hush_anisotropic_lambda1(z)) +
         HUSH_ANISO_SIDE * hush_anisotropic_lambda1(z * 2.0);
}
float hush_anisotropic_band(float x) {
  if (hush_anisotropic_p.mode.w == 0u) return hush_anisotropic_profile(x);
  return (HUSH_ANISO_SIDE * hush_anisotropic_profile(x - HUSH_ANISO_OFFSET) +
          HUSH_ANISO_CENTRE * hush_anisotropic_profile(x)) +
         HUSH_ANISO_SIDE * hush_anisotropic_profile(x + HUSH_ANISO_OFFSET);
}
// Channel i's weight at scale s for octaves [k0, k1) (anisotropic.hpp combine): lam times
// the identity's octave weight, or the sum over octaves of the capped gamma.
float hush_anisotropic_weight(uint i, int s, int k0, int k1, float lam, bool has_map,
                              float half_log, float sd) {
  if (i >= hush_anisotropic_p.shape.x) return 0.0;
  bool fbm = hush_anisotropic_p.mode.y == 0u;
  int rel = s - int(hush_anisotropic_p.shape.w);
  if (!has_map) {
    if (rel < k0 || rel >= k1) return 0.0;
    return (fbm ? hush_anisotropic_p.octave[rel].x : hush_anisotropic_p.consts.w) * lam;
  }
  float acc = 0.0;
  for (int k = k0; k < k1; ++k) {
    float prof = hush_anisotropic_band(float(rel - k) + half_log);
    float g = prof > 0.0
                  ? min(hush_anisotropic_pow2(rel - k) * (sd * prof), hush_anisotropic_p.consts.y)
                  : 0.0;
    acc = acc + (fbm ? hush_anisotropic_p.octave[k].x : hush_anisotropic_p.consts.w) * g;
  }
  return acc * lam;
}
float hush_anisotropic_channel_sum(vec4 a, vec4 b) {
  float s4 = (a.x + a.y) + (a.z + a.w);
  return hush_anisotropic_p.shape.y == 4u ? s4 : s4 + ((b.x + b.y) + (b.z + b.w));
}
// The noise at uv for the Jacobian columns dx = d(uv)/dx, dy = d(uv)/dy and, when has_map,
// the surface map t (hush::surface_map T: t[0] = (m00, m10), t[1] = (m01, m11)).
float hush_anisotropic_eval(vec2 uv, vec2 dx, vec2 dy, bool has_map, mat2 t) {
  if (hush_anisotropic_nonfinite(uv.x) || hush_anisotropic_nonfinite(uv.y))
    return uintBitsToFloat(HUSH_FLOAT_QNAN);
  uint kk = hush_anisotropic_p.shape.x;
  int scales = int(hush_anisotropic_p.shape.z);
  // A non-finite derivative filters everything (footprint.hpp): q = +inf, every lambda 0.
  bool everything = hush_anisotropic_nonfinite(dx.x) || hush_anisotropic_nonfinite(dx.y) ||
                    hush_anisotropic_nonfinite(dy.x) || hush_anisotropic_nonfinite(dy.y);
  // The map: a non-finite entry gives the zero map (surface_map::finite).
  bool finite_map = !(hush_anisotropic_nonfinite(t[0].x) || hush_anisotropic_nonfinite(t[0].y) ||
                      hush_anisotropic_nonfinite(t[1].x) || hush_anisotropic_nonfinite(t[1].y));
  mat2 m = finite_map ? t : mat2(0.0);
  float sd = has_map ? sqrt(abs(m[0].x * m[1].y - m[1].x * m[0].y)) : 0.0;
  float q[HUSH_ANISO_MAX_ORIENTATIONS];
  float half_log[HUSH_ANISO_MAX_ORIENTATIONS];
  for (uint i = 0u; i < HUSH_ANISO_MAX_ORIENTATIONS; ++i) {
    q[i] = 0.0;
    half_log[i] = 0.0;
    if (i >= kk) continue;
    vec2 d = hush_anisotropic_p.direction[i].xy;
    // q_i = |J^T d_i|^2 = (d_i . dx)^2 + (d_i . dy)^2: sums of squares.
    float a = d.x * dx.x + d.y * dx.y, c = d.x * dy.x + d.y * dy.y;
    q[i] = everything ? uintBitsToFloat(HUSH_FLOAT_EXP_MASK) : a * a + c * c;
    // |T^T d_i|^2 = (m00 d_x + m10 d_y)^2 + (m01 d_x + m11 d_y)^2.
    float tu = m[0].x * d.x + m[0].y * d.y, tv = m[1].x * d.x + m[1].y * d.y;
    if (has_map) half_log[i] = hush_anisotropic_log2(tu * tu + tv * tv) / 2.0;
  }
  bool turbulence = hush_anisotropic_p.mode.y != 0u;
  int passes = turbulence ? int(hush_anisotropic_p.mode.x) : 1;
  vec4 acc0[HUSH_ANISO_MAX_SCALES], acc1[HUSH_ANISO_MAX_SCALES];
  for (int p = 0; p < passes; ++p) {
    acc0[p] = vec4(0.0);
    acc1[p] = vec4(0.0);
  }
  float n = hush_anisotropic_p.consts.x;
  for (int s = 0; s < scales; ++s) {
    vec4 sc = hush_anisotropic_p.scale[s];  // kappa_s, texels per unit, offset
    float lam[HUSH_ANISO_MAX_ORIENTATIONS];
    for (uint i = 0u; i < HUSH_ANISO_MAX_ORIENTATIONS; ++i)
      lam[i] = i < kk ? hush_anisotropic_lambda(sc.x * q[i]) : 0.0;
    vec4 w0[HUSH_ANISO_MAX_SCALES], w1[HUSH_ANISO_MAX_SCALES];
    bool used = false;
    for (int p = 0; p < passes; ++p) {
      int k0 = turbulence ? p : 0;
      int k1 = turbulence ? p + 1 : int(hush_anisotropic_p.mode.x);
      float w[HUSH_ANISO_MAX_ORIENTATIONS];
      for (uint i = 0u; i < HUSH_ANISO_MAX_ORIENTATIONS; ++i)
        w[i] = hush_anisotropic_weight(i, s, k0, k1, lam[i], has_map,
                                       half_log[i], sd);
      w0[p] = vec4(w[0], w[1], w[2], w[3]);
      w1[p] = vec4(w[4], w[5], w[6], w[7]);
      used = used || any(notEqual(w0[p], vec4(0.0))) || any(notEqual(w1[p], vec4(0.0)));
    }
    if (!used) continue;
    // The band coordinate uv f_s / band + offset, split into cell (mod N, exact) and fraction.
    vec2 x = uv * sc.y + sc.zw;
    vec2 fl = floor(x);
    vec2 f = min(x - fl, vec2(HUSH_ONE_MINUS_ULP));
    vec2 cell = fl - n * floor(fl / n);
    ivec2 i0 = ivec2(cell);
    ivec2 i1 = ivec2(mix(cell + 1.0, vec2(0.0), equal(cell + 1.0, vec2(n))));
    // The CPU's bilinear blend (anisotropic.hpp accumulate), per texture.
    for (uint tex = 0u; tex < hush_anisotropic_p.shape.y / 4u; ++tex) {
      vec4 c00 = tex == 0u ? texelFetch(hush_anisotropic_tile0, i0, 0)
                           : texelFetch(hush_anisotropic_tile1, i0, 0);
      vec4 c10 = tex == 0u ? texelFetch(hush_anisotropic_tile0, ivec2(i1.x, i0.y), 0)
                           : texelFetch(hush_anisotropic_tile1, ivec2(i1.x, i0.y), 0);
      vec4 c01 = tex == 0u ? texelFetch(hush_anisotropic_tile0, ivec2(i0.x, i1.y), 0)
                           : texelFetch(hush_anisotropic_tile1, ivec2(i0.x, i1.y), 0);
      vec4 c11 = tex == 0u ? texelFetch(hush_anisotropic_tile0, i1, 0)
                           : texelFetch(hush_anisotropic_tile1, i1, 0);
      vec4 r0 = c00 + f.y * (c01 - c00), r1 = c10 + f.y * (c11 - c10);
      vec4 v = r0 + f.x * (r1 - r0);
      for (int p = 0; p < passes; ++p) {
        if (tex == 0u)
          acc0[p] = acc0[p] + w0[p] * v;
        else
          acc1[p] = acc1[p] + w1[p] * v;
      }
    }
  }
  if (!turbulence) return hush_anisotropic_channel_sum(acc0[0], acc1[0]);
  float r = 0.0;
  for (int p = 0; p < passes; ++p)
    r = r + hush_anisotropic_p.octave[p].y * abs(hush_anisotropic_channel_sum(acc0[p], acc1[p]));
  return r;
}

// ---- The functions a shader calls.
// Filtered noise at uv for the pixel's Jacobian: duv_dx = dFdx(uv), duv_dy = dFdy(uv).
float hush_anisotropic(vec2 uv, vec2 duv_dx, vec2 duv_dy) {
  return hush_anisotropic_eval(uv, duv_dx, duv_dy, false, mat2(1.0));
}
// The same for a given Jacobian: columns d(uv)/dx and d(uv)/dy.
float hush_anisotropic(vec2 uv, mat2 jacobian) {
  return hush_anisotropic_eval(uv, jacobian[0], jacobian[1], false, mat2(1.0));
}
// With distortion compensation for the surface-to-texture map T (hush::surface_map, local
// orthonormal surface coordinates (s, t) to (u, v)): columns (m00, m10) and (m01, m11).
float hush_anisotropic_mapped(vec2 uv, vec2 duv_dx, vec2 duv_dy, mat2 surface_to_texture) {
  return hush_anisotropic_eval(uv, duv_dx, duv_dy, true, surface_to_texture);
}
// The surface-to-texture map of the texture-to-surface tangents dp_du = dP/du, dp_dv = dP/dv
// (any 3D space with the surface's length unit; a 2D map: z = 0): T = [a1 a2]^-1 with a1, a2
// the tangents in the frame e1 = dp_du / |dp_du|, e2 = n x e1 (surface_map::from_triangle of
// the triangle 0, dp_du, dp_dv with uvs (0, 0), (1, 0), (0, 1)). Parallel or zero tangents
// give the zero map (the noise is then 0, the mean).
mat2 hush_anisotropic_surface_map(vec3 dp_du, vec3 dp_dv) {
  float l1 = length(dp_du);
  vec3 nrm = cross(dp_du, dp_dv);
  float ln = length(nrm);
  if (!(l1 > 0.0 && ln > 0.0) || hush_anisotropic_nonfinite(l1) ||
      hush_anisotropic_nonfinite(ln))
    return mat2(0.0);
  vec3 ex = dp_du / l1;
  vec3 ey = cross(nrm, dp_du) / (ln * l1);
  float a2x = dot(dp_dv, ex), a2y = dot(dp_dv, ey);
  float i00 = 1.0 / l1, i01 = -a2x / (l1 * a2y), i11 = 1.0 / a2y;
  return mat2(i00, 0.0, i01, i11);  // T = [i00 i01; 0 i11], column-major
}
float hush_anisotropic_surface(vec2 uv, vec2 duv_dx, vec2 duv_dy, vec3 dp_du, vec3 dp_dv) {
  return hush_anisotropic_eval(uv, duv_dx, duv_dy, true,
                               hush_anisotropic_surface_map(dp_du, dp_dv));
}
)glsl";

// The params block's declaration (its members in the order anisotropic_params_words writes).
inline std::string anisotropic_block_declaration() {
  return "uniform hush_anisotropic_params {\n"
         "  uvec4 shape;   // orientations K, channels (4 or 8), scales, base_scale\n"
         "  uvec4 mode;    // octaves, turbulence (1u) or fbm (0u), three-point lambda (1u),\n"
         "                 // three-point gamma (1u)\n"
         "  vec4 consts;   // tile size N, gamma cap, lambda cutoff (in powers of two),\n"
         "                 // 1 / sqrt(sum gain^2k)\n"
         "  vec4 direction[HUSH_ANISO_MAX_ORIENTATIONS];  // d_i = (cos, sin)(pi i / K) in .xy\n"
         "  vec4 scale[HUSH_ANISO_MAX_SCALES];   // kappa_s, texels per unit, offset (x, y)\n"
         "  vec4 octave[HUSH_ANISO_MAX_SCALES];  // octave weight (norm gain^k), gain^k\n"
         "} hush_anisotropic_p;\n";
}

}  // namespace detail

// The std140 words of the kit's params block for `noise` (member order as declared above).
inline std::vector<std::uint32_t> anisotropic_params_words(const anisotropic& noise) {
  namespace c = hush::detail::constants;
  const auto& p = noise.parameters();
  std140_writer w;
  w.uvec4(static_cast<std::uint32_t>(p.orientations), static_cast<std::uint32_t>(noise.channels()),
          static_cast<std::uint32_t>(p.scales), static_cast<std::uint32_t>(p.base_scale));
  w.uvec4(static_cast<std::uint32_t>(p.octaves), p.kind == fractal_kind::turbulence ? 1u : 0u,
          p.filtering == weight_rule::three_point ? 1u : 0u,
          p.compensation == weight_rule::three_point ? 1u : 0u);
  w.vec4(static_cast<float>(p.tile_size), static_cast<float>(noise.gamma_cap()),
         static_cast<float>(c::kAnisoWeightCutoff * c::kLog2E),
         static_cast<float>(noise.normalization()));
  for (int i = 0; i < c::kAnisoMaxOrientations; ++i) {
    const dvec2 d = i < p.orientations ? noise.direction(i) : dvec2{0, 0};
    w.vec4(static_cast<float>(d.x), static_cast<float>(d.y), 0.0f, 0.0f);
  }
  for (int s = 0; s < c::kAnisoMaxScales; ++s) {
    if (s < p.scales)
      w.vec4(static_cast<float>(noise.kappa(s)), static_cast<float>(noise.texels_per_unit(s)),
             static_cast<float>(noise.offset(s).x), static_cast<float>(noise.offset(s).y));
    else
      w.vec4(0.0f, 0.0f, 0.0f, 0.0f);
  }
  double g = 1.0;
  for (int k = 0; k < c::kAnisoMaxScales; ++k) {
    if (k < p.octaves)
      w.vec4(static_cast<float>(noise.octave_weight(k)), static_cast<float>(g), 0.0f, 0.0f);
    else
      w.vec4(0.0f, 0.0f, 0.0f, 0.0f);
    if (k < p.octaves) g *= p.gain;
  }
  return w.words();
}

// The kit: the functions above with their declarations, and the block and the two tiles.
// Throws hush::invalid_argument for least-squares rules (per-sample fits, CPU only).
inline shader_kit shader_for(const anisotropic& noise) {
  const auto& p = noise.parameters();
  if (p.filtering == weight_rule::least_squares || p.compensation == weight_rule::least_squares)
    hush::detail::raise_error(
        "hush::glsl::shader_for(anisotropic): least-squares rules fit per sample on the CPU; "
        "use weight_rule::centre or three_point in a shader");
  const unsigned n = static_cast<unsigned>(p.tile_size);
  shader_kit kit;
  shader_resource block;
  block.name = "hush_anisotropic_params";
  block.kind = resource_kind::uniform_block;
  block.binding = detail::kAnisotropicParamsBinding;
  block.binding_macro = "HUSH_ANISOTROPIC_PARAMS_BINDING";
  block.layout =
      "std140: uvec4 shape (K, channels, scales, base_scale) @0; uvec4 mode (octaves, "
      "turbulence, three-point lambda, three-point gamma) @16; vec4 consts (N, gamma cap, "
      "lambda cutoff, 1 / sqrt(sum gain^2k)) @32; vec4 direction[8] @48; vec4 scale[12] "
      "(kappa, texels per unit, offset x, y) @176; vec4 octave[12] (weight, gain^k) @368";
  block.words = anisotropic_params_words(noise);
  kit.resources.push_back(block);
  for (int t = 0; t < 2; ++t) {
    shader_resource tex;
    tex.name = t == 0 ? "hush_anisotropic_tile0" : "hush_anisotropic_tile1";
    tex.kind = resource_kind::texture_2d;
    tex.binding = t == 0 ? detail::kAnisotropicTile0Binding : detail::kAnisotropicTile1Binding;
    tex.binding_macro =
        t == 0 ? "HUSH_ANISOTROPIC_TILE0_BINDING" : "HUSH_ANISOTROPIC_TILE1_BINDING";
    tex.format = texel_format::rgba32f;
    tex.linear = false;
    tex.repeat = true;
    if (t == 1 && noise.channels() == 4) {
      tex.width = tex.height = 1;
      tex.words.assign(4, 0u);
      tex.layout = "RGBA32F 1 x 1 of zeros (K <= 4: not read)";
    } else {
      tex.width = tex.height = n;
      // The same call that fills the batch runner's tile textures (program.hpp textures()).
      const std::vector<float> texels = noise.tile().rgba(t);
      tex.words.reserve(texels.size());
      for (float v : texels) tex.words.push_back(float_word(v));
      tex.layout = "RGBA32F N x N, texel (x, y) = orientations " +
                   std::string(t == 0 ? "0-3" : "4-7") +
                   " of the subband tiles (anisotropic_tile::rgba), read with texelFetch";
    }
    kit.resources.push_back(tex);
  }
  std::string src = kShaderPrelude;
  src += "#ifndef HUSH_ANISOTROPIC_KIT\n#define HUSH_ANISOTROPIC_KIT\n";
  // The generated constants, once per shader whichever kits it holds.
  src += detail::constants_once();
  src += resource_layout("HUSH_ANISOTROPIC_PARAMS_BINDING", detail::kAnisotropicParamsBinding,
                         "std140") +
         detail::anisotropic_block_declaration();
  src += resource_layout("HUSH_ANISOTROPIC_TILE0_BINDING", detail::kAnisotropicTile0Binding, "") +
         "uniform highp sampler2D hush_anisotropic_tile0;\n";
  src += resource_layout("HUSH_ANISOTROPIC_TILE1_BINDING", detail::kAnisotropicTile1Binding, "") +
         "uniform highp sampler2D hush_anisotropic_tile1;\n";
  src += detail::kAnisotropicShaderBody;
  src += "#endif  // HUSH_ANISOTROPIC_KIT\n";
  kit.source = std::move(src);
  kit.versions = "430 core, Vulkan 450, 300 es";
  kit.usage =
      "// hush anisotropic noise in your shader (hush/glsl/anisotropic/shader.hpp).\n"
      "//   float hush_anisotropic(vec2 uv, vec2 duv_dx, vec2 duv_dy)   dFdx(uv), dFdy(uv)\n"
      "//   float hush_anisotropic(vec2 uv, mat2 jacobian)              columns duv/dx, duv/dy\n"
      "//   float hush_anisotropic_mapped(vec2 uv, vec2 duv_dx, vec2 duv_dy, mat2 T)\n"
      "//         T = hush::surface_map (surface to texture), columns (m00, m10), (m01, m11)\n"
      "//   float hush_anisotropic_surface(vec2 uv, vec2 duv_dx, vec2 duv_dy,\n"
      "//                                  vec3 dp_du, vec3 dp_dv)   texture-to-surface tangents\n"
      "//   mat2  hush_anisotropic_surface_map(vec3 dp_du, vec3 dp_dv)  their T\n"
      "// Equal to the CPU's float sample(uv, footprint::from_derivatives(duv_dx, duv_dy)[, T])\n"
      "// within hush::glsl::anisotropic_shader_tolerance (the batch runner's bound plus the\n"
      "// shader's float q_i = |J^T d_i|^2, map terms and band coordinate, 2^-23 (|uv| tpu_s + N)\n"
      "// texels: keep |uv| tpu_s <= 2^12). NaN uv gives NaN. One instance per program.\n";
  return kit;
}

// The files `hush glsl-export` writes: the kit source of the noise type (its text does not
// depend on the parameters) and its usage.
inline std::vector<std::pair<std::string, std::string>> anisotropic_shader_exports() {
  const shader_kit kit = shader_for(anisotropic{});
  return {{"hush_anisotropic_shader.glsl", kit.usage + kit.source}};
}

// The bound on |shader - CPU float sample| at one input (see the file comment): uv, the
// Jacobian columns dx, dy (floats, as the shader gets them), the map T or nullptr, and
// map_entry_error, an absolute bound on the error of each entry of T as the shader holds it
// (0 for a T passed in; hush_anisotropic_surface_map's float T: see its test).
inline double anisotropic_shader_tolerance(const anisotropic& a, const vec2& uv, const vec2& dx,
                                           const vec2& dy, const surface_map* map,
                                           double map_entry_error = 0.0) {
  namespace c = hush::detail::constants;
  const auto& p = a.parameters();
  const int kk = p.orientations, b = p.base_scale;
  const double u = std::ldexp(1.0, -24);
  const bool finite_j =
      std::isfinite(dx.x) && std::isfinite(dx.y) && std::isfinite(dy.x) && std::isfinite(dy.y);
  const footprint<2> fp = footprint<2>::from_derivatives(dx, dy);
  const double cut = c::kAnisoWeightCutoff * c::kLog2E;
  // lambda(z) in double with the cutoff; monotone non-increasing in z.
  auto lambda = [&](double z) {
    auto l1 = [&](double y) { return y > cut ? 0.0 : std::exp2(-y); };
    if (p.filtering != weight_rule::three_point) return l1(z);
    return c::kAnisoThreePointSide * l1(z / 2) + c::kAnisoThreePointCentre * l1(z) +
           c::kAnisoThreePointSide * l1(2 * z);
  };
  // The band profile's range over [lo, hi] (unimodal, peak at 0; three-point: per term).
  auto prof1 = [](double x) {
    return std::fabs(x) < 1.0 ? std::cos(c::kPi * x / 2) * std::cos(c::kPi * x / 2) : 0.0;
  };
  auto prof_range = [&](double lo, double hi, double& mn, double& mx) {
    auto one = [&](double l, double h, double& n1, double& x1) {
      n1 = std::min(prof1(l), prof1(h));
      x1 = prof1(std::min(std::max(0.0, l), h));
      if (!(l > -1e300)) n1 = 0.0;  // an unbounded interval reaches the profile's zero
    };
    if (p.compensation != weight_rule::three_point) return one(lo, hi, mn, mx);
    const double o = c::kAnisoThreePointOffset;
    double n0, x0, n1, x1, n2, x2;
    one(lo - o, hi - o, n0, x0);
    one(lo, hi, n1, x1);
    one(lo + o, hi + o, n2, x2);
    mn = c::kAnisoThreePointSide * (n0 + n2) + c::kAnisoThreePointCentre * n1;
    mx = c::kAnisoThreePointSide * (x0 + x2) + c::kAnisoThreePointCentre * x1;
  };
  // The map's quantities in double (the CPU's) and their error bounds (the shader's float).
  double sd = 0, sd_err = 0;
  surface_map m = map && map->finite() ? *map : surface_map::zero();
  if (map) {
    const double det = m.determinant();
    const double det_err =
        3 * u * (std::fabs(double(m.m00) * m.m11) + std::fabs(double(m.m01) * m.m10)) +
        map_entry_error * (std::fabs(m.m00) + std::fabs(m.m01) + std::fabs(m.m10) +
                           std::fabs(m.m11) + 2 * map_entry_error);
    sd = std::sqrt(std::fabs(det));
    sd_err = std::min(std::sqrt(det_err), sd > 0 ? det_err / sd : 1e300) + 2 * u * sd;
  }
  const auto passes = p.kind == fractal_kind::turbulence ? p.octaves : 1;
  double tol = 0;
  for (int i = 0; i < kk; ++i) {
    const dvec2 d = a.direction(i);
    // q_i and its interval (file comment: 2^-20 Q_i for both sides).
    const double q = a.filter_form(fp, i);
    const double ca = std::fabs(d.x * dx.x) + std::fabs(d.y * dx.y);
    const double cc = std::fabs(d.x * dy.x) + std::fabs(d.y * dy.y);
    const double q_err = std::ldexp(ca * ca + cc * cc, -20);
    // The map's half log-stretch and its interval.
    double hl = 0, hl_err = 0;
    if (map) {
      const double tu = double(m.m00) * d.x + double(m.m10) * d.y;
      const double tv = double(m.m01) * d.x + double(m.m11) * d.y;
      const double e_tu = 3 * u * (std::fabs(m.m00 * d.x) + std::fabs(m.m10 * d.y)) +
                          map_entry_error * (std::fabs(d.x) + std::fabs(d.y));
      const double e_tv = 3 * u * (std::fabs(m.m01 * d.x) + std::fabs(m.m11 * d.y)) +
                          map_entry_error * (std::fabs(d.x) + std::fabs(d.y));
      const double r = tu * tu + tv * tv;
      const double r_err = 2 * std::fabs(tu) * e_tu + 2 * std::fabs(tv) * e_tv + e_tu * e_tu +
                           e_tv * e_tv + 3 * u * r;
      hl = r > 0 ? 0.5 * std::log2(r) : -1e301;
      hl_err = r - r_err > 0 ? 0.5 * std::log2(r / (r - r_err)) : 1e301;
    }
    for (int s = 0; s < p.scales; ++s) {
      const double kappa = a.kappa(s);
      double lam_lo = 0, lam_hi = 0, lam = 0;
      if (finite_j) {
        lam = lambda(kappa * q);
        lam_lo = lambda(kappa * (q + q_err));
        lam_hi = lambda(std::max(kappa * (q - q_err), 0.0));
        if (fp.is_point()) lam = lam_lo = lam_hi = 1.0;
      }
      for (int pass = 0; pass < passes; ++pass) {
        const int k0 = passes > 1 ? pass : 0, k1 = passes > 1 ? pass + 1 : p.octaves;
        const double g = passes > 1 ? std::pow(p.gain, pass) : 1.0;
        double acc = 0, acc_lo = 0, acc_hi = 0;
        for (int k = k0; k < k1; ++k) {
          const double ow = passes > 1 ? a.normalization() : a.octave_weight(k);
          if (!map) {
            if (s == b + k) acc = acc_lo = acc_hi = ow;
            continue;
          }
          const double x = (s - b - k) + hl;
          double pmn, pmx;
          prof_range(x - hl_err, x + hl_err, pmn, pmx);
          double pc, dummy;
          prof_range(x, x, pc, dummy);
          const double sc = std::ldexp(1.0, s - b - k), cap = a.gamma_cap();
          acc += ow * std::min(sc * sd * pc, cap);
          acc_lo += ow * std::min(sc * std::max(sd - sd_err, 0.0) * pmn, cap);
          acc_hi += ow * std::min(sc * (sd + sd_err) * pmx, cap);
        }
        const double w = acc * lam;
        const double dw = std::max(acc_hi * lam_hi - w, w - acc_lo * lam_lo);
        // Per subband: the weight's error, the float weights' relative error (program.hpp
        // kWeightError, both sides), the band coordinate's rounding.
        const double coord = std::ldexp(
            std::max(std::fabs(uv.x), std::fabs(uv.y)) * a.texels_per_unit(s) + p.tile_size, -23);
        tol += g * (a.tile().max_abs(i) *
                        (dw + 2 * std::fabs(w) * noise_program<anisotropic>::kWeightError) +
                    std::fabs(w) * 2 * coord * a.tile().max_step(i));
      }
    }
  }
  return tol + 2 * a.float_budget();
}

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_ANISOTROPIC_SHADER_HPP
