// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The pieces of Gabor noise's Highway kernels (hush/gabor/simd-inl.h) that every
// path repeats: Poisson counts and word fields of the impulses' draws, the
// separable kernel (gabor/kernel.hpp) with its taper and products in lanes, and the
// noise's constants, directions and marks as lanes. NPR Gabor noise's splats
// (hush/npr_gabor/simd-inl.h) use the kernel too.
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/gabor/simd-inl.h, never included directly by users.
#if defined(HUSH_GABOR_KERNEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_GABOR_KERNEL_INL_H_
#undef HUSH_GABOR_KERNEL_INL_H_
#else
#define HUSH_GABOR_KERNEL_INL_H_
#endif

#include <cstddef>
#include <cstdint>
#include <vector>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/detail/constants.hpp"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace gabor_simd {

// Generic lane maths (types, multiply-adds, hashes and draws, exp, sin/cos,
// the lattice split, compression).
using namespace lanes::types;

using lanes::compressor;
using lanes::draw;
using lanes::exp_neg;
using lanes::exp_neg_finite;
using lanes::exp_neg_in_range;
using lanes::hash32;
using lanes::kMaxLanes;
using lanes::mul_add;
using lanes::neg_mul_add;
using lanes::sincos_turns;
using lanes::sincos_turns_in_range;
using lanes::split_axis;
using lanes::store_interleaved;
using lanes::stream_key;
using lanes::word_x;
using lanes::word_y;
using lanes::word_z;

// Poisson counts of words u (poisson_table::count): the number of thresholds
// <= u. Short tables (the common case: 25 thresholds for N' = 16 in 2D) are
// scanned in order, stopping once no lane's word reaches the next threshold
// (about the largest count in the vector); long ones are binary-searched with
// gathers. `flipped` holds the thresholds with the sign bit flipped (unsigned
// order as signed).
constexpr std::uint32_t kLinearTable = 64;
HWY_INLINE VU table_count(const std::int32_t* flipped, std::uint32_t n, VU u) {
  const DU du;
  const DI di;
  const VI us = hn::Xor(hn::BitCast(di, u), hn::Set(di, static_cast<std::int32_t>(0x80000000U)));
  if (n <= kLinearTable) {
    VI count = hn::Zero(di);
    for (std::uint32_t k = 0; k < n; ++k) {
      const auto below = hn::Not(hn::Gt(hn::Set(di, flipped[k]), us));  // T_k <= u
      if (hn::AllFalse(di, below)) break;  // sorted: no later threshold is reached either
      count = hn::Sub(count, hn::VecFromMask(di, below));
    }
    return hn::BitCast(du, count);
  }
  VU lo = hn::Zero(du);
  std::uint32_t step = 1;
  while (step * 2 <= n) step *= 2;
  for (; step > 0; step /= 2) {
    const VU cand = hn::Add(lo, hn::Set(du, step));  // try count >= cand
    const auto ok_index =
        hn::Not(hn::Gt(hn::BitCast(di, cand), hn::Set(di, static_cast<std::int32_t>(n))));
    const VI index = hn::IfThenElseZero(ok_index, hn::Sub(hn::BitCast(di, cand), hn::Set(di, 1)));
    const VI t = hn::GatherIndex(di, flipped, index);
    const auto take = hn::And(ok_index, hn::Not(hn::Gt(t, us)));  // T[cand - 1] <= u
    lo = hn::IfThenElse(hn::RebindMask(du, take), cand, lo);
  }
  return lo;
}
// The thresholds of `table` with the sign bit flipped, for table_count.
inline std::vector<std::int32_t> flipped_thresholds(const poisson_table& table) {
  std::vector<std::int32_t> f(table.thresholds().size() + 1, 0);
  for (std::size_t i = 0; i < table.thresholds().size(); ++i)
    f[i] = static_cast<std::int32_t>(table.thresholds()[i] ^ 0x80000000U);
  return f;
}

// Fields of words (gabor.hpp detail::gabor_byte, gabor_half) as floats:
// (2m + 1) 2^-9 = m 2^-8 + 2^-9, exact whichever way it is computed.
HWY_INLINE VF byte_value(VU w, unsigned i) {
  namespace c = detail::constants;
  const DF df;
  const DU du;
  VU m = hn::ShiftRightSame(w, static_cast<int>(c::kGaborByteBits * (3u - i)));
  if (i != 0) m = hn::And(m, hn::Set(du, c::kGaborByteMask));
  return mul_add(hn::ConvertTo(df, hn::BitCast(DI(), m)),
                 hn::Set(df, float(2 * c::kGaborByteScale)),
                 hn::Set(df, float(c::kGaborByteScale)));
}
HWY_INLINE VF half_value(VU w, unsigned i) {
  namespace c = detail::constants;
  const DF df;
  const DU du;
  VU m = hn::ShiftRightSame(w, static_cast<int>(c::kGaborHalfBits * (1u - i)));
  if (i != 0) m = hn::And(m, hn::Set(du, c::kGaborHalfMask));
  return mul_add(hn::ConvertTo(df, hn::BitCast(DI(), m)),
                 hn::Set(df, float(2 * c::kGaborHalfScale)),
                 hn::Set(df, float(c::kGaborHalfScale)));
}

// ---- The kernel (gabor/kernel.hpp) in lanes.
struct axis {
  VF d, d2, e, s, c;
};
HWY_INLINE axis axis_factors(VF d, VF neg_a, VF phi) {
  axis f;
  f.d = d;
  f.d2 = hn::Mul(d, d);
  f.e = exp_neg(hn::Mul(neg_a, f.d2));
  sincos_turns(hn::Mul(phi, d), f.s, f.c);
  return f;
}
// axis_factors of an impulse within the support (|d| < 1), whose |phi d| is
// below kTurnsReduceLimit when `small_turns`: the same values.
HWY_INLINE axis axis_factors_in_support(VF d, VF neg_a, VF phi, bool small_turns) {
  axis f;
  f.d = d;
  f.d2 = hn::Mul(d, d);
  f.e = exp_neg_in_range(hn::Mul(neg_a, f.d2));
  if (small_turns)
    sincos_turns_in_range(hn::Mul(phi, d), f.s, f.c);
  else
    sincos_turns(hn::Mul(phi, d), f.s, f.c);
  return f;
}
struct row {
  VF we, c, s, d2;
};
HWY_INLINE row row_of(VF w, const axis& y) { return {hn::Mul(w, y.e), y.c, y.s, y.d2}; }
HWY_INLINE row row_of(VF w, const axis& y, const axis& z) {
  return {hn::Mul(w, hn::Mul(y.e, z.e)), hn::Sub(hn::Mul(y.c, z.c), hn::Mul(y.s, z.s)),
          hn::Add(hn::Mul(y.s, z.c), hn::Mul(y.c, z.s)), hn::Add(y.d2, z.d2)};
}
// gabor_taper_v: clamp((1 - s) k, 0, 1); 0 exactly when s >= 1.
HWY_INLINE VF taper_v(VF s, VF k) {
  const DF df;
  const VF one = hn::Set(df, 1.0f);
  return hn::Max(hn::Min(hn::Mul(hn::Sub(one, s), k), one), hn::Zero(df));
}
HWY_INLINE VF taper(VF s, VF k) {
  const DF df;
  const VF v = taper_v(s, k);
  return hn::Mul(hn::Mul(v, v), neg_mul_add(hn::Set(df, 2.0f), v, hn::Set(df, 3.0f)));
}
HWY_INLINE void taper_derivative(VF s, VF k, VF& tau, VF& dtau) {
  const DF df;
  const VF v = taper_v(s, k);
  tau = hn::Mul(hn::Mul(v, v), neg_mul_add(hn::Set(df, 2.0f), v, hn::Set(df, 3.0f)));
  dtau = hn::Mul(hn::Mul(hn::Set(df, -6.0f), k), hn::Mul(v, hn::Sub(hn::Set(df, 1.0f), v)));
}
// gabor_pair_of_products: (ec b - es q) tau(s), 0 for s >= 1.
HWY_INLINE VF pair_of_products(VF ec, VF es, VF b, VF q, VF s, VF k) {
  return hn::Mul(neg_mul_add(es, q, hn::Mul(ec, b)), taper(s, k));
}
// gabor_pair: the products of x's and the row's factors, then the above.
HWY_INLINE VF pair(const axis& x, const row& r, VF k) {
  return pair_of_products(hn::Mul(x.e, x.c), hn::Mul(x.e, x.s), hn::Mul(r.we, r.c),
                          hn::Mul(r.we, r.s), hn::Add(x.d2, r.d2), k);
}
// gabor_gradient_of_harmonics: value, u, v with dg/dd_a = u d_a - v phi_a
// from pc = p cos, ps = p sin.
HWY_INLINE void gradient_of_harmonics(VF pc, VF ps, VF s, VF k, VF a, VF& value, VF& u, VF& v) {
  const DF df;
  VF tau, dtau;
  taper_derivative(s, k, tau, dtau);
  value = hn::Mul(pc, tau);
  u = hn::Mul(hn::Add(pc, pc), neg_mul_add(a, tau, dtau));
  v = hn::Mul(hn::Set(df, float(detail::constants::kTwoPi)), hn::Mul(ps, tau));
}
// gabor_pair_gradient_of_products.
HWY_INLINE void pair_gradient_of_products(VF ec, VF es, VF b, VF q, VF s, VF k, VF a, VF& value,
                                          VF& u, VF& v) {
  gradient_of_harmonics(neg_mul_add(es, q, hn::Mul(ec, b)), mul_add(es, b, hn::Mul(ec, q)), s, k,
                        a, value, u, v);
}
// gabor_pair_with_gradient.
HWY_INLINE void pair_gradient(const axis& x, const row& r, VF k, VF a, VF& value, VF& u, VF& v) {
  pair_gradient_of_products(hn::Mul(x.e, x.c), hn::Mul(x.e, x.s), hn::Mul(r.we, r.c),
                            hn::Mul(r.we, r.s), hn::Add(x.d2, r.d2), k, a, value, u, v);
}

// ---- The noise's constants as lanes.
template <int D>
struct consts {
  VF neg_a, a, k, scale, grad_scale;
  // Marks (gabor_marks): 2D theta0 and spread (turns), phi0, dphi, the fixed
  // frequency (anisotropic); 3D frame and cap.
  VF theta0, spread, phi0, dphi, half, fixed[3], axis[3], frame_t[3], frame_b[3], frame_axis[3],
      one_minus_cap;
  gabor_kind kind;
  // Every impulse's |phi_a d_a| (|d_a| < 1) is below kTurnsReduceLimit.
  bool small_turns;
  explicit consts(const gabor<D>& g) {
    const DF df;
    neg_a = hn::Set(df, float(-g.kernel().envelope_exponent()));
    a = hn::Set(df, float(g.kernel().envelope_exponent()));
    k = hn::Set(df, float(1.0 / (1.0 - detail::constants::kGaborTaperStart)));
    scale = hn::Set(df, float(g.scale()));
    grad_scale = hn::Set(df, float(g.scale() * g.inverse_cell()));
    const gabor_marks<D>& m = g.marks();
    kind = m.kind();
    theta0 = hn::Set(df, float(m.theta0()));
    spread = hn::Set(df, float(m.spread_turns()));
    phi0 = hn::Set(df, float(m.phi0()));
    dphi = hn::Set(df, float(m.dphi()));
    half = hn::Set(df, 0.5f);
    one_minus_cap = hn::Set(df, float(1.0 - m.cos_cap()));
    // |phi| <= phi0 + dphi / 2 (hybrid; phi0 otherwise), with room for rounding.
    small_turns = m.phi0() + m.dphi() < 0.5 * detail::constants::kTurnsReduceLimit;
    for (int i = 0; i < 3; ++i) {
      fixed[i] = hn::Set(df, i < D ? float(m.fixed_frequency()[i]) : 0.0f);
      axis[i] = hn::Set(df, i < D ? float(m.axis()[i]) : 0.0f);
      frame_t[i] = hn::Set(df, float(m.frame_t()[i]));
      frame_b[i] = hn::Set(df, float(m.frame_b()[i]));
      frame_axis[i] = hn::Set(df, float(m.frame_axis()[i]));
    }
  }
};

// gabor_marks<3>::direction in lanes.
template <int D>
HWY_INLINE void direction(const consts<D>& c, VF u1, VF u2, VF* dir) {
  const DF df;
  const VF one = hn::Set(df, 1.0f);
  const VF ct = neg_mul_add(c.one_minus_cap, u1, one);
  const VF st = hn::Sqrt(hn::Mul(hn::Sub(one, ct), hn::Add(one, ct)));
  VF s, co;
  sincos_turns(u2, s, co);
  const VF lx = hn::Mul(st, co), ly = hn::Mul(st, s);
  for (int i = 0; i < 3; ++i)
    dir[i] = mul_add(c.frame_axis[i], ct, mul_add(c.frame_t[i], lx, hn::Mul(c.frame_b[i], ly)));
}

// gabor<D>::mark_values + gabor_marks::draw from an impulse's words: the
// weight and frequency vector (cycles per cell).
template <int D>
HWY_INLINE void marks(const consts<D>& c, const VU* words, VF& w, VF* phi) {
  const DF df;
  w = hn::Sub(hn::Mul(hn::Set(df, 2.0f), byte_value(words[0], D)), hn::Set(df, 1.0f));
  if (c.kind == gabor_kind::anisotropic) {
    for (int i = 0; i < D; ++i) phi[i] = c.fixed[i];
    return;
  }
  const bool hybrid = c.kind == gabor_kind::hybrid;
  if constexpr (D == 2) {
    const VF f =
        hybrid ? mul_add(c.dphi, hn::Sub(half_value(words[1], 0), c.half), c.phi0) : c.phi0;
    VF s, co;
    sincos_turns(mul_add(c.spread, hn::Sub(byte_value(words[0], 3), c.half), c.theta0), s, co);
    phi[0] = hn::Mul(f, co);
    phi[1] = hn::Mul(f, s);
  } else {
    const VF f =
        hybrid ? mul_add(c.dphi, hn::Sub(half_value(words[2], 0), c.half), c.phi0) : c.phi0;
    VF dir[3];
    direction(c, half_value(words[1], 0), half_value(words[1], 1), dir);
    for (int i = 0; i < 3; ++i) phi[i] = hn::Mul(f, dir[i]);
  }
}

}  // namespace gabor_simd
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_GABOR_KERNEL_INL_H_ toggle
