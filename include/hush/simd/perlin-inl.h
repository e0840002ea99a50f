// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernels for improved Perlin noise in 2D and 3D: batches of points
// and uniform grids, values and optionally analytic gradients. Compiled once
// per SIMD target (the "-inl.h" convention: toggle include guard below, no
// normal guard); reached through hush/simd/dispatch.hpp, never included
// directly by users.
//
// The kernels repeat perlin.hpp's float algorithm operation by operation:
// same lattice split (in double for grids, exact float floor for points),
// same hash words, gradient index and table, Horner fade, lerp a + t(b - a),
// dot products summed left to right, and the same final scale. So:
//  - under HUSH_STRICT_FP (no contraction) every value and gradient is bit
//    for bit the scalar result (tests/simd/perlin_simd_test.cpp, every
//    compiled target);
//  - otherwise multiply-adds are fused where that is faster, and results
//    stay within perlin.hpp's float budget of the double reference (2^-16);
//    measured differences to scalar are a few float ulps (docs/performance.md).
// Points whose coordinates are all finite and below 2^31 in magnitude take
// the vector split; other vectors (NaN, Inf, huge, or periodic noise) split
// lane by lane through core/lattice.hpp, so hard cases behave exactly like
// scalar evaluation (NaN in gives NaN out).

// Toggle guard: included once per target by foreach_target.h (Highway's
// hwy/examples/skeleton-inl.h pattern).
#if defined(HUSH_SIMD_PERLIN_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_SIMD_PERLIN_INL_H_
#undef HUSH_SIMD_PERLIN_INL_H_
#else
#define HUSH_SIMD_PERLIN_INL_H_
#endif

#include <algorithm>
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
#include "hush/fractal.hpp"
#include "hush/perlin.hpp"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace perlin_simd {

using DF = hn::ScalableTag<float>;
using DU = hn::RebindToUnsigned<DF>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VU = hn::Vec<DU>;

// Largest lane count any target has (AVX-512: 16 floats; SVE may have more,
// up to 2048 bits). Lookup tables are padded to it so every chunk load is in
// bounds.
constexpr std::size_t kMaxLanes = 64;

// a * b + c: two roundings under HUSH_STRICT_FP (as the scalar code is
// compiled), one fused rounding otherwise.
HWY_INLINE VF mul_add(VF a, VF b, VF c) {
#if HUSH_CONFIG_STRICT_FP
  return hn::Add(hn::Mul(a, b), c);
#else
  return hn::MulAdd(a, b, c);
#endif
}
// lerp(a, b, t) = a + t * (b - a), as detail::lerp.
HWY_INLINE VF lerp(VF a, VF b, VF t) { return mul_add(t, hn::Sub(b, a), a); }

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

// hash32 (core/hash.hpp) in 32-bit lanes.
HWY_INLINE VU hash32(VU x) {
  namespace c = detail::constants;
  const DU du;
  x = hn::Xor(x, hn::ShiftRight<c::kHashShift1>(x));
  x = hn::Mul(x, hn::Set(du, c::kHashMul1));
  x = hn::Xor(x, hn::ShiftRight<c::kHashShift2>(x));
  x = hn::Mul(x, hn::Set(du, c::kHashMul2));
  return hn::Xor(x, hn::ShiftRight<c::kHashShift3>(x));
}

// lattice_word_x/y/z (core/hash.hpp) in lanes: i * P_x, rotl(j * P_y, R_y),
// rotl(k * P_z, R_z).
HWY_INLINE VU word_x(VU i) { return hn::Mul(i, hn::Set(DU(), detail::constants::kLatticePrimeX)); }
HWY_INLINE VU word_y(VU j) {
  namespace c = detail::constants;
  return hn::RotateRight<32 - c::kLatticeRotateY>(hn::Mul(j, hn::Set(DU(), c::kLatticePrimeY)));
}
HWY_INLINE VU word_z(VU k) {
  namespace c = detail::constants;
  return hn::RotateRight<32 - c::kLatticeRotateZ>(hn::Mul(k, hn::Set(DU(), c::kLatticePrimeZ)));
}
template <int kAxis>
HWY_INLINE VU word(VU i) {
  if constexpr (kAxis == 0) return word_x(i);
  if constexpr (kAxis == 1) return word_y(i);
  if constexpr (kAxis == 2) return word_z(i);
}

// perlin.hpp's float gradient tables, padded to kMaxLanes (zeros past the
// real entries) so that every chunk load in lookup() stays in bounds.
struct tables {
  float g2x[kMaxLanes], g2y[kMaxLanes], g3x[kMaxLanes], g3y[kMaxLanes], g3z[kMaxLanes];
};
inline const tables& gradient_tables() {
  static const tables t = [] {
    using src = detail::perlin_tables<float>;
    tables r{};
    std::copy(src::g2x.begin(), src::g2x.end(), r.g2x);
    std::copy(src::g2y.begin(), src::g2y.end(), r.g2y);
    std::copy(src::g3x.begin(), src::g3x.end(), r.g3x);
    std::copy(src::g3y.begin(), src::g3y.end(), r.g3y);
    std::copy(src::g3z.begin(), src::g3z.end(), r.g3z);
    return r;
  }();
  return t;
}

// table[idx] per lane for idx < kEntries: one in-register permute per chunk
// of Lanes entries (one for 8 entries on AVX2, two for 12), then a select.
template <int kEntries>
HWY_INLINE VF lookup(const float* HWY_RESTRICT table, VU idx) {
  const DF df;
  const DU du;
  const DI di;
  const std::size_t n = hn::Lanes(df);
  const VU lane_mask = hn::Set(du, static_cast<std::uint32_t>(n - 1));
  const auto within = hn::IndicesFromVec(df, hn::BitCast(di, hn::And(idx, lane_mask)));
  VF r = hn::TableLookupLanes(hn::LoadU(df, table), within);
  for (std::size_t base = n; base < static_cast<std::size_t>(kEntries); base += n) {
    // Indices are small, so a signed compare (the one every target has) is exact.
    const auto in_chunk = hn::RebindMask(
        df, hn::Gt(hn::BitCast(di, idx), hn::Set(di, static_cast<std::int32_t>(base) - 1)));
    r = hn::IfThenElse(in_chunk, hn::TableLookupLanes(hn::LoadU(df, table + base), within), r);
  }
  return r;
}

HWY_INLINE VU grad_index2(VU h) { return hn::ShiftRight<detail::constants::kPerlin2GradShift>(h); }
HWY_INLINE VU grad_index3(VU h) {
  namespace c = detail::constants;
  const VU top = hn::ShiftRight<c::kPerlin3IndexShift>(h);
  return hn::ShiftRight<c::kPerlin3IndexShift>(
      hn::Mul(top, hn::Set(DU(), static_cast<std::uint32_t>(c::kPerlin3GradCount))));
}

// One axis of a batch of lattice lookups: hash words of the two cells, the
// fraction, its fade and (for gradients) the fade's derivative.
struct axis {
  VU w0, w1;
  VF f, s, ds;
};

// ---- 2D core: perlin<2>::eval2 in lanes. ky0/ky1 already hold key ^ word_y.
template <bool kGradient>
HWY_INLINE void core2(const axis& x, VU ky0, VU ky1, const axis& y, VF& value, VF& gx_out,
                      VF& gy_out) {
  const DF df;
  const tables& tab = gradient_tables();
  const VF one = hn::Set(df, 1.0f);
  const VF fx = x.f, fy = y.f, fx1 = hn::Sub(fx, one), fy1 = hn::Sub(fy, one);
  const VU g00 = grad_index2(hash32(hn::Xor(x.w0, ky0)));
  const VU g10 = grad_index2(hash32(hn::Xor(x.w1, ky0)));
  const VU g01 = grad_index2(hash32(hn::Xor(x.w0, ky1)));
  const VU g11 = grad_index2(hash32(hn::Xor(x.w1, ky1)));
  constexpr int kN = detail::constants::kPerlin2GradCount;
  const VF ax00 = lookup<kN>(tab.g2x, g00), ay00 = lookup<kN>(tab.g2y, g00);
  const VF ax10 = lookup<kN>(tab.g2x, g10), ay10 = lookup<kN>(tab.g2y, g10);
  const VF ax01 = lookup<kN>(tab.g2x, g01), ay01 = lookup<kN>(tab.g2y, g01);
  const VF ax11 = lookup<kN>(tab.g2x, g11), ay11 = lookup<kN>(tab.g2y, g11);
  const VF d00 = mul_add(ax00, fx, hn::Mul(ay00, fy));
  const VF d10 = mul_add(ax10, fx1, hn::Mul(ay10, fy));
  const VF d01 = mul_add(ax01, fx, hn::Mul(ay01, fy1));
  const VF d11 = mul_add(ax11, fx1, hn::Mul(ay11, fy1));
  const VF u = x.s, v = y.s;
  const VF x0 = lerp(d00, d10, u), x1 = lerp(d01, d11, u);
  const VF scale = hn::Set(df, float(detail::constants::kPerlin2Scale));
  value = hn::Mul(scale, lerp(x0, x1, v));
  if constexpr (kGradient) {
    const VF gx = mul_add(x.ds, lerp(hn::Sub(d10, d00), hn::Sub(d11, d01), v),
                          lerp(lerp(ax00, ax10, u), lerp(ax01, ax11, u), v));
    const VF gy = mul_add(y.ds, hn::Sub(x1, x0), lerp(lerp(ay00, ay10, u), lerp(ay01, ay11, u), v));
    gx_out = hn::Mul(scale, gx);
    gy_out = hn::Mul(scale, gy);
  } else {
    (void)gx_out;
    (void)gy_out;
  }
}

// ---- 3D core: perlin<3>::eval3 in lanes. kyz[b + 2c] = key ^ word_y(j_b) ^ word_z(k_c).
template <bool kGradient>
HWY_INLINE void core3(const axis& x, const VU* kyz, const axis& y, const axis& z, VF& value,
                      VF* grad) {
  const DF df;
  const tables& tab = gradient_tables();
  const VF one = hn::Set(df, 1.0f);
  const VF f[2][3] = {{x.f, y.f, z.f}, {hn::Sub(x.f, one), hn::Sub(y.f, one), hn::Sub(z.f, one)}};
  constexpr int kN = detail::constants::kPerlin3GradCount;
  VF d[8], gxs[8], gys[8], gzs[8];
  for (int n = 0; n < 8; ++n) {
    const int a = n & 1, b = (n >> 1) & 1, c = n >> 2;
    const VU g = grad_index3(hash32(hn::Xor(a ? x.w1 : x.w0, kyz[b + 2 * c])));
    gxs[n] = lookup<kN>(tab.g3x, g);
    gys[n] = lookup<kN>(tab.g3y, g);
    gzs[n] = lookup<kN>(tab.g3z, g);
    // (gx fx + gy fy) + gz fz, summed left to right as in eval3.
    d[n] = mul_add(gzs[n], f[c][2], mul_add(gxs[n], f[a][0], hn::Mul(gys[n], f[b][1])));
  }
  const VF u = x.s, v = y.s, w = z.s;
  const VF x00 = lerp(d[0], d[1], u), x10 = lerp(d[2], d[3], u);
  const VF x01 = lerp(d[4], d[5], u), x11 = lerp(d[6], d[7], u);
  const VF y0 = lerp(x00, x10, v), y1 = lerp(x01, x11, v);
  const VF scale = hn::Set(df, float(detail::constants::kPerlin3Scale));
  value = hn::Mul(scale, lerp(y0, y1, w));
  if constexpr (kGradient) {
    auto blend = [&](const VF* q) {
      return lerp(lerp(lerp(q[0], q[1], u), lerp(q[2], q[3], u), v),
                  lerp(lerp(q[4], q[5], u), lerp(q[6], q[7], u), v), w);
    };
    const VF ex = lerp(lerp(hn::Sub(d[1], d[0]), hn::Sub(d[3], d[2]), v),
                       lerp(hn::Sub(d[5], d[4]), hn::Sub(d[7], d[6]), v), w);
    const VF ey = lerp(hn::Sub(x10, x00), hn::Sub(x11, x01), w);
    const VF ez = hn::Sub(y1, y0);
    grad[0] = hn::Mul(scale, mul_add(x.ds, ex, blend(gxs)));
    grad[1] = hn::Mul(scale, mul_add(y.ds, ey, blend(gys)));
    grad[2] = hn::Mul(scale, mul_add(z.ds, ez, blend(gzs)));
  }
}

// perlin<D>'s core on one vector. kyz[b + 2c] = key ^ word_y(j_b) ^
// word_z(k_c) (2D: kyz[0], kyz[1]; z unused).
template <bool kGradient, int D>
HWY_INLINE void core(const axis& x, const VU* kyz, const axis& y, const axis& z, VF& value,
                     VF* grad) {
  if constexpr (D == 2) {
    (void)z;
    core2<kGradient>(x, kyz[0], kyz[1], y, value, grad[0], grad[1]);
  } else {
    core3<kGradient>(x, kyz, y, z, value, grad);
  }
}

// kyz for core() from per-lane axes (points) ...
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
// ... and from row-constant words (grids; z words 0 in 2D).
HWY_INLINE void key_words(std::uint32_t key, std::uint32_t y0, std::uint32_t y1, std::uint32_t z0,
                          std::uint32_t z1, VU* kyz) {
  const DU du;
  kyz[0] = hn::Set(du, key ^ y0 ^ z0);
  kyz[1] = hn::Set(du, key ^ y1 ^ z0);
  kyz[2] = hn::Set(du, key ^ y0 ^ z1);
  kyz[3] = hn::Set(du, key ^ y1 ^ z1);
}

// D interleaved vectors (gradients) to dst.
template <int D>
HWY_INLINE void store_interleaved(const VF* g, float* HWY_RESTRICT dst) {
  const DF df;
  if constexpr (D == 2)
    hn::StoreInterleaved2(g[0], g[1], df, dst);
  else
    hn::StoreInterleaved3(g[0], g[1], g[2], df, dst);
}

}  // namespace perlin_simd

namespace perlin_simd {

// ---- Points: splitting float coordinates into lattice axes.

// Vector split, valid when every lane is finite with |x| < 2^31: floor and
// x - floor(x) are exact in float, so this equals lattice_split's double
// computation (including its clamp below 1 for tiny negative x).
template <bool kGradient, int kAxis>
HWY_INLINE axis split_fast(VF xv) {
  const DF df;
  const DI di;
  const DU du;
  const VF fl = hn::Floor(xv);
  const VF f = hn::Min(hn::Sub(xv, fl), hn::Set(df, detail::one_minus_ulp<float>()));
  const VU i0 = hn::BitCast(du, hn::ConvertTo(di, fl));
  axis a;
  a.w0 = word<kAxis>(i0);
  a.w1 = word<kAxis>(hn::Add(i0, hn::Set(du, 1u)));
  a.f = f;
  a.s = fade(f);
  if constexpr (kGradient) a.ds = fade_derivative(f);
  return a;
}

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
  a.f = hn::Load(df, fs);
  a.s = fade(a.f);
  if constexpr (kGradient) a.ds = fade_derivative(a.f);
  return a;
}

// Lane-by-lane split of float coordinates: NaN, Inf, |x| >= 2^31 and
// periodic axes. Same result as scalar evaluation by construction.
template <bool kGradient, int kAxis>
HWY_INLINE axis split_lanes(VF xv, std::uint32_t period) {
  const DF df;
  HWY_ALIGN float xs[kMaxLanes];
  double q[kMaxLanes];
  hn::Store(xv, df, xs);
  for (std::size_t l = 0; l < hn::Lanes(df); ++l) q[l] = double(xs[l]);
  return split_doubles<kGradient, kAxis>(q, period);
}

template <bool kGradient, int kAxis>
HWY_INLINE axis split(VF xv, std::uint32_t period) {
  const DF df;
  if (period == 0 && hn::AllTrue(df, hn::Lt(hn::Abs(xv), hn::Set(df, 2147483648.0f))))
    return split_fast<kGradient, kAxis>(xv);
  return split_lanes<kGradient, kAxis>(xv, period);
}

// One vector of D-dimensional points (interleaved) -> values (and interleaved gradients).
template <bool kGradient, int D>
HWY_INLINE void points_vector(std::uint32_t key, const std::uint32_t* period,
                              const float* HWY_RESTRICT pts, float* HWY_RESTRICT value,
                              float* HWY_RESTRICT grad) {
  const DF df;
  VF c[3];
  if constexpr (D == 2)
    hn::LoadInterleaved2(df, pts, c[0], c[1]);
  else
    hn::LoadInterleaved3(df, pts, c[0], c[1], c[2]);
  const axis ax = split<kGradient, 0>(c[0], period[0]);
  const axis ay = split<kGradient, 1>(c[1], period[1]);
  axis az{};
  if constexpr (D == 3) az = split<kGradient, 2>(c[2], period[2]);
  VU kyz[4];
  key_words<D>(hn::Set(DU(), key), ay, az, kyz);
  VF v, g[3];
  core<kGradient, D>(ax, kyz, ay, az, v, g);
  hn::StoreU(v, df, value);
  if constexpr (kGradient) store_interleaved<D>(g, grad);
}

// Runs `vector_fn` over n points of D floats each; the last partial vector
// goes through zero-padded buffers, so no lane reads or writes out of bounds.
template <int D, class Fn>
HWY_INLINE void for_each_point_vector(std::size_t n, const float* pts, float* value, float* grad,
                                      Fn vector_fn) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    vector_fn(pts + i * D, value + i, grad ? grad + i * D : nullptr);
  if (i == n) return;
  const std::size_t rest = n - i;
  HWY_ALIGN float in[kMaxLanes * D] = {}, out[kMaxLanes], g[kMaxLanes * D];
  std::memcpy(in, pts + i * D, rest * D * sizeof(float));
  vector_fn(in, out, g);
  std::memcpy(value + i, out, rest * sizeof(float));
  if (grad) std::memcpy(grad + i * D, g, rest * D * sizeof(float));
}

// for_each_point_vector with the gradient choice made once per batch:
// vector_fn(std::bool_constant<kGradient>, pts, value, grad).
template <int D, class Fn>
HWY_INLINE void run_points(std::size_t n, const float* pts, float* value, float* grad,
                           Fn vector_fn) {
  if (grad)
    for_each_point_vector<D>(n, pts, value, grad, [&](const float* p, float* v, float* g) {
      vector_fn(std::true_type{}, p, v, g);
    });
  else
    for_each_point_vector<D>(n, pts, value, nullptr, [&](const float* p, float* v, float*) {
      vector_fn(std::false_type{}, p, v, nullptr);
    });
}

}  // namespace perlin_simd

// Perlin at n interleaved points (x0, y0[, z0], x1, ...); values into
// `value[n]`, and interleaved gradients into `grad[D n]` unless grad is null.
template <int D>
void perlin_points(std::uint32_t key, const std::uint32_t* period, const float* pts, std::size_t n,
                   float* value, float* grad) {
  perlin_simd::run_points<D>(
      n, pts, value, grad, [&](auto gradient, const float* p, float* v, float* g) {
        perlin_simd::points_vector<decltype(gradient)::value, D>(key, period, p, v, g);
      });
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

// ---- Grids: the x axis is split once per column (in double, by
// lattice_split, exactly as scalar evaluation does) and reused by every row;
// y (and z) are split once per row (slice) and broadcast.
struct column_table {
  std::vector<float> f, s, ds;
  std::vector<std::uint32_t> w0, w1;
  std::size_t padded = 0;

  // Column i's x coordinate is position(i), a double.
  template <class Position>
  column_table(std::size_t n, std::uint32_t period, bool gradient, Position position) {
    const std::size_t lanes = hn::Lanes(DF());
    padded = (n + lanes - 1) / lanes * lanes;
    f.assign(padded, 0.0f);
    s.assign(padded, 0.0f);
    w0.assign(padded, 0u);
    w1.assign(padded, 0u);
    if (gradient) ds.assign(padded, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
      const lattice_coord<float> c = lattice_split<float>(position(i), period);
      f[i] = c.f;
      s[i] = detail::fade(c.f);
      if (gradient) ds[i] = detail::fade_derivative(c.f);
      w0[i] = lattice_word_x(c.i0);
      w1[i] = lattice_word_x(c.i1);
    }
  }
  template <bool kGradient>
  HWY_INLINE axis load(std::size_t i) const {
    const DF df;
    const DU du;
    axis a;
    a.w0 = hn::LoadU(du, w0.data() + i);
    a.w1 = hn::LoadU(du, w1.data() + i);
    a.f = hn::LoadU(df, f.data() + i);
    a.s = hn::LoadU(df, s.data() + i);
    if constexpr (kGradient) a.ds = hn::LoadU(df, ds.data() + i);
    return a;
  }
};

// A row-constant axis (y or z): scalar split broadcast to all lanes.
struct row_axis {
  std::uint32_t w0, w1;
  axis a;
};
template <bool kGradient, int kAxis>
HWY_INLINE row_axis broadcast_axis(double p, std::uint32_t period) {
  const DF df;
  const lattice_coord<float> c = lattice_split<float>(p, period);
  row_axis r;
  r.w0 = kAxis == 1 ? lattice_word_y(c.i0) : lattice_word_z(c.i0);
  r.w1 = kAxis == 1 ? lattice_word_y(c.i1) : lattice_word_z(c.i1);
  r.a.f = hn::Set(df, c.f);
  r.a.s = hn::Set(df, detail::fade(c.f));
  if constexpr (kGradient) r.a.ds = hn::Set(df, detail::fade_derivative(c.f));
  return r;
}

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

template <bool kGradient, int D>
void perlin_grid(std::uint32_t key, const std::uint32_t* period, const grid<D>& g, float* value,
                 float* grad) {
  const std::size_t nx = g.size[0], ny = g.size[1], nz = D == 3 ? g.size[D - 1] : 1;
  const std::size_t lanes = hn::Lanes(DF());
  const column_table cols(nx, period[0], kGradient,
                          [&](std::size_t i) { return g.origin[0] + g.step[0] * double(i); });
  for (std::size_t k = 0; k < nz; ++k) {
    row_axis z{};
    if constexpr (D == 3)
      z = broadcast_axis<kGradient, 2>(g.origin[2] + g.step[2] * double(k), period[2]);
    for (std::size_t j = 0; j < ny; ++j) {
      const row_axis y =
          broadcast_axis<kGradient, 1>(g.origin[1] + g.step[1] * double(j), period[1]);
      VU kyz[4];
      key_words(key, y.w0, y.w1, z.w0, z.w1, kyz);
      const std::size_t row = k * ny + j;
      for (std::size_t i = 0; i < nx; i += lanes) {
        VF v, gr[3];
        core<kGradient, D>(cols.load<kGradient>(i), kyz, y.a, z.a, v, gr);
        store_row<D>(i, nx, v, gr, value + row * nx, kGradient ? grad + row * nx * D : nullptr);
      }
    }
  }
}

}  // namespace perlin_simd

// Perlin on a uniform grid (C order, i fastest); gradients interleaved (D
// per sample) unless grad is null.
template <int D>
void perlin_grid(std::uint32_t key, const std::uint32_t* period, const grid<D>& g, float* value,
                 float* grad) {
  if (grad)
    perlin_simd::perlin_grid<true, D>(key, period, g, value, grad);
  else
    perlin_simd::perlin_grid<false, D>(key, period, g, value, nullptr);
}
inline void perlin2_grid(std::uint32_t key, const std::uint32_t* period, const grid<2>& g,
                         float* value, float* grad) {
  perlin_grid<2>(key, period, g, value, grad);
}
inline void perlin3_grid(std::uint32_t key, const std::uint32_t* period, const grid<3>& g,
                         float* value, float* grad) {
  perlin_grid<3>(key, period, g, value, grad);
}

namespace perlin_simd {

// ---- Fractal sums of Perlin bands (fractal.hpp): each band is a Perlin
// field evaluated by the cores above at the band position f_i x + o_i, which
// fractal::band_position forms in double exactly as scalar evaluation does;
// the weighted sum is accumulated band by band in the same order and with
// the same operations as fractal::value / value_and_gradient.
template <int D>
struct band_config {
  std::uint32_t key;
  std::uint32_t period[3];
  float weight;  // T(w_i)
  float chain;   // T(w_i f_i): the band gradient's factor
};

template <int D>
std::vector<band_config<D>> band_configs(const fractal<perlin<D>>& fr) {
  std::vector<band_config<D>> r(static_cast<std::size_t>(fr.band_count()));
  for (int b = 0; b < fr.band_count(); ++b) {
    const auto& prm = fr.band_noise(b).parameters();
    band_config<D>& c = r[static_cast<std::size_t>(b)];
    c.key = seed_key(prm.seed);
    for (int a = 0; a < 3; ++a)
      c.period[a] = a < D ? static_cast<std::uint32_t>(prm.period[a]) : 0u;
    c.weight = float(fr.band_raw_weight(b));
    c.chain = float(fr.band_raw_weight(b) * fr.band_frequency(b));
  }
  return r;
}

// acc += band value (and gradient) with fractal.hpp's operations.
template <bool kGradient, int D>
HWY_INLINE void accumulate(bool turbulence, const band_config<D>& c, VF v, const VF* g, VF& acc,
                           VF* gacc) {
  const DF df;
  const VF w = hn::Set(df, c.weight);
  if constexpr (kGradient) {
    // sign = -1 where turbulence folds a negative value; w sign v, chain sign g.
    const VF sign =
        turbulence ? hn::IfThenElse(hn::Lt(v, hn::Zero(df)), hn::Set(df, -1.0f), hn::Set(df, 1.0f))
                   : hn::Set(df, 1.0f);
    acc = hn::Add(acc, hn::Mul(hn::Mul(w, sign), v));
    const VF chain = hn::Mul(hn::Set(df, c.chain), sign);
    for (int a = 0; a < D; ++a) gacc[a] = hn::Add(gacc[a], hn::Mul(chain, g[a]));
  } else {
    (void)g;
    (void)gacc;
    acc = hn::Add(acc, hn::Mul(w, turbulence ? hn::Abs(v) : v));
  }
}

// One vector of fractal points: band positions per lane in double.
template <bool kGradient, int D>
HWY_INLINE void fractal_points_vector(const fractal<perlin<D>>& fr,
                                      const std::vector<band_config<D>>& bands,
                                      const float* HWY_RESTRICT pts, float* HWY_RESTRICT value,
                                      float* HWY_RESTRICT grad) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const bool turbulence = fr.parameters().kind == fractal_kind::turbulence;
  VF acc = hn::Zero(df), gacc[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
  vec<double, D> p[kMaxLanes];  // the lanes' points in double, once for all bands
  for (std::size_t l = 0; l < lanes; ++l)
    for (int a = 0; a < D; ++a) p[l][a] = double(pts[l * D + a]);
  double q[3][kMaxLanes];
  for (std::size_t b = 0; b < bands.size(); ++b) {
    for (std::size_t l = 0; l < lanes; ++l) {
      const vec<double, D> qb = fr.band_position(static_cast<int>(b), p[l]);
      for (int a = 0; a < D; ++a) q[a][l] = qb[a];
    }
    const band_config<D>& c = bands[b];
    const axis ax = split_doubles<kGradient, 0>(q[0], c.period[0]);
    const axis ay = split_doubles<kGradient, 1>(q[1], c.period[1]);
    axis az{};
    if constexpr (D == 3) az = split_doubles<kGradient, 2>(q[2], c.period[2]);
    VU kyz[4];
    key_words<D>(hn::Set(DU(), c.key), ay, az, kyz);
    VF v, g[3];
    core<kGradient, D>(ax, kyz, ay, az, v, g);
    accumulate<kGradient, D>(turbulence, c, v, g, acc, gacc);
  }
  const VF scale = hn::Set(df, float(fr.scale()));
  if constexpr (kGradient) {
    hn::StoreU(hn::Mul(acc, scale), df, value);
    for (int a = 0; a < D; ++a) gacc[a] = hn::Mul(gacc[a], scale);
    store_interleaved<D>(gacc, grad);
  } else {
    hn::StoreU(hn::Mul(scale, acc), df, value);
  }
}

// A fractal on a grid: per band, a column table of the band's x positions
// and a per-row split of its y (and z) positions.
template <bool kGradient, int D>
void fractal_grid(const fractal<perlin<D>>& fr, const grid<D>& g, float* value, float* grad) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const std::vector<band_config<D>> bands = band_configs(fr);
  const bool turbulence = fr.parameters().kind == fractal_kind::turbulence;
  const std::size_t nx = g.size[0], ny = g.size[1], nz = D == 3 ? g.size[D - 1] : 1;
  auto position = [&](int b, int axis_index, double coordinate) {
    vec<double, D> p;  // axes are independent in f x + o: the other coordinates do not matter
    p[axis_index] = coordinate;
    return fr.band_position(b, p)[axis_index];
  };
  std::vector<column_table> cols;
  cols.reserve(bands.size());
  for (std::size_t b = 0; b < bands.size(); ++b)
    cols.emplace_back(nx, bands[b].period[0], kGradient, [&](std::size_t i) {
      return position(static_cast<int>(b), 0, g.origin[0] + g.step[0] * double(i));
    });
  const std::size_t padded = cols.empty() ? 0 : cols[0].padded;
  std::vector<float> acc(padded), gacc(kGradient ? padded * D : 0);
  const VF scale = hn::Set(df, float(fr.scale()));
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j) {
      std::fill(acc.begin(), acc.end(), 0.0f);
      std::fill(gacc.begin(), gacc.end(), 0.0f);
      for (std::size_t b = 0; b < bands.size(); ++b) {
        const band_config<D>& c = bands[b];
        const int bi = static_cast<int>(b);
        const row_axis y = broadcast_axis<kGradient, 1>(
            position(bi, 1, g.origin[1] + g.step[1] * double(j)), c.period[1]);
        row_axis z{};
        if constexpr (D == 3)
          z = broadcast_axis<kGradient, 2>(position(bi, 2, g.origin[2] + g.step[2] * double(k)),
                                           c.period[2]);
        VU kyz[4];
        key_words(c.key, y.w0, y.w1, z.w0, z.w1, kyz);
        for (std::size_t i = 0; i < nx; i += lanes) {
          VF v, gr[3];
          core<kGradient, D>(cols[b].load<kGradient>(i), kyz, y.a, z.a, v, gr);
          VF a = hn::LoadU(df, acc.data() + i), ga[3];
          if constexpr (kGradient)
            for (int d = 0; d < D; ++d) ga[d] = hn::LoadU(df, gacc.data() + d * padded + i);
          accumulate<kGradient, D>(turbulence, c, v, gr, a, ga);
          hn::StoreU(a, df, acc.data() + i);
          if constexpr (kGradient)
            for (int d = 0; d < D; ++d) hn::StoreU(ga[d], df, gacc.data() + d * padded + i);
        }
      }
      const std::size_t row = k * ny + j;
      for (std::size_t i = 0; i < nx; i += lanes) {
        const VF a = hn::LoadU(df, acc.data() + i);
        VF gs[3];
        if constexpr (kGradient)
          for (int d = 0; d < D; ++d)
            gs[d] = hn::Mul(hn::LoadU(df, gacc.data() + d * padded + i), scale);
        store_row<D>(i, nx, kGradient ? hn::Mul(a, scale) : hn::Mul(scale, a), gs, value + row * nx,
                     kGradient ? grad + row * nx * D : nullptr);
      }
    }
}

}  // namespace perlin_simd

// Fractal sums of Perlin (fBm, turbulence) at interleaved points or on a
// grid; same layout conventions as the Perlin entry points above.
template <int D>
void fractal_points(const fractal<perlin<D>>& fr, const float* pts, std::size_t n, float* value,
                    float* grad) {
  const std::vector<perlin_simd::band_config<D>> bands = perlin_simd::band_configs(fr);
  perlin_simd::run_points<D>(
      n, pts, value, grad, [&](auto gradient, const float* p, float* v, float* g) {
        perlin_simd::fractal_points_vector<decltype(gradient)::value, D>(fr, bands, p, v, g);
      });
}
inline void fractal2_points(const fractal<perlin<2>>& fr, const float* xy, std::size_t n,
                            float* value, float* grad) {
  fractal_points<2>(fr, xy, n, value, grad);
}
inline void fractal3_points(const fractal<perlin<3>>& fr, const float* xyz, std::size_t n,
                            float* value, float* grad) {
  fractal_points<3>(fr, xyz, n, value, grad);
}
inline void fractal2_grid(const fractal<perlin<2>>& fr, const grid<2>& g, float* value,
                          float* grad) {
  if (grad)
    perlin_simd::fractal_grid<true, 2>(fr, g, value, grad);
  else
    perlin_simd::fractal_grid<false, 2>(fr, g, value, nullptr);
}
inline void fractal3_grid(const fractal<perlin<3>>& fr, const grid<3>& g, float* value,
                          float* grad) {
  if (grad)
    perlin_simd::fractal_grid<true, 3>(fr, g, value, grad);
  else
    perlin_simd::fractal_grid<false, 3>(fr, g, value, nullptr);
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_SIMD_PERLIN_INL_H_ toggle
