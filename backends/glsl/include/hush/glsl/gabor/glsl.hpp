// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL library bodies of Gabor-type noises (hush/glsl/gabor/program.hpp lists
// them and states their contract): detail/elementary.hpp's exp and sin/cos,
// hush::rng streams, gabor.hpp's word fields and gabor_kernel.hpp's taper,
// separable kernel (grids) and point form (points), operation by operation.
// Part of library(); references only generated constants (generator.hpp) and
// hashing/lattice functions.
#ifndef HUSH_GLSL_GABOR_GLSL_HPP
#define HUSH_GLSL_GABOR_GLSL_HPP

namespace hush {
namespace glsl {
namespace detail {

// detail/elementary.hpp and gabor_kernel.hpp, operation by operation.
constexpr const char* kGaborBody = R"glsl(
// ---- Elementary functions (detail/elementary.hpp): the CPU float algorithm.
float hush_exp_neg(float x) {
  // Below the floor (or -Inf): 0; NaN stays NaN (tested on the bits).
  if (!(x >= HUSH_EXP_FLOOR))
    return (floatBitsToUint(x) & ~HUSH_FLOAT_SIGN_MASK) > HUSH_FLOAT_EXP_MASK ? x : 0.0;
  x = x > 0.0 ? 0.0 : x;
  float n = floor(x * HUSH_LOG2E + 1.0 / float(2));
  float r = (x - n * HUSH_LN2_HI) - n * HUSH_LN2_LO;
  float p = HUSH_EXP_POLY[HUSH_EXP_DEGREE];
  for (uint i = HUSH_EXP_DEGREE; i > 0u; --i) p = p * r + HUSH_EXP_POLY[i - 1u];
  return p * uintBitsToFloat(uint(int(n) + int(HUSH_FLOAT_EXP_BIAS)) << HUSH_FLOAT_MANTISSA_BITS);
}
// (sin, cos)(2 pi t), t in turns.
vec2 hush_sincos_turns(float t) {
  float u = abs(t) < HUSH_TURNS_REDUCE_LIMIT ? t : t - floor(t);
  float q = floor(u * float(4) + 1.0 / float(2));
  float r = u - q * (1.0 / float(4));
  float z = r * r;
  float ps = HUSH_SIN_POLY[HUSH_SIN_DEGREE];
  for (uint i = HUSH_SIN_DEGREE; i > 0u; --i) ps = ps * z + HUSH_SIN_POLY[i - 1u];
  float pc = HUSH_COS_POLY[HUSH_COS_DEGREE];
  for (uint i = HUSH_COS_DEGREE; i > 0u; --i) pc = pc * z + HUSH_COS_POLY[i - 1u];
  float s = r * ps;
  float k = q - float(4) * floor(q * (1.0 / float(4)));
  bool odd = k == 1.0 || k == float(3);
  float sin_sign = k >= float(2) ? -1.0 : 1.0;
  float cos_sign = (k == 1.0 || k == float(2)) ? -1.0 : 1.0;
  return vec2((odd ? pc : s) * sin_sign, (odd ? s : pc) * cos_sign);
}

// ---- Gabor noise pieces (gabor.hpp, gabor_kernel.hpp).
// hush::rng(seed, stream): key hash32(seed, stream); word c = hash32(key ^ hash32(c)).
uint hush_stream_key(uint seed, uint stream) { return hush_hash32(seed, stream); }
uint hush_stream_word(uint key, uint counter) { return hush_hash32(key ^ hush_hash32(counter)); }
// Word fields as values in (0, 1), exact: byte i (0 = high), half i (0 = high).
float hush_gabor_byte(uint w, uint i) {
  uint m = (w >> (HUSH_GABOR_BYTE_BITS * (uint(3) - i))) & HUSH_GABOR_BYTE_MASK;
  return float((m << 1u) | 1u) * HUSH_GABOR_BYTE_SCALE;
}
float hush_gabor_half(uint w, uint i) {
  uint m = (w >> (HUSH_GABOR_HALF_BITS * (1u - i))) & HUSH_GABOR_HALF_MASK;
  return float((m << 1u) | 1u) * HUSH_GABOR_HALF_SCALE;
}
// The taper tau(s) = v^2 (3 - 2v), v = clamp((1 - s) k, 0, 1), and (tau, dtau/ds).
float hush_gabor_taper_v(float s, float k) {
  float v = (1.0 - s) * k;
  v = v < 1.0 ? v : 1.0;
  return v > 0.0 ? v : 0.0;
}
float hush_gabor_taper(float s, float k) {
  float v = hush_gabor_taper_v(s, k);
  return (v * v) * (float(3) - float(2) * v);
}
vec2 hush_gabor_taper_derivative(float s, float k) {
  float v = hush_gabor_taper_v(s, k);
  return vec2((v * v) * (float(3) - float(2) * v), (-float(6) * k) * (v * (1.0 - v)));
}
// One axis of the separable kernel: offset d, d^2, e^{-A d^2}, sin and cos(2 pi phi d).
struct hush_gabor_axis {
  float d, d2, e, s, c;
};
hush_gabor_axis hush_gabor_axis_factors(float d, float neg_a, float phi) {
  hush_gabor_axis f;
  f.d = d;
  f.d2 = d * d;
  f.e = hush_exp_neg(neg_a * f.d2);
  vec2 sc = hush_sincos_turns(phi * d);
  f.s = sc.x;
  f.c = sc.y;
  return f;
}
// The kernel along every axis but x: weight times envelope, cos, sin, d^2.
struct hush_gabor_row {
  float we, c, s, d2;
};
hush_gabor_row hush_gabor_row_of(float w, hush_gabor_axis y) {
  return hush_gabor_row(w * y.e, y.c, y.s, y.d2);
}
hush_gabor_row hush_gabor_row_of(float w, hush_gabor_axis y, hush_gabor_axis z) {
  return hush_gabor_row(w * (y.e * z.e), y.c * z.c - y.s * z.s, y.s * z.c + y.c * z.s, y.d2 + z.d2);
}
// gabor_pair: (e_x c_x (we c) - e_x s_x (we s)) tau(s), the CPU's products.
float hush_gabor_pair(hush_gabor_axis x, hush_gabor_row r, float k) {
  float ec = x.e * x.c, es = x.e * x.s, b = r.we * r.c, q = r.we * r.s;
  return (ec * b - es * q) * hush_gabor_taper(x.d2 + r.d2, k);
}
// gabor_gradient_of_harmonics: (value, u, v) of p cos(2 pi theta) tau(s) from pc = p cos
// and ps = p sin, d/dd_a = u d_a - v phi_a; both forms (pair, point term) end here.
vec3 hush_gabor_gradient_of_harmonics(float pc, float ps, float s, float k, float a) {
  vec2 tw = hush_gabor_taper_derivative(s, k);
  return vec3(pc * tw.x, (pc + pc) * (tw.y - a * tw.x), HUSH_TWO_PI * (ps * tw.x));
}
// (value, u, v) of the separable pair.
vec3 hush_gabor_pair_gradient(hush_gabor_axis x, hush_gabor_row r, float k, float a) {
  float ec = x.e * x.c, es = x.e * x.s, b = r.we * r.c, q = r.we * r.s;
  return hush_gabor_gradient_of_harmonics(ec * b - es * q, es * b + ec * q, x.d2 + r.d2, k, a);
}
// The point form (gabor_point_phase, gabor_point_term): theta = <phi, d> summed as
// phi_x d_x + phi_y d_y (3D: phi_x d_x + (phi_y d_y + phi_z d_z)), and one impulse's
// w e^{-A s} cos(2 pi theta) tau(s): one exp and one sin/cos instead of dim of each.
float hush_gabor_point_phase(vec3 phi, vec3 d, uint dim) {
  return dim == uint(2) ? phi.x * d.x + phi.y * d.y : phi.x * d.x + (phi.y * d.y + phi.z * d.z);
}
float hush_gabor_point_term(float w, float s, float theta, float neg_a, float k) {
  return ((w * hush_exp_neg(neg_a * s)) * hush_sincos_turns(theta).y) * hush_gabor_taper(s, k);
}
// (value, u, v) of the point term.
vec3 hush_gabor_point_term_gradient(float w, float s, float theta, float neg_a, float k, float a) {
  float p = w * hush_exp_neg(neg_a * s);
  vec2 sc = hush_sincos_turns(theta);
  return hush_gabor_gradient_of_harmonics(p * sc.y, p * sc.x, s, k, a);
}
// The key of cell `cell`'s solid stream: hush::rng(lattice_hash(key, cell), solid stream)
// (gabor<D>::for_each_impulse); dim = 2 ignores cell.z.
uint hush_gabor_cell_stream(uint key, uvec3 cell, uint dim) {
  uint seed = dim == uint(2) ? hush_lattice_hash(key, cell.x, cell.y)
                        : hush_lattice_hash(key, cell.x, cell.y, cell.z);
  return hush_stream_key(seed, HUSH_GABOR_SOLID_STREAM);
}
// gabor<3>::unit_normal in float: n scaled by its largest magnitude, then normalised;
// false for a zero normal (the solid noise). n must be finite. GLSL allows x / y within
// 2.5 ulp and sqrt within ~3 ulp (GLSL 4.30 sec. 4.7.1), so this and the basis below are
// within ~2^-21 relative of the CPU's double frame rounded to float (the tolerance of
// tests/gabor/glsl_gabor_test.cpp accounts for it).
bool hush_gabor_unit_normal(vec3 n, out vec3 u) {
  float big = max(abs(n.x), max(abs(n.y), abs(n.z)));
  u = vec3(0.0);
  if (!(big > 0.0)) return false;
  vec3 m = vec3(n.x / big, n.y / big, n.z / big);
  float len = sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
  u = vec3(m.x / len, m.y / len, m.z / len);
  return true;
}
// detail::orthonormal_basis (Duff et al., JCGT 2017) of unit n, in float; the sign of
// n.z taken from its sign bit (copysign: -0 counts as negative).
void hush_gabor_basis(vec3 n, out vec3 t, out vec3 b) {
  float sgn = (floatBitsToUint(n.z) & HUSH_FLOAT_SIGN_MASK) != 0u ? -1.0 : 1.0;
  float a = -1.0 / (sgn + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + sgn * n.x * n.x * a, sgn * c, -sgn * n.x);
  b = vec3(c, sgn + n.y * n.y * a, -n.y);
}
// The key of surface cell `cell`'s stream (gabor<3>::for_each_surface_impulse).
uint hush_gabor_surface_stream(uint key, uvec3 cell) {
  return hush_stream_key(hush_lattice_hash(key, cell.x, cell.y, cell.z), HUSH_GABOR_SURFACE_STREAM);
}
// Surface noise's offsets of d (surface cells) from the plane of unit normal n and
// tangents t, b: (zn along n, z2 = zn^2 / h^2, dk in the plane in kernel cells).
vec4 hush_gabor_plane_offsets(vec3 d, vec3 n, vec3 t, vec3 b) {
  float zn = (n.x * d.x + n.y * d.y) + n.z * d.z;
  return vec4(zn, (zn * zn) * HUSH_GABOR_SURFACE_INV_H2,
              ((t.x * d.x + t.y * d.y) + t.z * d.z) * HUSH_GABOR_SURFACE_CELL,
              ((b.x * d.x + b.y * d.y) + b.z * d.z) * HUSH_GABOR_SURFACE_CELL);
}
// gabor_filter (gabor_kernel.hpp) in float for a dim-D footprint fp (S, noise units; the
// upper-left dim x dim block is read), k = 2 A sigma^2 / r^2, mk = pi^2 / A:
// Q = V diag(1 / (1 + k l)) V^T, M = V diag(mk k l / (1 + k l)) V^T
// and amplitude = prod sqrt(q_i), with (V, l) the footprint's eigensystem by cyclic Jacobi.
// Returns the amplitude; q, m with element (i, j) at [j][i] (symmetric; in 2D the third
// row and column are 0).
float hush_gabor_filter(mat3 fp, uint dim, float k, float mk, out mat3 q, out mat3 m) {
  mat3 a, v;
  for (uint i = 0u; i < uint(3); ++i)
    for (uint j = 0u; j < uint(3); ++j) {
      a[j][i] = (i < dim && j < dim) ? fp[j][i] : 0.0;
      v[j][i] = i == j ? 1.0 : 0.0;
    }
  for (uint sweep = 0u; sweep < HUSH_GABOR_JACOBI_SWEEPS; ++sweep) {
    float off = 0.0, diag = 0.0;
    for (uint i = 0u; i < uint(3); ++i) {
      diag += a[i][i] * a[i][i];
      for (uint j = i + 1u; j < uint(3); ++j) off += a[j][i] * a[j][i];
    }
    if (!(off > HUSH_GABOR_JACOBI_TOLERANCE * diag)) break;
    for (uint p = 0u; p < uint(3); ++p)
      for (uint r = p + 1u; r < uint(3); ++r) {
        float apq = a[r][p];
        if (apq == 0.0) continue;
        float theta = (a[r][r] - a[p][p]) / (float(2) * apq);
        float t = (theta >= 0.0 ? 1.0 : -1.0) / (abs(theta) + sqrt(theta * theta + 1.0));
        if (hush_is_nonfinite(theta)) t = 0.0;
        float c = 1.0 / sqrt(t * t + 1.0), sn = t * c;
        for (uint x = 0u; x < uint(3); ++x) {  // columns p and r
          float axp = a[p][x], axq = a[r][x];
          a[p][x] = c * axp - sn * axq;
          a[r][x] = sn * axp + c * axq;
        }
        for (uint x = 0u; x < uint(3); ++x) {  // rows p and r
          float apx = a[x][p], aqx = a[x][r];
          a[x][p] = c * apx - sn * aqx;
          a[x][r] = sn * apx + c * aqx;
        }
        for (uint x = 0u; x < uint(3); ++x) {
          float vxp = v[p][x], vxq = v[r][x];
          v[p][x] = c * vxp - sn * vxq;
          v[r][x] = sn * vxp + c * vxq;
        }
      }
  }
  float qd[3], md[3], amp = 1.0;
  for (uint i = 0u; i < uint(3); ++i) {
    float kl = k * max(a[i][i], 0.0);
    if (!(kl == kl)) kl = 0.0;
    qd[i] = 1.0 / (1.0 + kl);
    md[i] = mk * (hush_is_nonfinite(kl) ? 1.0 : kl / (1.0 + kl));
    if (i < dim) amp *= sqrt(qd[i]);
  }
  for (uint i = 0u; i < uint(3); ++i)
    for (uint j = 0u; j < uint(3); ++j) {
      float qq = 0.0, mm = 0.0;
      for (uint e = 0u; e < dim; ++e) {
        qq += v[e][i] * qd[e] * v[e][j];
        mm += v[e][i] * md[e] * v[e][j];
      }
      q[j][i] = qq;
      m[j][i] = mm;
    }
  return amp;
}
)glsl";

}  // namespace detail

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_GABOR_GLSL_HPP
