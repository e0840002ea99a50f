// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The lane toolbox the SIMD kernels share (hush/<noise>/*-inl.h): float lane
// types, multiply-adds as the scalar code is compiled, core/hash.hpp's hashes,
// core/rng.hpp's stream keys and draws, core/lattice.hpp's split of an axis,
// detail/elementary.hpp's exp and sin/cos, detail/approx_math.hpp's exp2 and
// log2, compression of selected lanes, interleaved stores and the batch
// driver. Only generic lane maths lives here; each noise's own algorithm stays
// in its kernel. Every function repeats its scalar counterpart operation by
// operation, so under HUSH_STRICT_FP a kernel built on them gives the scalar
// bits on every target. Compiled once per SIMD target (the "-inl.h"
// convention: toggle guard below); included by the kernels, never by users.
#if defined(HUSH_SIMD_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_SIMD_LANES_INL_H_
#undef HUSH_SIMD_LANES_INL_H_
#else
#define HUSH_SIMD_LANES_INL_H_
#endif

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/detail/constants.hpp"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace lanes {
namespace hn = hwy::HWY_NAMESPACE;

// Full vectors of floats and of their 32-bit integers; kernels take them with
// `using namespace lanes::types;`.
namespace types {
using DF = hn::ScalableTag<float>;
using DU = hn::RebindToUnsigned<DF>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VU = hn::Vec<DU>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;
}  // namespace types
using namespace types;

// Largest float lane count of any target (SVE's 2048 bits), for buffers and
// table padding sized once for every target.
constexpr std::size_t kMaxLanes = 64;

// ---- Arithmetic as the scalar code is compiled.

// a * b + c for any float or double vector: two roundings under HUSH_STRICT_FP
// (the scalar code is compiled without contraction there), one fused rounding
// otherwise.
template <class V>
HWY_INLINE V mul_add(V a, V b, V c) {
#if HUSH_CONFIG_STRICT_FP
  return hn::Add(hn::Mul(a, b), c);
#else
  return hn::MulAdd(a, b, c);
#endif
}
// c - a * b, rounded as mul_add.
template <class V>
HWY_INLINE V neg_mul_add(V a, V b, V c) {
#if HUSH_CONFIG_STRICT_FP
  return hn::Sub(c, hn::Mul(a, b));
#else
  return hn::NegMulAdd(a, b, c);
#endif
}

// ---- core/hash.hpp in 32-bit lanes.

// hash32 without its last step x ^= x >> kHashShift3, which changes only the
// low kHashShift3 bits: bits kHashShift3 ... 31 equal hash32's, the rest do
// not. For callers that read only the high bits.
HWY_INLINE VU hash32_high(VU x) {
  namespace c = detail::constants;
  const DU du;
  x = hn::Xor(x, hn::ShiftRight<c::kHashShift1>(x));
  x = hn::Mul(x, hn::Set(du, c::kHashMul1));
  x = hn::Xor(x, hn::ShiftRight<c::kHashShift2>(x));
  return hn::Mul(x, hn::Set(du, c::kHashMul2));
}
// hash32(x): every bit of the scalar hash.
HWY_INLINE VU hash32(VU x) {
  const VU h = hash32_high(x);
  return hn::Xor(h, hn::ShiftRight<detail::constants::kHashShift3>(h));
}

// lattice_word_x/y/z: i * P_x, rotl(j * P_y, R_y), rotl(k * P_z, R_z), mod 2^32.
HWY_INLINE VU word_x(VU i) { return hn::Mul(i, hn::Set(DU(), detail::constants::kLatticePrimeX)); }
HWY_INLINE VU word_y(VU j) {
  namespace c = detail::constants;
  return hn::RotateRight<32 - c::kLatticeRotateY>(hn::Mul(j, hn::Set(DU(), c::kLatticePrimeY)));
}
HWY_INLINE VU word_z(VU k) {
  namespace c = detail::constants;
  return hn::RotateRight<32 - c::kLatticeRotateZ>(hn::Mul(k, hn::Set(DU(), c::kLatticePrimeZ)));
}
// The lattice word of axis kAxis (0: x, 1: y, 2: z).
template <int kAxis>
HWY_INLINE VU word(VU i) {
  if constexpr (kAxis == 0) return word_x(i);
  if constexpr (kAxis == 1) return word_y(i);
  if constexpr (kAxis == 2) return word_z(i);
}

// ---- core/rng.hpp in 32-bit lanes: hush::rng streams drawn per lane.
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

// ---- core/lattice.hpp in lanes.
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

// ---- detail/elementary.hpp in lanes (the float branch, op for op).

// e^x for x in [kExpFloor, 0] (no NaN): exp_neg without its clamps, which are
// identities there. Within 2^-22 relative, as exp_neg.
HWY_INLINE VF exp_neg_in_range(VF x) {
  namespace c = detail::constants;
  const DF df;
  const DI di;
  const VF n = hn::Floor(mul_add(x, hn::Set(df, float(c::kLog2E)), hn::Set(df, 0.5f)));
  const VF r = neg_mul_add(n, hn::Set(df, float(c::kLn2Lo)),
                           neg_mul_add(n, hn::Set(df, float(c::kLn2Hi)), x));
  VF p = hn::Set(df, float(c::kExpPoly[c::kExpDegree]));
  for (int i = c::kExpDegree - 1; i >= 0; --i)
    p = mul_add(p, r, hn::Set(df, float(c::kExpPoly[i])));
  const VI bits = hn::ShiftLeft<23>(hn::Add(hn::ConvertTo(di, n), hn::Set(di, 127)));
  return hn::Mul(p, hn::BitCast(df, bits));
}
// exp_neg: e^x for any x; x > 0 is taken as 0, x < kExpFloor gives 0, NaN
// gives that NaN. Within 2^-22 relative.
HWY_INLINE VF exp_neg(VF x) {
  namespace c = detail::constants;
  const DF df;
  const VF zero = hn::Zero(df), lo = hn::Set(df, float(c::kExpFloor));
  const VF v = exp_neg_in_range(hn::Max(hn::IfThenElse(hn::Gt(x, zero), zero, x), lo));
  // Below the floor: 0; NaN: the NaN itself (as the scalar code returns x).
  return hn::IfThenElse(hn::IsNaN(x), x, hn::IfThenElseZero(hn::Ge(x, lo), v));
}
// exp_neg for x that is not NaN: the same values without its NaN case.
HWY_INLINE VF exp_neg_finite(VF x) {
  const DF df;
  const VF lo = hn::Set(df, float(detail::constants::kExpFloor));
  return hn::IfThenZeroElse(hn::Lt(x, lo), exp_neg_in_range(hn::Max(hn::Min(x, hn::Zero(df)), lo)));
}

// sin/cos of 2 pi u for |u| < 1/2 + kTurnsReduceLimit: the quadrant q (an
// integer), r = u - q / 4, and the polynomials s ~ sin(2 pi r), pc ~ cos(2 pi r).
HWY_INLINE void sincos_quadrant(VF u, VF& q, VF& s, VF& pc) {
  namespace c = detail::constants;
  const DF df;
  q = hn::Floor(mul_add(u, hn::Set(df, 4.0f), hn::Set(df, 0.5f)));
  const VF r = neg_mul_add(q, hn::Set(df, 0.25f), u);
  const VF z = hn::Mul(r, r);
  VF ps = hn::Set(df, float(c::kSinPoly[c::kSinDegree]));
  for (int i = c::kSinDegree - 1; i >= 0; --i)
    ps = mul_add(ps, z, hn::Set(df, float(c::kSinPoly[i])));
  pc = hn::Set(df, float(c::kCosPoly[c::kCosDegree]));
  for (int i = c::kCosDegree - 1; i >= 0; --i)
    pc = mul_add(pc, z, hn::Set(df, float(c::kCosPoly[i])));
  s = hn::Mul(r, ps);
}
// sincos_turns: sin(2 pi t), cos(2 pi t) for any finite t (t in turns),
// within 2^-23 absolute; non-finite t gives NaN.
HWY_INLINE void sincos_turns(VF t, VF& sin_out, VF& cos_out) {
  namespace c = detail::constants;
  const DF df;
  const VF u = hn::IfThenElse(hn::Lt(hn::Abs(t), hn::Set(df, float(c::kTurnsReduceLimit))), t,
                              hn::Sub(t, hn::Floor(t)));
  VF q, s, pc;
  sincos_quadrant(u, q, s, pc);
  const VF k = neg_mul_add(hn::Set(df, 4.0f), hn::Floor(hn::Mul(q, hn::Set(df, 0.25f))), q);
  const VF one = hn::Set(df, 1.0f), two = hn::Set(df, 2.0f), three = hn::Set(df, 3.0f);
  const MF k1 = hn::Eq(k, one), k2 = hn::Eq(k, two), k3 = hn::Eq(k, three);
  const MF odd = hn::Or(k1, k3);
  const VF sin_sign = hn::IfThenElse(hn::Ge(k, two), hn::Set(df, -1.0f), one);
  const VF cos_sign = hn::IfThenElse(hn::Or(k1, k2), hn::Set(df, -1.0f), one);
  sin_out = hn::Mul(hn::IfThenElse(odd, pc, s), sin_sign);
  cos_out = hn::Mul(hn::IfThenElse(odd, s, pc), cos_sign);
}
// sincos_turns for finite |t| < kTurnsReduceLimit: no reduction (the identity
// there), and the quadrant's signs as sign bits from its integer (multiplying
// by +-1 and flipping the sign bit agree on every non-NaN value). The same
// values as sincos_turns.
HWY_INLINE void sincos_turns_in_range(VF t, VF& sin_out, VF& cos_out) {
  const DF df;
  const DI di;
  VF q, s, pc;
  sincos_quadrant(t, q, s, pc);
  // k = q mod 4 (|q| < 2^24: exact as an integer): sin < 0 for k = 2, 3; cos
  // < 0 for k = 1, 2; the two swap for odd k.
  const VI k = hn::ConvertTo(di, q);
  const VI two = hn::Set(di, 2);
  const VF sin_sign = hn::BitCast(df, hn::ShiftLeft<30>(hn::And(k, two)));
  const VF cos_sign = hn::BitCast(df, hn::ShiftLeft<30>(hn::And(hn::Add(k, hn::Set(di, 1)), two)));
  const MF odd = hn::RebindMask(df, hn::TestBit(k, hn::Set(di, 1)));
  sin_out = hn::Xor(hn::IfThenElse(odd, pc, s), sin_sign);
  cos_out = hn::Xor(hn::IfThenElse(odd, s, pc), cos_sign);
}

// ---- detail/approx_math.hpp in lanes (the float branch, op for op).

// Polynomial coefficients rounded to float as the scalar code rounds them
// (float(c)), at compile time.
template <int N>
struct float_coefficients {
  float v[N];
};
template <int N>
constexpr float_coefficients<N> to_float(const double (&d)[N]) {
  float_coefficients<N> r{};
  for (int i = 0; i < N; ++i) r.v[i] = static_cast<float>(d[i]);
  return r;
}
constexpr auto kExp2 = to_float(detail::constants::kAnisoSeries.exp2);
constexpr auto kLog2 = to_float(detail::constants::kAnisoSeries.log2);

// Horner's rule p = (...(k[N-1] x + k[N-2]) x + ...) x + k[0], unrolled, each
// step one mul_add.
template <int N, int M = N - 1>
HWY_INLINE VF horner(const float_coefficients<N>& k, VF x, VF p) {
  const DF df;
  p = mul_add(p, x, hn::Set(df, k.v[M - 1]));
  if constexpr (M - 1 > 0)
    return horner<N, M - 1>(k, x, p);
  else
    return p;
}
template <int N>
HWY_INLINE VF horner(const float_coefficients<N>& k, VF x) {
  return horner<N>(k, x, hn::Set(DF(), k.v[N - 1]));
}

// exp2_nonpositive: 2^y for y in [-126, 0], within 4 ulp relative for y in
// [-25, 0]; NaN gives NaN. y < -126 gives an unspecified value: callers
// select their cutoff and discard those lanes.
HWY_INLINE VF exp2_nonpositive(VF y) {
  const DF df;
  const DI di;
  const VF n = hn::Floor(hn::Add(y, hn::Set(df, 0.5f)));
  const VF r = hn::Sub(y, n);
  const VF p = horner(kExp2, r);
  // 2^n from exponent bits; n < -126 (beyond the cutoff) is clamped, the
  // caller discards those lanes.
  const VF nc = hn::Max(n, hn::Set(df, -126.0f));
  const auto e = hn::ShiftLeft<23>(hn::Add(hn::ConvertTo(di, nc), hn::Set(di, 127)));
  return hn::Mul(p, hn::BitCast(df, e));
}

// log2_positive: log2(m) for m > 0, within 2^-21 absolute plus 2 ulp of the
// result; -inf below the smallest normal float, +inf stays +inf.
HWY_INLINE VF log2_positive(VF m) {
  namespace c = detail::constants;
  const DF df;
  const DU du;
  const DI di;
  const auto tiny = hn::Not(hn::Ge(m, hn::Set(df, std::numeric_limits<float>::min())));
  const auto huge = hn::Not(hn::Lt(m, hn::Set(df, std::numeric_limits<float>::infinity())));
  const VU b = hn::BitCast(du, m);
  auto e = hn::Sub(hn::BitCast(di, hn::ShiftRight<23>(b)), hn::Set(di, 127));
  VF a = hn::BitCast(df, hn::Or(hn::And(b, hn::Set(du, 0x007fffffu)), hn::Set(du, 0x3f800000u)));
  const auto big = hn::Gt(a, hn::Set(df, float(c::kSqrt2)));
  a = hn::IfThenElse(big, hn::Mul(a, hn::Set(df, 0.5f)), a);
  e = hn::IfThenElse(hn::RebindMask(di, big), hn::Add(e, hn::Set(di, 1)), e);
  const VF z = hn::Div(hn::Sub(a, hn::Set(df, 1.0f)), hn::Add(a, hn::Set(df, 1.0f)));
  const VF p = horner(kLog2, hn::Mul(z, z));
  VF r = mul_add(p, z, hn::ConvertTo(df, e));
  r = hn::IfThenElse(tiny, hn::Set(df, -std::numeric_limits<float>::infinity()), r);
  return hn::IfThenElse(huge, m, r);
}

// ---- Compression of selected lanes to the front of a vector. AVX-512 has it
// in one instruction (Highway's Compress); Highway 1.0.3's 4- and 8-lane
// versions copy a 1 KiB table onto the stack on every call, so for up to 8
// lanes the lane indices come from a table of our own, built at compile time.
// Either way the indices serve every vector compressed by the same mask.
template <int N>
struct compress_indices {
  std::int32_t idx[1 << N][N];
};
template <int N>
constexpr compress_indices<N> make_compress_indices() {
  compress_indices<N> t{};
  for (int bits = 0; bits < (1 << N); ++bits) {
    int k = 0;
    for (int l = 0; l < N; ++l)
      if (bits & (1 << l)) t.idx[bits][k++] = l;
    for (int l = 0; l < N; ++l)
      if (!(bits & (1 << l))) t.idx[bits][k++] = l;
  }
  return t;
}
alignas(64) inline constexpr compress_indices<8> kCompress8 = make_compress_indices<8>();
alignas(64) inline constexpr compress_indices<4> kCompress4 = make_compress_indices<4>();

// The selected lanes of vectors (floats or words) moved to the front by one
// mask, in lane order; the other lanes follow (their order unspecified). The
// lane indices are found once per mask (AVX-512: one compress of the lane
// numbers, then a one-uop permutation per vector instead of a two-uop
// compress each), from the tables above for 4 and 8 lanes.
struct compressor {
  using indices = decltype(hn::IndicesFromVec(DF(), hn::Zero(DI())));
  static indices of(MF m) {
    const DF df;
    const DI di;
    const std::size_t lanes = hn::Lanes(df);
    if (lanes == 8 || lanes == 4) {
      std::uint8_t bits[8] = {};
      hn::StoreMaskBits(df, m, bits);
      const std::int32_t* i = lanes == 8 ? kCompress8.idx[bits[0]] : kCompress4.idx[bits[0] & 15];
      return hn::SetTableIndices(df, i);
    }
    return hn::IndicesFromVec(df, hn::Compress(hn::Iota(di, 0), hn::RebindMask(di, m)));
  }
  explicit compressor(MF m) : idx(of(m)) {}
  VF operator()(VF v) const { return hn::TableLookupLanes(v, idx); }
  VU operator()(VU v) const {
    return hn::BitCast(DU(), hn::TableLookupLanes(hn::BitCast(DF(), v), idx));
  }
  indices idx;
};

// ---- Points in memory.

// g[0 .. D) (D = 2 or 3, lane l of each vector: point l) stored interleaved
// to dst[0 .. D Lanes): x0, y0[, z0], x1, ...
template <int D>
HWY_INLINE void store_interleaved(const VF* g, float* HWY_RESTRICT dst) {
  const DF df;
  if constexpr (D == 2)
    hn::StoreInterleaved2(g[0], g[1], df, dst);
  else
    hn::StoreInterleaved3(g[0], g[1], g[2], df, dst);
}

// The batch driver: fn(first, pts, value, grad) over n points of D floats,
// one vector of lanes at a time from point `first`; the last partial vector
// goes through zero-padded buffers, so no lane reads or writes out of bounds
// (its lanes past n read zeros, their results are dropped). grad may be null
// (values only; fn then gets null).
template <int D, class Fn>
HWY_INLINE void for_each_vector(std::size_t n, const float* pts, float* value, float* grad,
                                const Fn& fn) {
  constexpr std::size_t kMax = kMaxLanes;
  const std::size_t lanes = hn::Lanes(DF());
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) fn(i, pts + i * D, value + i, grad ? grad + i * D : nullptr);
  if (i == n) return;
  const std::size_t rest = n - i;
  HWY_ALIGN float in[kMax * D] = {}, out[kMax] = {}, g[kMax * D] = {};
  std::memcpy(in, pts + i * D, rest * D * sizeof(float));
  fn(i, in, out, grad ? g : nullptr);
  std::memcpy(value + i, out, rest * sizeof(float));
  if (grad) std::memcpy(grad + i * D, g, rest * D * sizeof(float));
}

}  // namespace lanes
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_SIMD_LANES_INL_H_ toggle
