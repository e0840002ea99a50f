// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The GLSL bodies of wavelet noise (include/hush/wavelet.hpp), part of hush's
// function library (hush/glsl/library.hpp). They port the CPU's float
// algorithm function by function: the B-spline kernels from the generated
// piece tables, the separable sums in the CPU's order (z innermost), the
// general projections, tile variants, the anti-aliasing fade, infinite noise
// and the distribution remapping.
//
// The tile is data, so these functions exist only where the including shader
// says how to read it, by defining before the library:
//   HUSH_WAVELET_TILE(i)    float, element i of wavelet_tile::coefficients() (rows of
//                           x, 3D rows padded: hush_wavelet_tile_coef), e.g.
//                           an SSBO element or texelFetch(samplerBuffer, int(i)).x;
//   HUSH_WAVELET_BLEND(i)   (optional) coefficient i of the tile-variant tile
//                           (wavelet_blend_tile); without it variants read 0;
//   HUSH_WAVELET_TABLE(i)  (optional) entry i of the distribution table (its size is an
//                           argument of hush_wavelet_output).
//   or HUSH_WAVELET_TILE_AT(c) in place of HUSH_WAVELET_TILE: the coefficient at
//                           ivec3 coordinates c, each in [0, n) (c.z = 0 in 2D);
// Without either the library holds no wavelet code at all, so it still compiles in any
// stage under #version 330 core. The bodies are guarded (HUSH_WAVELET_BODY): a shader may
// hold them twice (the library and wavelet_body() again, hush/glsl/wavelet/shader.hpp).
//
// A band is evaluated from its tap-0 cells (hush_wv_i0, modulo the tile size,
// or the global index modulo 2^32 with variants) and fractions, which the
// runner takes from the CPU's double-precision split (compute_source.hpp,
// banded layouts), so the GPU sees the CPU's cells and fractions bit for bit.
// Accuracy: hush/glsl/wavelet/program.hpp.
//
// Loop budget: llvmpipe ends every loop of a shader invocation once their
// iterations together reach 65535 (LP_MAX_TGSI_LOOP_ITERATIONS, "shared between
// every loop"), silently. The plain B-spline sums are therefore straight-line
// code (generated below), small loops have constant trip counts, and the widened
// exact projection along a general normal integrates over B2's pieces only (as
// the CPU does). Each coefficient read still enters the tile-variant loop once
// (kept a loop: unrolled into every inlined read, it made llvmpipe's JIT of the
// 3D sample runner take minutes, and Mesa 22.3's linker crash), so the exact
// projection along a general normal costs about 3000 iterations per band:
// llvmpipe evaluates up to 16 such bands correctly (asserted in
// tests/wavelet/glsl_wavelet_test.cpp; it truncates from about 21 on). Real GPUs
// have no such limit.
#ifndef HUSH_GLSL_WAVELET_GLSL_HPP
#define HUSH_GLSL_WAVELET_GLSL_HPP

#include <string>

namespace hush {
namespace glsl {
namespace detail {

constexpr const char* kWaveletBody = R"glsl(
#if (defined(HUSH_WAVELET_TILE) || defined(HUSH_WAVELET_TILE_AT)) && !defined(HUSH_WAVELET_BODY)
#define HUSH_WAVELET_BODY
// ---- Wavelet noise (Cook & DeRose 2005; include/hush/wavelet.hpp), the CPU's float algorithm.
// Kernel pieces, Horner from the highest power (core/bspline.hpp piece_value).
float hush_bspline_piece(int p, float t) {
  int o = p * int(HUSH_BSPLINE_ORDER);
  float r = HUSH_BSPLINE_PIECES[o + int(HUSH_BSPLINE_ORDER) - 1];
  for (int j = int(HUSH_BSPLINE_ORDER) - 2; j >= 0; --j) r = r * t + HUSH_BSPLINE_PIECES[o + j];
  return r;
}
float hush_dbspline_piece(int p, float t) {
  int o = p * (int(HUSH_BSPLINE_ORDER) - 1);
  float r = HUSH_BSPLINE_DPIECES[o + int(HUSH_BSPLINE_ORDER) - 2];
  for (int j = int(HUSH_BSPLINE_ORDER) - 2 - 1; j >= 0; --j) r = r * t + HUSH_BSPLINE_DPIECES[o + j];
  return r;
}
float hush_bspline2_piece(int p, float t) {
  int o = p * int(HUSH_BSPLINE_ORDER);
  float r = HUSH_BSPLINE2_PIECES[o + int(HUSH_BSPLINE_ORDER) - 1];
  for (int j = int(HUSH_BSPLINE_ORDER) - 2; j >= 0; --j) r = r * t + HUSH_BSPLINE2_PIECES[o + j];
  return r;
}
float hush_dbspline2_piece(int p, float t) {
  int o = p * (int(HUSH_BSPLINE_ORDER) - 1);
  float r = HUSH_BSPLINE2_DPIECES[o + int(HUSH_BSPLINE_ORDER) - 2];
  for (int j = int(HUSH_BSPLINE_ORDER) - 2 - 1; j >= 0; --j) r = r * t + HUSH_BSPLINE2_DPIECES[o + j];
  return r;
}
float hush_beta_piece(int p, float t) {
  int o = p * int(HUSH_BETA_ORDER);
  float r = HUSH_BETA_PIECES[o + int(HUSH_BETA_ORDER) - 1];
  for (int j = int(HUSH_BETA_ORDER) - 2; j >= 0; --j) r = r * t + HUSH_BETA_PIECES[o + j];
  return r;
}
float hush_dbeta_piece(int p, float t) {
  int o = p * (int(HUSH_BETA_ORDER) - 1);
  float r = HUSH_BETA_DPIECES[o + int(HUSH_BETA_ORDER) - 2];
  for (int j = int(HUSH_BETA_ORDER) - 2 - 1; j >= 0; --j) r = r * t + HUSH_BETA_DPIECES[o + j];
  return r;
}
// Kernels at distance d (0 outside the support; core/bspline.hpp kernel_at).
float hush_kernel_b(float d) {
  float u = d + HUSH_BSPLINE_HALF_SUPPORT;
  if (!(u > 0.0 && u < float(HUSH_BSPLINE_PIECE_COUNT))) return 0.0;
  int p = int(floor(u));
  return hush_bspline_piece(p, u - float(p));
}
float hush_kernel_db(float d) {
  float u = d + HUSH_BSPLINE_HALF_SUPPORT;
  if (!(u > 0.0 && u < float(HUSH_BSPLINE_PIECE_COUNT))) return 0.0;
  int p = int(floor(u));
  return hush_dbspline_piece(p, u - float(p));
}
float hush_kernel_b2(float d) {
  float u = d + HUSH_BSPLINE2_HALF_SUPPORT;
  if (!(u > 0.0 && u < float(HUSH_BSPLINE2_PIECE_COUNT))) return 0.0;
  int p = int(floor(u));
  return hush_bspline2_piece(p, u - float(p));
}
float hush_kernel_db2(float d) {
  float u = d + HUSH_BSPLINE2_HALF_SUPPORT;
  if (!(u > 0.0 && u < float(HUSH_BSPLINE2_PIECE_COUNT))) return 0.0;
  int p = int(floor(u));
  return hush_dbspline2_piece(p, u - float(p));
}
float hush_kernel_beta(float d) {
  float u = d + HUSH_BETA_HALF_SUPPORT;
  if (!(u > 0.0 && u < float(HUSH_BETA_PIECE_COUNT))) return 0.0;
  int p = int(floor(u));
  return hush_beta_piece(p, u - float(p));
}
float hush_kernel_dbeta(float d) {
  float u = d + HUSH_BETA_HALF_SUPPORT;
  if (!(u > 0.0 && u < float(HUSH_BETA_PIECE_COUNT))) return 0.0;
  int p = int(floor(u));
  return hush_dbeta_piece(p, u - float(p));
}

// One band's kernel along one axis: taps at cells i0 + first ... (wavelet.hpp wavelet_axis).
struct hush_wavelet_axis {
  int first;
  int count;
  float w[HUSH_WAVELET_MAX_TAPS];
  float dw[HUSH_WAVELET_MAX_TAPS];
};
hush_wavelet_axis hush_wavelet_axis_plain(float f) {
  hush_wavelet_axis ax;
  ax.first = 0;
  ax.count = int(HUSH_BSPLINE_PIECE_COUNT);
  for (int j = 0; j < int(HUSH_BSPLINE_PIECE_COUNT); ++j) {
    ax.w[j] = hush_bspline_piece(ax.count - 1 - j, f);
    ax.dw[j] = hush_dbspline_piece(ax.count - 1 - j, f);
  }
  return ax;
}
hush_wavelet_axis hush_wavelet_axis_unit() {  // the trivial z axis of 2D noise
  hush_wavelet_axis ax;
  ax.first = 0;
  ax.count = 1;
  ax.w[0] = 1.0;
  ax.dw[0] = 0.0;
  return ax;
}
hush_wavelet_axis hush_wavelet_axis_beta(float f) {
  hush_wavelet_axis ax;
  ax.first = int(HUSH_BETA_FIRST_TAP);
  ax.count = int(HUSH_BETA_TAPS);
  for (int j = 0; j < ax.count; ++j) {
    float d = f + HUSH_WAVELET_CELL_OFFSET - float(ax.first + j);
    ax.w[j] = hush_kernel_beta(d);
    ax.dw[j] = hush_kernel_dbeta(d);
  }
  return ax;
}
hush_wavelet_axis hush_wavelet_axis_b2(float f) {
  hush_wavelet_axis ax;
  ax.first = int(HUSH_BSPLINE2_FIRST_TAP);
  ax.count = int(HUSH_BSPLINE2_TAPS);
  for (int j = 0; j < ax.count; ++j) {
    float d = f + HUSH_WAVELET_CELL_OFFSET - float(ax.first + j);
    ax.w[j] = hush_kernel_b2(d);
    ax.dw[j] = hush_kernel_db2(d);
  }
  return ax;
}
// B widened by s >= 1 at relative position y, weights normalised to sum 1.
hush_wavelet_axis hush_wavelet_axis_widened(float y, float s) {
  hush_wavelet_axis ax;
  float reach = HUSH_BSPLINE_HALF_SUPPORT * s;
  ax.first = int(floor(y - reach)) + 1;
  ax.count = min(int(ceil(y + reach)) - ax.first, int(HUSH_WAVELET_MAX_TAPS));
  float inv = 1.0 / s;
  float sum = 0.0, dsum = 0.0;
  // Every slot is written (taps past count are outside the support: 0), so that no
  // write to the private array depends on the lane (llvmpipe mishandles that in
  // divergent code).
  for (int j = 0; j < int(HUSH_WAVELET_MAX_TAPS); ++j) {
    float u = (y - float(ax.first + j)) * inv;
    ax.w[j] = hush_kernel_b(u);
    sum += ax.w[j];
    ax.dw[j] = hush_kernel_db(u) * inv;
    dsum += ax.dw[j];
  }
  float norm = 1.0 / sum;
  for (int j = 0; j < int(HUSH_WAVELET_MAX_TAPS); ++j) {
    ax.dw[j] = (ax.dw[j] - ax.w[j] * norm * dsum) * norm;
    ax.w[j] *= norm;
  }
  return ax;
}
// The plain B-spline at any relative position y (taps floor(y - 1/2) ...).
hush_wavelet_axis hush_wavelet_axis_at(float y) {
  float c = floor(y - HUSH_WAVELET_CELL_OFFSET);
  hush_wavelet_axis ax = hush_wavelet_axis_plain(y - HUSH_WAVELET_CELL_OFFSET - c);
  ax.first = int(c);
  return ax;
}

// The band being evaluated: tile size, dimension, tap-0 cells, and for tile
// variants the cell pitch (0: the periodic tile) and the band's key.
uint hush_wv_n;
uint hush_wv_dim;
uvec3 hush_wv_i0;
int hush_wv_cell;
uint hush_wv_key;

int hush_wavelet_wrap(uint i0, int k) {
  int n = int(hush_wv_n), x = int(i0) + k;
  return x < 0 ? x + n : (x >= n ? x - n : x);
}
// Storage index of local coordinates under variant h (wavelet_variant_access::variant_index).
int hush_wavelet_variant_index(uint h, ivec3 l) {
  uint perms = hush_wv_dim == 2u ? HUSH_WAVELET_PERMUTATIONS2 : HUSH_WAVELET_PERMUTATIONS3;
  uint p = ((h >> HUSH_WAVELET_VARIANT_SHIFT) * perms) >> HUSH_WAVELET_VARIANT_SHIFT;
  ivec3 src = ivec3(0, 1, 2);
  if (hush_wv_dim == 2u) {
    src.x = int(p);
    src.y = 1 - src.x;
  } else {
    int first = int(p / 2u), lo = first == 0 ? 1 : 0, hi = first == 2 ? 1 : 2;
    src = ivec3(first, (p & 1u) != 0u ? hi : lo, (p & 1u) != 0u ? lo : hi);
  }
  int n = int(hush_wv_n), idx = 0, stride = 1;
  for (int a = 0; a < int(hush_wv_dim); ++a) {
    int v = l[src[a]];
    if (((h >> uint(a)) & 1u) != 0u) v = n - 1 - v;
    idx += v * stride;
    stride *= n;
  }
  return idx;
}
// Coefficient at tap offsets k from the band's tap-0 cells of the periodic tile.
// Rows of m = n (2D) or n + HUSH_WAVELET_ROW_PAD (3D) floats (wavelet_tile::coefficients).
// With HUSH_WAVELET_TILE_AT(ivec3 c) the tile is read by its coefficient coordinates c
// (c.z = 0 in 2D), e.g. texelFetch of an n^D texture (hush/glsl/wavelet/shader.hpp).
float hush_wavelet_tile_coef(ivec3 k) {
  ivec3 c = ivec3(hush_wavelet_wrap(hush_wv_i0.x, k.x), hush_wavelet_wrap(hush_wv_i0.y, k.y),
                  hush_wavelet_wrap(hush_wv_i0.z, k.z));
#ifdef HUSH_WAVELET_TILE_AT
  return HUSH_WAVELET_TILE_AT(c);
#else
  int n = int(hush_wv_n), m = n + (hush_wv_dim == 2u ? 0 : int(HUSH_WAVELET_ROW_PAD));
  return HUSH_WAVELET_TILE(c.x + m * (c.y + n * c.z));
#endif
}
// Coefficient at tap offsets k from the band's tap-0 cells (periodic tile or variants).
float hush_wavelet_coef(ivec3 k) {
  int n = int(hush_wv_n);
  if (hush_wv_cell == 0) return hush_wavelet_tile_coef(k);
#ifdef HUSH_WAVELET_BLEND
  uvec2 t[3] = uvec2[3](uvec2(0u), uvec2(0u), uvec2(0u));
  ivec2 l[3] = ivec2[3](ivec2(0), ivec2(0), ivec2(0));
  ivec3 count = ivec3(1);
  uint pitch = uint(hush_wv_cell);
  for (int a = 0; a <= 2; ++a) {  // constant trip counts: llvmpipe unrolls them (see below)
    if (a >= int(hush_wv_dim)) break;
    int r = int(hush_wv_i0[a] % pitch) + k[a];
    int carry = r < 0 ? -1 : (r >= hush_wv_cell ? 1 : 0);
    r -= carry * hush_wv_cell;
    t[a].x = hush_wv_i0[a] / pitch + uint(carry);
    l[a].x = r;
    t[a].y = t[a].x - 1u;
    l[a].y = r + hush_wv_cell;
    count[a] = r + hush_wv_cell < n ? 2 : 1;
  }
  float sum = 0.0;
  // The 2^D cell combinations (count.z = 1 in 2D). The bound is not a constant so that
  // the compiler keeps this a loop: unrolled in each of the many inlined copies of this
  // function, it made llvmpipe's compile of the 3D runner take minutes (and crash).
  for (int m = 0; m < 8 * min(hush_wv_cell, 1); ++m) {
    ivec3 pick = ivec3(m & 1, (m >> 1) & 1, (m >> 2) & 1);
    if (pick.x < count.x && pick.y < count.y && pick.z < count.z) {
      uint h = hush_wv_dim == 2u
                   ? hush_lattice_hash(hush_wv_key, t[0][pick.x], t[1][pick.y])
                   : hush_lattice_hash(hush_wv_key, t[0][pick.x], t[1][pick.y], t[2][pick.z]);
      ivec3 loc = ivec3(l[0][pick.x], l[1][pick.y], hush_wv_dim > 2u ? l[2][pick.z] : 0);
      sum += HUSH_WAVELET_BLEND(hush_wavelet_variant_index(h, loc));
    }
  }
  return sum;
#else
  return 0.0;
#endif
}

// Separable sums, z innermost: (value, d/dx, d/dy, d/dz) in coefficient units
// (wavelet.hpp wavelet_separable).
vec4 hush_wavelet_separable(hush_wavelet_axis ax0, hush_wavelet_axis ax1, hush_wavelet_axis ax2) {
  vec4 r = vec4(0.0);
  for (int a = 0; a < ax0.count; ++a) {
    float t = 0.0, ty = 0.0, tz = 0.0;
    for (int b = 0; b < ax1.count; ++b) {
      float s = 0.0, sz = 0.0;
      for (int c = 0; c < ax2.count; ++c) {
        float v = hush_wavelet_coef(ivec3(ax0.first + a, ax1.first + b, ax2.first + c));
        s += ax2.w[c] * v;
        sz += ax2.dw[c] * v;
      }
      t += ax1.w[b] * s;
      ty += ax1.dw[b] * s;
      tz += ax1.w[b] * sz;
    }
    r.x += ax0.w[a] * t;
    r.y += ax0.dw[a] * t;
    r.z += ax0.w[a] * ty;
    r.w += ax0.w[a] * tz;
  }
  return r;
}

@UNROLLED@
// The paper's approximate projection along a general unit normal u (wavelet_general_approx).
vec4 hush_wavelet_general_approx(vec3 y, vec3 u, vec3 s) {
  int w = 0;
  for (int a = 1; a <= 2; ++a)
    if (abs(u[a]) > abs(u[w])) w = a;
  int ax_u = w == 0 ? 1 : 0, ax_v = w == 2 ? 1 : 2;
  float half_ = HUSH_BSPLINE_HALF_SUPPORT;
  float l1 = 0.0;
  for (int a = 0; a <= 2; ++a) l1 += abs(u[a]) * s[a];
  vec3 reach;
  for (int a = 0; a <= 2; ++a) reach[a] = half_ * (s[a] + abs(u[a]) * l1);
  float stretch = 1.0 / HUSH_WAVELET_STRETCH;
  float sw = 0.0, sv = 0.0;
  vec3 sdw = vec3(0.0), sg = vec3(0.0);
  int u_lo = int(ceil(y[ax_u] - reach[ax_u])), u_hi = int(floor(y[ax_u] + reach[ax_u]));
  int v_lo = int(ceil(y[ax_v] - reach[ax_v])), v_hi = int(floor(y[ax_v] + reach[ax_v]));
  ivec3 k;
  vec3 d;
  for (int ku = u_lo; ku <= u_hi; ++ku) {
    k[ax_u] = ku;
    d[ax_u] = y[ax_u] - float(ku);
    for (int kv = v_lo; kv <= v_hi; ++kv) {
      k[ax_v] = kv;
      d[ax_v] = y[ax_v] - float(kv);
      float p = u[ax_u] * d[ax_u] + u[ax_v] * d[ax_v];
      float lo = -HUSH_FLOAT_HUGE, hi = HUSH_FLOAT_HUGE;
      bool empty = false;
      for (int a = 0; a <= 2; ++a) {
        float A = ((a == w ? 0.0 : d[a]) - u[a] * p * stretch) / s[a];
        float C = ((a == w ? 1.0 : 0.0) - u[a] * u[w] * stretch) / s[a];
        if (C == 0.0) {
          empty = empty || !(abs(A) < half_);
          continue;
        }
        float e0 = (-half_ - A) / C, e1 = (half_ - A) / C;
        lo = max(lo, min(e0, e1));
        hi = min(hi, max(e0, e1));
      }
      if (empty || !(lo < hi)) continue;
      int w_lo = int(floor(y[w] - hi)), w_hi = int(ceil(y[w] - lo));
      for (int kw = w_lo; kw <= w_hi; ++kw) {
        k[w] = kw;
        d[w] = y[w] - float(kw);
        float ud = u[0] * d[0] + u[1] * d[1] + u[2] * d[2];
        vec3 e, b;
        for (int a = 0; a <= 2; ++a) {
          e[a] = (d[a] - u[a] * ud * stretch) / s[a];
          b[a] = hush_kernel_b(e[a]);
        }
        float weight = b[0] * b[1] * b[2];
        if (weight == 0.0) continue;
        float c = hush_wavelet_coef(k);
        sw += weight;
        sv += weight * c;
        vec3 q = vec3(hush_kernel_db(e[0]) * b[1] * b[2] / s[0],
                      hush_kernel_db(e[1]) * b[2] * b[0] / s[1],
                      hush_kernel_db(e[2]) * b[0] * b[1] / s[2]);
        float uq = u[0] * q[0] + u[1] * q[1] + u[2] * q[2];
        for (int a = 0; a <= 2; ++a) {
          float gw = q[a] - u[a] * uq * stretch;
          sdw[a] += gw;
          sg[a] += gw * c;
        }
      }
    }
  }
  if (!(sw > 0.0)) return vec4(0.0);
  float inv = 1.0 / sw;
  float value = sv * inv;
  return vec4(value, (sg - value * sdw) * inv);
}

// The exact projection along a general unit normal u (wavelet_general_exact): the
// line integral split at its knots, 5-point Gauss-Legendre per piece. Where the CPU
// collects and sorts the knots, the GPU walks them in order (no private arrays): from
// t, the next knot is the nearest of B2's next knot and, per axis and knot family
// (offsets (m - 3/2) s_a modulo 1), the next crossing (k + frac - y_a) / u_a, the same
// values as the CPU's.
vec4 hush_wavelet_general_exact(vec3 y, vec3 u, vec3 s) {
  float reach = HUSH_BSPLINE2_HALF_SUPPORT, stretch = HUSH_WAVELET_STRETCH;
  float half_ = HUSH_BSPLINE_HALF_SUPPORT;
  bool plain = s == vec3(1.0);
  vec4 r = vec4(0.0);
  float t = -reach;
  for (int piece = 0; piece < int(HUSH_WAVELET_MAX_KNOTS) && t < reach; ++piece) {
    float next = -reach + stretch * (floor((t + reach) / stretch) + 1.0);
    if (!(next > t)) next += stretch;
    next = min(next, reach);
    for (int a = 0; a <= 2; ++a) {
      // Widened: the pieces of B2 only (wavelet_general_exact).
      if (u[a] != 0.0 && plain) {
        for (int m = 0; m < 4; ++m) {
          float delta = (float(m) - half_) * s[a];
          float frac = delta - floor(delta);
          float pos = y[a] + t * u[a] - frac;
          float k = u[a] > 0.0 ? floor(pos) + 1.0 : ceil(pos) - 1.0;
          float tn = (k + frac - y[a]) / u[a];
          if (!(tn > t)) tn = (k + sign(u[a]) + frac - y[a]) / u[a];
          if (tn > t) next = min(next, tn);
        }
      }
    }
    float t0 = t, t1 = next;
    t = next;
    if (t1 > t0) {
      float mid = (t0 + t1) / 2.0, h = (t1 - t0) / 2.0;
      for (int q = 0; q < int(HUSH_GAUSS_ORDER); ++q) {
        float tq = mid + h * HUSH_GAUSS_NODE[q];
        float wq = h * HUSH_GAUSS_WEIGHT[q] * hush_kernel_b2(tq);
        vec3 ya = y + tq * u;
        if (plain)
          r += wq * hush_wavelet_plain3(hush_wavelet_axis_at(ya.x), hush_wavelet_axis_at(ya.y),
                                        hush_wavelet_axis_at(ya.z));
        else
          r += wq * hush_wavelet_separable(hush_wavelet_axis_widened(ya.x, s.x),
                                           hush_wavelet_axis_widened(ya.y, s.y),
                                           hush_wavelet_axis_widened(ya.z, s.z));
      }
    }
  }
  return r;
}

// One band at fraction f of its tap-0 cells (hush_wv_* set): wavelet::band_kernel.
// project: a normal is given (unit u; axis = its axis when axis-aligned, else -1);
// s: the per-axis widening factors.
vec4 hush_wavelet_band(vec3 f, bool project, int axis, vec3 u, bool exact, vec3 s) {
  if (project && axis < 0) {
    vec3 y = f + vec3(HUSH_WAVELET_CELL_OFFSET);
    return exact ? hush_wavelet_general_exact(y, u, s) : hush_wavelet_general_approx(y, u, s);
  }
  bool widened = s != vec3(1.0);
  hush_wavelet_axis ax[3];
  for (int a = 0; a <= 2; ++a) {
    if (a >= int(hush_wv_dim))
      ax[a] = hush_wavelet_axis_unit();
    else if (project && a == axis)
      ax[a] = exact ? hush_wavelet_axis_beta(f[a]) : hush_wavelet_axis_b2(f[a]);
    else if (widened && s[a] != 1.0)
      ax[a] = hush_wavelet_axis_widened(f[a] + HUSH_WAVELET_CELL_OFFSET, s[a]);
    else
      ax[a] = hush_wavelet_axis_plain(f[a]);
  }
  if (!widened && !project)  // the plain B-spline on every axis: straight-line sums
    return hush_wv_dim == 2u ? hush_wavelet_plain2(ax[0], ax[1]) : hush_wavelet_plain3(ax[0], ax[1], ax[2]);
  return hush_wavelet_separable(ax[0], ax[1], ax[2]);
}

// The largest width of a footprint matrix S (core/footprint.hpp max_width).
float hush_footprint_max_width(mat2 S) {
  float mean = (S[0][0] + S[1][1]) / 2.0, halfd = (S[0][0] - S[1][1]) / 2.0;
  float r = length(vec2(halfd, S[1][0]));
  return sqrt(max(mean + r, 0.0));
}
float hush_footprint_max_width(mat3 S) {
  float off = S[1][0] * S[1][0] + S[2][0] * S[2][0] + S[2][1] * S[2][1];
  float q = (S[0][0] + S[1][1] + S[2][2]) / HUSH_THREE;
  vec3 dg = vec3(S[0][0], S[1][1], S[2][2]) - vec3(q);
  float p2 = dot(dg, dg) + 2.0 * off;
  if (p2 <= 0.0) return sqrt(max(q, 0.0));
  float p = sqrt(p2 / (2.0 * HUSH_THREE));
  mat3 B = (S - q * mat3(1.0)) / p;
  float r = clamp(determinant(B) / 2.0, -1.0, 1.0);
  return sqrt(max(q + 2.0 * p * cos(acos(r) / HUSH_THREE), 0.0));
}
// Whether a footprint of largest width wmax filters everything (core/footprint.hpp).
bool hush_wavelet_filters_everything(float wmax) { return !(wmax < HUSH_FOOTPRINT_MAX_WIDTH); }
// Basis widening of a band of frequency freq along an axis where the pixel's squared
// extent is extent2 (wavelet::make_plan): sqrt(1 + max(0, c^2 - c0^2)), capped at c = c1.
float hush_wavelet_widen(float extent2, float freq) {
  float c0 = HUSH_WAVELET_WIDEN_START;
  float c1 = HUSH_WAVELET_WIDEN_END;
  return sqrt(min(1.0 + max(0.0, extent2 * freq * freq - c0 * c0), 1.0 + c1 * c1 - c0 * c0));
}
// The anti-aliasing fade of a band whose coefficients are 2^level pixels apart.
float hush_wavelet_fade_weight(float level) {
  if (!(level > 0.0)) return 1.0;
  if (level >= 1.0) return 0.0;
  return hush_fade(1.0 - level);
}
// erf (Abramowitz & Stegun 7.1.26, |error| <= 1.5e-7) and erfc from it.
float hush_erf(float x) {
  float ax = abs(x);
  float t = 1.0 / (1.0 + HUSH_ERF_P * ax);
  float poly = t * (HUSH_ERF_A[0] + t * (HUSH_ERF_A[1] + t * (HUSH_ERF_A[2] + t * (HUSH_ERF_A[3] + t * HUSH_ERF_A[4]))));
  float e = 1.0 - poly * exp(-ax * ax);
  return x < 0.0 ? -e : e;
}
float hush_erfc(float x) { return 1.0 - hush_erf(x); }
// Scale and distribution remapping of the band sum acc = (value, gradient)
// (wavelet::eval and wavelet::remap); `everything`: the footprint filtered all.
vec4 hush_wavelet_output(vec4 acc, bool everything, float scale, uint dist, float gscale,
                         uint table_size) {
  float v = everything ? 0.0 : acc.x * scale;
  vec3 g = everything ? vec3(0.0) : acc.yzw * scale;
  if (dist == 0u) {
    v = v * gscale;
    g = g * gscale;
  } else if (dist == 1u) {
    float x = v * HUSH_INV_SQRT2;
    g = g * (2.0 * HUSH_INV_SQRT_2PI * exp(-x * x));
    v = hush_erf(x);
  } else {
#ifdef HUSH_WAVELET_TABLE
    float x = v * HUSH_INV_SQRT2;
    float m1 = float(table_size - 1u);
    float pos = hush_erfc(-x) / 2.0 * m1;
    uint i = min(uint(pos), table_size - 2u);
    float t = pos - float(i);
    float a = HUSH_WAVELET_TABLE(i), b = HUSH_WAVELET_TABLE(i + 1u);
    g = g * ((b - a) * m1 * HUSH_INV_SQRT_2PI * exp(-x * x));
    v = a + t * (b - a);
#endif
  }
  return vec4(v, g);
}
#endif  // HUSH_WAVELET_TILE or HUSH_WAVELET_TILE_AT, once
)glsl";

// The plain B-spline's separable sums as straight-line GLSL (no loop: see the loop
// budget above), in the CPU's order: hush_wavelet_plain2 (2D: value, d/dx, d/dy, 0)
// and hush_wavelet_plain3 (z innermost), over taps ax.first + 0 ... 2.
inline std::string wavelet_unrolled_sums() {
  std::string s =
      "// The plain B-spline's sums, unrolled (generated by hush/glsl/wavelet/glsl.hpp).\n"
      "vec4 hush_wavelet_plain2(hush_wavelet_axis ax0, hush_wavelet_axis ax1) {\n"
      "  vec4 r = vec4(0.0);\n  float t, ty, v;\n";
  const char* j[3] = {"0", "1", "2"};
  for (int a = 0; a < 3; ++a) {
    s += "  t = 0.0;\n  ty = 0.0;\n";
    for (int b = 0; b < 3; ++b)
      s += std::string("  v = hush_wavelet_coef(ivec3(ax0.first + ") + j[a] + ", ax1.first + " +
           j[b] + ", 0));\n  t += ax1.w[" + j[b] + "] * v;\n  ty += ax1.dw[" + j[b] + "] * v;\n";
    s += std::string("  r.x += ax0.w[") + j[a] + "] * t;\n  r.y += ax0.dw[" + j[a] +
         "] * t;\n  r.z += ax0.w[" + j[a] + "] * ty;\n";
  }
  s += "  return r;\n}\n"
       "vec4 hush_wavelet_plain3(hush_wavelet_axis ax0, hush_wavelet_axis ax1, "
       "hush_wavelet_axis ax2) {\n"
       "  vec4 r = vec4(0.0);\n  float t, ty, tz, s, sz, v;\n";
  for (int a = 0; a < 3; ++a) {
    s += "  t = 0.0;\n  ty = 0.0;\n  tz = 0.0;\n";
    for (int b = 0; b < 3; ++b) {
      s += "  s = 0.0;\n  sz = 0.0;\n";
      for (int c = 0; c < 3; ++c)
        s += std::string("  v = hush_wavelet_coef(ivec3(ax0.first + ") + j[a] + ", ax1.first + " +
             j[b] + ", ax2.first + " + j[c] + "));\n  s += ax2.w[" + j[c] +
             "] * v;\n  sz += ax2.dw[" + j[c] + "] * v;\n";
      s += std::string("  t += ax1.w[") + j[b] + "] * s;\n  ty += ax1.dw[" + j[b] +
           "] * s;\n  tz += ax1.w[" + j[b] + "] * sz;\n";
    }
    s += std::string("  r.x += ax0.w[") + j[a] + "] * t;\n  r.y += ax0.dw[" + j[a] +
         "] * t;\n  r.z += ax0.w[" + j[a] + "] * ty;\n  r.w += ax0.w[" + j[a] + "] * tz;\n";
  }
  return s + "  return r;\n}\n";
}

// The wavelet part of the library: the bodies above with the unrolled sums in place.
inline std::string wavelet_body() {
  std::string s = kWaveletBody;
  const std::string marker = "@UNROLLED@\n";
  s.replace(s.find(marker), marker.size(), wavelet_unrolled_sums());
  return s;
}

}  // namespace detail
}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_WAVELET_GLSL_HPP
