// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernels for Gabor noise (hush/gabor.hpp): points, uniform grids and
// samples with footprints (filtered, 2D and 3D), values and optionally
// gradients, and samples with normals (surface noise). Compiled once per
// SIMD target (the "-inl.h" convention: toggle include guard below); reached through
// hush/simd/dispatch.hpp, never included directly by users.
//
// They repeat gabor.hpp's float algorithm operation by operation: the same
// lattice split (in double), per-cell hush::rng streams and Poisson table
// counts (integer comparisons), the same word fields and marks, hush's own exp
// and sin/cos (simd/lanes-inl.h, mirroring detail/elementary.hpp),
// the same separable kernel products and taper, and, per sample, the same
// order of accumulation (cells in raster order, impulses in stream order):
//  - under HUSH_STRICT_FP every value and gradient is bit for bit the scalar
//    result (tests/simd/gabor_simd_test.cpp, every compiled target);
//  - otherwise multiply-adds may be fused, within the float budget of
//    gabor.hpp.
// How they are fast:
//  - points and filtered samples where the call crowds them (at least
//    kShareMinPointsPerCell per cell of their range): sorted by cell, each cell's impulses
//    drawn once for all the points that see it; per cell its 3^D cells' impulses copied once
//    into one candidate list in the summation order, which each of its points tests in full
//    vectors (lanes across impulses, no branch) and compresses the kept ones into a pair
//    list; the kernel then runs over the list (shared_points below). Filtered samples:
//    each point's filter computed once in double; in 2D (values) the test also computes
//    each candidate's exponent and phase with the point's filter, in 3D and with
//    gradients each lane of the kernel takes its point's filter by a permutation
//    (shared_filtered);
//  - other points and filtered samples, and samples with normals: one lane per point
//    (samples: each lane's filter, and for surface noise its tangent frame, computed in double
//    as the scalar code does, and gathered per term); per cell and impulse the lanes draw in
//    lockstep (the counter's hash is shared), and only impulses within a lane's support are
//    kept, compressed into a list that the kernel then evaluates in full vectors; each
//    point's terms are summed in stream order. The unfiltered kernel of kept impulses skips exp's and sin/cos's range
//    handling (identities within the support: exp_neg_in_range, sincos_turns_in_range);
//  - grids: samples in blocks that share their cell along y (and z) and span several cells
//    along x (kBlockX: 256 samples per row, up to 64 rows; 3D 64 x 32 x 16), each impulse of
//    the cells that the block's samples see evaluated once per block: its factors along y
//    (and z) once per row (slice), along x once per column, and per sample only their products
//    (gabor_kernel.hpp's separable form), unmasked (the float taper is exactly 0 outside the
//    support) over the x-vectors that reach the impulse's disk in that row (the row skip);
//    each cell's impulses drawn once into a small cache for the blocks that see it (the draw
//    cache). Grids with fewer than kMinRun samples per cell along x go through the points
//    path instead.

#if defined(HUSH_GABOR_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_GABOR_SIMD_INL_H_
#undef HUSH_GABOR_SIMD_INL_H_
#else
#define HUSH_GABOR_SIMD_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/constants.hpp"
#include "hush/simd/lanes-inl.h"

// The noise class comes first, not from here: hush/gabor.hpp includes these
// kernels at its end (hush/gabor/simd_kernel.hpp), as src/simd/gabor.cpp does.
HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace gabor_simd {

// Generic lane maths (types, multiply-adds, hashes, exp, sin/cos, compression).
using namespace lanes::types;

using lanes::compressor;
using lanes::exp_neg;
using lanes::exp_neg_finite;
using lanes::exp_neg_in_range;
using lanes::hash32;
using lanes::kMaxLanes;
using lanes::mul_add;
using lanes::neg_mul_add;
using lanes::sincos_turns;
using lanes::sincos_turns_in_range;
using lanes::store_interleaved;
using lanes::word_x;
using lanes::word_y;
using lanes::word_z;

// Grids with fewer samples per cell along x than this take the points path.
constexpr double kMinRun = 8.0;
// Grid blocks' width along x (2D, 3D): several cells, so that an impulse's
// factors along y (and z) serve that many samples; the block's sums stay in
// L1/L2 (2D: rows of one cell, ~64 x 256 floats; 3D: 32 x 16 rows).
constexpr std::size_t kBlockX[2] = {256, 64};

// ---- hush::rng in lanes.
// hush::rng(seed, stream)'s key: hash32(seed, stream) = hash32(hash32(seed + gamma) ^ stream).
HWY_INLINE VU stream_key(VU seed, std::uint32_t stream) {
  const DU du;
  return hash32(hn::Xor(hash32(hn::Add(seed, hn::Set(du, detail::constants::kGoldenGamma))),
                        hn::Set(du, stream)));
}
// Draw `counter` of the streams with keys `key`: hash32(key ^ hash32(counter)).
HWY_INLINE VU draw(VU key, std::uint32_t counter) {
  return hash32(hn::Xor(key, hn::Set(DU(), hush::hash32(counter))));
}

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

// ---- The kernel (gabor_kernel.hpp) in lanes.
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

// ---- One lane per point: candidates, then the kernel over the kept ones.

// The impulses kept for a batch of lanes, in the order each lane sums them.
struct tuples {
  std::vector<std::uint32_t> lane, w0, w1, w2;
  std::vector<float> d[3];
  std::vector<float> val, g[3];
  std::size_t n = 0;
  void reserve(std::size_t cap) {
    const std::size_t c = cap + kMaxLanes;
    for (auto* v : {&lane, &w0, &w1, &w2}) v->resize(c);
    for (auto* v : {&d[0], &d[1], &d[2], &val, &g[0], &g[1], &g[2]}) v->resize(c);
  }
};

// A lane batch's split positions: per axis the cell and the fraction (cell
// units), as lattice_split<float> of position * inverse cell in double.
struct lanes_split {
  HWY_ALIGN std::uint32_t cell[3][kMaxLanes];
  HWY_ALIGN float frac[3][kMaxLanes];
  bool bad[kMaxLanes];  // a non-finite coordinate: the result is NaN
  // Filtered samples: each lane's filter amplitude, which scales its sums (1: unfiltered).
  float amp[kMaxLanes];
  lanes_split() { std::fill(amp, amp + kMaxLanes, 1.0f); }
};

// Appends to `t` every impulse of the process (solid: `table`, `stream`, the
// 3^E cells around each lane's cell) within a lane's support, in raster order
// of the cells and stream order of the impulses. `keep(d, d2, s)` is the
// support test per lane (a mask over the lanes); E is the process's dimension.
template <int E, class Keep>
void collect(std::uint32_t key, std::uint32_t stream, const std::vector<std::int32_t>& flipped,
             int words, const lanes_split& sp, tuples& t, Keep keep) {
  const DF df;
  const DU du;
  const DI di;
  const VU lane_ids = hn::Iota(du, 0);
  VU base[3];
  VF frac[3];
  for (int a = 0; a < E; ++a) {
    base[a] = hn::Load(du, sp.cell[a]);
    frac[a] = hn::Load(df, sp.frac[a]);
  }
  const std::int32_t* thr = flipped.data();
  const auto nthr = static_cast<std::uint32_t>(flipped.size() - 1);
  constexpr int kCells = E == 2 ? 9 : 27;
  t.n = 0;
  for (int n = 0; n < kCells; ++n) {
    int o[3] = {0, 0, 0};
    for (int a = 0, m = n; a < E; ++a, m /= 3) o[a] = m % 3 - 1;
    VU h = hn::Xor(hn::Set(du, key),
                   word_x(hn::Add(base[0], hn::Set(du, static_cast<std::uint32_t>(o[0])))));
    h = hn::Xor(h, word_y(hn::Add(base[1], hn::Set(du, static_cast<std::uint32_t>(o[1])))));
    if constexpr (E == 3)
      h = hn::Xor(h, word_z(hn::Add(base[2], hn::Set(du, static_cast<std::uint32_t>(o[2])))));
    const VU skey = stream_key(hash32(h), stream);
    const VU count = nthr == 0 ? hn::Zero(du) : table_count(thr, nthr, draw(skey, 0));
    const std::uint32_t kmax = hn::GetLane(hn::MaxOfLanes(du, count));
    VF ov[3];  // the cell offset o; an impulse's offset is frac - (o + u) (detail::gabor_offset)
    for (int a = 0; a < E; ++a) ov[a] = hn::Set(df, float(o[a]));
    for (std::uint32_t k = 0; k < kmax; ++k) {
      const std::uint32_t counter = 1 + k * static_cast<std::uint32_t>(words);
      VU w[3];
      w[0] = draw(skey, counter);
      VF d[3], d2[3];
      for (int a = 0; a < E; ++a) {
        d[a] = hn::Sub(frac[a], hn::Add(ov[a], byte_value(w[0], static_cast<unsigned>(a))));
        d2[a] = hn::Mul(d[a], d[a]);
      }
      const auto active =
          hn::RebindMask(df, hn::Lt(hn::BitCast(di, hn::Set(du, k)), hn::BitCast(di, count)));
      const MF in = hn::And(active, keep(d, d2));
      if (hn::AllFalse(df, in)) continue;
      for (int j = 1; j < words; ++j) w[j] = draw(skey, counter + static_cast<std::uint32_t>(j));
      // Compress in registers, then store whole vectors (the buffers have a
      // vector of slack): the memory form of compress is microcoded and slow
      // on some CPUs (AMD Zen 4).
      const compressor kept(in);
      const std::size_t at = t.n;
      hn::StoreU(kept(lane_ids), du, t.lane.data() + at);
      for (int a = 0; a < E; ++a) hn::StoreU(kept(d[a]), df, t.d[a].data() + at);
      std::uint32_t* wd[3] = {t.w0.data(), t.w1.data(), t.w2.data()};
      for (int j = 0; j < words; ++j) hn::StoreU(kept(w[j]), du, wd[j] + at);
      t.n = at + hn::CountTrue(df, in);
    }
  }
}

// s = |d|^2 and theta = <phi, d> (gabor_point_phase) in the scalar order.
template <int D>
HWY_INLINE VF point_s(const VF* d) {
  if constexpr (D == 2)
    return hn::Add(hn::Mul(d[0], d[0]), hn::Mul(d[1], d[1]));
  else
    return hn::Add(hn::Mul(d[0], d[0]), hn::Add(hn::Mul(d[1], d[1]), hn::Mul(d[2], d[2])));
}
template <int D>
HWY_INLINE VF point_phase(const VF* phi, const VF* d) {
  if constexpr (D == 2)
    return mul_add(phi[1], d[1], hn::Mul(phi[0], d[0]));
  else
    return mul_add(phi[0], d[0], mul_add(phi[2], d[2], hn::Mul(phi[1], d[1])));
}
// sin/cos(2 pi theta) of kept impulses: |theta| <= |phi| |d| < |phi|, so
// c.small_turns holds for theta as for each axis' phase.
template <int D>
HWY_INLINE void sincos_kept(const consts<D>& c, VF theta, VF& sn, VF& cs) {
  if (c.small_turns)
    sincos_turns_in_range(theta, sn, cs);
  else
    sincos_turns(theta, sn, cs);
}
// gabor_point_term of kept impulses (s < 1): w e^{-A s} cos(2 pi theta) tau(s).
template <int D>
HWY_INLINE VF point_value(const consts<D>& c, VF w, VF s, VF theta) {
  VF sn, cs;
  sincos_kept(c, theta, sn, cs);
  return hn::Mul(hn::Mul(hn::Mul(w, exp_neg_in_range(hn::Mul(c.neg_a, s))), cs), taper(s, c.k));
}

// The unfiltered kernel (gabor<D>::eval) of one vector of impulses with
// weight wt, frequency phi and offsets d, in the point form (gabor_point_term)
// or with Grid the separable pair (gabor_pair; grids on the points path): the
// value into val, and with G the gradient terms u d_a - v phi_a into g[a].
// Lanes outside the support (s >= 1: the padding of a pair list) give values
// that nobody reads.
template <int D, bool G, bool Grid>
HWY_INLINE void unfiltered_terms(const consts<D>& c, VF wt, const VF* phi, const VF* d,
                                 float* HWY_RESTRICT val, float* const* g) {
  const DF df;
  VF value, u, v;
  if constexpr (Grid) {
    axis ax[3];
    for (int a = 0; a < D; ++a)
      ax[a] = axis_factors_in_support(d[a], c.neg_a, phi[a], c.small_turns);
    row r;
    if constexpr (D == 2)
      r = row_of(wt, ax[1]);
    else
      r = row_of(wt, ax[1], ax[2]);
    if constexpr (G)
      pair_gradient(ax[0], r, c.k, c.a, value, u, v);
    else
      value = pair(ax[0], r, c.k);
  } else {
    const VF s = point_s<D>(d), theta = point_phase<D>(phi, d);
    if constexpr (G) {
      VF sn, cs;
      sincos_kept(c, theta, sn, cs);
      const VF p = hn::Mul(wt, exp_neg_in_range(hn::Mul(c.neg_a, s)));
      gradient_of_harmonics(hn::Mul(p, cs), hn::Mul(p, sn), s, c.k, c.a, value, u, v);
    } else {
      value = point_value(c, wt, s, theta);
    }
  }
  hn::StoreU(value, df, val);
  if constexpr (G)
    for (int a = 0; a < D; ++a) hn::StoreU(hn::Sub(hn::Mul(u, d[a]), hn::Mul(v, phi[a])), df, g[a]);
}

// The unfiltered kernel of every kept impulse (gabor<D>::eval; Grid: the
// separable pair), into t.val (and with G, the gradient terms u d_a - v phi_a
// into t.g).
template <int D, bool G, bool Grid>
void eval_unfiltered(const consts<D>& c, tuples& t) {
  const DF df;
  const DU du;
  const std::size_t lanes = hn::Lanes(df);
  for (std::size_t i = 0; i < t.n; i += lanes) {
    VU w[3] = {hn::LoadU(du, t.w0.data() + i), hn::LoadU(du, t.w1.data() + i),
               hn::LoadU(du, t.w2.data() + i)};
    VF wt, phi[3], d[3];
    marks<D>(c, w, wt, phi);
    for (int a = 0; a < D; ++a) d[a] = hn::LoadU(df, t.d[a].data() + i);
    float* const g[3] = {t.g[0].data() + i, t.g[1].data() + i, t.g[2].data() + i};
    unfiltered_terms<D, G, Grid>(c, wt, phi, d, t.val.data() + i, g);
  }
}

// Per-lane filters of a batch (gabor<D>::filtered_eval): gabor_filter<D> of each lane's
// footprint in double, as detail::gabor_filter_coefs<float, E> (Q's upper triangle q, M's
// with its off-diagonal doubled m2); the amplitude goes to lanes_split::amp.
// Per lane: q and -m2 (detail::gabor_filter_coefs, m2 negated: see filtered_exponent).
struct lanes_filter {
  HWY_ALIGN float q[6][kMaxLanes];
  HWY_ALIGN float nm2[6][kMaxLanes];
  template <int E>
  void set(std::size_t l, const detail::gabor_filter_coefs<float, E>& f) {
    for (int e = 0; e < f.kSize; ++e) {
      q[e][l] = f.q[e];
      nm2[e][l] = -f.m2[e];
    }
  }
};

// The filtered kernel's exponent -A d^T Q d - Phi^T M Phi and phase <Phi, Q d>
// (gabor<D>::filtered_pair's order) of offsets d and frequencies phi; qd = Q d.
// pp: Phi_r Phi_c for r <= c (detail::gabor_sym order). nm2: -m2, so that the sum is
// -Phi^T M Phi itself (negation is exact: the same x as the scalar order, one
// operation fewer).
template <int E>
HWY_INLINE void filtered_exponent(VF neg_a, const VF* q, const VF* nm2, const VF* d, const VF* phi,
                                  const VF* pp, VF* qd, VF& x, VF& theta) {
  for (int r = 0; r < E; ++r) {
    VF z = hn::Mul(q[detail::gabor_sym<E>(r, 0)], d[0]);
    for (int col = 1; col < E; ++col) z = mul_add(q[detail::gabor_sym<E>(r, col)], d[col], z);
    qd[r] = z;
  }
  VF dqd = hn::Mul(d[0], qd[0]);
  theta = hn::Mul(phi[0], qd[0]);
  for (int r = 1; r < E; ++r) {
    dqd = mul_add(d[r], qd[r], dqd);
    theta = mul_add(phi[r], qd[r], theta);
  }
  VF natt = hn::Mul(nm2[0], pp[0]);
  for (int k = 1; k < E * (E + 1) / 2; ++k) natt = mul_add(nm2[k], pp[k], natt);
  // d^T Q d in [0, s] and att in [0, pi^2 |Phi|^2 / A) up to rounding (Q's eigenvalues
  // in (0, 1], M's in [0, pi^2 / A); rounded to float either may be slightly
  // indefinite: exp_neg_finite takes a positive sum as 0). Both are finite for every
  // footprint (gabor_filter clamps the eigenvalues, NaN too). |theta| <= |Q Phi| |d| <
  // |Phi| (sincos_kept).
  x = mul_add(neg_a, dqd, natt);
}
template <int E>
HWY_INLINE void phi_products(const VF* phi, VF* pp) {
  for (int r = 0, k = 0; r < E; ++r)
    for (int col = r; col < E; ++col, ++k) pp[k] = hn::Mul(phi[r], phi[col]);
}

// gabor<D>::filtered_pair in lanes, operation by operation, in E dimensions:
// filter q, -m2 (detail::gabor_filter_coefs; filtered_exponent) per lane, offsets d, s = |d|^2,
// weight w, frequency phi; the term (without the amplitude) into value and, with G, its
// derivative by d into grad.
template <int D, int E, bool G>
HWY_INLINE void filtered_pair(const consts<D>& c, const VF* q, const VF* nm2, const VF* d, VF s,
                              VF w, const VF* phi, VF& value, VF* grad) {
  const DF df;
  VF qd[E], pp[E * (E + 1) / 2], x, theta;
  phi_products<E>(phi, pp);
  filtered_exponent<E>(c.neg_a, q, nm2, d, phi, pp, qd, x, theta);
  const VF p = hn::Mul(w, exp_neg_finite(x));
  VF sn, cs;
  sincos_kept(c, theta, sn, cs);
  if constexpr (G) {
    VF mu[E];  // Q Phi
    for (int r = 0; r < E; ++r) {
      mu[r] = hn::Mul(q[detail::gabor_sym<E>(r, 0)], phi[0]);
      for (int col = 1; col < E; ++col)
        mu[r] = mul_add(q[detail::gabor_sym<E>(r, col)], phi[col], mu[r]);
    }
    VF tau, dtau;
    taper_derivative(s, c.k, tau, dtau);
    const VF pc = hn::Mul(p, cs);
    const VF ps =
        hn::Mul(hn::Set(df, float(detail::constants::kTwoPi)), hn::Mul(hn::Mul(p, tau), sn));
    value = hn::Mul(pc, tau);
    const VF dtau2 = hn::Add(dtau, dtau), a2 = hn::Add(c.a, c.a);
    for (int r = 0; r < E; ++r) {
      const VF inner = neg_mul_add(a2, hn::Mul(tau, qd[r]), hn::Mul(dtau2, d[r]));
      grad[r] = neg_mul_add(ps, mu[r], hn::Mul(pc, inner));
    }
  } else {
    value = hn::Mul(hn::Mul(p, cs), taper(s, c.k));
  }
}

// The filtered kernel of every kept impulse (gabor<D>::filtered_eval), each with its
// lane's filter (gathered by the tuple's lane).
template <int D, bool G>
void eval_filtered(const consts<D>& c, const lanes_filter& f, tuples& t) {
  const DF df;
  const DU du;
  const DI di;
  const std::size_t lanes = hn::Lanes(df);
  for (std::size_t i = 0; i < t.n; i += lanes) {
    VU w[3] = {hn::LoadU(du, t.w0.data() + i), hn::LoadU(du, t.w1.data() + i),
               hn::LoadU(du, t.w2.data() + i)};
    const VI li = hn::BitCast(di, hn::LoadU(du, t.lane.data() + i));
    VF wt, phi[3], d[3], d2[3], q[D * (D + 1) / 2], m[D * (D + 1) / 2];
    marks<D>(c, w, wt, phi);
    for (int a = 0; a < D; ++a) {
      d[a] = hn::LoadU(df, t.d[a].data() + i);
      d2[a] = hn::Mul(d[a], d[a]);
    }
    const VF s = D == 2 ? hn::Add(d2[0], d2[1]) : hn::Add(d2[0], hn::Add(d2[1], d2[2]));
    for (int e = 0; e < D * (D + 1) / 2; ++e) {
      q[e] = hn::GatherIndex(df, f.q[e], li);
      m[e] = hn::GatherIndex(df, f.nm2[e], li);
    }
    VF value, g[3];
    filtered_pair<D, D, G>(c, q, m, d, s, wt, phi, value, g);
    hn::StoreU(value, df, t.val.data() + i);
    if constexpr (G)
      for (int a = 0; a < D; ++a) hn::StoreU(g[a], df, t.g[a].data() + i);
  }
}

// Per-lane tangent frames of a batch of surface samples (gabor<3>::surface_eval):
// unit normal n and tangents t, b, rounded to float as the scalar code rounds them.
struct lanes_frame {
  HWY_ALIGN float n[3][kMaxLanes];
  HWY_ALIGN float t[3][kMaxLanes];
  HWY_ALIGN float b[3][kMaxLanes];
};

// (a0 d0 + a1 d1) + a2 d2, as the scalar code writes it.
HWY_INLINE VF dot3(const VF* a, const VF* d) {
  return mul_add(a[2], d[2], mul_add(a[1], d[1], hn::Mul(a[0], d[0])));
}

// Surface noise's distances of offsets d (surface-cell units) to the lane's
// plane: zn along the normal, z2 = zn^2 / h^2, and dk, s = |dk|^2 in the plane
// (kernel cell units).
struct plane_offsets {
  VF zn, z2, dk[2], s;
};
HWY_INLINE plane_offsets plane_of(const VF* d, const VF* nt, const VF* tt, const VF* bt) {
  namespace k = detail::constants;
  const DF df;
  const VF to_kernel = hn::Set(df, float(k::kGaborSurfaceCell));
  const VF inv_h2 = hn::Set(df, float((k::kGaborSurfaceCell / k::kGaborSurfaceSlab) *
                                      (k::kGaborSurfaceCell / k::kGaborSurfaceSlab)));
  plane_offsets o;
  o.zn = dot3(nt, d);
  o.z2 = hn::Mul(hn::Mul(o.zn, o.zn), inv_h2);
  o.dk[0] = hn::Mul(dot3(tt, d), to_kernel);
  o.dk[1] = hn::Mul(dot3(bt, d), to_kernel);
  o.s = mul_add(o.dk[1], o.dk[1], hn::Mul(o.dk[0], o.dk[0]));
  return o;
}

// The surface kernel of every kept impulse (gabor<3>::surface_eval's loop body,
// operation by operation), each with its lane's frame and plane filter.
template <bool G>
void eval_surface(const consts<3>& c, const lanes_filter& f, const lanes_frame& fr, tuples& t) {
  namespace k = detail::constants;
  const DF df;
  const DU du;
  const DI di;
  const std::size_t lanes = hn::Lanes(df);
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f), two = hn::Set(df, 2.0f);
  const VF to_kernel = hn::Set(df, float(k::kGaborSurfaceCell));
  const VF inv_h2 = hn::Set(df, float((k::kGaborSurfaceCell / k::kGaborSurfaceSlab) *
                                      (k::kGaborSurfaceCell / k::kGaborSurfaceSlab)));
  for (std::size_t i = 0; i < t.n; i += lanes) {
    const VU w[3] = {hn::LoadU(du, t.w0.data() + i), hn::LoadU(du, t.w1.data() + i),
                     hn::LoadU(du, t.w2.data() + i)};
    const VI li = hn::BitCast(di, hn::LoadU(du, t.lane.data() + i));
    VF d[3], nt[3], tt[3], bt[3];
    for (int a = 0; a < 3; ++a) {
      d[a] = hn::LoadU(df, t.d[a].data() + i);
      nt[a] = hn::GatherIndex(df, fr.n[a], li);
      tt[a] = hn::GatherIndex(df, fr.t[a], li);
      bt[a] = hn::GatherIndex(df, fr.b[a], li);
    }
    const plane_offsets o = plane_of(d, nt, tt, bt);
    // The impulse's weight, 3D direction (anisotropic: omega0) and |Phi|.
    const VF wt = hn::Sub(hn::Mul(two, byte_value(w[0], 3)), one);
    VF dir[3], phi = c.phi0;
    if (c.kind == gabor_kind::anisotropic) {
      for (int a = 0; a < 3; ++a) dir[a] = c.axis[a];
    } else {
      direction(c, half_value(w[1], 0), half_value(w[1], 1), dir);
      if (c.kind == gabor_kind::hybrid)
        phi = mul_add(c.dphi, hn::Sub(half_value(w[2], 0), c.half), c.phi0);
    }
    const VF vt = dot3(tt, dir), vb = dot3(bt, dir);
    VF fq = phi;
    if (c.kind != gabor_kind::anisotropic) {
      const VF len2 = mul_add(vb, vb, hn::Mul(vt, vt));
      fq = hn::IfThenElseZero(hn::Gt(len2, zero), hn::Div(phi, hn::Sqrt(len2)));
    }
    const VF ph[2] = {hn::Mul(fq, vt), hn::Mul(fq, vb)};
    VF q[3], m[3];
    for (int e = 0; e < 3; ++e) {
      q[e] = hn::GatherIndex(df, f.q[e], li);
      m[e] = hn::GatherIndex(df, f.nm2[e], li);
    }
    VF slab_tau, slab_dtau;
    taper_derivative(o.z2, c.k, slab_tau, slab_dtau);
    VF gs, gk[2];
    filtered_pair<3, 2, G>(c, q, m, o.dk, o.s, wt, ph, gs, gk);
    hn::StoreU(hn::Mul(gs, slab_tau), df, t.val.data() + i);
    if constexpr (G) {
      // d/dd of (kernel * slab taper): in the plane through dk, along n through z2.
      const VF dz = hn::Mul(gs, hn::Mul(slab_dtau, hn::Mul(hn::Add(o.zn, o.zn), inv_h2)));
      for (int a = 0; a < 3; ++a) {
        const VF in_plane = hn::Mul(mul_add(gk[1], bt[a], hn::Mul(gk[0], tt[a])), to_kernel);
        hn::StoreU(mul_add(dz, nt[a], hn::Mul(in_plane, slab_tau)), df, t.g[a].data() + i);
      }
    }
  }
}

// detail::gabor_point_sum of the n terms v[0, n): term q into partial sum
// q mod 4 (one 4-lane vector; missing terms are +0, which changes no partial
// sum), then (s0 + s1) + (s2 + s3). The first kPointSumChunks chunks of four
// without a branch on n (a loop's exit, mispredicted once per point, cost ~7 ns
// per 2D point); v is read up to 4 kPointSumChunks floats from v, whatever n.
constexpr std::size_t kPointSumChunks = 6;  // 24 terms: a point's 16 (N' = 16) and more
HWY_INLINE float point_sum(const float* HWY_RESTRICT v, std::size_t n) {
  const hn::CappedTag<float, 4> d4;
  HWY_ALIGN float part[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  if (hn::Lanes(d4) == 4) {
    const hn::RebindToSigned<decltype(d4)> i4;
    const auto lane = hn::Iota(i4, 0);
    const auto count =
        hn::Set(i4, static_cast<std::int32_t>(std::min<std::size_t>(n, 4 * kPointSumChunks)));
    auto acc = hn::Zero(d4);
    HWY_UNROLL(6)
    for (std::size_t k = 0; k < kPointSumChunks; ++k) {
      const auto in = hn::Lt(hn::Add(lane, hn::Set(i4, static_cast<std::int32_t>(4 * k))), count);
      acc = hn::Add(acc, hn::IfThenElseZero(hn::RebindMask(d4, in), hn::LoadU(d4, v + 4 * k)));
    }
    for (std::size_t q = 4 * kPointSumChunks; HWY_UNLIKELY(q < n); q += 4)
      acc = hn::Add(acc, hn::IfThenElseZero(hn::FirstN(d4, n - q), hn::LoadU(d4, v + q)));
    hn::Store(acc, d4, part);
  } else {  // HWY_SCALAR: one lane
    for (std::size_t q = 0; q < n; ++q) part[q & 3] += v[q];
  }
  return (part[0] + part[1]) + (part[2] + part[3]);
}

// Sums each lane's terms in their order and writes value = sum * scale (and
// gradient = g * gradient scale), NaN for bad lanes. `used` lanes are written.
// Fours: the point form's sum by fours (detail::gabor_point_sum; a lane's
// q-th term into its partial sum q mod 4), else one chain per lane.
template <int D, bool G, bool Fours = false>
void finish(const tuples& t, const lanes_split& sp, std::size_t used, float scale, float grad_scale,
            float* value, float* grad) {
  float sum[kMaxLanes], g[3][kMaxLanes];
  const std::size_t lanes = hn::Lanes(DF());
  if constexpr (Fours) {
    float part[4][kMaxLanes], gpart[3][4][kMaxLanes];
    std::uint32_t k[kMaxLanes];
    std::fill(k, k + lanes, 0u);
    for (int j = 0; j < 4; ++j) {
      std::fill(part[j], part[j] + lanes, 0.0f);
      if constexpr (G)
        for (int a = 0; a < D; ++a) std::fill(gpart[a][j], gpart[a][j] + lanes, 0.0f);
    }
    for (std::size_t i = 0; i < t.n; ++i) {
      const std::uint32_t l = t.lane[i], j = k[l]++ & 3u;
      part[j][l] += t.val[i];
      if constexpr (G)
        for (int a = 0; a < D; ++a) gpart[a][j][l] += t.g[a][i];
    }
    for (std::size_t l = 0; l < lanes; ++l) {
      sum[l] = (part[0][l] + part[1][l]) + (part[2][l] + part[3][l]);
      if constexpr (G)
        for (int a = 0; a < D; ++a)
          g[a][l] = (gpart[a][0][l] + gpart[a][1][l]) + (gpart[a][2][l] + gpart[a][3][l]);
    }
  } else {
    std::fill(sum, sum + lanes, 0.0f);
    if constexpr (G)
      for (int a = 0; a < D; ++a) std::fill(g[a], g[a] + lanes, 0.0f);
    for (std::size_t i = 0; i < t.n; ++i) {
      const std::uint32_t l = t.lane[i];
      sum[l] += t.val[i];
      if constexpr (G)
        for (int a = 0; a < D; ++a) g[a][l] += t.g[a][i];
    }
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // (sum * amplitude) * scale as the scalar code (amplitude 1 unfiltered: the same value).
  for (std::size_t l = 0; l < used; ++l) {
    value[l] = sp.bad[l] ? nan : (sum[l] * sp.amp[l]) * scale;
    if constexpr (G)
      for (int a = 0; a < D; ++a)
        grad[l * D + a] = sp.bad[l] ? nan : (g[a][l] * sp.amp[l]) * grad_scale;
  }
}

// Splits lane l's coordinates x (double) into cell and fraction with the
// inverse cell side `inv` (gabor<D>::eval's split).
template <int D>
HWY_INLINE void split_lane(lanes_split& sp, std::size_t l, const double* x, double inv) {
  bool bad = false;
  for (int a = 0; a < D; ++a) {
    const lattice_coord<float> c = lattice_split<float>(x[a] * inv);
    sp.cell[a][l] = c.i0;
    sp.frac[a][l] = c.f;
    bad = bad || std::isnan(c.f);
  }
  sp.bad[l] = bad;
}
template <int D>
HWY_INLINE void clear_lane(lanes_split& sp, std::size_t l) {
  for (int a = 0; a < 3; ++a) {
    sp.cell[a][l] = 0;
    sp.frac[a][l] = 0.5f;
  }
  sp.bad[l] = true;
}

// The vector split of one axis (lattice_split<float>(x * inv) of every lane,
// bit for bit), valid when every lane's x * inv is finite with |x inv| < 2^31;
// false (nothing written) otherwise: the caller splits lane by lane.
HWY_INLINE bool split_axis(VF x, double inv, std::uint32_t* cell, float* frac) {
#if HWY_HAVE_FLOAT64 && HWY_TARGET != HWY_SCALAR
  const DF df;
  const hn::Half<DF> dh;
  const hn::Repartition<double, DF> dd;
  const hn::Rebind<float, decltype(dd)> df_of_d;
  const hn::Rebind<std::int32_t, decltype(dd)> di_of_d;
  const auto vinv = hn::Set(dd, inv);
  const auto limit = hn::Set(dd, 2147483648.0);
  const auto lo = hn::Mul(hn::PromoteTo(dd, hn::LowerHalf(dh, x)), vinv);
  const auto hi = hn::Mul(hn::PromoteTo(dd, hn::UpperHalf(dh, x)), vinv);
  if (!hn::AllTrue(dd, hn::Lt(hn::Abs(lo), limit)) || !hn::AllTrue(dd, hn::Lt(hn::Abs(hi), limit)))
    return false;
  const auto flo = hn::Floor(lo), fhi = hn::Floor(hi);
  const VF f = hn::Combine(df, hn::DemoteTo(df_of_d, hn::Sub(hi, fhi)),
                           hn::DemoteTo(df_of_d, hn::Sub(lo, flo)));
  hn::StoreU(hn::Min(f, hn::Set(df, detail::one_minus_ulp<float>())), df, frac);
  const DI di;
  const VI c = hn::Combine(di, hn::DemoteTo(di_of_d, fhi), hn::DemoteTo(di_of_d, flo));
  hn::StoreU(hn::BitCast(DU(), c), DU(), cell);
  return true;
#else
  (void)x;
  (void)inv;
  (void)cell;
  (void)frac;
  return false;
#endif
}

// Splits lanes [0, used) of a batch with split_lane (positions pos(i, x), x:
// D doubles) and marks the rest unused.
template <int D, class Position>
void split_lanes(lanes_split& sp, std::size_t first, std::size_t used, double inv, Position pos) {
  const std::size_t lanes = hn::Lanes(DF());
  for (std::size_t l = 0; l < lanes; ++l) {
    if (l < used) {
      double x[3];
      pos(first + l, x);
      split_lane<D>(sp, l, x, inv);
    } else {
      clear_lane<D>(sp, l);
    }
  }
}

// Unfiltered solid noise at `count` positions: split(first, used) fills `sp`
// for the batch of lanes starting at position `first`.
// The same with eval(consts, tuples, first) filling t.val (and t.g) for the batch of lanes
// starting at position `first`.
// The process a batch draws from: solid noise (cells r wide, 3^D of them) or
// surface noise (3D cells r sqrt(3/2) wide, 27 of them).
struct process {
  std::uint32_t stream;
  const poisson_table* table;
  int words;
  float scale, grad_scale;
};
template <int D>
process solid_process(const gabor<D>& g) {
  return {detail::constants::kGaborSolidStream, &g.table(), g.words_per_impulse(), float(g.scale()),
          float(g.scale() * g.inverse_cell())};
}

// Noise of process `pr` at `count` positions: split(first, used) fills `sp`
// for the batch of lanes starting at position `first`, keep(d, d2) is the
// support test, and eval(consts, tuples, first) fills t.val (and t.g).
// Fours: the point form's sum by fours (finish).
template <int D, int E, bool G, bool Fours = false, class Split, class Keep, class Eval>
void process_points(const gabor<D>& g, const process& pr, std::size_t count, lanes_split& sp,
                    Split split, Keep keep, float* value, float* grad, Eval eval) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const consts<D> c(g);
  tuples t;
  t.reserve(static_cast<std::size_t>(E == 2 ? 9 : 27) * pr.table->max_count() * lanes);
  const std::vector<std::int32_t> flipped = flipped_thresholds(*pr.table);
  for (std::size_t first = 0; first < count; first += lanes) {
    const std::size_t used = std::min(lanes, count - first);
    split(first, used);
    collect<E>(g.key(), pr.stream, flipped, pr.words, sp, t, keep);
    eval(c, t, first);
    float* gr = G ? grad + first * E : nullptr;
    finish<E, G, Fours>(t, sp, used, pr.scale, pr.grad_scale, value + first, gr);
  }
}

// Unfiltered (or, with eval, filtered) solid noise at `count` positions.
template <int D, bool G, bool Fours = false, class Split, class Eval>
void points_with(const gabor<D>& g, std::size_t count, lanes_split& sp, Split split, float* value,
                 float* grad, Eval eval) {
  auto keep = [](const VF*, const VF* d2) {
    const VF s = D == 2 ? hn::Add(d2[0], d2[1]) : hn::Add(d2[0], hn::Add(d2[1], d2[2]));
    return hn::Lt(s, hn::Set(DF(), 1.0f));
  };
  process_points<D, D, G, Fours>(g, solid_process(g), count, sp, split, keep, value, grad, eval);
}

// Unfiltered solid noise at `count` positions: random points, or with Grid a
// grid's samples (the separable form, as every grid).
template <int D, bool G, bool Grid, class Split>
void points(const gabor<D>& g, std::size_t count, lanes_split& sp, Split split, float* value,
            float* grad) {
  points_with<D, G, !Grid>(
      g, count, sp, split, value, grad,
      [](const consts<D>& c, tuples& t, std::size_t) { eval_unfiltered<D, G, Grid>(c, t); });
}

// ---- Points that share cells (gabor_points): each cell's impulses drawn once per call.
//
// The lockstep path above draws a cell once per lane batch, at the pace of the
// batch's largest count (54% of the slots used for N' = 16 on 16 lanes), and
// every point's 3^D cells again for each batch. Here a call's points are
// counting-sorted by cell within a box of cells (the call's cell range with a
// margin of one cell, clipped around the median cell to kShareBoxPerPoint n +
// kShareBoxMin cells); every cell next to an occupied one has its impulses
// drawn once (lanes across cells for the counts, across impulses for the words
// and marks, so the orientation's sin/cos is computed once per impulse), stored
// in the box's raster order: a point's 3^(D-1) rows of 3 cells are 3^(D-1)
// contiguous ranges. Per point each range is tested in full vectors (lanes
// across impulses) and the impulses within the support are compressed into a
// list, in the scalar order (cells in raster order, impulses in stream order);
// the kernel then runs over the list in full vectors and each point sums its
// own terms in order, so the result is the lockstep path's (and the scalar
// one's under HUSH_STRICT_FP) bit for bit. Finite points outside the box take
// the lockstep path; non-finite ones give NaN directly.
constexpr double kShareBoxPerPoint = 16.0;
// Fewer points per cell of the box than this (2D, 3D): the lockstep path is
// faster (each point draws its 3^D cells nearly alone; measured crossovers
// about 1.5 points per cell in 2D and below 0.9 in 3D, AVX2 and AVX3).
constexpr double kShareMinPointsPerCell[2] = {2.0, 0.5};
constexpr double kShareBoxMin = 1024.0;
// Kept pairs evaluated at once (the pair list is flushed beyond this): the test's three or
// four lists and the kernel's values stay in L1 (16 to 20 KB; with 4096 pairs, 64 to 80 KB,
// the 2D points and filtered samples took 5 to 12% longer on AVX3, 4 to 6% on AVX2).
constexpr std::size_t kSharePairs = 1024;
// Impulses whose stream keys and counters draw_box hashes at once (a chunk in L1).
constexpr std::size_t kDrawChunk = 1024;
// Impulses drawn per band of slabs (shared_points): ~400 KB of them, in L2. At least
// kShareBandMinSlabs slabs per band: each band draws its two neighbouring slabs again, which
// one-slab bands of a large 3D box made 3 draws per slab (sparse 3D points ~17% slower).
constexpr std::size_t kShareBandImpulses = 16384;
constexpr std::size_t kShareBandMinSlabs = 8;
// Points per shared_points call (larger calls are cut): keeps box indices and
// impulse offsets within 32 bits for every N' (a point's value does not
// depend on the cut).
constexpr std::size_t kShareMaxPoints = std::size_t(1) << 20;

// Pairs (point, impulse) within the support, each point's in its order.
struct shared_pairs {
  // Values only: s, theta and w of each kept impulse (filtered 2D: and the exponent x);
  // with gradients (and filtered 3D): d, phi and w.
  std::vector<float> d[3], w, phi[3], val, g[3], s, theta, x;
  std::size_t n = 0;
  void reserve(std::size_t cap) {
    for (auto* v : {&d[0], &d[1], &d[2], &w, &phi[0], &phi[1], &phi[2], &val, &g[0], &g[1], &g[2],
                    &s, &theta, &x})
      v->resize(cap + kMaxLanes);
  }
};

// Splits the whole batch of points pts[first...] (D interleaved floats, a
// vector's worth) in lanes into cell[a] and frac[a] (a vector each, any
// alignment); false where some lane is not ordinary (split_axis; the outputs
// are then partial).
template <int D>
HWY_INLINE bool split_whole(const float* pts, std::size_t first, double inv,
                            std::uint32_t* const* cell, float* const* frac) {
  const DF df;
  VF c[3];
  if constexpr (D == 2)
    hn::LoadInterleaved2(df, pts + first * D, c[0], c[1]);
  else
    hn::LoadInterleaved3(df, pts + first * D, c[0], c[1], c[2]);
  bool ok = true;
  for (int a = 0; a < D && ok; ++a) ok = split_axis(c[a], inv, cell[a], frac[a]);
  return ok;
}

// Splits lanes [0, used) of the batch of points pts[first...] (D interleaved
// floats) into sp: in lanes when the batch is whole and every lane ordinary,
// else lane by lane (lattice_split in double, as gabor<D>::eval).
template <int D>
void split_batch(lanes_split& sp, const float* pts, std::size_t first, std::size_t used,
                 double inv) {
  const std::size_t lanes = hn::Lanes(DF());
  std::uint32_t* const cell[3] = {sp.cell[0], sp.cell[1], sp.cell[2]};
  float* const frac[3] = {sp.frac[0], sp.frac[1], sp.frac[2]};
  if (used == lanes && split_whole<D>(pts, first, inv, cell, frac)) {
    std::fill(sp.bad, sp.bad + lanes, false);
    return;
  }
  split_lanes<D>(sp, first, used, inv, [pts](std::size_t i, double* x) {
    for (int a = 0; a < D; ++a)
      x[a] = static_cast<double>(pts[i * D + static_cast<std::size_t>(a)]);
  });
}

// The cells of a call's points (split_batch), and the box of cells that the
// shared path covers: per axis [lo, hi] relative to cell `ref` (wrapping
// 32-bit differences), plus a margin of one cell each side.
template <int D>
struct point_cells {
  std::vector<std::uint32_t> cell[D];
  std::vector<float> frac[D];
  std::vector<std::uint8_t> ok;  // every coordinate finite
  std::uint32_t ref[D] = {};
  std::int64_t lo[D] = {}, hi[D] = {}, side[D] = {}, stride[D] = {};
  std::size_t box = 0;  // cells in the box with its margins; 0: no finite point

  std::int64_t rel(int a, std::size_t i) const {
    return static_cast<std::int64_t>(static_cast<std::int32_t>(cell[a][i] - ref[a]));
  }
  std::vector<std::int64_t> v;  // median scratch

  // Splits the n points (whole batches straight into cell, frac, ok; others
  // lane by lane through split_batch) and finds ref (the first finite point's
  // cell) and lo, hi (min and max of rel: in int32 vectors, as rel's wrapping
  // differences). Every list has a vector of slack; ok's is zero.
  void build(const float* pts, std::size_t n, double inv) {
    const DF df;
    const DU du;
    const DI di;
    const std::size_t lanes = hn::Lanes(df);
    box = 0;
    for (int a = 0; a < D; ++a) {
      cell[a].resize(n + lanes);
      frac[a].resize(n + lanes);
    }
    ok.resize(n + lanes);
    std::fill(ok.begin() + static_cast<std::ptrdiff_t>(n), ok.end(), std::uint8_t{0});
    bool found = false;  // ref set
    VI vlo[D], vhi[D];
    for (int a = 0; a < D; ++a) {
      vlo[a] = hn::Set(di, std::numeric_limits<std::int32_t>::max());
      vhi[a] = hn::Set(di, std::numeric_limits<std::int32_t>::min());
      lo[a] = std::numeric_limits<std::int64_t>::max();
      hi[a] = std::numeric_limits<std::int64_t>::min();
    }
    lanes_split sp;
    for (std::size_t first = 0; first < n; first += lanes) {
      const std::size_t used = std::min(lanes, n - first);
      std::uint32_t* cl[3] = {};
      float* fr[3] = {};
      for (int a = 0; a < D; ++a) {
        cl[a] = cell[a].data() + first;
        fr[a] = frac[a].data() + first;
      }
      if (used == lanes && split_whole<D>(pts, first, inv, cl, fr)) {
        std::fill(ok.begin() + static_cast<std::ptrdiff_t>(first),
                  ok.begin() + static_cast<std::ptrdiff_t>(first + lanes), std::uint8_t{1});
        if (!found) {
          found = true;
          for (int a = 0; a < D; ++a) ref[a] = cell[a][first];
        }
        for (int a = 0; a < D; ++a) {
          const VI r =
              hn::BitCast(di, hn::Sub(hn::LoadU(du, cell[a].data() + first), hn::Set(du, ref[a])));
          vlo[a] = hn::Min(vlo[a], r);
          vhi[a] = hn::Max(vhi[a], r);
        }
        continue;
      }
      split_batch<D>(sp, pts, first, used, inv);
      for (std::size_t l = 0; l < used; ++l) {
        const std::size_t i = first + l;
        for (int a = 0; a < D; ++a) {
          cell[a][i] = sp.cell[a][l];
          frac[a][i] = sp.frac[a][l];
        }
        ok[i] = !sp.bad[l];
        if (!ok[i]) continue;
        if (!found) {
          found = true;
          for (int a = 0; a < D; ++a) ref[a] = cell[a][i];
        }
        for (int a = 0; a < D; ++a) {
          lo[a] = std::min(lo[a], rel(a, i));
          hi[a] = std::max(hi[a], rel(a, i));
        }
      }
    }
    if (!found) return;
    for (int a = 0; a < D; ++a) {
      lo[a] = std::min<std::int64_t>(lo[a], hn::GetLane(hn::MinOfLanes(di, vlo[a])));
      hi[a] = std::max<std::int64_t>(hi[a], hn::GetLane(hn::MaxOfLanes(di, vhi[a])));
    }
    std::size_t r = 0;  // the first finite point (the median's fallback)
    while (!ok[r]) ++r;
    const double budget = kShareBoxPerPoint * double(n) + kShareBoxMin;
    double cells = 1.0;
    for (int a = 0; a < D; ++a) cells *= double(hi[a] - lo[a] + 3);
    if (cells > budget) {  // clip around the median cell: sides of budget^(1/D) with margins
      const auto half =
          static_cast<std::int64_t>(std::floor((std::pow(budget, 1.0 / D) - 3.0) / 2.0));
      // The median of at most ~4096 points taken at a fixed stride: a centre
      // for the window, not more (nth_element over every point cost ~30 ns per point).
      const std::size_t every = std::max<std::size_t>(1, n / 4096);
      for (int a = 0; a < D; ++a) {
        v.clear();
        for (std::size_t i = 0; i < n; i += every)
          if (ok[i]) v.push_back(rel(a, i));
        if (v.empty()) v.push_back(rel(a, r));
        auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
        std::nth_element(v.begin(), mid, v.end());
        lo[a] = std::max(lo[a], *mid - half);
        hi[a] = std::min(hi[a], *mid + half);
      }
      // Then shrunk to the cells of the points inside (a far point must not
      // make the box look sparse).
      std::int64_t in_lo[D], in_hi[D];
      for (int a = 0; a < D; ++a) {
        in_lo[a] = hi[a];
        in_hi[a] = lo[a];
      }
      bool any = false;
      for (std::size_t i = 0; i < n; ++i) {
        bool in = ok[i] != 0;
        for (int a = 0; a < D && in; ++a) in = rel(a, i) >= lo[a] && rel(a, i) <= hi[a];
        if (!in) continue;
        any = true;
        for (int a = 0; a < D; ++a) {
          in_lo[a] = std::min(in_lo[a], rel(a, i));
          in_hi[a] = std::max(in_hi[a], rel(a, i));
        }
      }
      if (any)  // else the window stays (no point inside: the lockstep path)
        for (int a = 0; a < D; ++a) {
          lo[a] = in_lo[a];
          hi[a] = in_hi[a];
        }
    }
    box = 1;
    for (int a = 0; a < D; ++a) {
      side[a] = hi[a] - lo[a] + 3;
      stride[a] = static_cast<std::int64_t>(box);
      box *= static_cast<std::size_t>(side[a]);
    }
  }
  // The box indices of points i ... i + lanes - 1 (kOut outside the box or not
  // finite: ok's slack lanes are outside), and which are inside. In unsigned
  // lanes: x in [lo, hi] exactly where (x - lo) mod 2^32 <= hi - lo.
  hn::Mask<DU> box_index(std::size_t i, VU& idx) const {
    const DU du;
    const hn::Rebind<std::uint8_t, DU> d8;
    auto in = hn::Ne(hn::PromoteTo(du, hn::LoadU(d8, ok.data() + i)), hn::Zero(du));
    idx = hn::Zero(du);
    for (int a = 0; a < D; ++a) {
      const VU x = hn::Sub(hn::LoadU(du, cell[a].data() + i),
                           hn::Set(du, ref[a] + static_cast<std::uint32_t>(lo[a])));
      in = hn::And(in, hn::Lt(x, hn::Set(du, static_cast<std::uint32_t>(hi[a] - lo[a] + 1))));
      idx = hn::Add(idx, hn::Mul(hn::Add(x, hn::Set(du, 1u)),
                                 hn::Set(du, static_cast<std::uint32_t>(stride[a]))));
    }
    idx = hn::IfThenElse(in, idx, hn::Set(du, kOut));
    return in;
  }
  static constexpr std::uint32_t kOut = std::numeric_limits<std::uint32_t>::max();
  // The lattice cell along axis a of box coordinate x.
  std::uint32_t lattice(int a, std::int64_t x) const {
    return ref[a] + static_cast<std::uint32_t>(lo[a] - 1 + x);
  }
};

// The cells of a box next to an occupied one (first[b] < first[b + 1], first:
// the counting sort's offsets, box + 1 + a vector of them readable), marked
// all ones in need[0, box), zero elsewhere: the occupied cells dilated by one
// cell along each axis in turn, whole vectors over flat box indices. A shift
// by stride[a] never reaches a wrong cell: the box's margin cells are never
// occupied, and zero padding lies beyond the box on both sides. Returns need's
// first box cell (a vector of zeros readable past the box).
template <int D>
std::uint32_t* mark_needed(const point_cells<D>& pc, const std::uint32_t* first,
                           std::vector<std::uint32_t>& need, std::vector<std::uint32_t>& scratch) {
  const DU du;
  const std::size_t lanes = hn::Lanes(du);
  const std::size_t box = pc.box;
  const std::size_t pad = static_cast<std::size_t>(pc.stride[D - 1]) + lanes;
  // The D passes alternate between the buffers and end in need.
  std::vector<std::uint32_t>* buf[2] = {D % 2 == 0 ? &need : &scratch,
                                        D % 2 == 0 ? &scratch : &need};
  std::uint32_t* p[2];
  for (int k = 0; k < 2; ++k) {
    buf[k]->resize(box + 2 * pad);
    p[k] = buf[k]->data() + pad;
    std::fill(p[k] - pad, p[k], 0u);
  }
  for (std::size_t i = 0; i < box; i += lanes)
    hn::StoreU(hn::VecFromMask(du, hn::Ne(hn::LoadU(du, first + i + 1), hn::LoadU(du, first + i))),
               du, p[0] + i);
  std::fill(p[0] + box, p[0] + box + pad, 0u);  // whole vectors wrote past the box
  for (int a = 0; a < D; ++a) {
    const std::uint32_t* in = p[a % 2];
    std::uint32_t* out = p[1 - a % 2];
    const auto s = static_cast<std::size_t>(pc.stride[a]);
    for (std::size_t i = 0; i < box; i += lanes)
      hn::StoreU(hn::Or(hn::Or(hn::LoadU(du, in + i - s), hn::LoadU(du, in + i)),
                        hn::LoadU(du, in + i + s)),
                 du, out + i);
    std::fill(out + box, out + box + pad, 0u);
  }
  return p[D % 2];
}

// The impulses of the cells of a box next to an occupied one, in box order:
// start[idx] ... start[idx + 1] are cell idx's; per impulse its position in
// the cell, its cell's box x coordinate, weight and frequency (marks).
struct box_impulses {
  std::vector<std::uint32_t> start;
  std::vector<float> pos[3], bx, w, phi[3];
  // draw_box's scratch: the needed cells (box index and x), their lattice
  // coordinates along y (z), stream keys and counts; per impulse of a chunk
  // (kDrawChunk) its stream key and counter.
  std::vector<std::uint32_t> cells, cx, coord[3], key, count, ikey, ictr;
};

// Draws the impulses of the cells of box indices [lo, hi) (whole rows of
// side[0] cells) marked in need (mark_needed; need is overwritten there with the
// cells' counts, so a later call over some of the same cells draws them again
// alike): start[idx] for idx in [lo, hi], from 0. Every list is written in whole
// vectors and sized to a whole number of vectors past its end: what lies there
// is finite (zeros or an earlier call's values) and never summed.
template <int D>
void draw_box(const gabor<D>& g, const consts<D>& c, const point_cells<D>& pc, std::uint32_t* need,
              std::size_t lo, std::size_t hi, box_impulses& out) {
  const DF df;
  const DU du;
  const std::size_t lanes = hn::Lanes(df);
  // The needed cells in increasing box index, row by row (a row's coordinates
  // along y and z once, no division per cell).
  const auto side0 = static_cast<std::size_t>(pc.side[0]);
  for (auto* v : {&out.cells, &out.cx}) v->resize(hi - lo + lanes);
  for (int a = 1; a < D; ++a) out.coord[a].resize(hi - lo + lanes);
  std::uint32_t* const cells = out.cells.data();
  std::uint32_t* const cx = out.cx.data();
  std::uint32_t* const coord[3] = {nullptr, out.coord[1].data(), out.coord[2].data()};
  const VU iota = hn::Iota(du, 0), vside = hn::Set(du, static_cast<std::uint32_t>(side0));
  std::size_t nc = 0;
  for (std::size_t r = lo / side0; r < hi / side0; ++r) {
    const std::size_t row_first = nc, base = r * side0;
    for (std::size_t x = 0; x < side0; x += lanes) {
      const VU xs = hn::Add(iota, hn::Set(du, static_cast<std::uint32_t>(x)));
      const auto m =
          hn::And(hn::Ne(hn::LoadU(du, need + base + x), hn::Zero(du)), hn::Lt(xs, vside));
      const compressor kept(hn::RebindMask(df, m));
      hn::StoreU(kept(hn::Add(xs, hn::Set(du, static_cast<std::uint32_t>(base)))), du, cells + nc);
      hn::StoreU(kept(xs), du, cx + nc);
      nc += hn::CountTrue(du, m);
    }
    std::int64_t rest = static_cast<std::int64_t>(r);
    for (int a = 1; a < D; ++a) {
      std::fill(coord[a] + row_first, coord[a] + nc, pc.lattice(a, rest % pc.side[a]));
      rest /= pc.side[a];
    }
  }
  // Counts and stream keys, lanes across cells (collect's hash, operation by operation).
  std::vector<std::uint32_t>&key = out.key, &count = out.count;
  key.resize(nc + lanes);
  count.resize(nc + lanes);
  const std::vector<std::int32_t> flipped = flipped_thresholds(g.table());
  const auto nthr = static_cast<std::uint32_t>(flipped.size() - 1);
  const VU x0 = hn::Set(du, pc.lattice(0, 0));
  for (std::size_t j = 0; j < nc; j += lanes) {
    VU h = hn::Xor(hn::Set(du, g.key()), word_x(hn::Add(x0, hn::LoadU(du, cx + j))));
    h = hn::Xor(h, word_y(hn::LoadU(du, coord[1] + j)));
    if constexpr (D == 3) h = hn::Xor(h, word_z(hn::LoadU(du, coord[2] + j)));
    const VU skey = stream_key(hash32(h), detail::constants::kGaborSolidStream);
    hn::StoreU(skey, du, key.data() + j);
    hn::StoreU(nthr == 0 ? hn::Zero(du) : table_count(flipped.data(), nthr, draw(skey, 0)), du,
               count.data() + j);
  }
  // Offsets per box cell: the counts in need (its other cells are zero), summed.
  for (std::size_t j = 0; j < nc; ++j) need[cells[j]] = count[j];
  out.start.resize(pc.box + 1);
  std::uint32_t* const start = out.start.data();
  std::uint32_t total = 0;
  for (std::size_t idx = lo; idx < hi; ++idx) {
    start[idx] = total;
    total += need[idx];
  }
  start[hi] = total;
  // Per impulse its box x, and its stream key and counter in a chunk of about
  // kDrawChunk impulses (in L1, not a list of the box's ~n of them): a whole
  // vector per cell (a later cell overwrites what reaches past a cell), more for
  // a longer one; each chunk's whole vectors hashed into words, positions and
  // marks, lanes across impulses.
  const std::size_t size = total + lanes;
  for (auto* v : {&out.bx, &out.pos[0], &out.pos[1], &out.pos[2], &out.w, &out.phi[0], &out.phi[1],
                  &out.phi[2]})
    v->resize(size);
  for (auto* v : {&out.ikey, &out.ictr}) v->resize(kDrawChunk + g.table().max_count() + 2 * lanes);
  std::uint32_t* const ikey = out.ikey.data();
  std::uint32_t* const ictr = out.ictr.data();
  float* const bx = out.bx.data();
  const auto words = static_cast<std::uint32_t>(g.words_per_impulse());
  // The impulses [base, base + m) (m: whole vectors, or the rest past total).
  auto hash_chunk = [&](std::size_t base, std::size_t m) {
    for (std::size_t i = 0; i < m; i += lanes) {
      const VU k = hn::LoadU(du, ikey + i), ctr = hn::LoadU(du, ictr + i);
      VU wd[3] = {hn::Zero(du), hn::Zero(du), hn::Zero(du)};
      for (std::uint32_t j = 0; j < words; ++j)
        wd[j] = hash32(hn::Xor(k, hash32(hn::Add(ctr, hn::Set(du, j)))));
      VF wt, phi[3];
      marks<D>(c, wd, wt, phi);
      for (int a = 0; a < D; ++a) {
        hn::StoreU(byte_value(wd[0], static_cast<unsigned>(a)), df, out.pos[a].data() + base + i);
        hn::StoreU(phi[a], df, out.phi[a].data() + base + i);
      }
      hn::StoreU(wt, df, out.w.data() + base + i);
    }
  };
  const VU ctr0 = hn::Add(hn::Mul(iota, hn::Set(du, words)), hn::Set(du, 1u));
  const VU step = hn::Set(du, static_cast<std::uint32_t>(lanes) * words);
  std::size_t base = 0;  // the chunk's first impulse (a whole number of vectors)
  for (std::size_t j = 0, o = 0; j < nc; ++j) {
    const VU k = hn::Set(du, key[j]);
    const VF b = hn::Set(df, static_cast<float>(cx[j]));
    VU ctr = ctr0;
    const std::size_t local = o - base;
    hn::StoreU(k, du, ikey + local);
    hn::StoreU(ctr, du, ictr + local);
    hn::StoreU(b, df, bx + o);
    for (std::size_t e = lanes; e < count[j]; e += lanes) {
      ctr = hn::Add(ctr, step);
      hn::StoreU(k, du, ikey + local + e);
      hn::StoreU(ctr, du, ictr + local + e);
      hn::StoreU(b, df, bx + o + e);
    }
    o += count[j];
    if (o - base >= kDrawChunk) {
      const std::size_t m = (o - base) / lanes * lanes;
      hash_chunk(base, m);
      // The rest (under a vector) to the chunk's front.
      hn::StoreU(hn::LoadU(du, ikey + m), du, ikey);
      hn::StoreU(hn::LoadU(du, ictr + m), du, ictr);
      base += m;
    }
  }
  hash_chunk(base, total - base);
}

// Whether a call's points are clearly too sparse to share their cells, judged
// from at most ~1024 of them at a fixed stride (their cells in double, the
// window of kShareBoxPerPoint n + kShareBoxMin cells around their median,
// shrunk to the sampled points inside): an estimated density below half of
// kShareMinPointsPerCell. Only picks the path; both give the same values.
template <int D>
bool clearly_sparse(const float* pts, std::size_t n, double inv) {
  const std::size_t every = std::max<std::size_t>(1, n / 1024);
  std::vector<double> c[D];
  for (std::size_t i = 0; i < n; i += every) {
    double x[D];
    bool finite = true;
    for (int a = 0; a < D; ++a) {
      x[a] = std::floor(double(pts[i * D + static_cast<std::size_t>(a)]) * inv);
      finite = finite && std::isfinite(x[a]);
    }
    if (finite)
      for (int a = 0; a < D; ++a) c[a].push_back(x[a]);
  }
  const std::size_t m = c[0].size();
  if (m == 0) return true;
  const double half =
      std::floor((std::pow(kShareBoxPerPoint * double(n) + kShareBoxMin, 1.0 / D) - 3.0) / 2.0);
  double med[D];
  for (int a = 0; a < D; ++a) {
    std::vector<double> v = c[a];
    auto mid = v.begin() + static_cast<std::ptrdiff_t>(m / 2);
    std::nth_element(v.begin(), mid, v.end());
    med[a] = *mid;
  }
  double lo[D], hi[D];
  for (int a = 0; a < D; ++a) {
    lo[a] = med[a] + half;
    hi[a] = med[a] - half;
  }
  std::size_t inside = 0;
  for (std::size_t j = 0; j < m; ++j) {
    bool in = true;
    for (int a = 0; a < D && in; ++a) in = std::fabs(c[a][j] - med[a]) <= half;
    if (!in) continue;
    ++inside;
    for (int a = 0; a < D; ++a) {
      lo[a] = std::min(lo[a], c[a][j]);
      hi[a] = std::max(hi[a], c[a][j]);
    }
  }
  if (inside == 0) return true;
  double cells = 1.0;
  for (int a = 0; a < D; ++a) cells *= hi[a] - lo[a] + 1.0;
  const double estimate = double(inside) * double(n) / double(m);
  return estimate < 0.5 * kShareMinPointsPerCell[D - 2] * cells;
}

// Everything shared_points allocates, kept per thread between calls: a
// fresh allocation per call cost a fifth of the time in page faults (262144
// points, ~50 bytes each; the memory stays with the thread).
// The candidate impulses of one cell's points (shared_points): per impulse
// o + u along each axis (its cell's offset plus its position in the cell,
// exact: detail::gabor_offset), frequency and weight, in the points' summation order.
struct cell_candidates {
  std::vector<float> pos[3], phi[3], w;
  std::vector<float> pp[3];  // 2D filtered values: Phi_r Phi_c, r <= c (phi_products)
  void reserve(std::size_t cap) {
    for (auto* v : {&pos[0], &pos[1], &pos[2], &phi[0], &phi[1], &phi[2], &w, &pp[0], &pp[1], &pp[2]})
      if (v->size() < cap) v->resize(cap);
  }
};

// A point of the box in cell order: its index in the call, its cell's box
// index and its fractions (one record: the counting sort writes each point
// once, to a random place).
template <int D>
struct sorted_point {
  std::uint32_t point, at;
  float frac[D];
};

template <int D>
struct shared_workspace {
  point_cells<D> pc;
  box_impulses im;
  shared_pairs t;
  cell_candidates cc;
  std::vector<std::uint32_t> at, first, fill, pend;
  std::vector<sorted_point<D>> sorted;
  std::vector<std::uint32_t> need, need_scratch;
  std::vector<std::size_t> rest, pend_end;
};

// The calling thread's T (a workspace, kept between calls: no allocation or zero-fill
// per call), returned from a call that is not inlined: with the thread_local in
// shared_points itself, GCC recomputed its address where it would otherwise keep it (in
// code built for a shared library, a __tls_get_addr call: 9% of a 2D call of 262144
// points).
template <class T>
HWY_NOINLINE T& thread_local_of() {
  static thread_local T ws;
  return ws;
}

// shared_points' kernels (Eval): t's pairs [0, t.n), point pend[p]'s in
// [pend_end[p - 1], pend_end[p]), into t.val (and with G the gradient terms into t.g).
// kOffsets: the pairs carry d and phi (else s and theta: the unfiltered values);
// kExponent: and the exponent x, computed in the test with filter_of(the point's sorted
// position). point_scale(p): pending point p's factor on its sums; flushed(np) after
// each flush.
//
// The unfiltered kernel (gabor<D>::eval) in the point form.
template <int D, bool G>
struct shared_unfiltered {
  static constexpr bool kOffsets = G;
  static constexpr bool kExponent = false;
  void prepare(const std::vector<sorted_point<D>>&) {}
  struct point_filter {};
  point_filter filter_of(std::size_t) const { return {}; }
  float point_scale(std::size_t) const { return 1.0f; }
  void flushed(std::size_t) {}
  void operator()(const consts<D>& c, shared_pairs& t, const std::vector<std::uint32_t>&,
                  const std::vector<std::size_t>&) const {
    const DF df;
    const std::size_t lanes = hn::Lanes(df);
    for (std::size_t i = 0; i < t.n; i += lanes) {
      const VF wt = hn::LoadU(df, t.w.data() + i);
      if constexpr (!G) {
        hn::StoreU(point_value(c, wt, hn::LoadU(df, t.s.data() + i),
                               hn::LoadU(df, t.theta.data() + i)),
                   df, t.val.data() + i);
        continue;
      }
      VF d[3], phi[3];
      for (int a = 0; a < D; ++a) {
        d[a] = hn::LoadU(df, t.d[a].data() + i);
        phi[a] = hn::LoadU(df, t.phi[a].data() + i);
      }
      float* const gp[3] = {t.g[0].data() + i, t.g[1].data() + i, t.g[2].data() + i};
      unfiltered_terms<D, G, false>(c, wt, phi, d, t.val.data() + i, gp);
    }
  }
};

// gabor_filter<2> of the n footprints fps in lanes of doubles: its operations in its
// order (build_2d's closed form), so the same values bit for bit under HUSH_STRICT_FP
// (IEEE division and square root are correctly rounded; no fused operations here). The
// scalar branches are masks (the projection onto the positive semi-definite matrices
// computed only where some lane needs it). out[e * stride + p]: point p's
// detail::gabor_filter_coefs<float, 2> (q, m2,
// amplitude: 7 entries; m2 negated, as filtered_exponent takes it); stride >= n rounded
// up to whole vectors of doubles.
inline void filters_2d(const footprint<2>* fps, std::size_t n, double a, double inv_r, float* out,
                       std::size_t stride) {
  using DD = hn::ScalableTag<double>;
  using VD = hn::Vec<DD>;
  const DD dd;
  const hn::Rebind<float, DD> dfh;
  const std::size_t lanes = hn::Lanes(dd);
  const double k = 2.0 * a * detail::constants::kPixelFilterSigma *
                   detail::constants::kPixelFilterSigma * inv_r * inv_r;
  const double mk = detail::constants::kPi * detail::constants::kPi / a;
  const VD zero = hn::Zero(dd), one = hn::Set(dd, 1.0);
  // Whole batches read the footprints' stored upper triangles (S's entries (0,0),
  // (0,1), (1,1), in this order) as one interleaved load: lanes filled one by one and
  // loaded back as a vector stalled on store forwarding (~10 cycles per point).
  static_assert(sizeof(footprint<2>) == 3 * sizeof(float), "footprint<2>: 3 floats, no padding");
  HWY_ALIGN double cov[3][kMaxLanes];  // the last batch's entries; zero past n
  for (std::size_t p0 = 0; p0 < n; p0 += lanes) {
    VD a00, a01, a11;
    if (p0 + lanes <= n) {
      hn::Vec<decltype(dfh)> s00, s01, s11;
      hn::LoadInterleaved3(dfh, fps[p0].data(), s00, s01, s11);
      a00 = hn::PromoteTo(dd, s00);
      a01 = hn::PromoteTo(dd, s01);
      a11 = hn::PromoteTo(dd, s11);
    } else {
      for (std::size_t l = 0; l < lanes; ++l) {
        const bool in = p0 + l < n;
        cov[0][l] = in ? static_cast<double>(fps[p0 + l].covariance(0, 0)) : 0.0;
        cov[1][l] = in ? static_cast<double>(fps[p0 + l].covariance(0, 1)) : 0.0;
        cov[2][l] = in ? static_cast<double>(fps[p0 + l].covariance(1, 1)) : 0.0;
      }
      a00 = hn::Load(dd, cov[0]);
      a01 = hn::Load(dd, cov[1]);
      a11 = hn::Load(dd, cov[2]);
    }
    // gabor_filter<2>::build_2d, operation by operation: NaN counts as 0.
    VD sa = hn::IfThenElseZero(hn::Eq(a00, a00), a00);
    VD sb = hn::IfThenElseZero(hn::Eq(a01, a01), a01);
    VD sc = hn::IfThenElseZero(hn::Eq(a11, a11), a11);
    VD det = hn::Sub(hn::Mul(sa, sc), hn::Mul(sb, sb));
    const auto psd = hn::And(hn::And(hn::Ge(sa, zero), hn::Ge(sc, zero)), hn::Ge(det, zero));
    // Without a lane off the positive semi-definite matrices (every footprint but
    // rounding's near-singular ones and unchecked input): no square root.
    if (!hn::AllTrue(dd, psd)) {
      const VD halfv = hn::Set(dd, 0.5);
      const VD mean = hn::Mul(halfv, hn::Add(sa, sc)), half = hn::Mul(halfv, hn::Sub(sa, sc));
      const VD rad = hn::Sqrt(hn::Add(hn::Mul(half, half), hn::Mul(sb, sb)));
      const VD hi = hn::Add(mean, rad), lo = hn::Sub(mean, rad);
      // hi / (rad + rad) only where hi > 0 (rad > 0 there); 0 elsewhere.
      const auto pos = hn::Gt(hi, zero);
      const VD f =
          hn::IfThenElseZero(pos, hn::Div(hi, hn::IfThenElse(pos, hn::Add(rad, rad), one)));
      sa = hn::IfThenElse(psd, sa, hn::Mul(hn::Sub(sa, lo), f));
      sb = hn::IfThenElse(psd, sb, hn::Mul(sb, f));
      sc = hn::IfThenElse(psd, sc, hn::Mul(hn::Sub(sc, lo), f));
      det = hn::IfThenElseZero(psd, det);
    }
    const VD vk = hn::Set(dd, k), vmk = hn::Set(dd, mk);
    const VD ka = hn::Mul(vk, sa), kb = hn::Mul(vk, sb), kc = hn::Mul(vk, sc);
    const VD kkd = hn::Mul(hn::Mul(vk, vk), det);
    const VD inv = hn::Div(one, hn::Add(hn::Add(hn::Add(one, ka), kc), kkd));
    // The upper triangles (detail::gabor_filter_coefs): q, then -m2 (M's off-diagonal
    // doubled).
    const VD q[3] = {hn::Mul(hn::Add(one, kc), inv), hn::Neg(hn::Mul(kb, inv)),
                     hn::Mul(hn::Add(one, ka), inv)};
    const VD m[3] = {hn::Mul(vmk, hn::Mul(hn::Add(ka, kkd), inv)), hn::Mul(vmk, hn::Mul(kb, inv)),
                     hn::Mul(vmk, hn::Mul(hn::Add(kc, kkd), inv))};
    for (int e = 0; e < 3; ++e) {
      const auto m2 = hn::DemoteTo(dfh, m[e]);
      hn::StoreU(hn::DemoteTo(dfh, q[e]), dfh, out + e * stride + p0);
      hn::StoreU(hn::Neg(e == 1 ? hn::Add(m2, m2) : m2), dfh, out + (3 + e) * stride + p0);
    }
    const VD amp = hn::Sqrt(inv);
    hn::StoreU(hn::DemoteTo(dfh, amp), dfh, out + 6 * stride + p0);
  }
}

// prepare(sorted) sees the points in the order in which they reach the kernel.
//
// The filtered kernel (gabor<D>::filtered_eval) with each point's footprint fps[point]:
// its filter computed once per point, a chunk of points at a time as the test reaches
// them (in double, rounded to float as
// detail::gabor_filter_coefs rounds it; 2D in lanes of doubles, filters_2d), its
// amplitude applied to the point's sums (point_scale). The terms:
//  - 2D values (kExponent): each candidate's exponent and phase in the test, with the
//    point's filter in registers (filter_of), then the point form's kernel over the kept
//    pairs (exp, cos, taper only). In 2D about a third of the candidates are kept (pi / 9
//    of the 3 x 3 cells): cheaper than fetching each pair's filter;
//  - 3D (4 pi / 81 kept) and gradients: filtered_pair over the pairs in full vectors, each
//    lane taking its point's filter from a vector of the filters of consecutive points (a
//    permutation).
template <int D, bool G>
struct shared_filtered {
  static constexpr bool kExponent = D == 2 && !G;
  static constexpr bool kOffsets = !kExponent;
  static constexpr std::size_t kSym = D * (D + 1) / 2, kAmp = 2 * kSym, kCoef = kAmp + 1;
  static constexpr std::size_t kChunk = 512;  // points: their coefficients stay in L1 / L2
  // Kept between calls (thread_local_of): a call allocates and zero-fills nothing.
  struct buffers {
    std::vector<footprint<D>> chunk_fps;  // the footprints of one chunk, in sorted order
    // Per point from sorted position `base` on: q, -m2 (detail::gabor_filter_coefs) and
    // the amplitude, coef[k * stride + (position - base)], for the pending points and
    // the chunk the test is in.
    std::vector<float> coef;
    std::size_t stride = 0;
    std::vector<std::int32_t> ends;  // the pending points' ends, then kWindow sentinels
    std::vector<std::uint32_t> ahead;  // the next chunk's points (their call indices)
  };
  shared_filtered(const footprint<D>* f, double a, double inv_r)
      : fps(f), envelope(a), inv(inv_r), buf(thread_local_of<buffers>()) {}
  const footprint<D>* fps;
  double envelope, inv;  // A, 1 / r
  buffers& buf;
  const std::vector<sorted_point<D>>* sorted = nullptr;
  std::size_t base = 0;   // the sorted position of coef's first column
  std::size_t ready = 0;  // the points before this sorted position have their filters
  std::size_t next = 0;   // the sorted position of the first pending point
  std::size_t chunk_first = 0;  // the sorted position of the chunk computed last

  void prepare(const std::vector<sorted_point<D>>& s) {
    sorted = &s;
    base = ready = next = chunk_first = 0;
    buf.ahead.clear();
    reserve(0);
  }
  // Room for `keep` columns and a chunk: whole vectors of doubles of slack (filters_2d
  // writes them), and a vector of floats past the last column (the kernel's loads start
  // at any pending point). The first `keep` columns are kept.
  void reserve(std::size_t keep) {
    const std::size_t lanes = hn::Lanes(DF());
    const std::size_t need = (keep + kChunk + lanes) / lanes * lanes + lanes;
    if (need <= buf.stride) return;
    const std::size_t wide = std::max(need, 2 * buf.stride);
    std::vector<float> grown(kCoef * wide);
    for (std::size_t k = 0; k < kCoef && keep > 0; ++k)
      std::copy_n(buf.coef.data() + k * buf.stride, keep, grown.data() + k * wide);
    buf.coef.swap(grown);
    buf.stride = wide;
  }
  // The filters of the chunk from sorted position `ready`, the pending points' moved to
  // the front first (a flush holds ~64 of them). Its footprints are gathered in one loop
  // (in cell order they are read at random: filter_of fetched them during the chunk
  // before), then the filters computed in a loop of independent iterations (the divisions and
  // square roots overlap across points). A chunk at a time, just before the test needs
  // it: the coefficients are read from L1 / L2, not written to memory and read back.
  void compute_chunk() {
    const std::size_t keep = ready - next, m = std::min(kChunk, sorted->size() - ready);
    if (next > base)
      for (std::size_t k = 0; k < kCoef; ++k) {
        float* row = buf.coef.data() + k * buf.stride;
        std::memmove(row, row + (next - base), keep * sizeof(float));
      }
    base = next;
    reserve(keep);
    std::vector<footprint<D>>& cf = buf.chunk_fps;
    cf.resize(m);
    for (std::size_t k = 0; k < m; ++k) cf[k] = fps[(*sorted)[ready + k].point];
    // The next chunk's points, whose footprints filter_of fetches while this one is tested.
    buf.ahead.clear();
    for (std::size_t k = ready + m, e = std::min(ready + m + kChunk, sorted->size()); k < e; ++k)
      buf.ahead.push_back((*sorted)[k].point);
    chunk_first = ready;
    float* const out = buf.coef.data() + keep;
    const std::size_t stride = buf.stride;
    if constexpr (D == 2) {
      filters_2d(cf.data(), m, envelope, inv, out, stride);
    } else {
      for (std::size_t k = 0; k < m; ++k) {
        const detail::gabor_filter_coefs<float, D> f(gabor_filter<D>(cf[k], envelope, inv));
        for (std::size_t e = 0; e < kSym; ++e) {
          out[e * stride + k] = f.q[e];
          out[(kSym + e) * stride + k] = -f.m2[e];
        }
        out[kAmp * stride + k] = f.amplitude;
      }
    }
    ready += m;
  }
  // The filter of the point at sorted position sp in every lane (the test's terms); the
  // test reaches the points in sorted order, and a pending point's filter is ready.
  struct point_filter {
    VF q[kSym], nm2[kSym];
  };
  point_filter filter_of(std::size_t sp) {
    if (sp >= ready) compute_chunk();
    // One footprint of the next chunk per point: gathered cold, each was a cache miss (11%
    // of a 2D call of 262144 samples on AVX3). All of them fetched at once when the chunk
    // starts cost 2 to 4% more on AVX2 (a burst of misses), and fetching through the
    // record a chunk ahead (not yet in cache) cost more than it saved.
    if (sp - chunk_first < buf.ahead.size()) hwy::Prefetch(fps + buf.ahead[sp - chunk_first]);
    const DF df;
    const float* const col = buf.coef.data() + (sp - base);
    const std::size_t stride = buf.stride;
    point_filter f;
    for (std::size_t k = 0; k < kSym; ++k) {
      f.q[k] = hn::Set(df, col[k * stride]);
      f.nm2[k] = hn::Set(df, col[(kSym + k) * stride]);
    }
    return f;
  }
  // Pending point p's factor on its sums, and the end of a flush of np points.
  float point_scale(std::size_t p) const { return buf.coef[kAmp * buf.stride + (next - base) + p]; }
  void flushed(std::size_t np) { next += np; }

  void operator()(const consts<D>& c, shared_pairs& t, const std::vector<std::uint32_t>& pend,
                  const std::vector<std::size_t>& pend_end) {
    const DF df;
    const DI di;
    const std::size_t lanes = hn::Lanes(df);
    if constexpr (kExponent) {
      // w e^x cos(2 pi theta) tau(s) (gabor<D>::filtered_pair's value).
      for (std::size_t i = 0; i < t.n; i += lanes) {
        VF sn, cs;
        sincos_kept(c, hn::LoadU(df, t.theta.data() + i), sn, cs);
        const VF p =
            hn::Mul(hn::LoadU(df, t.w.data() + i), exp_neg_finite(hn::LoadU(df, t.x.data() + i)));
        hn::StoreU(hn::Mul(hn::Mul(p, cs), taper(hn::LoadU(df, t.s.data() + i), c.k)), df,
                   t.val.data() + i);
      }
      return;
    }
    // Each pending point's end as int32, then kWindow sentinels (never <= a pair).
    constexpr std::size_t kWindow = 3;
    const std::size_t np = pend.size();
    std::vector<std::int32_t>& ends = buf.ends;
    ends.resize(np + kWindow);
    for (std::size_t q = 0; q < np; ++q) ends[q] = static_cast<std::int32_t>(pend_end[q]);
    for (std::size_t q = np; q < np + kWindow; ++q)
      ends[q] = std::numeric_limits<std::int32_t>::max();
    const std::int32_t* const e = ends.data();
    const float* const cf = buf.coef.data() + (next - base);
    const std::size_t stride = buf.stride;
    const VI iota = hn::Iota(di, 0);
    const std::int32_t width = static_cast<std::int32_t>(lanes);
    std::size_t p = 0;  // the first pending point with pairs at or past i
    for (std::size_t i = 0; i < t.n; i += lanes) {
      const std::int32_t i32 = static_cast<std::int32_t>(i);
      const VI pair = hn::Add(iota, hn::Set(di, i32));
      // Each lane's point as p + local, local = #{q >= p : ends[q] <= pair}, from a fixed
      // window of kWindow points (a loop on how many end here would mispredict about
      // once per vector); `done`: the window's points that end within this vector.
      VI local = hn::Zero(di);
      std::size_t done = 0;
      HWY_UNROLL(3)
      for (std::size_t k = 0; k < kWindow; ++k) {
        local = hn::Sub(local, hn::VecFromMask(di, hn::Gt(pair, hn::Set(di, e[p + k] - 1))));
        done += e[p + k] <= i32 + width ? 1 : 0;
      }
      // The same entries either way: each lane's point's, bit for bit. While fewer than
      // kWindow points end here, local < kWindow <= lanes: a permutation of the entries
      // of points p ... p + lanes - 1 (more only where points have no pairs: gathered).
      VF ent[kAmp];
      if (HWY_LIKELY(done < kWindow)) {
        const auto idx = hn::IndicesFromVec(df, local);
        for (std::size_t k = 0; k < kAmp; ++k)
          ent[k] = hn::TableLookupLanes(hn::LoadU(df, cf + k * stride + p), idx);
      } else {
        for (std::size_t q = p + kWindow; q < np && e[q] <= i32 + width; ++q, ++done)
          local = hn::Sub(local, hn::VecFromMask(di, hn::Gt(pair, hn::Set(di, e[q] - 1))));
        for (std::size_t k = 0; k < kAmp; ++k)
          ent[k] = hn::GatherIndex(df, cf + k * stride + p, local);
      }
      VF d[3], phi[3];
      for (int a = 0; a < D; ++a) {
        d[a] = hn::LoadU(df, t.d[a].data() + i);
        phi[a] = hn::LoadU(df, t.phi[a].data() + i);
      }
      VF value, gr[3];
      filtered_pair<D, D, G>(c, ent, ent + kSym, d, point_s<D>(d), hn::LoadU(df, t.w.data() + i),
                             phi, value, gr);
      hn::StoreU(value, df, t.val.data() + i);
      if constexpr (G)
        for (int a = 0; a < D; ++a) hn::StoreU(gr[a], df, t.g[a].data() + i);
      p += done;
    }
  }
};

// Solid noise at the n points pts (D interleaved floats) with the kernel eval
// (shared_unfiltered, shared_filtered), values into value, interleaved gradients into
// grad with G; lockstep(p, index, m, value, grad) evaluates on the lockstep path the m
// points p (gathered), the call's points index[0 .. m) (null: the call's first m).
template <int D, bool G, class Lockstep, class Eval>
void shared_points(const gabor<D>& g, const float* pts, std::size_t n, float* value, float* grad,
                   Lockstep lockstep, Eval& eval) {
  const DF df;
  const DU du;
  const std::size_t lanes = hn::Lanes(df);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  if (clearly_sparse<D>(pts, n, g.inverse_cell())) {
    lockstep(pts, nullptr, n, value, grad);
    return;
  }
  shared_workspace<D>& ws = thread_local_of<shared_workspace<D>>();
  ws.pc.build(pts, n, g.inverse_cell());
  const point_cells<D>& pc = ws.pc;
  // Counting sort of the box's points by cell; the rest: NaN, or the lockstep path.
  std::vector<std::uint32_t>& at = ws.at;
  std::vector<std::uint32_t>& first = ws.first;
  std::vector<sorted_point<D>>& sorted = ws.sorted;
  std::vector<std::size_t>& rest = ws.rest;
  // `sorted` is only resized below, never cleared: growing an emptied vector would
  // zero-fill every record on every call (~5% of a call).
  rest.clear();
  constexpr auto kOut = point_cells<D>::kOut;
  // Too few points per cell to share the draws: the lockstep path for all
  // (decided before the sort where even n points are too few).
  double interior = 1.0;
  for (int a = 0; a < D; ++a) interior *= double(pc.hi[a] - pc.lo[a] + 1);
  const double too_few = kShareMinPointsPerCell[D - 2] * interior;
  if (pc.box == 0 || double(n) < too_few) {
    lockstep(pts, nullptr, n, value, grad);
    return;
  }
  // Box indices in vectors, the histogram of the inside (first[b + 1]: cell b's points).
  at.resize(n + lanes);
  first.assign(pc.box + 1 + lanes, 0);  // a vector past the end for mark_needed
  std::uint32_t* const count = first.data() + 1;
  std::size_t inside = 0;
  for (std::size_t i = 0; i < n; i += lanes) {
    VU idx;
    const auto in = pc.box_index(i, idx);
    hn::StoreU(idx, du, at.data() + i);
    const std::size_t k = hn::CountTrue(du, in);
    inside += k;
    if (k == lanes) {
      for (std::size_t l = 0; l < lanes; ++l) ++count[at[i + l]];
      continue;
    }
    for (std::size_t l = 0, used = std::min(lanes, n - i); l < used; ++l) {
      const std::size_t p = i + l;
      if (at[p] != kOut) {
        ++count[at[p]];
      } else if (pc.ok[p]) {
        rest.push_back(p);
      } else {
        value[p] = nan;
        if (G)
          for (int a = 0; a < D; ++a) grad[p * D + a] = nan;
      }
    }
  }
  if (double(inside) < too_few) {
    lockstep(pts, nullptr, n, value, grad);
    return;
  }
  {
    for (std::size_t b = 0; b < pc.box; ++b) first[b + 1] += first[b];
    // In sorted order: the point, its cell and fractions (read in order below:
    // gathering them per point would miss the cache on every point).
    sorted.resize(inside);
    std::vector<std::uint32_t>& fill = ws.fill;
    fill.assign(first.begin(), first.begin() + static_cast<std::ptrdiff_t>(pc.box));
    // Each record goes to a random place in the list (a cache miss): the
    // destination kAhead points on is fetched early.
    constexpr std::size_t kAhead = 16;
    for (std::size_t i = 0; i < n; ++i) {
      if (i + kAhead < n && at[i + kAhead] != kOut)
        hwy::Prefetch(sorted.data() + fill[at[i + kAhead]]);
      if (at[i] != kOut) {
        sorted_point<D>& sp = sorted[fill[at[i]]++];
        sp.point = static_cast<std::uint32_t>(i);
        sp.at = at[i];
        for (int a = 0; a < D; ++a) sp.frac[a] = pc.frac[a][i];
      }
    }
  }
  if (!sorted.empty()) {
    // The cells each occupied cell's points see, in raster order (x fastest).
    constexpr int kCells = D == 2 ? 9 : 27, kRows = kCells / 3;
    std::int64_t offset[kCells];
    for (int m = 0; m < kCells; ++m) {
      offset[m] = 0;
      for (int a = 0, r = m; a < D; ++a, r /= 3) offset[m] += (r % 3 - 1) * pc.stride[a];
    }
    std::uint32_t* const need = mark_needed<D>(pc, first.data(), ws.need, ws.need_scratch);
    const consts<D> c(g);
    box_impulses& im = ws.im;
    eval.prepare(sorted);

    shared_pairs& t = ws.t;
    t.n = 0;
    t.reserve(kSharePairs + static_cast<std::size_t>(kCells) * g.table().max_count() + lanes);
    std::vector<std::uint32_t>& pend = ws.pend;        // points whose pairs are in t
    std::vector<std::size_t>& pend_end = ws.pend_end;  // the end of each one's pairs
    pend.clear();
    pend_end.clear();
    const float scale = float(g.scale()), grad_scale = float(g.scale() * g.inverse_cell());
    auto flush = [&] {
      eval(c, t, pend, pend_end);
      for (std::size_t p = 0, b = 0; p < pend.size(); b = pend_end[p++]) {
        // Sums by fours (detail::gabor_point_sum), unfiltered and filtered alike.
        const float sum = point_sum(t.val.data() + b, pend_end[p] - b);
        float gs[3] = {0.0f, 0.0f, 0.0f};
        if constexpr (G)
          for (int a = 0; a < D; ++a) gs[a] = point_sum(t.g[a].data() + b, pend_end[p] - b);
        // (sum * amplitude) * scale as the scalar code (unfiltered: * 1, the same value).
        const float amp = eval.point_scale(p);
        value[pend[p]] = (sum * amp) * scale;
        if constexpr (G)
          for (int a = 0; a < D; ++a) grad[pend[p] * D + a] = (gs[a] * amp) * grad_scale;
      }
      eval.flushed(pend.size());
      t.n = 0;
      pend.clear();
      pend_end.clear();
    };
    const VF one = hn::Set(df, 1.0f);
    // Raw pointers and a local pair count: the compiler would reload the
    // vectors' pointers after every store otherwise.
    float* const td[3] = {t.d[0].data(), t.d[1].data(), t.d[2].data()};
    float* const tw = t.w.data();
    float* const ts = t.s.data();
    float* const ttheta = t.theta.data();
    float* const tx = t.x.data();
    float* const tphi[3] = {t.phi[0].data(), t.phi[1].data(), t.phi[2].data()};
    // The candidates of the points of one cell, in their order (rows of 3
    // cells in raster order, impulses in stream order), copied once per cell
    // into one list: per impulse o + u (float) and its marks.
    cell_candidates& cc = ws.cc;
    cc.reserve(static_cast<std::size_t>(kCells) * g.table().max_count() + 2 * lanes);
    float* const cpos[3] = {cc.pos[0].data(), cc.pos[1].data(), cc.pos[2].data()};
    float* const cphi[3] = {cc.phi[0].data(), cc.phi[1].data(), cc.phi[2].data()};
    float* const cw = cc.w.data();
    float* const cpp[3] = {cc.pp[0].data(), cc.pp[1].data(), cc.pp[2].data()};
    // The impulses are drawn a band of slabs (rows in 2D, planes in 3D) at a time, with the
    // band's two neighbouring slabs, when the points reach it: they stay in L2 between the
    // draw and their three reads (the whole box drawn first read them back from memory:
    // ~10% of a 2D call of 262144 points on AVX3). The margin slabs hold no points.
    const auto slab = static_cast<std::size_t>(pc.stride[D - 1]);
    const std::size_t band = std::max<std::size_t>(
        kShareBandMinSlabs,
        static_cast<std::size_t>(double(kShareBandImpulses) /
                                 std::max(double(slab) * g.table().mean(), 1.0)));
    std::size_t band_end = 0;  // the sorted position where the drawn band's points end
    const std::uint32_t* start = nullptr;
    const float *bx = nullptr, *iw = nullptr, *pos[3] = {}, *iphi[3] = {};
    for (std::size_t run = 0; run < sorted.size();) {
      const std::int64_t idx = sorted[run].at;
      if (run == band_end) {
        const std::size_t s0 = static_cast<std::size_t>(idx) / slab;
        const std::size_t s1 = std::min(s0 + band, pc.box / slab - 1);
        band_end = first[s1 * slab];
        draw_box<D>(g, c, pc, need, (s0 - 1) * slab, (s1 + 1) * slab, im);
        start = im.start.data();
        bx = im.bx.data();
        iw = im.w.data();
        for (int a = 0; a < 3; ++a) {
          pos[a] = im.pos[a < D ? a : D - 1].data();
          iphi[a] = im.phi[a < D ? a : D - 1].data();
        }
      }
      std::size_t run_end = run + 1;
      while (run_end < sorted.size() && sorted[run_end].at == sorted[run].at) ++run_end;
      const VF bxp = hn::Set(df, static_cast<float>(idx % pc.side[0]));
      std::size_t nc = 0;
      for (int r = 0; r < kRows; ++r) {
        // Row r: cells x - 1 ... x + 1 at offsets o (y, z) of the points' cell.
        const std::int64_t mid = idx + offset[3 * r + 1];
        const std::size_t b = start[static_cast<std::size_t>(mid - 1)];
        const std::size_t e = start[static_cast<std::size_t>(mid + 2)];
        VF orow[3];
        for (int a = 1, m = r; a < D; ++a, m /= 3)
          orow[a] = hn::Set(df, static_cast<float>(m % 3 - 1));
        // Whole vectors (the buffers have a vector of slack): the next row's
        // copy overwrites what this one writes beyond its end.
        for (std::size_t k = b; k < e; k += lanes) {
          const std::size_t dst = nc + (k - b);
          // o + u per axis, exact (detail::gabor_offset).
          hn::StoreU(hn::Add(hn::Sub(hn::LoadU(df, bx + k), bxp), hn::LoadU(df, pos[0] + k)), df,
                     cpos[0] + dst);
          for (int a = 1; a < D; ++a)
            hn::StoreU(hn::Add(orow[a], hn::LoadU(df, pos[a] + k)), df, cpos[a] + dst);
          VF ph[3];
          for (int a = 0; a < D; ++a) {
            ph[a] = hn::LoadU(df, iphi[a] + k);
            hn::StoreU(ph[a], df, cphi[a] + dst);
          }
          if constexpr (Eval::kExponent) {
            VF pp[3];
            phi_products<D>(ph, pp);
            for (int j = 0; j < D * (D + 1) / 2; ++j) hn::StoreU(pp[j], df, cpp[j] + dst);
          }
          hn::StoreU(hn::LoadU(df, iw + k), df, cw + dst);
        }
        nc += e - b;
      }
      // Pad to whole vectors with candidates far outside every support: o + u = 8
      // along x (d_x = frac - 8; the other axes keep finite values of earlier rows).
      hn::StoreU(hn::Set(df, 8.0f), df, cpos[0] + nc);
      for (std::size_t sp = run; sp < run_end; ++sp) {
        VF f[3];
        for (int a = 0; a < D; ++a) f[a] = hn::Set(df, sorted[sp].frac[a]);
        const typename Eval::point_filter pf = eval.filter_of(sp);
        std::size_t to = t.n;
        for (std::size_t k = 0; k < nc; k += lanes) {
          // frac - (o + u), as the scalar code. No branch on an empty
          // mask (storing nothing is cheaper than a mispredicted branch).
          VF d[3], ph[3];
          for (int a = 0; a < D; ++a) {
            d[a] = hn::Sub(f[a], hn::LoadU(df, cpos[a] + k));
            ph[a] = hn::LoadU(df, cphi[a] + k);
          }
          const VF s = point_s<D>(d);
          const MF in = hn::Lt(s, one);
          const compressor kept(in);
          if constexpr (Eval::kExponent) {
            VF pp[3], qd[3], x, theta;
            for (int e = 0; e < D * (D + 1) / 2; ++e) pp[e] = hn::LoadU(df, cpp[e] + k);
            filtered_exponent<D>(c.neg_a, pf.q, pf.nm2, d, ph, pp, qd, x, theta);
            hn::StoreU(kept(s), df, ts + to);
            hn::StoreU(kept(theta), df, ttheta + to);
            hn::StoreU(kept(x), df, tx + to);
          } else if constexpr (Eval::kOffsets) {
            for (int a = 0; a < D; ++a) {
              hn::StoreU(kept(d[a]), df, td[a] + to);
              hn::StoreU(kept(ph[a]), df, tphi[a] + to);
            }
          } else {
            // Values need only s and theta: two lists instead of 2 D.
            hn::StoreU(kept(s), df, ts + to);
            hn::StoreU(kept(point_phase<D>(ph, d)), df, ttheta + to);
          }
          hn::StoreU(kept(hn::LoadU(df, cw + k)), df, tw + to);
          to += hn::CountTrue(df, in);
        }
        t.n = to;
        pend.push_back(sorted[sp].point);
        pend_end.push_back(t.n);
        if (t.n >= kSharePairs) flush();
      }
      run = run_end;
    }
    flush();
  }
  if (rest.empty()) return;
  const std::size_t m = rest.size();
  std::vector<float> rp(m * D), v(m), gv(G ? m * D : 0);
  for (std::size_t j = 0; j < m; ++j)
    for (int a = 0; a < D; ++a) rp[j * D + a] = pts[rest[j] * D + a];
  lockstep(rp.data(), rest.data(), m, v.data(), G ? gv.data() : nullptr);
  for (std::size_t j = 0; j < m; ++j) {
    value[rest[j]] = v[j];
    if (G)
      for (int a = 0; a < D; ++a) grad[rest[j] * D + a] = gv[j * D + a];
  }
}

// ---- Grids: blocks of samples that share their cell.

// One axis of a grid, split as scalar evaluation splits grid.position(): the
// cell and fraction of (origin + step (first + i)) * inverse cell for i in [0, n),
// and runs of equal cells (at most `cap` long).
struct grid_axis {
  std::vector<std::uint32_t> cell;
  std::vector<float> frac;
  std::vector<char> bad;
  std::vector<std::size_t> run_start;  // runs [run_start[r], run_start[r + 1])
  grid_axis(double origin, double step, std::size_t first, std::size_t n, double inv,
            std::size_t cap)
      : cell(n), frac(n), bad(n) {
    for (std::size_t i = 0; i < n; ++i) {
      const lattice_coord<float> c =
          lattice_split<float>((origin + step * static_cast<double>(first + i)) * inv);
      cell[i] = c.i0;
      frac[i] = c.f;
      bad[i] = std::isnan(c.f) ? 1 : 0;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (i == 0 || cell[i] != cell[i - 1] || i - run_start.back() == cap) run_start.push_back(i);
    run_start.push_back(n);
  }
  std::size_t runs() const { return run_start.size() - 1; }
  std::size_t longest_run() const {
    std::size_t m = 0;
    for (std::size_t r = 0; r + 1 < run_start.size(); ++r)
      m = std::max(m, run_start[r + 1] - run_start[r]);
    return m;
  }
};

// The factors of one impulse along one axis of a block: for the block's
// samples [from, n) (padded to whole vectors with fractions far outside), offset
// d = frac - (o + u) (detail::gabor_offset), d^2 and the axis factors; `lo`, `hi`: the range of
// samples with d^2 < 1 (contiguous: frac is monotonic within a cell); along
// x (`ox`: each sample's o, the impulse's cell relative to the sample's) also
// the products e c and e s (gabor_pair_of_products' x side).
struct block_factors {
  std::vector<float> d, d2, e, s, c, ec, es;
  // Along x, per vector: the least d^2 of its lanes (a NaN lane counts as 0:
  // such a vector is never skipped).
  std::vector<float> vmin;
  std::size_t lo = 0, hi = 0;
  explicit block_factors(std::size_t cap)
      : d(cap), d2(cap), e(cap), s(cap), c(cap), ec(cap), es(cap), vmin(cap) {}
  void compute(const float* frac, std::size_t n_pad, float o, float u, VF neg_a, VF phi,
               const float* ox = nullptr, std::size_t from = 0) {
    const DF df;
    const std::size_t lanes = hn::Lanes(df);
    const VF ou = hn::Set(df, o), uu = hn::Set(df, u);
    lo = n_pad;
    hi = 0;
    for (std::size_t i = from; i < n_pad; i += lanes) {
      const VF dv = hn::Sub(hn::LoadU(df, frac + i), hn::Add(ox ? hn::LoadU(df, ox + i) : ou, uu));
      const VF d2v = hn::Mul(dv, dv);
      hn::StoreU(dv, df, d.data() + i);
      hn::StoreU(d2v, df, d2.data() + i);
      if (ox)
        vmin[i / lanes] = hn::GetLane(hn::MinOfLanes(df, hn::IfThenZeroElse(hn::IsNaN(d2v), d2v)));
      if (hn::AllFalse(df, hn::Lt(d2v, hn::Set(df, 1.0f)))) continue;
      lo = std::min(lo, i);
      hi = i + lanes;
      const axis f = axis_factors(dv, neg_a, phi);
      hn::StoreU(f.e, df, e.data() + i);
      hn::StoreU(f.s, df, s.data() + i);
      hn::StoreU(f.c, df, c.data() + i);
      hn::StoreU(hn::Mul(f.e, f.c), df, ec.data() + i);
      hn::StoreU(hn::Mul(f.e, f.s), df, es.data() + i);
    }
  }
};

template <int D, bool G>
struct grid_kernel {
  const gabor<D>& g;
  const consts<D> c;
  std::size_t cap[3];
  std::vector<float> acc, gacc[3];
  std::size_t stride = 0;  // floats per block row
  // The block's fractions per axis, padded (x to whole vectors).
  std::vector<float> frac[3];
  block_factors fx, fy, fz;
  // Along x: each sample's cell relative to the block's first (padded), the
  // runs of equal cells, the cells to visit, and o per sample for one of them.
  struct xrun {
    std::int32_t rel;
    std::size_t begin, end;
  };
  std::vector<std::int32_t> rel;
  static constexpr std::int32_t kFar = 1 << 20;  // rel of non-finite samples and padding
  std::vector<float> ox;
  std::vector<xrun> xruns;
  std::vector<std::int32_t> visits;

  // Each cell's impulses (positions, weight, frequency: stream order) drawn
  // once for the blocks that see it, in a direct-mapped cache keyed by the
  // cell (the low bits of its indices pick the slot: blocks go along x, so the
  // cells in use stay apart); a slot shared by two cells in use only repeats
  // a draw.
  struct drawn {
    float u[3], wt, phi[3];
  };
  struct slot {
    bool used = false;
    std::uint32_t key[3] = {};
    std::vector<drawn> imp;
  };
  static constexpr std::uint32_t kSlotsX = 64, kSlotsYZ = 4;
  std::vector<slot> cache{kSlotsX * kSlotsYZ * (D == 3 ? kSlotsYZ : 1)};
  const std::vector<drawn>& impulses(const std::uint32_t (&cell)[D]) {
    std::size_t i = cell[0] % kSlotsX + kSlotsX * (cell[1] % kSlotsYZ);
    if (D == 3) i += kSlotsX * kSlotsYZ * (cell[D - 1] % kSlotsYZ);
    slot& sl = cache[i];
    bool hit = sl.used;
    for (int a = 0; a < D; ++a) hit = hit && sl.key[a] == cell[a];
    if (hit) return sl.imp;
    sl.used = true;
    for (int a = 0; a < D; ++a) sl.key[a] = cell[a];
    sl.imp.clear();
    g.for_each_impulse(cell, [&](const std::uint32_t* w) {
      drawn d{};
      for (int a = 0; a < D; ++a) d.u[a] = gabor<D>::template impulse_position<float>(w, a);
      float mv[4] = {};
      vec<float, D> phi;
      g.template mark_values<float>(w, mv);
      g.marks().template draw<float>(mv, d.wt, phi);
      for (int a = 0; a < D; ++a) d.phi[a] = phi[a];
      sl.imp.push_back(d);
    });
    return sl.imp;
  }

  explicit grid_kernel(const gabor<D>& noise, std::size_t cx, std::size_t cy, std::size_t cz)
      : g(noise),
        c(noise),
        cap{cx, cy, cz},
        fx(cx + kMaxLanes),
        fy(cy + kMaxLanes),
        fz(cz + kMaxLanes) {
    stride = cx + kMaxLanes;
    const std::size_t cells = stride * cy * cz;
    acc.resize(cells);
    if (G)
      for (int a = 0; a < D; ++a) gacc[a].resize(cells);
    for (int a = 0; a < 3; ++a) frac[a].resize(cap[a] + kMaxLanes);
    rel.resize(stride);
    ox.resize(stride);
  }

  // Adds one impulse's terms (factors along each axis in fx, fy, fz) to the
  // block's sums: per row the row's side of gabor_pair_of_products, per
  // sample only the products and the taper, which is 0 outside the support
  // (no mask: adding +-0 leaves every sum as the scalar path's).
  void add_impulse(const float* phi, float wt, std::size_t ny, std::size_t nz) {
    const DF df;
    const std::size_t lanes = hn::Lanes(df);
    const VF phx = hn::Set(df, phi[0]);
    for (std::size_t kk = 0; kk < nz; ++kk) {
      if constexpr (D == 3)
        if (!(fz.d2[kk] < 1.0f)) continue;
      for (std::size_t jj = std::min(fy.lo, ny); jj < std::min(fy.hi, ny); ++jj) {
        if (!(fy.d2[jj] < 1.0f)) continue;
        detail::gabor_row<float> r;
        if constexpr (D == 2) {
          r = detail::gabor_row_of(
              wt, detail::gabor_axis<float>{fy.d[jj], fy.d2[jj], fy.e[jj], fy.s[jj], fy.c[jj]});
        } else {
          r = detail::gabor_row_of(
              wt, detail::gabor_axis<float>{fy.d[jj], fy.d2[jj], fy.e[jj], fy.s[jj], fy.c[jj]},
              detail::gabor_axis<float>{fz.d[kk], fz.d2[kk], fz.e[kk], fz.s[kk], fz.c[kk]});
        }
        const VF b = hn::Set(df, r.we * r.c), q = hn::Set(df, r.we * r.s);
        const VF rd2 = hn::Set(df, r.d2);
        // Local restrict pointers: the sums' stores alias no factor, so the
        // loop keeps them in registers.
        float* HWY_RESTRICT arow = acc.data() + (kk * ny + jj) * stride;
        const float* HWY_RESTRICT xec = fx.ec.data();
        const float* HWY_RESTRICT xes = fx.es.data();
        const float* HWY_RESTRICT xd2 = fx.d2.data();
        // The row's chord of the support, by whole vectors: a vector whose
        // least d^2 plus the row's is >= 1 only adds +-0 (float addition and
        // the taper's steps are monotonic), so skipping it changes nothing.
        std::size_t ib = fx.lo, ie = fx.hi;
        while (ib < ie && !(fx.vmin[ib / lanes] + r.d2 < 1.0f)) ib += lanes;
        while (ie > ib && !(fx.vmin[ie / lanes - 1] + r.d2 < 1.0f)) ie -= lanes;
        for (std::size_t ii = ib; ii < ie; ii += lanes) {
          const VF ec = hn::LoadU(df, xec + ii), es = hn::LoadU(df, xes + ii);
          const VF s2 = hn::Add(hn::LoadU(df, xd2 + ii), rd2);
          if constexpr (G) {
            VF v, uu, vv;
            pair_gradient_of_products(ec, es, b, q, s2, c.k, c.a, v, uu, vv);
            hn::StoreU(hn::Add(hn::LoadU(df, arow + ii), v), df, arow + ii);
            const VF dd[3] = {hn::LoadU(df, fx.d.data() + ii), hn::Set(df, fy.d[jj]),
                              hn::Set(df, D == 3 ? fz.d[kk] : 0.0f)};
            const VF ph[3] = {phx, hn::Set(df, phi[1]), hn::Set(df, D == 3 ? phi[D - 1] : 0.0f)};
            for (int a = 0; a < D; ++a) {
              float* grow = gacc[a].data() + (kk * ny + jj) * stride;
              const VF term = hn::Sub(hn::Mul(uu, dd[a]), hn::Mul(vv, ph[a]));
              hn::StoreU(hn::Add(hn::LoadU(df, grow + ii), term), df, grow + ii);
            }
          } else {
            hn::StoreU(hn::Add(hn::LoadU(df, arow + ii), pair_of_products(ec, es, b, q, s2, c.k)),
                       df, arow + ii);
          }
        }
      }
    }
  }

  // One block: samples [i0, i0 + nx) x [j0, j0 + ny) x [k0, k0 + nz) of the
  // axes, along y (and z) all in the cell (ay.cell[j0], az.cell[k0]), along x
  // in any cells: each impulse's factors along y (and z) are computed once for
  // the whole width, and its chord of each row is cut by no block edge but the
  // block's.
  void block(const grid_axis* axes, std::size_t i0, std::size_t nx, std::size_t j0, std::size_t ny,
             std::size_t k0, std::size_t nz, const hush::grid<D>& gr, float* value, float* grad) {
    const DF df;
    const DI di;
    const std::size_t lanes = hn::Lanes(df);
    const std::size_t nx_pad = (nx + lanes - 1) / lanes * lanes;
    const std::size_t n[3] = {nx, ny, nz}, first[3] = {i0, j0, k0};
    for (int a = 0; a < D; ++a) {
      std::copy(axes[a].frac.begin() + static_cast<std::ptrdiff_t>(first[a]),
                axes[a].frac.begin() + static_cast<std::ptrdiff_t>(first[a] + n[a]),
                frac[a].begin());
      std::fill(frac[a].begin() + static_cast<std::ptrdiff_t>(n[a]), frac[a].end(),
                4.0f);  // d^2 > 1
    }
    const std::size_t rows = ny * nz;
    std::fill(acc.begin(), acc.begin() + static_cast<std::ptrdiff_t>(rows * stride), 0.0f);
    if constexpr (G)
      for (int a = 0; a < D; ++a)
        std::fill(gacc[a].begin(), gacc[a].begin() + static_cast<std::ptrdiff_t>(rows * stride),
                  0.0f);
    // Along x: each sample's cell relative to the first finite sample's (a
    // non-finite sample, or padding, far away: its value is NaN or unused),
    // the runs of equal cells, and the cells to visit (each run's and its
    // neighbours, ascending: per sample the scalar order o = -1, 0, 1).
    std::size_t f0 = 0;
    while (f0 < nx && axes[0].bad[i0 + f0]) ++f0;
    const std::uint32_t ref = f0 < nx ? axes[0].cell[i0 + f0] : 0u;
    xruns.clear();
    visits.clear();
    for (std::size_t i = 0; i < nx_pad; ++i) {
      if (i >= nx || axes[0].bad[i0 + i]) {
        rel[i] = kFar;
        continue;
      }
      rel[i] = static_cast<std::int32_t>(axes[0].cell[i0 + i] - ref);
      if (xruns.empty() || xruns.back().rel != rel[i] || xruns.back().end != i)
        xruns.push_back({rel[i], i, i + 1});
      else
        xruns.back().end = i + 1;
    }
    for (const xrun& x : xruns)
      for (std::int32_t o = -1; o <= 1; ++o) visits.push_back(x.rel + o);
    std::sort(visits.begin(), visits.end());
    visits.erase(std::unique(visits.begin(), visits.end()), visits.end());
    const std::uint32_t base[3] = {ref, axes[1].cell[j0], D == 3 ? axes[D - 1].cell[k0] : 0u};
    for (int oz = D == 3 ? -1 : 0; oz <= (D == 3 ? 1 : 0); ++oz)
      for (int oy = -1; oy <= 1; ++oy)
        for (const std::int32_t X : visits) {
          // The samples within one cell of X (contiguous: cells are monotonic
          // along x), by whole vectors, and their o = X - rel (clamped: from 2
          // on, d^2 >= 1 exactly).
          std::size_t lo = nx_pad, hi = 0;
          for (const xrun& x : xruns)
            if (x.rel >= X - 1 && x.rel <= X + 1) {
              lo = std::min(lo, x.begin);
              hi = std::max(hi, x.end);
            }
          if (lo >= hi) continue;
          lo = lo / lanes * lanes;
          hi = (hi + lanes - 1) / lanes * lanes;
          const VI xv = hn::Set(di, X), two = hn::Set(di, 2);
          for (std::size_t i = lo; i < hi; i += lanes) {
            const VI o = hn::Sub(xv, hn::LoadU(di, rel.data() + i));
            hn::StoreU(hn::ConvertTo(df, hn::Min(hn::Max(o, hn::Neg(two)), two)), df,
                       ox.data() + i);
          }
          std::uint32_t cell[D];
          cell[0] = ref + static_cast<std::uint32_t>(X);
          cell[1] = base[1] + static_cast<std::uint32_t>(oy);
          if constexpr (D == 3) cell[2] = base[2] + static_cast<std::uint32_t>(oz);
          for (const drawn& im : impulses(cell)) {
            const float* u = im.u;
            const float* phi = im.phi;
            const float wt = im.wt;
            fy.compute(frac[1].data(), (ny + lanes - 1) / lanes * lanes, float(oy), u[1], c.neg_a,
                       hn::Set(df, phi[1]));
            if (fy.lo >= fy.hi) continue;
            if constexpr (D == 3) {
              fz.compute(frac[2].data(), (nz + lanes - 1) / lanes * lanes, float(oz), u[2], c.neg_a,
                         hn::Set(df, phi[2]));
              if (fz.lo >= fz.hi) continue;
            }
            fx.compute(frac[0].data(), hi, 0.0f, u[0], c.neg_a, hn::Set(df, phi[0]), ox.data(), lo);
            if (fx.lo >= fx.hi) continue;
            add_impulse(phi, wt, ny, nz);
          }
        }
    // Out: value = sum * scale, gradient = sum * (scale / cell); NaN where a
    // coordinate of the sample is not finite.
    const float scale = float(g.scale()), gscale = float(g.scale() * g.inverse_cell());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::size_t gx = gr.size[0], gy = gr.size[1];
    const VF vscale = hn::Set(df, scale), vnan = hn::Set(df, nan);
    const VI far = hn::Set(di, kFar);
    for (std::size_t kk = 0; kk < nz; ++kk)
      for (std::size_t jj = 0; jj < ny; ++jj) {
        const bool row_bad = axes[1].bad[j0 + jj] || (D == 3 && axes[D - 1].bad[k0 + kk]);
        const std::size_t out_row = ((k0 + kk) * gy + (j0 + jj)) * gx + i0;
        const float* arow = acc.data() + (kk * ny + jj) * stride;
        std::size_t ii = 0;
        if (!row_bad)  // whole vectors; rel marks the non-finite samples
          for (; ii + lanes <= nx; ii += lanes) {
            const MF bad = hn::RebindMask(df, hn::Eq(hn::LoadU(di, rel.data() + ii), far));
            hn::StoreU(hn::IfThenElse(bad, vnan, hn::Mul(hn::LoadU(df, arow + ii), vscale)), df,
                       value + out_row + ii);
          }
        for (; ii < nx; ++ii)
          value[out_row + ii] = row_bad || axes[0].bad[i0 + ii] ? nan : arow[ii] * scale;
        if constexpr (G)
          for (ii = 0; ii < nx; ++ii) {
            const bool bad = row_bad || axes[0].bad[i0 + ii];
            for (int a = 0; a < D; ++a)
              grad[(out_row + ii) * D + static_cast<std::size_t>(a)] =
                  bad ? nan : gacc[a][(kk * ny + jj) * stride + ii] * gscale;
          }
      }
  }
};

// The slab [first, first + count) of a grid's slowest axis (value and grad
// start at its first sample): blocks of shared cells when there are enough
// samples per cell along x, else the points path on the grid's positions.
template <int D, bool G>
void grid(const gabor<D>& g, const hush::grid<D>& whole, std::size_t first, std::size_t count,
          float* value, float* grad) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const double inv = g.inverse_cell();
  const std::size_t caps[3] = {64, D == 2 ? 64u : 32u, 16};
  hush::grid<D> gr = whole;  // the slab's sizes (output indexing); positions from `whole`
  gr.size[D - 1] = count;
  std::vector<grid_axis> axes;
  axes.reserve(D);
  for (int a = 0; a < D; ++a)
    axes.emplace_back(whole.origin[a], whole.step[a], a == D - 1 ? first : 0, gr.size[a], inv,
                      caps[a]);
  const double per_cell = static_cast<double>(gr.size[0]) / static_cast<double>(axes[0].runs());
  const std::size_t nx = gr.size[0], ny = gr.size[1];
  if (per_cell < kMinRun) {
    lanes_split sp;
    auto split = [&](std::size_t batch, std::size_t used) {
      for (std::size_t l = 0; l < lanes; ++l) {
        if (l >= used) {
          clear_lane<D>(sp, l);
          continue;
        }
        const std::size_t idx = batch + l, i = idx % nx, j = (idx / nx) % ny, k = idx / (nx * ny);
        const std::size_t ijk[3] = {i, j, k};
        bool bad = false;
        for (int a = 0; a < D; ++a) {
          sp.cell[a][l] = axes[a].cell[ijk[a]];
          sp.frac[a][l] = axes[a].frac[ijk[a]];
          bad = bad || axes[a].bad[ijk[a]];
        }
        sp.bad[l] = bad;
      }
    };
    points<D, G, true>(g, gr.count(), sp, split, value, grad);
    return;
  }
  // Block buffers sized by the longest runs, not the caps: small grids do not pay for
  // (and page-fault in) buffers they never fill.
  // Along x, blocks of kBlockX samples whatever their cells (see block()) where
  // the finite samples' cells step by at most one (so a block's cells relative to
  // its first are small and ascend or descend); else (only where coordinates are
  // so large that a double's spacing exceeds a cell) blocks of one cell's run.
  bool steps_of_one = true;
  for (std::size_t i = 0, last = nx; i < nx && steps_of_one; ++i) {
    if (axes[0].bad[i]) continue;
    if (last < nx) {
      const auto step = static_cast<std::int32_t>(axes[0].cell[i] - axes[0].cell[last]);
      steps_of_one = step >= -1 && step <= 1;
    }
    last = i;
  }
  const std::size_t bx = std::min(nx, kBlockX[D - 2]);
  grid_kernel<D, G> kernel(g, bx, axes[1].longest_run(), D == 3 ? axes[D - 1].longest_run() : 1);
  auto each_block = [&](auto&& f) {
    if (steps_of_one)
      for (std::size_t i0 = 0; i0 < nx; i0 += bx) f(i0, std::min(bx, nx - i0));
    else
      for (std::size_t xr = 0; xr < axes[0].runs(); ++xr)
        f(axes[0].run_start[xr], axes[0].run_start[xr + 1] - axes[0].run_start[xr]);
  };
  const std::size_t zruns = D == 3 ? axes[D - 1].runs() : 1;
  for (std::size_t zr = 0; zr < zruns; ++zr) {
    const std::size_t k0 = D == 3 ? axes[D - 1].run_start[zr] : 0;
    const std::size_t k1 = D == 3 ? axes[D - 1].run_start[zr + 1] : 1;
    for (std::size_t yr = 0; yr < axes[1].runs(); ++yr) {
      const std::size_t j0 = axes[1].run_start[yr], j1 = axes[1].run_start[yr + 1];
      each_block([&](std::size_t i0, std::size_t n) {
        kernel.block(axes.data(), i0, n, j0, j1 - j0, k0, k1 - k0, gr, value, grad);
      });
    }
  }
}

}  // namespace gabor_simd

// Gabor noise at n interleaved float points on the lockstep path (one lane per
// point); values into value[n], interleaved gradients into grad[D n] unless
// grad is null.
template <int D>
void gabor_points_lockstep(const gabor<D>& g, const float* pts, std::size_t n, float* value,
                           float* grad) {
  namespace gs = gabor_simd;
  const double inv = g.inverse_cell();
  gs::lanes_split sp;
  auto split = [&](std::size_t first, std::size_t used) {
    gs::split_batch<D>(sp, pts, first, used, inv);
  };
  if (grad)
    gs::points<D, true, false>(g, n, sp, split, value, grad);
  else
    gs::points<D, false, false>(g, n, sp, split, value, nullptr);
}

// Gabor noise at n interleaved float points (the shared-cell path, its box's
// outliers on the lockstep path); values into value[n], interleaved gradients
// into grad[D n] unless grad is null.
template <int D>
void gabor_points(const gabor<D>& g, const float* pts, std::size_t n, float* value, float* grad) {
  auto lockstep = [&g](const float* p, const std::size_t*, std::size_t m, float* v, float* gr) {
    gabor_points_lockstep<D>(g, p, m, v, gr);
  };
  for (std::size_t first = 0; first < n; first += gabor_simd::kShareMaxPoints) {
    const std::size_t m = std::min(gabor_simd::kShareMaxPoints, n - first);
    const float* p = pts + first * D;
    if (grad) {
      gabor_simd::shared_unfiltered<D, true> eval;
      gabor_simd::shared_points<D, true>(g, p, m, value + first, grad + first * D, lockstep, eval);
    } else {
      gabor_simd::shared_unfiltered<D, false> eval;
      gabor_simd::shared_points<D, false>(g, p, m, value + first, nullptr, lockstep, eval);
    }
  }
}
inline void gabor2_points(const gabor<2>& g, const float* xy, std::size_t n, float* value,
                          float* grad) {
  gabor_points<2>(g, xy, n, value, grad);
}
inline void gabor3_points(const gabor<3>& g, const float* xyz, std::size_t n, float* value,
                          float* grad) {
  gabor_points<3>(g, xyz, n, value, grad);
}

// Gabor noise filtered over footprints on the lockstep path (one lane per point): the
// n interleaved float points pts with the footprints fps[index[i]] (index null:
// fps[i]); values into value[n], interleaved gradients into grad[D n] unless grad is
// null.
template <int D>
void gabor_filtered_lockstep(const gabor<D>& g, const float* pts, const footprint<D>* fps,
                             const std::size_t* index, std::size_t n, float* value, float* grad) {
  namespace gs = gabor_simd;
  const gs::DF df;
  const std::size_t lanes = hn::Lanes(df);
  const double inv = g.inverse_cell(), a = g.kernel().envelope_exponent();
  gs::lanes_split sp;
  gs::lanes_filter filt;
  auto split = [&](std::size_t first, std::size_t used) {
    gs::split_batch<D>(sp, pts, first, used, inv);
    for (std::size_t l = 0; l < lanes; ++l) {
      if (l >= used) {  // unused lanes keep no impulse (bad): any finite filter
        for (int e = 0; e < 6; ++e) filt.q[e][l] = filt.nm2[e][l] = 0.0f;
        sp.amp[l] = 0.0f;
        continue;
      }
      const detail::gabor_filter_coefs<float, D> f(
          gabor_filter<D>(fps[index ? index[first + l] : first + l], a, inv));
      filt.set<D>(l, f);
      sp.amp[l] = f.amplitude;
    }
  };
  if (grad)
    gs::points_with<D, true, true>(g, n, sp, split, value, grad,
                                   [&filt](const gs::consts<D>& c, gs::tuples& t, std::size_t) {
                                     gs::eval_filtered<D, true>(c, filt, t);
                                   });
  else
    gs::points_with<D, false, true>(g, n, sp, split, value, nullptr,
                                    [&filt](const gs::consts<D>& c, gs::tuples& t, std::size_t) {
                                      gs::eval_filtered<D, false>(c, filt, t);
                                    });
}

// Gabor noise filtered over footprints (gabor<D>::sample(p, fp), no normals) at n
// interleaved float points, as gabor_points: the shared-cell path with the filtered
// kernel, its box's outliers on the lockstep path; values into value[n], interleaved
// gradients into grad[D n] unless grad is null.
template <int D>
void gabor_filtered(const gabor<D>& g, const float* pts, const footprint<D>* fps, std::size_t n,
                    float* value, float* grad) {
  const double a = g.kernel().envelope_exponent(), inv = g.inverse_cell();
  for (std::size_t first = 0; first < n; first += gabor_simd::kShareMaxPoints) {
    const std::size_t m = std::min(gabor_simd::kShareMaxPoints, n - first);
    const float* p = pts + first * D;
    const footprint<D>* f = fps + first;
    auto lockstep = [&g, f](const float* lp, const std::size_t* index, std::size_t lm, float* v,
                            float* gr) { gabor_filtered_lockstep<D>(g, lp, f, index, lm, v, gr); };
    if (grad) {
      gabor_simd::shared_filtered<D, true> eval(f, a, inv);
      gabor_simd::shared_points<D, true>(g, p, m, value + first, grad + first * D, lockstep, eval);
    } else {
      gabor_simd::shared_filtered<D, false> eval(f, a, inv);
      gabor_simd::shared_points<D, false>(g, p, m, value + first, nullptr, lockstep, eval);
    }
  }
}
inline void gabor2_filtered(const gabor<2>& g, const float* xy, const footprint<2>* fps,
                            std::size_t n, float* value, float* grad) {
  gabor_filtered<2>(g, xy, fps, n, value, grad);
}
inline void gabor3_filtered(const gabor<3>& g, const float* xyz, const footprint<3>* fps,
                            std::size_t n, float* value, float* grad) {
  gabor_filtered<3>(g, xyz, fps, n, value, grad);
}

// Surface noise (gabor<3>::sample(p, normal, fp)) at n interleaved float
// points with interleaved float normals and footprints (null: point
// footprints); values into value[n], interleaved gradients into grad[3 n]
// unless grad is null. As the scalar code: a non-finite normal gives NaN, a
// zero normal the solid noise filtered over fp.
inline void gabor3_surface(const gabor<3>& g, const float* xyz, const float* normals,
                           const footprint<3>* fps, std::size_t n, float* value, float* grad) {
  namespace gs = gabor_simd;
  const gs::DF df;
  const std::size_t lanes = hn::Lanes(df);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Sort the samples into surface (unit normal), solid (zero normal) and NaN.
  std::vector<std::size_t> surface, solid;
  std::vector<vec<double, 3>> unit;
  for (std::size_t i = 0; i < n; ++i) {
    const vec<double, 3> nv{normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
    vec<double, 3> u;
    if (!std::isfinite(nv.x) || !std::isfinite(nv.y) || !std::isfinite(nv.z)) {
      value[i] = nan;
      if (grad) grad[3 * i] = grad[3 * i + 1] = grad[3 * i + 2] = nan;
    } else if (gabor<3>::unit_normal(nv, u)) {
      surface.push_back(i);
      unit.push_back(u);
    } else {
      solid.push_back(i);
    }
  }
  const footprint<3> point_fp{};
  auto fp_of = [&](std::size_t i) -> const footprint<3>& { return fps ? fps[i] : point_fp; };
  if (!solid.empty()) {  // the solid path on the gathered samples, scattered back
    std::vector<float> p(3 * solid.size()), v(solid.size()), gv(grad ? 3 * solid.size() : 0);
    std::vector<footprint<3>> f(solid.size());
    for (std::size_t j = 0; j < solid.size(); ++j) {
      for (int a = 0; a < 3; ++a) p[3 * j + a] = xyz[3 * solid[j] + a];
      f[j] = fp_of(solid[j]);
    }
    gabor_filtered<3>(g, p.data(), f.data(), solid.size(), v.data(), grad ? gv.data() : nullptr);
    for (std::size_t j = 0; j < solid.size(); ++j) {
      value[solid[j]] = v[j];
      if (grad)
        for (int a = 0; a < 3; ++a) grad[3 * solid[j] + a] = gv[3 * j + a];
    }
  }
  if (surface.empty()) return;
  const std::size_t m = surface.size();
  std::vector<float> v(m), gv(grad ? 3 * m : 0);
  gs::lanes_split sp;
  gs::lanes_filter filt;
  gs::lanes_frame frame;
  auto split = [&](std::size_t first, std::size_t used) {
    gs::split_lanes<3>(sp, first, used, g.inverse_surface_cell(), [&](std::size_t j, double* x) {
      for (int a = 0; a < 3; ++a) x[a] = static_cast<double>(xyz[3 * surface[j] + a]);
    });
    for (std::size_t l = 0; l < lanes; ++l) {
      if (l >= used) {  // unused lanes: any finite frame and filter (their sums are dropped)
        for (int a = 0; a < 3; ++a) frame.n[a][l] = frame.t[a][l] = frame.b[a][l] = 0.0f;
        for (int e = 0; e < 3; ++e) filt.q[e][l] = filt.nm2[e][l] = 0.0f;
        sp.amp[l] = 0.0f;
        continue;
      }
      vec<double, 3> t, b;
      const std::size_t j = first + l;
      const detail::gabor_filter_coefs<float, 2> fl(g.surface_frame(unit[j], fp_of(surface[j]), t, b));
      for (int a = 0; a < 3; ++a) {
        frame.n[a][l] = static_cast<float>(unit[j][a]);
        frame.t[a][l] = static_cast<float>(t[a]);
        frame.b[a][l] = static_cast<float>(b[a]);
      }
      filt.set<2>(l, fl);
      sp.amp[l] = fl.amplitude;
    }
  };
  // The slab and disk tests of surface_eval, per lane of the batch.
  auto keep = [&](const gs::VF* d, const gs::VF*) {
    gs::VF nt[3], tt[3], bt[3];
    for (int a = 0; a < 3; ++a) {
      nt[a] = hn::Load(df, frame.n[a]);
      tt[a] = hn::Load(df, frame.t[a]);
      bt[a] = hn::Load(df, frame.b[a]);
    }
    const gs::plane_offsets o = gs::plane_of(d, nt, tt, bt);
    const gs::VF one = hn::Set(df, 1.0f);
    return hn::And(hn::Lt(o.z2, one), hn::Lt(o.s, one));
  };
  const gs::process pr{detail::constants::kGaborSurfaceStream, &g.surface_table(),
                       gabor<3>::words_for(g.parameters().kind, 3), float(g.surface_scale()),
                       float(g.surface_scale() * g.inverse_surface_cell())};
  if (grad)
    gs::process_points<3, 3, true>(g, pr, m, sp, split, keep, v.data(), gv.data(),
                                   [&](const gs::consts<3>& c, gs::tuples& t, std::size_t) {
                                     gs::eval_surface<true>(c, filt, frame, t);
                                   });
  else
    gs::process_points<3, 3, false>(g, pr, m, sp, split, keep, v.data(), nullptr,
                                    [&](const gs::consts<3>& c, gs::tuples& t, std::size_t) {
                                      gs::eval_surface<false>(c, filt, frame, t);
                                    });
  for (std::size_t j = 0; j < m; ++j) {
    value[surface[j]] = v[j];
    if (grad)
      for (int a = 0; a < 3; ++a) grad[3 * surface[j] + a] = gv[3 * j + a];
  }
}

// Gabor noise on the slab [first, first + count) of a uniform grid's slowest
// axis (C order, i fastest; value and grad start at the slab's first sample);
// gradients interleaved (D per sample) unless grad is null. Each sample's
// value does not depend on the slab (exec::parallel's slabs give the whole
// grid's result).
template <int D>
void gabor_grid(const gabor<D>& g, const grid<D>& gr, std::size_t first, std::size_t count,
                float* value, float* grad) {
  if (count == 0) return;
  if (grad)
    gabor_simd::grid<D, true>(g, gr, first, count, value, grad);
  else
    gabor_simd::grid<D, false>(g, gr, first, count, value, nullptr);
}
inline void gabor2_grid(const gabor<2>& g, const grid<2>& gr, std::size_t first, std::size_t count,
                        float* value, float* grad) {
  gabor_grid<2>(g, gr, first, count, value, grad);
}
inline void gabor3_grid(const gabor<3>& g, const grid<3>& gr, std::size_t first, std::size_t count,
                        float* value, float* grad) {
  gabor_grid<3>(g, gr, first, count, value, grad);
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_GABOR_SIMD_INL_H_ toggle
