// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernels for improved Perlin noise in 2D and 3D: batches of points
// and uniform grids, values and optionally analytic gradients. Compiled once
// per SIMD target (the "-inl.h" convention: toggle include guard below, no
// normal guard); reached through hush/simd/dispatch.hpp, never included
// directly by users.
//
// The kernels compute perlin.hpp's float algorithm: same lattice split (in
// double for grids, exact float floor for points), same hash words, gradient
// index and table, Horner fade, lerp a + t(b - a), dot products and final
// scale. Where they take another route to the same number it is exact:
//  - the gradient index reads the top bits of the lattice hash, which
//    lowbias32's last step leaves alone, so it is skipped (hash32_high);
//  - the 3D index ((h >> 16) * 12) >> 16 is one 16-bit high multiply;
//  - 3D corner dot products g . f are one rounding of +-f_p +- f_q (gradient
//    components are 0 or +-1); targets narrower than 16 lanes form them by
//    selects and sign flips instead of table lookups, and grids split them
//    into a per-row part g_y f_y + g_z f_z and the x term;
//  - grid rows hash once per lattice point, not once per sample and corner;
//  - 3D grid rows with gradients (and fractal grids' bands) use the
//    affine-in-x form per (row, cell) that perlin.hpp's grid_values uses
//    too, its corner data blended in z once per (slice, y cell)
//    (slice_gradient_coefs / row_gradient_coefs / row_gradient, op for op).
// So:
//  - under HUSH_STRICT_FP (no contraction) every value and gradient is bit
//    for bit the scalar result (tests/perlin/perlin_simd_test.cpp, every
//    compiled target; zeros are +0 on every path, see perlin.hpp);
//  - otherwise multiply-adds are fused where that is faster, and results
//    stay within perlin.hpp's float budget of the double reference (2^-16);
//    measured differences to scalar are a few float ulps (docs/design.md).
// Points whose coordinates are all finite and below 2^22 in magnitude take
// the vector split; other vectors (NaN, Inf, huge, or periodic noise) split
// lane by lane through core/lattice.hpp, so hard cases behave exactly like
// scalar evaluation (NaN in gives NaN out).

// Toggle guard: included once per target by foreach_target.h (Highway's
// hwy/examples/skeleton-inl.h pattern).
#if defined(HUSH_PERLIN_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_PERLIN_SIMD_INL_H_
#undef HUSH_PERLIN_SIMD_INL_H_
#else
#define HUSH_PERLIN_SIMD_INL_H_
#endif

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/constants.hpp"
#include "hush/simd/lanes-inl.h"

// The noise class comes first, not from here: hush/perlin.hpp includes these
// kernels at its end (hush/perlin/simd_kernel.hpp), as src/simd/perlin.cpp does.
HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace perlin_simd {

// Generic lane maths: simd/lanes-inl.h. mul_add takes any float vector width
// (3D grid rows form their cells' coefficients in vectors narrower than VF
// where a row has few cells). Lookup tables are padded to kMaxLanes so every
// chunk load is in bounds.
using namespace lanes::types;
#if HWY_TARGET != HWY_SCALAR
using DU16 = hn::Repartition<std::uint16_t, DU>;
#endif

using lanes::for_each_vector;
using lanes::hash32_high;
using lanes::kMaxLanes;
using lanes::mul_add;
using lanes::store_interleaved;
using lanes::word;

// lerp(a, b, t) = a + t * (b - a), as detail::lerp.
template <class V>
HWY_INLINE V lerp(V a, V b, V t) {
  return mul_add(t, hn::Sub(b, a), a);
}
// scale * v + 0 (perlin.hpp's 3D output: zeros become +0). Adding 0 to the
// exact product rounds nothing, so the fused form equals the two-step one
// and may be used under strict FP too.
HWY_INLINE VF scale_plus_zero(VF scale, VF v) { return hn::MulAdd(scale, v, hn::Zero(DF())); }

// detail::fade: t^3 (t (6t - 15) + 10), Horner form in the same order.
HWY_INLINE VF fade(VF t) {
  namespace c = detail::constants;
  const DF df;
  const VF inner =
      mul_add(t, mul_add(t, hn::Set(df, float(c::kFade5)), hn::Set(df, float(c::kFade4))),
              hn::Set(df, float(c::kFade3)));
  return hn::Mul(hn::Mul(hn::Mul(t, t), t), inner);
}
HWY_INLINE VF fade_derivative(VF t) {
  namespace c = detail::constants;
  const DF df;
  const VF inner =
      mul_add(t, mul_add(t, hn::Set(df, float(5 * c::kFade5)), hn::Set(df, float(4 * c::kFade4))),
              hn::Set(df, float(3 * c::kFade3)));
  return hn::Mul(hn::Mul(t, t), inner);
}

// The gradient index reads the top bits of the lattice hash, so it uses
// lanes::hash32_high, which skips hash32's last step x ^= x >> 16: bits
// 16 ... 31 equal hash32's, and they are all Perlin's gradient index reads
// (2D: 29 ... 31; 3D: 16 ... 31).
static_assert(detail::constants::kHashShift3 >= 16 && detail::constants::kPerlin2GradShift >= 16 &&
                  detail::constants::kPerlin3IndexShift >= 16,
              "the gradient index must read only hash bits the last xorshift leaves alone");

// perlin.hpp's float gradient tables, padded to kMaxLanes with zeros so that
// every chunk load in lookup() stays in bounds. Constant data at fixed
// addresses: loops load them once.
struct padded_table {
  float v[kMaxLanes];
};
template <std::size_t N>
constexpr padded_table pad(const std::array<float, N>& src) {
  padded_table t{};
  for (std::size_t i = 0; i < N; ++i) t.v[i] = src[i];
  return t;
}
using float_tables = detail::perlin_tables<float>;
alignas(64) constexpr padded_table kG2x = pad(float_tables::g2x);
alignas(64) constexpr padded_table kG2y = pad(float_tables::g2y);
alignas(64) constexpr padded_table kG3x = pad(float_tables::g3x);
alignas(64) constexpr padded_table kG3y = pad(float_tables::g3y);
alignas(64) constexpr padded_table kG3z = pad(float_tables::g3z);

// table[idx] per lane for idx < kEntries: one in-register permute per chunk
// of Lanes entries (one for 8 entries on AVX2, two for 12), then a select.
template <int kEntries>
HWY_INLINE VF lookup(const padded_table& table, VU idx) {
  const DF df;
  const DU du;
  const DI di;
  const std::size_t n = hn::Lanes(df);
  // Within-chunk positions; an index below the lane count already is one.
  const VU in = static_cast<std::size_t>(kEntries) <= hn::MaxLanes(df)
                    ? idx
                    : hn::And(idx, hn::Set(du, static_cast<std::uint32_t>(n - 1)));
  const auto within = hn::IndicesFromVec(df, hn::BitCast(di, in));
  VF r = hn::TableLookupLanes(hn::LoadU(df, table.v), within);
  for (std::size_t base = n; base < static_cast<std::size_t>(kEntries); base += n) {
    // Indices are small, so a signed compare (the one every target has) is exact.
    const auto in_chunk = hn::RebindMask(
        df, hn::Gt(hn::BitCast(di, idx), hn::Set(di, static_cast<std::int32_t>(base) - 1)));
    r = hn::IfThenElse(in_chunk, hn::TableLookupLanes(hn::LoadU(df, table.v + base), within), r);
  }
  return r;
}

// 2D gradient index: the top 3 hash bits.
HWY_INLINE VU grad_index2(VU h) { return hn::ShiftRight<detail::constants::kPerlin2GradShift>(h); }

// 3D: ((h >> 16) * 12) >> 16 is the high half of the 16-bit product of h's
// top half and 12, so MulHigh on 16-bit lanes leaves the index in bits
// 16 ... 19 of each 32-bit lane (bits 0 ... 15 hold the low half's product,
// which nothing reads).
HWY_INLINE VU grad_index3_high(VU h) {
  namespace c = detail::constants;
  static_assert(c::kPerlin3IndexShift == 16, "the 16-bit high multiply needs a shift of 16");
#if HWY_TARGET == HWY_SCALAR
  // One-lane vectors cannot be reinterpreted as 16-bit lanes: (h >> 16) * 12
  // has the index in the same bits.
  return hn::Mul(hn::ShiftRight<16>(h), hn::Set(DU(), std::uint32_t(c::kPerlin3GradCount)));
#else
  const DU16 d16;
  return hn::BitCast(
      DU(), hn::MulHigh(hn::BitCast(d16, h), hn::Set(d16, std::uint16_t(c::kPerlin3GradCount))));
#endif
}
HWY_INLINE VU grad_index3(VU h) { return hn::ShiftRight<16>(grad_index3_high(h)); }

// The 3D gradients are the 12 cube edges, index n -> (x, y, z):
//   n < 4: (+-1, +-1, 0), n < 8: (+-1, 0, +-1), else (0, +-1, +-1),
// first sign from bit 0 of n, second from bit 1 (constants.hpp's tables).
static_assert(
    [] {
      for (int n = 0; n < detail::constants::kPerlin3GradCount; ++n) {
        const double s0 = (n & 1) ? -1 : 1, s1 = (n & 2) ? -1 : 1;
        const double want[3] = {n < 8 ? s0 : 0, n < 4 ? s1 : (n < 8 ? 0 : s0), n < 4 ? 0 : s1};
        if (detail::constants::kPerlin3GradX[n] != want[0] ||
            detail::constants::kPerlin3GradY[n] != want[1] ||
            detail::constants::kPerlin3GradZ[n] != want[2])
          return false;
      }
      return true;
    }(),
    "dot3_select assumes the cube-edge layout of the 3D gradient table");

// g . (fx, fy, fz) for the 3D gradient of hash h without a table: pick the
// two coordinates the edge uses, flip their signs and add. The sum is the
// rounding of the same exact real as gx fx + (gy fy + gz fz); only the sign
// of a zero result can differ, and outputs are +0-canonical (perlin.hpp).
HWY_INLINE VF dot3_select(VU h, VF fx, VF fy, VF fz) {
  const DF df;
  const DU du;
  const DI di;
  const VU k = grad_index3_high(h);  // index in bits 16 ... 19
  const auto below8 = hn::RebindMask(df, hn::Lt(hn::BitCast(di, k), hn::Set(di, 8 << 16)));
  const auto below4 = hn::RebindMask(df, hn::Lt(hn::BitCast(di, k), hn::Set(di, 4 << 16)));
  const VF p = hn::IfThenElse(below8, fx, fy);
  const VF q = hn::IfThenElse(below4, fy, fz);
  const VU sign = hn::Set(du, 0x80000000u);
  const VF sp = hn::BitCast(df, hn::And(hn::ShiftLeft<15>(k), sign));  // bit 0 of the index
  const VF sq = hn::BitCast(df, hn::And(hn::ShiftLeft<14>(k), sign));  // bit 1
  return hn::Add(hn::Xor(p, sp), hn::Xor(q, sq));
}

// Targets whose vector holds the whole 12-entry table look gradients up with
// one permute per component; narrower ones select (dot3_select).
constexpr bool kOnePermuteTable3 =
    hn::MaxLanes(DF()) >= static_cast<std::size_t>(detail::constants::kPerlin3GradCount);

// One axis of a batch of lattice lookups: hash words of the two cells, the
// fraction f, f - 1, the fade and (for gradients) the fade's derivative.
struct axis {
  VU w0, w1;
  VF f, f1, s, ds;
};

// Per-corner inputs of the blend: dot products d and, for gradients, the
// gradient components. Corner n = a + 2b + 4c is at offset (a, b, c).
struct corners {
  VF d[8], gx[8], gy[8], gz[8];
};

// Corner dot products from hashes: kyz[b + 2c] = key ^ word_y(j_b) ^
// word_z(k_c) (2D: kyz[0], kyz[1]).
template <bool kGradient, int D>
HWY_INLINE void hashed_corners(const axis& x, const VU* kyz, const axis& y, const axis& z,
                               corners& k) {
  constexpr int kCorners = 1 << D;
  HWY_UNROLL(8)
  for (int n = 0; n < kCorners; ++n) {
    const int a = n & 1, b = (n >> 1) & 1, c = n >> 2;
    const VU h = hash32_high(hn::Xor(a ? x.w1 : x.w0, kyz[b + 2 * c]));
    const VF fx = a ? x.f1 : x.f, fy = b ? y.f1 : y.f;
    if constexpr (D == 2) {
      constexpr int kN = detail::constants::kPerlin2GradCount;
      const VU g = grad_index2(h);
      k.gx[n] = lookup<kN>(kG2x, g);
      k.gy[n] = lookup<kN>(kG2y, g);
      k.d[n] = mul_add(k.gx[n], fx, hn::Mul(k.gy[n], fy));
    } else {
      constexpr int kN = detail::constants::kPerlin3GradCount;
      const VF fz = c ? z.f1 : z.f;
      if constexpr (kGradient || kOnePermuteTable3) {
        const VU g = grad_index3(h);
        k.gx[n] = lookup<kN>(kG3x, g);
        k.gy[n] = lookup<kN>(kG3y, g);
        k.gz[n] = lookup<kN>(kG3z, g);
        // gx fx + (gy fy + gz fz), as perlin.hpp sums it.
        k.d[n] = mul_add(k.gx[n], fx, mul_add(k.gy[n], fy, hn::Mul(k.gz[n], fz)));
      } else {
        k.d[n] = dot3_select(h, fx, fy, fz);
      }
    }
  }
}

// ---- The blend: perlin<D>::eval2 / eval3 after the dot products, in lanes.
template <bool kGradient>
HWY_INLINE void finish2(const corners& k, const axis& x, const axis& y, VF& value, VF* grad) {
  const DF df;
  const VF u = x.s, v = y.s;
  const VF x0 = lerp(k.d[0], k.d[1], u), x1 = lerp(k.d[2], k.d[3], u);
  const VF scale = hn::Set(df, float(detail::constants::kPerlin2Scale));
  value = hn::Mul(scale, lerp(x0, x1, v));
  if constexpr (kGradient) {
    const VF gx = mul_add(x.ds, lerp(hn::Sub(k.d[1], k.d[0]), hn::Sub(k.d[3], k.d[2]), v),
                          lerp(lerp(k.gx[0], k.gx[1], u), lerp(k.gx[2], k.gx[3], u), v));
    const VF gy = mul_add(y.ds, hn::Sub(x1, x0),
                          lerp(lerp(k.gy[0], k.gy[1], u), lerp(k.gy[2], k.gy[3], u), v));
    grad[0] = hn::Mul(scale, gx);
    grad[1] = hn::Mul(scale, gy);
  } else {
    (void)grad;
  }
}

template <bool kGradient>
HWY_INLINE void finish3(const corners& k, const axis& x, const axis& y, const axis& z, VF& value,
                        VF* grad) {
  const DF df;
  const VF* d = k.d;
  const VF u = x.s, v = y.s, w = z.s;
  const VF x00 = lerp(d[0], d[1], u), x10 = lerp(d[2], d[3], u);
  const VF x01 = lerp(d[4], d[5], u), x11 = lerp(d[6], d[7], u);
  const VF y0 = lerp(x00, x10, v), y1 = lerp(x01, x11, v);
  const VF scale = hn::Set(df, float(detail::constants::kPerlin3Scale));
  value = scale_plus_zero(scale, lerp(y0, y1, w));
  if constexpr (kGradient) {
    auto blend = [&](const VF* q) {
      return lerp(lerp(lerp(q[0], q[1], u), lerp(q[2], q[3], u), v),
                  lerp(lerp(q[4], q[5], u), lerp(q[6], q[7], u), v), w);
    };
    const VF ex = lerp(lerp(hn::Sub(d[1], d[0]), hn::Sub(d[3], d[2]), v),
                       lerp(hn::Sub(d[5], d[4]), hn::Sub(d[7], d[6]), v), w);
    const VF ey = lerp(hn::Sub(x10, x00), hn::Sub(x11, x01), w);
    const VF ez = hn::Sub(y1, y0);
    grad[0] = scale_plus_zero(scale, mul_add(x.ds, ex, blend(k.gx)));
    grad[1] = scale_plus_zero(scale, mul_add(y.ds, ey, blend(k.gy)));
    grad[2] = scale_plus_zero(scale, mul_add(z.ds, ez, blend(k.gz)));
  } else {
    (void)grad;
  }
}

template <bool kGradient, int D>
HWY_INLINE void finish(const corners& k, const axis& x, const axis& y, const axis& z, VF& value,
                       VF* grad) {
  if constexpr (D == 2) {
    (void)z;
    finish2<kGradient>(k, x, y, value, grad);
  } else {
    finish3<kGradient>(k, x, y, z, value, grad);
  }
}

// ---- 3D grid rows with gradients: perlin.hpp's slice_gradient_coefs,
// row_gradient_coefs and row_gradient (the affine-in-x form, docs/design.md),
// op for op, in lanes over cells (coefficients, in vectors of descriptor DC)
// and over columns (samples). Tables hold entry m of cell rank r at
// [m * stride + r].

// The slice data (detail::slice_gradient_coef) of cells [r, r + Lanes(dc))
// from their corner gradients (gx, gy, gz per corner n at [n * stride + r])
// and the slice's z axis (fraction f, f - 1, fade w and slope w').
template <class DC>
HWY_INLINE void slice_coefs(DC dc, std::size_t stride, std::size_t r, const float* gx,
                            const float* gy, const float* gz, float fz, float fz1, float w_s,
                            float w_ds, float* out) {
  namespace d = detail;
  using V = hn::Vec<DC>;
  const V w = hn::Set(dc, w_s), dw = hn::Set(dc, w_ds);
  const V fzc[2] = {hn::Set(dc, fz), hn::Set(dc, fz1)};
  auto load = [&](const float* t, int n)
                  HWY_ATTR { return hn::LoadU(dc, t + static_cast<std::size_t>(n) * stride + r); };
  HWY_UNROLL(2)
  for (int a = 0; a < 2; ++a) {
    HWY_UNROLL(2)
    for (int b = 0; b < 2; ++b) {
      const int n[2] = {a + 2 * b, a + 2 * b + 4};
      V qx[2], qy[2], qz[2], e[2];
      for (int c = 0; c < 2; ++c) {
        qx[c] = load(gx, n[c]);
        qy[c] = load(gy, n[c]);
        qz[c] = load(gz, n[c]);
        // gz (f_z - c) is exact (components are 0 or +-1): one rounding.
        e[c] = hn::Sub(hn::Mul(qz[c], fzc[c]), a ? qx[c] : hn::Zero(dc));
      }
      auto store = [&](int q, V x) HWY_ATTR {
        hn::StoreU(
            x, dc,
            out + static_cast<std::size_t>(d::slice_gradient_coef_index(q, a, b)) * stride + r);
      };
      store(d::kZgx, lerp(qx[0], qx[1], w));
      store(d::kZgy, lerp(qy[0], qy[1], w));
      store(d::kZgz, lerp(qz[0], qz[1], w));
      store(d::kZe, lerp(e[0], e[1], w));
      store(d::kWgx, hn::Mul(dw, hn::Sub(qx[1], qx[0])));
      store(d::kWgy, hn::Mul(dw, hn::Sub(qy[1], qy[0])));
      store(d::kWe, hn::Mul(dw, hn::Sub(e[1], e[0])));
    }
  }
}

// The row_gradient_coef coefficients of cells [r, r + Lanes(dc)) from their
// slice data sc and the row's y axis (fraction f, f - 1, fade v, slope v').
template <class DC>
HWY_INLINE void row_coefs(DC dc, std::size_t stride, std::size_t r, const float* sc, float fy_f,
                          float fy_f1, float v_s, float v_ds, float* out) {
  namespace d = detail;
  using V = hn::Vec<DC>;
  const V v = hn::Set(dc, v_s), dv = hn::Set(dc, v_ds);
  const V fy0 = hn::Set(dc, fy_f), fy1 = hn::Set(dc, fy_f1);
  V lgx[2], lc[2], ya[2], yb[2], za[2], zb[2];
  HWY_UNROLL(2)
  for (int a = 0; a < 2; ++a) {
    auto q = [&](int kind, int b) HWY_ATTR {
      return hn::LoadU(
          dc, sc + static_cast<std::size_t>(d::slice_gradient_coef_index(kind, a, b)) * stride + r);
    };
    const V zgx0 = q(d::kZgx, 0), zgx1 = q(d::kZgx, 1);
    const V zgy0 = q(d::kZgy, 0), zgy1 = q(d::kZgy, 1);
    lgx[a] = lerp(zgx0, zgx1, v);
    const V mygx = hn::Sub(zgx1, zgx0);
    const V zc0 = mul_add(zgy0, fy0, q(d::kZe, 0)), zc1 = mul_add(zgy1, fy1, q(d::kZe, 1));
    lc[a] = lerp(zc0, zc1, v);
    const V myc = hn::Sub(zc1, zc0);
    const V lgy = lerp(zgy0, zgy1, v);
    const V lgz = lerp(q(d::kZgz, 0), q(d::kZgz, 1), v);
    za[a] = lerp(q(d::kWgx, 0), q(d::kWgx, 1), v);
    const V wc0 = mul_add(q(d::kWgy, 0), fy0, q(d::kWe, 0));
    const V wc1 = mul_add(q(d::kWgy, 1), fy1, q(d::kWe, 1));
    zb[a] = hn::Add(lerp(wc0, wc1, v), lgz);
    ya[a] = hn::Mul(dv, mygx);
    yb[a] = mul_add(dv, myc, lgy);
  }
  auto store = [&](int m, V x)
                   HWY_ATTR { hn::StoreU(x, dc, out + static_cast<std::size_t>(m) * stride + r); };
  store(d::kEA, hn::Sub(lgx[1], lgx[0]));
  store(d::kEB, hn::Sub(lc[1], lc[0]));
  store(d::kX0, lgx[0]);
  store(d::kV0B, lc[0]);
  store(d::kY0A, ya[0]);
  store(d::kY0B, yb[0]);
  store(d::kDYA, hn::Sub(ya[1], ya[0]));
  store(d::kDYB, hn::Sub(yb[1], yb[0]));
  store(d::kZ0A, za[0]);
  store(d::kZ0B, zb[0]);
  store(d::kDZA, hn::Sub(za[1], za[0]));
  store(d::kDZB, hn::Sub(zb[1], zb[0]));
}
HWY_INLINE void row_gradient(const VF* co, const axis& x, VF& value, VF* grad) {
  namespace d = detail;
  const VF f = x.f, u = x.s;
  const VF delta = mul_add(co[d::kEA], f, co[d::kEB]);
  const VF gx = mul_add(x.ds, delta, mul_add(u, co[d::kEA], co[d::kX0]));
  const VF gy =
      mul_add(u, mul_add(co[d::kDYA], f, co[d::kDYB]), mul_add(co[d::kY0A], f, co[d::kY0B]));
  const VF gz =
      mul_add(u, mul_add(co[d::kDZA], f, co[d::kDZB]), mul_add(co[d::kZ0A], f, co[d::kZ0B]));
  const VF scale = hn::Set(DF(), float(d::constants::kPerlin3Scale));
  value = scale_plus_zero(scale, mul_add(u, delta, mul_add(co[d::kX0], f, co[d::kV0B])));
  grad[0] = scale_plus_zero(scale, gx);
  grad[1] = scale_plus_zero(scale, gy);
  grad[2] = scale_plus_zero(scale, gz);
}

// kyz for hashed_corners() from per-lane axes (points) ...
template <int D>
HWY_INLINE void key_words(VU key, const axis& y, const axis& z, VU* kyz) {
  kyz[0] = hn::Xor(key, y.w0);
  kyz[1] = hn::Xor(key, y.w1);
  if constexpr (D == 3) {
    kyz[2] = hn::Xor(kyz[0], z.w1);
    kyz[3] = hn::Xor(kyz[1], z.w1);
    kyz[0] = hn::Xor(kyz[0], z.w0);
    kyz[1] = hn::Xor(kyz[1], z.w0);
  } else {
    (void)z;
  }
}

// ---- Points: splitting float coordinates into lattice axes.

// Fractions, fades and the second cell's word of an axis whose first word
// and fraction are known.
template <bool kGradient>
HWY_INLINE void fill_axis(VF f, axis& a) {
  a.f = f;
  a.f1 = hn::Sub(f, hn::Set(DF(), 1.0f));
  a.s = fade(f);
  if constexpr (kGradient) a.ds = fade_derivative(f);
}

// Vector split, valid when every lane is finite with |x| < 2^22: floor and
// x - floor(x) are exact in float, so this equals lattice_split's double
// computation (including its clamp below 1 for tiny negative x). The cell
// comes from the float's bits: floor(x) + 1.5 * 2^23 is exact for
// |floor(x)| <= 2^22 and its bit pattern is 0x4B400000 + floor(x), two's
// complement (cheaper than a conversion with overflow handling).
constexpr float kFastSplitLimit = 4194304.0f;  // 2^22
constexpr float kCellMagic = 12582912.0f;      // 1.5 * 2^23
constexpr std::uint32_t kCellMagicBits = 0x4B400000u;
template <bool kGradient, int kAxis>
HWY_INLINE axis split_fast(VF xv) {
  namespace c = detail::constants;
  const DF df;
  const DU du;
  const VF fl = hn::Floor(xv);
  const VU i0 =
      hn::Sub(hn::BitCast(du, hn::Add(fl, hn::Set(df, kCellMagic))), hn::Set(du, kCellMagicBits));
  // (i + 1) P = i P + P: the second cell's product is one add away.
  constexpr std::uint32_t kPrime = kAxis == 0   ? c::kLatticePrimeX
                                   : kAxis == 1 ? c::kLatticePrimeY
                                                : c::kLatticePrimeZ;
  const VU m0 = hn::Mul(i0, hn::Set(du, kPrime));
  const VU m1 = hn::Add(m0, hn::Set(du, kPrime));
  axis a;
  if constexpr (kAxis == 0) {
    a.w0 = m0;
    a.w1 = m1;
  } else {
    constexpr int kRotate = kAxis == 1 ? c::kLatticeRotateY : c::kLatticeRotateZ;
    a.w0 = hn::RotateRight<32 - kRotate>(m0);
    a.w1 = hn::RotateRight<32 - kRotate>(m1);
  }
  fill_axis<kGradient>(hn::Min(hn::Sub(xv, fl), hn::Set(df, detail::one_minus_ulp<float>())), a);
  return a;
}
static_assert(detail::constants::kLatticeRotateY > 0 && detail::constants::kLatticeRotateZ > 0,
              "split_fast rotates by 32 - R");

// Lane-by-lane split of double coordinates q[lane] through core/lattice.hpp:
// exactly what scalar evaluation computes.
template <bool kGradient, int kAxis>
HWY_INLINE axis split_doubles(const double* q, std::uint32_t period) {
  const DF df;
  const DU du;
  HWY_ALIGN float fs[kMaxLanes];
  HWY_ALIGN std::uint32_t i0s[kMaxLanes], i1s[kMaxLanes];
  for (std::size_t l = 0; l < hn::Lanes(df); ++l) {
    const lattice_coord<float> c = lattice_split<float>(q[l], period);
    i0s[l] = c.i0;
    i1s[l] = c.i1;
    fs[l] = c.f;
  }
  axis a;
  a.w0 = word<kAxis>(hn::Load(du, i0s));
  a.w1 = word<kAxis>(hn::Load(du, i1s));
  fill_axis<kGradient>(hn::Load(df, fs), a);
  return a;
}

// Lane-by-lane split of float coordinates: NaN, Inf, |x| >= 2^22 and
// periodic axes. Same result as scalar evaluation by construction.
template <bool kGradient, int kAxis>
HWY_NOINLINE axis split_lanes(VF xv, std::uint32_t period) {
  const DF df;
  HWY_ALIGN float xs[kMaxLanes];
  double q[kMaxLanes];
  hn::Store(xv, df, xs);
  for (std::size_t l = 0; l < hn::Lanes(df); ++l) q[l] = double(xs[l]);
  return split_doubles<kGradient, kAxis>(q, period);
}

// Lanes with |x| < 2^22 (false for NaN): where the vector split is exact.
HWY_INLINE hn::Mask<DF> in_fast_range(VF x) {
  const DF df;
  return hn::Lt(hn::Abs(x), hn::Set(df, kFastSplitLimit));
}

template <bool kGradient, int kAxis>
HWY_INLINE axis split(VF xv, std::uint32_t period) {
  if (period == 0 && hn::AllTrue(DF(), in_fast_range(xv))) return split_fast<kGradient, kAxis>(xv);
  return split_lanes<kGradient, kAxis>(xv, period);
}

// Split points -> values (and interleaved gradients) of one vector.
template <bool kGradient, int D>
HWY_INLINE void points_from_axes(VU key, const axis& ax, const axis& ay, const axis& az,
                                 float* HWY_RESTRICT value, float* HWY_RESTRICT grad) {
  VU kyz[4];
  key_words<D>(key, ay, az, kyz);
  corners k;
  hashed_corners<kGradient, D>(ax, kyz, ay, az, k);
  VF v, g[3];
  finish<kGradient, D>(k, ax, ay, az, v, g);
  hn::StoreU(v, DF(), value);
  if constexpr (kGradient) store_interleaved<D>(g, grad);
}

// A vector with a lane the fast split cannot take, or periodic noise: each
// axis splits by the vector or lane by lane, whichever is exact. Out of line,
// so that the common path keeps its registers.
template <bool kGradient, int D>
HWY_NOINLINE void points_vector_lanes(VU key, const std::uint32_t* period, VF x, VF y, VF z,
                                      float* HWY_RESTRICT value, float* HWY_RESTRICT grad) {
  const axis ax = split<kGradient, 0>(x, period[0]);
  const axis ay = split<kGradient, 1>(y, period[1]);
  axis az{};
  if constexpr (D == 3) az = split<kGradient, 2>(z, period[2]);
  points_from_axes<kGradient, D>(key, ax, ay, az, value, grad);
}

// One vector of D-dimensional points (interleaved) -> values (and
// interleaved gradients), if every lane can take the vector split: returns
// false, writing nothing, if one cannot (then points_vector_lanes does it).
template <bool kGradient, int D>
HWY_INLINE bool points_vector_fast(VU key, const float* HWY_RESTRICT pts, float* HWY_RESTRICT value,
                                   float* HWY_RESTRICT grad) {
  const DF df;
  VF x, y, z = hn::Zero(df);
  if constexpr (D == 2)
    hn::LoadInterleaved2(df, pts, x, y);
  else
    hn::LoadInterleaved3(df, pts, x, y, z);
  auto fast = hn::And(in_fast_range(x), in_fast_range(y));
  if constexpr (D == 3) fast = hn::And(fast, in_fast_range(z));
  if (HWY_UNLIKELY(!hn::AllTrue(df, fast))) return false;
  axis az{};
  if constexpr (D == 3) az = split_fast<kGradient, 2>(z);
  points_from_axes<kGradient, D>(key, split_fast<kGradient, 0>(x), split_fast<kGradient, 1>(y), az,
                                 value, grad);
  return true;
}

// Any vector of points, periodic noise included.
template <bool kGradient, int D>
HWY_INLINE void points_vector(VU key, bool plain, const std::uint32_t* period,
                              const float* HWY_RESTRICT pts, float* HWY_RESTRICT value,
                              float* HWY_RESTRICT grad) {
  if (plain && points_vector_fast<kGradient, D>(key, pts, value, grad)) return;
  const DF df;
  VF x, y, z = hn::Zero(df);
  if constexpr (D == 2)
    hn::LoadInterleaved2(df, pts, x, y);
  else
    hn::LoadInterleaved3(df, pts, x, y, z);
  points_vector_lanes<kGradient, D>(key, period, x, y, z, value, grad);
}

// Runs `vector_fn(pts, value, grad)` over n points of D floats each, one
// vector at a time (lanes::for_each_vector: the tail through zero-padded buffers).
// One call site, so the vector function inlines into the loop.
template <bool kGradient, int D, class Fn>
HWY_INLINE void for_each_point_vector(std::size_t n, const float* pts, float* value, float* grad,
                                      const Fn& vector_fn) {
  for_each_vector<D>(n, pts, value, kGradient ? grad : nullptr,
                     [&](std::size_t, const float* p, float* v, float* g)
                         HWY_ATTR { vector_fn(p, v, g); });
}

template <bool kGradient, int D>
HWY_NOINLINE void perlin_points(std::uint32_t key, const std::uint32_t* period, const float* pts,
                                std::size_t n, float* value, float* grad) {
  const VU vkey = hn::Set(DU(), key);
  bool plain = true;
  for (int a = 0; a < D; ++a) plain = plain && period[a] == 0;
  // Whole vectors, then the rest through zero-padded buffers (no lane reads
  // or writes out of bounds). points_vector inlines at both sites.
  const std::size_t lanes = hn::Lanes(DF());
  std::size_t i = 0;
  while (i + lanes <= n) {
    // The common case runs in a loop without calls, which keeps its constants
    // in registers; a vector it cannot take leaves it for points_vector.
    if (plain)
      for (; i + lanes <= n; i += lanes)
        if (!points_vector_fast<kGradient, D>(vkey, pts + i * D, value + i,
                                              kGradient ? grad + i * D : nullptr))
          break;
    if (i + lanes > n) break;
    points_vector<kGradient, D>(vkey, plain, period, pts + i * D, value + i,
                                kGradient ? grad + i * D : nullptr);
    i += lanes;
  }
  if (i == n) return;
  const std::size_t rest = n - i;
  HWY_ALIGN float in[kMaxLanes * D] = {}, out[kMaxLanes], g[kMaxLanes * D];
  std::memcpy(in, pts + i * D, rest * D * sizeof(float));
  points_vector<kGradient, D>(vkey, plain, period, in, out, g);
  std::memcpy(value + i, out, rest * sizeof(float));
  if constexpr (kGradient) std::memcpy(grad + i * D, g, rest * D * sizeof(float));
}

}  // namespace perlin_simd

// Perlin at n interleaved points (x0, y0[, z0], x1, ...); values into
// `value[n]`, and interleaved gradients into `grad[D n]` unless grad is null.
template <int D>
void perlin_points(std::uint32_t key, const std::uint32_t* period, const float* pts, std::size_t n,
                   float* value, float* grad) {
  if (grad)
    perlin_simd::perlin_points<true, D>(key, period, pts, n, value, grad);
  else
    perlin_simd::perlin_points<false, D>(key, period, pts, n, value, nullptr);
}
inline void perlin2_points(std::uint32_t key, const std::uint32_t* period, const float* xy,
                           std::size_t n, float* value, float* grad) {
  perlin_points<2>(key, period, xy, n, value, grad);
}
inline void perlin3_points(std::uint32_t key, const std::uint32_t* period, const float* xyz,
                           std::size_t n, float* value, float* grad) {
  perlin_points<3>(key, period, xyz, n, value, grad);
}

namespace perlin_simd {

// ---- Grids. The x axis is split once per column (in double, by
// lattice_split, exactly as scalar evaluation does) and reused by every row;
// y (and z) are split once per row and broadcast.
//
// Consecutive columns share cells (the benchmark has 37 per cell), and the
// corner gradients of a cell are the same for every sample of a row in it.
// So each row hashes its lattice points once and keeps, per cell and corner,
// the gradient's x component gx and the row-constant rest of the dot product
//   K = gy f_y (2D),  K = gy f_y + gz f_z (3D),
// and a sample needs d = gx f_x + K: exactly the scalar sums (perlin.hpp).
// A vector of columns spans at most Lanes cells, so its cells' entries are
// one unaligned load and a permute away. Rows whose cells are not shared
// (steps near or above one cell) hash per sample instead.
struct grid_columns {
  std::size_t n = 0, padded = 0, cells = 0;
  std::vector<float> f, s, ds;
  std::vector<std::uint32_t> w0, w1;    // per column: x words of its cell's two lattice points
  std::vector<std::uint32_t> local;     // per column: its cell's rank minus its vector's base
  std::vector<std::uint32_t> base;      // per vector of columns: the rank of its first cell
  std::vector<std::uint32_t> cw0, cw1;  // per cell rank: x words, padded to whole vectors
  bool shared = false;                  // at least two columns per cell on average

  // Column i's x coordinate is position(i), a double.
  template <class Position>
  grid_columns(std::size_t count, std::uint32_t period, bool gradient, Position position)
      : n(count) {
    const std::size_t lanes = hn::Lanes(DF());
    padded = (n + lanes - 1) / lanes * lanes;
    f.assign(padded, 0.0f);
    s.assign(padded, 0.0f);
    w0.assign(padded, 0u);
    w1.assign(padded, 0u);
    local.assign(padded, 0u);
    base.assign(padded / lanes, 0u);
    if (gradient) ds.assign(padded, 0.0f);
    std::uint32_t rank = 0, prev_i0 = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const lattice_coord<float> c = lattice_split<float>(position(i), period);
      f[i] = c.f;
      s[i] = detail::fade(c.f);
      if (gradient) ds[i] = detail::fade_derivative(c.f);
      w0[i] = lattice_word_x(c.i0);
      w1[i] = lattice_word_x(c.i1);
      // A new cell starts where i0 changes (i1 follows from i0 and the period).
      if (i > 0 && c.i0 != prev_i0) ++rank;
      if (i == 0 || c.i0 != prev_i0) {
        cw0.push_back(w0[i]);
        cw1.push_back(w1[i]);
      }
      prev_i0 = c.i0;
      if (i % lanes == 0) base[i / lanes] = rank;
      local[i] = rank - base[i / lanes];  // < lanes: each column adds at most one cell
    }
    // Padding lanes repeat the last column's cell: a vector's lanes then share
    // one cell exactly when its last lane's local rank is 0 (corners_at).
    for (std::size_t i = n; i < padded; ++i) local[i] = local[n - 1];
    cells = cw0.size();
    cw0.resize((cells + lanes - 1) / lanes * lanes, 0u);
    cw1.resize(cw0.size(), 0u);
    shared = detail::grid_cells_shared(cells, n);
  }

  template <bool kGradient>
  HWY_INLINE axis load(std::size_t i) const {
    const DU du;
    axis a;
    a.w0 = hn::LoadU(du, w0.data() + i);
    a.w1 = hn::LoadU(du, w1.data() + i);
    fill_axis_loaded<kGradient>(i, a);
    return a;
  }
  // Fractions and fades only (the table path needs no words).
  template <bool kGradient>
  HWY_INLINE void fill_axis_loaded(std::size_t i, axis& a) const {
    const DF df;
    a.f = hn::LoadU(df, f.data() + i);
    a.f1 = hn::Sub(a.f, hn::Set(df, 1.0f));
    a.s = hn::LoadU(df, s.data() + i);
    if constexpr (kGradient) a.ds = hn::LoadU(df, ds.data() + i);
  }
};

// A row-constant axis (y or z): scalar split broadcast to all lanes.
struct row_axis {
  std::uint32_t w0 = 0, w1 = 0;
  float f = 0, f1 = 0, s = 0, ds = 0;
  axis a;
};
template <bool kGradient, int kAxis>
HWY_INLINE row_axis broadcast_axis(double p, std::uint32_t period) {
  const DF df;
  const lattice_coord<float> c = lattice_split<float>(p, period);
  row_axis r;
  r.w0 = kAxis == 1 ? lattice_word_y(c.i0) : lattice_word_z(c.i0);
  r.w1 = kAxis == 1 ? lattice_word_y(c.i1) : lattice_word_z(c.i1);
  r.f = c.f;
  r.f1 = c.f - 1.0f;
  r.s = detail::fade(c.f);
  if constexpr (kGradient) r.ds = detail::fade_derivative(c.f);
  r.a.f = hn::Set(df, r.f);
  r.a.f1 = hn::Set(df, r.f1);
  r.a.s = hn::Set(df, r.s);
  if constexpr (kGradient) r.a.ds = hn::Set(df, r.ds);
  return r;
}

// The lattice words and fractions of one grid row (2D: z unused).
struct grid_row {
  std::uint32_t key;
  row_axis y, z;
  // key ^ word_y(j_b) ^ word_z(k_c) for corner offsets (b, c), index b + 2c.
  std::uint32_t kyz(int b, int c) const { return key ^ (b ? y.w1 : y.w0) ^ (c ? z.w1 : z.w0); }
};

// Per-row, per-cell corner data for the shared-cell path: for corner n and
// cell rank r, gx (and for gradients gy, gz) and K, at [n * stride + r].
// kAffine (3D with gradients): instead of K, the cells' slice data
// (detail::slice_gradient_coef, rebuilt when the slice or the y cell
// changes) and the row's gradient coefficients (detail::row_gradient_coef)
// at [m * stride + r]; samples then read only those.
template <bool kGradient, int D, bool kAffine = kGradient&& D == 3>
struct row_tables {
  static_assert(!kAffine || (kGradient && D == 3), "the affine row gradient is 3D");
  static constexpr int kCorners = 1 << D;
  std::size_t stride = 0;
  std::vector<float> gx, k, gy, gz, slice, coef;
  // The y/z words the gradients were hashed for: consecutive rows in the same
  // y (and z) cell keep them and only recompute k (the benchmark's grids have
  // 37 rows per cell); kAffine: the z fraction the slice data is for.
  std::uint32_t hashed_kyz[4] = {};
  bool hashed = false;
  float slice_fz = 0;

  explicit row_tables(const grid_columns& cols) {
    const std::size_t lanes = hn::Lanes(DF());
    stride = cols.cw0.size() + lanes;  // a vector's load at its base rank stays inside
    const std::size_t size = stride * kCorners;
    gx.assign(size, 0.0f);
    if (!kAffine) k.assign(size, 0.0f);
    gy.assign(size, 0.0f);
    if (D == 3) gz.assign(size, 0.0f);
    if (kAffine) {
      slice.assign(stride * detail::kSliceGradientCoefs, 0.0f);
      coef.assign(stride * detail::kRowGradientCoefs, 0.0f);
    }
  }

  // The corner gradients of cells [r, r + lanes) (x words wx) against the
  // row's y/z words.
  HWY_INLINE void hash_cells(const VU* wx, const std::uint32_t* words, std::size_t r) {
    const DF df;
    const DU du;
    HWY_UNROLL(8)
    for (int n = 0; n < kCorners; ++n) {
      const int a = n & 1, b = (n >> 1) & 1, c = n >> 2;
      const std::size_t at = static_cast<std::size_t>(n) * stride + r;
      const VU h = hash32_high(hn::Xor(wx[a], hn::Set(du, words[b + 2 * c])));
      if constexpr (D == 2) {
        constexpr int kN = detail::constants::kPerlin2GradCount;
        const VU g = grad_index2(h);
        hn::StoreU(lookup<kN>(kG2x, g), df, gx.data() + at);
        hn::StoreU(lookup<kN>(kG2y, g), df, gy.data() + at);
      } else {
        constexpr int kN = detail::constants::kPerlin3GradCount;
        const VU g = grad_index3(h);
        hn::StoreU(lookup<kN>(kG3x, g), df, gx.data() + at);
        hn::StoreU(lookup<kN>(kG3y, g), df, gy.data() + at);
        hn::StoreU(lookup<kN>(kG3z, g), df, gz.data() + at);
      }
    }
  }

  // fn(dc, r) for every chunk of cells [r, r + Lanes(dc)): chunks of at most
  // 8 lanes where the row's cells fit in one (a 64-sample row of the
  // benchmark has 2 or 3 cells, and this machine's 512-bit operations cost
  // two 256-bit ones), whole vectors otherwise.
  template <class Fn>
  static HWY_INLINE void for_each_cell_chunk(std::size_t cells, const Fn& fn) {
    using DC = hn::CappedTag<float, 8>;
    if (hn::MaxLanes(DC()) < hn::MaxLanes(DF()) && cells <= hn::Lanes(DC())) {
      fn(DC(), std::size_t(0));
      return;
    }
    for (std::size_t r = 0; r < cells; r += hn::Lanes(DF())) fn(DF(), r);
  }

  // Hashes the row's lattice points (cells' x words against the row's y/z
  // words) unless the previous row had the same ones, then forms k (or, for
  // kAffine, the slice data where the slice changed and the row's
  // coefficients).
  HWY_INLINE void build(const grid_columns& cols, const grid_row& row) {
    const DF df;
    const DU du;
    const std::size_t lanes = hn::Lanes(df);
    const std::uint32_t words[4] = {row.kyz(0, 0), row.kyz(1, 0), row.kyz(0, 1), row.kyz(1, 1)};
    const bool same = hashed && std::equal(words, words + 4, hashed_kyz);
    std::copy(words, words + 4, hashed_kyz);
    hashed = true;
    if constexpr (kAffine) {
      if (!same)
        for (std::size_t r = 0; r < cols.cw0.size(); r += lanes) {
          const VU wx[2] = {hn::LoadU(du, cols.cw0.data() + r), hn::LoadU(du, cols.cw1.data() + r)};
          hash_cells(wx, words, r);
        }
      // NaN fractions never compare equal: such slices are rebuilt every row.
      const bool new_slice = !same || !(row.z.f == slice_fz);
      slice_fz = row.z.f;
      for_each_cell_chunk(cols.cells, [&](auto dc, std::size_t r) HWY_ATTR {
        if (new_slice)
          slice_coefs(dc, stride, r, gx.data(), gy.data(), gz.data(), row.z.f, row.z.f1, row.z.s,
                      row.z.ds, slice.data());
        row_coefs(dc, stride, r, slice.data(), row.y.f, row.y.f1, row.y.s, row.y.ds, coef.data());
      });
      return;
    }
    for (std::size_t r = 0; r < cols.cw0.size(); r += lanes) {
      if (!same) {
        const VU wx[2] = {hn::LoadU(du, cols.cw0.data() + r), hn::LoadU(du, cols.cw1.data() + r)};
        hash_cells(wx, words, r);
      }
      HWY_UNROLL(8)
      for (int n = 0; n < kCorners; ++n) {
        const int b = (n >> 1) & 1, c = n >> 2;
        const std::size_t at = static_cast<std::size_t>(n) * stride + r;
        const VF cy = hn::LoadU(df, gy.data() + at);
        const VF fy = hn::Set(df, b ? row.y.f1 : row.y.f);
        VF kk;
        if constexpr (D == 2)
          kk = hn::Mul(cy, fy);
        else
          kk = mul_add(cy, fy,
                       hn::Mul(hn::LoadU(df, gz.data() + at), hn::Set(df, c ? row.z.f1 : row.z.f)));
        hn::StoreU(kk, df, k.data() + at);
      }
    }
  }

  // Calls fn(b, entry) for the vector of columns starting at column i, with
  // b its first cell's rank and entry(table, at) giving each lane the entry
  // of its cell. Where all lanes share one cell (most vectors when cells hold
  // many samples) a broadcast replaces the permute. fn inlines into each
  // branch on its own, so the entries stay in registers.
  template <class Fn>
  HWY_INLINE void with_entries(const grid_columns& cols, std::size_t i, const Fn& fn) const {
    const DF df;
    const std::size_t lanes = hn::Lanes(df);
    const std::size_t b = cols.base[i / lanes];
    if (cols.local[i + lanes - 1] == 0) {
      fn(b,
         [&](const std::vector<float>& t, std::size_t at) HWY_ATTR { return hn::Set(df, t[at]); });
    } else {
      const DU du;
      const DI di;
      const auto idx =
          hn::IndicesFromVec(df, hn::BitCast(di, hn::LoadU(du, cols.local.data() + i)));
      fn(b, [&](const std::vector<float>& t, std::size_t at)
                HWY_ATTR { return hn::TableLookupLanes(hn::LoadU(df, t.data() + at), idx); });
    }
  }
  // out from the entries at cell rank b, read per corner by entry(table, index).
  template <class Entry>
  HWY_INLINE void corners_from(std::size_t b, const axis& x, corners& out,
                               const Entry& entry) const {
    HWY_UNROLL(8)
    for (int n = 0; n < kCorners; ++n) {
      const std::size_t at = static_cast<std::size_t>(n) * stride + b;
      const VF cx = entry(gx, at);
      out.d[n] = mul_add(cx, (n & 1) ? x.f1 : x.f, entry(k, at));
      if constexpr (kGradient) {
        out.gx[n] = cx;
        out.gy[n] = entry(gy, at);
        if constexpr (D == 3) out.gz[n] = entry(gz, at);
      }
    }
  }
  // kAffine: the value and gradient from the cell coefficients at rank b.
  template <class Entry>
  HWY_INLINE void affine_from(std::size_t b, const axis& x, const Entry& entry, VF& value,
                              VF* grad) const {
    VF co[detail::kRowGradientCoefs];
    HWY_UNROLL(12)
    for (int m = 0; m < detail::kRowGradientCoefs; ++m)
      co[m] = entry(coef, static_cast<std::size_t>(m) * stride + b);
    row_gradient(co, x, value, grad);
  }
};

// One grid row's evaluation, either path: vector_out(i, value, gradient)
// receives each vector of columns [i, i + lanes).
template <bool kGradient, int D, bool kAffine = kGradient&& D == 3>
struct row_evaluator {
  const grid_columns& cols;
  row_tables<kGradient, D, kAffine> tables;

  explicit row_evaluator(const grid_columns& c) : cols(c), tables(c) {}

  // Makes `row` current (the shared path builds its cell tables).
  HWY_INLINE void prepare(const grid_row& row) {
    if (cols.shared) tables.build(cols, row);
  }
  // out(value, gradient) for the vector of columns [i, i + lanes) of the
  // prepared row; out inlines into each branch, keeping its inputs in registers.
  template <class Out>
  HWY_INLINE void vector(const grid_row& row, std::size_t i, const Out& out) const {
    VF v, g[3];
    corners k;
    if (cols.shared) {
      axis x;
      cols.fill_axis_loaded<kGradient>(i, x);
      tables.with_entries(cols, i, [&](std::size_t b, const auto& entry) HWY_ATTR {
        if constexpr (kAffine) {
          tables.affine_from(b, x, entry, v, g);
        } else {
          tables.corners_from(b, x, k, entry);
          finish<kGradient, D>(k, x, row.y.a, row.z.a, v, g);
        }
        out(v, g);
      });
    } else {
      const DU du;
      const VU kyz[4] = {hn::Set(du, row.kyz(0, 0)), hn::Set(du, row.kyz(1, 0)),
                         hn::Set(du, row.kyz(0, 1)), hn::Set(du, row.kyz(1, 1))};
      const axis x = cols.load<kGradient>(i);
      hashed_corners<kGradient, D>(x, kyz, row.y.a, row.z.a, k);
      finish<kGradient, D>(k, x, row.y.a, row.z.a, v, g);
      out(v, g);
    }
  }
  // vector_out(i, value, gradient) for every vector of columns of `row`.
  template <class Out>
  HWY_INLINE void run(const grid_row& row, const Out& vector_out) {
    prepare(row);
    for (std::size_t i = 0; i < cols.n; i += hn::Lanes(DF()))
      vector(row, i, [&](VF v, const VF* g) HWY_ATTR { vector_out(i, v, g); });
  }
};

// Stores one vector of results for columns [i, i + lanes) of a row, through
// a buffer when the row ends inside the vector.
template <int D>
HWY_INLINE void store_row(std::size_t i, std::size_t nx, VF v, const VF* g, float* row_value,
                          float* row_grad) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const bool full = i + lanes <= nx;
  HWY_ALIGN float vb[kMaxLanes], gb[kMaxLanes * D];
  hn::StoreU(v, df, full ? row_value + i : vb);
  if (row_grad) store_interleaved<D>(g, full ? row_grad + i * D : gb);
  if (full) return;
  std::memcpy(row_value + i, vb, (nx - i) * sizeof(float));
  if (row_grad) std::memcpy(row_grad + i * D, gb, (nx - i) * D * sizeof(float));
}

// The rows (j, k) of the slab [first, first + count) of the slowest axis, in
// output order: f(j, k, r) with r the row's index inside the slab.
template <int D, class F>
HWY_INLINE void for_each_row(const grid<D>& g, std::size_t first, std::size_t count, const F& f) {
  const std::size_t j0 = D == 2 ? first : 0, j1 = D == 2 ? first + count : g.size[1];
  const std::size_t k0 = D == 3 ? first : 0, k1 = D == 3 ? first + count : 1;
  std::size_t r = 0;
  for (std::size_t k = k0; k < k1; ++k)
    for (std::size_t j = j0; j < j1; ++j, ++r) f(j, k, r);
}

template <bool kGradient, int D>
void perlin_grid(std::uint32_t key, const std::uint32_t* period, const grid<D>& g,
                 std::size_t first, std::size_t count, float* value, float* grad) {
  const std::size_t nx = g.size[0];
  const grid_columns cols(nx, period[0], kGradient,
                          [&](std::size_t i) { return g.coordinate(0, i); });
  row_evaluator<kGradient, D> rows(cols);
  grid_row row{key, {}, {}};
  std::size_t split_k = ~std::size_t(0);  // the slice row.z holds
  for_each_row<D>(g, first, count, [&](std::size_t j, std::size_t k, std::size_t r) HWY_ATTR {
    if constexpr (D == 3) {
      if (k != split_k)
        row.z = broadcast_axis<kGradient, 2>(g.coordinate(2, k), period[2]);
      split_k = k;
    }
    row.y = broadcast_axis<kGradient, 1>(g.coordinate(1, j), period[1]);
    float* row_value = value + r * nx;
    float* row_grad = kGradient ? grad + r * nx * D : nullptr;
    rows.run(row, [&](std::size_t i, VF v, const VF* gr)
                      HWY_ATTR { store_row<D>(i, nx, v, gr, row_value, row_grad); });
  });
}

}  // namespace perlin_simd

// Perlin on a uniform grid (C order, i fastest); gradients interleaved (D
// per sample) unless grad is null; the slab [first, first + count) of the
// slowest axis (hush/simd/dispatch.hpp).
template <int D>
void perlin_grid(std::uint32_t key, const std::uint32_t* period, const grid<D>& g,
                 std::size_t first, std::size_t count, float* value, float* grad) {
  if (grad)
    perlin_simd::perlin_grid<true, D>(key, period, g, first, count, value, grad);
  else
    perlin_simd::perlin_grid<false, D>(key, period, g, first, count, value, nullptr);
}
inline void perlin2_grid(std::uint32_t key, const std::uint32_t* period, const grid<2>& g,
                         std::size_t first, std::size_t count, float* value, float* grad) {
  perlin_grid<2>(key, period, g, first, count, value, grad);
}
inline void perlin3_grid(std::uint32_t key, const std::uint32_t* period, const grid<3>& g,
                         std::size_t first, std::size_t count, float* value, float* grad) {
  perlin_grid<3>(key, period, g, first, count, value, grad);
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_PERLIN_SIMD_INL_H_ toggle
