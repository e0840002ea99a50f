// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Wavelet noise's bands in lanes, separable: each band's positions split into cell
// and fraction as lattice_split<float> does, the B-spline weights of each axis, and
// the nested sums over the tile's taps (separable3; in 3D a 4-float row load per
// lane and (y, z) row, rows3). The kernels of hush/wavelet/simd-inl.h build on it.
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/wavelet/simd-inl.h, never included directly by users.
#if defined(HUSH_WAVELET_SEPARABLE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_WAVELET_SEPARABLE_INL_H_
#undef HUSH_WAVELET_SEPARABLE_INL_H_
#else
#define HUSH_WAVELET_SEPARABLE_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include <hwy/highway.h>

#include "hush/core/lattice.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace wavelet_simd {

// Generic lane maths: simd/lanes-inl.h.
using namespace lanes::types;

using lanes::kMaxLanes;
using lanes::mul_add;
using lanes::store_interleaved;

// detail::piece_value in lanes: Horner, highest power first.
template <int P, int O>
HWY_INLINE VF piece(const detail::piecewise_kernel<P, O>& k, int p, VF t) {
  const DF df;
  VF r = hn::Set(df, static_cast<float>(k.c[p][O - 1]));
  for (int j = O - 2; j >= 0; --j) r = mul_add(r, t, hn::Set(df, static_cast<float>(k.c[p][j])));
  return r;
}

// One axis of a band in lanes: the stride-scaled, wrapped index of each of its N
// taps (3: the B-spline; beta or B2 along a projection's normal: more), their
// weights and (for gradients) the weights' derivatives.
template <int N>
struct axis_n {
  static constexpr int kTaps = N;
  VI idx[N];
  VF w[N], dw[N];
};
using axis = axis_n<3>;

// cell + k modulo n for cell in [0, n) and |k| < n.
HWY_INLINE VI wrap_add(VI cell, VI k, int n) {
  const DI di;
  const VI nv = hn::Set(di, n);
  VI c = hn::Add(cell, k);
  c = hn::IfThenElse(hn::Lt(c, hn::Zero(di)), hn::Add(c, nv), c);
  return hn::IfThenElse(hn::Lt(c, nv), c, hn::Sub(c, nv));
}

// cell -> the N tap indices (cell + first + j modulo n) times the axis stride.
template <int N>
HWY_INLINE void tap_indices(VI cell, VI first, int n, int stride, VI (&idx)[N]) {
  const DI di;
  const VI nv = hn::Set(di, n), sv = hn::Set(di, stride);
  VI c = wrap_add(cell, first, n);
  for (int j = 0; j < N; ++j) {
    idx[j] = hn::Mul(c, sv);
    c = hn::Add(c, hn::Set(di, 1));
    c = hn::IfThenElse(hn::Lt(c, nv), c, hn::Sub(c, nv));
  }
}
// The same with first = 0 (cell + j: one wrap per step, as for plain points).
HWY_INLINE void tap_indices(VI cell, int n, int stride, VI (&idx)[3]) {
  const DI di;
  const VI nv = hn::Set(di, n), sv = hn::Set(di, stride);
  VI c = cell;
  for (int j = 0; j < 3; ++j) {
    idx[j] = hn::Mul(c, sv);
    c = hn::Add(c, hn::Set(di, 1));
    c = hn::IfThenElse(hn::Lt(c, nv), c, hn::Sub(c, nv));
  }
}

// detail::kernel_at(k, d) in lanes, for distances whose piece floor(d + P/2) is in
// [lo, hi] (or outside the support, where the kernel is 0): the same operations.
template <int P, int O>
HWY_INLINE VF kernel_lanes(const detail::piecewise_kernel<P, O>& k, VF d, int lo, int hi) {
  const DF df;
  const VF u = hn::Add(d, hn::Set(df, static_cast<float>(P / 2.0)));
  const VF p = hn::Floor(u);
  const VF t = hn::Sub(u, p);
  VF r = hn::Zero(df);
  for (int q = std::max(lo, 0); q <= std::min(hi, P - 1); ++q)
    r = hn::IfThenElse(hn::Eq(p, hn::Set(df, static_cast<float>(q))), piece(k, q, t), r);
  const auto inside =
      hn::And(hn::Gt(u, hn::Zero(df)), hn::Lt(u, hn::Set(df, static_cast<float>(P))));
  return hn::IfThenElseZero(inside, r);
}

// detail::wavelet_axis_fixed's weights (beta or B2 along a normal) at fraction f:
// tap j at distance d = (f + 1/2) - (first + j), whose u = d + P/2 lies in
// [lo, lo + 1], lo = floor(1/2 - first - j + P/2) (rounding reaches lo + 1 at most).
template <bool kGradient, int P, int O>
HWY_INLINE void fixed_weights(VF f, const detail::piecewise_kernel<P, O>& k,
                              const detail::piecewise_kernel<P, O - 1>& dk,
                              axis_n<detail::fixed_kernel_taps<P>()>& a) {
  constexpr int kFirst = detail::fixed_kernel_first_tap<P>();
  const DF df;
  const VF fh = hn::Add(f, hn::Set(df, static_cast<float>(detail::constants::kWaveletCellOffset)));
  for (int j = 0; j < detail::fixed_kernel_taps<P>(); ++j) {
    const VF d = hn::Sub(fh, hn::Set(df, static_cast<float>(kFirst + j)));
    const int lo = (1 - 2 * (kFirst + j) + P) / 2;
    a.w[j] = kernel_lanes(k, d, lo, lo + 1);
    if constexpr (kGradient) a.dw[j] = kernel_lanes(dk, d, lo, lo + 1);
  }
}

template <bool kGradient>
HWY_INLINE void weights(VF f, axis& a) {
  for (int j = 0; j < 3; ++j) a.w[j] = piece(detail::kBspline, 2 - j, f);
  if constexpr (kGradient)
    for (int j = 0; j < 3; ++j) a.dw[j] = piece(detail::kBsplineDerivative, 2 - j, f);
}

// Band coordinate q = x freq + off of every lane, split as lattice_split<float>(q, n):
// cell in [0, n) and fraction in [0, 1). Returns false (nothing written) when a lane
// is not finite or |q| >= 2^31; the caller then splits lane by lane.
HWY_INLINE bool split_vector(VF x, double freq, double off, int n, VI& cell, VF& f) {
#if HWY_TARGET == HWY_SCALAR
  (void)x;
  (void)freq;
  (void)off;
  (void)n;
  (void)cell;
  (void)f;
  return false;
#else
  const DF df;
  const DI di;
  const hn::Half<DF> dh;
  const hn::Half<DI> dih;
  const hn::Repartition<double, DF> dd;
  using VD = hn::Vec<decltype(dd)>;
  const VD fv = hn::Set(dd, freq), ov = hn::Set(dd, off), nv = hn::Set(dd, double(n));
  const VD limit = hn::Set(dd, 2147483648.0);
  const VD lo = hn::Add(hn::Mul(hn::PromoteTo(dd, hn::LowerHalf(dh, x)), fv), ov);
  const VD hi = hn::Add(hn::Mul(hn::PromoteTo(dd, hn::UpperHalf(dh, x)), fv), ov);
  if (!hn::AllTrue(dd, hn::Lt(hn::Abs(lo), limit)) || !hn::AllTrue(dd, hn::Lt(hn::Abs(hi), limit)))
    return false;
  const auto part = [&](VD q, hn::Vec<decltype(dh)>& fh, hn::Vec<decltype(dih)>& ch) {
    const VD fl = hn::Floor(q);
    fh = hn::Min(hn::DemoteTo(dh, hn::Sub(q, fl)), hn::Set(dh, detail::one_minus_ulp<float>()));
    // floor(q) mod n, exact for |q| < 2^31 (the quotient's rounding error is below 1/n).
    ch = hn::DemoteTo(dih, hn::Sub(fl, hn::Mul(nv, hn::Floor(hn::Div(fl, nv)))));
  };
  hn::Vec<decltype(dh)> flo, fhi;
  hn::Vec<decltype(dih)> clo, chi;
  part(lo, flo, clo);
  part(hi, fhi, chi);
  f = hn::Combine(df, fhi, flo);
  cell = hn::Combine(di, chi, clo);
  return true;
#endif
}

// Axis a of the band for one vector of points (coordinates x, the lanes' double
// positions p for the lane-by-lane fallback): cell and fraction as lattice_split.
template <int D>
HWY_INLINE void band_split(const wavelet<D>& w, int band, int a, VF x, VI& cell, VF& f) {
  const DF df;
  const DI di;
  const int n = w.parameters().tile_size;
  const vec<double, D> zero{};
  const double off = w.band_position(band, zero)[a];
  if (split_vector(x, w.band_frequency(band), off, n, cell, f)) return;
  HWY_ALIGN float fs[kMaxLanes], xl[kMaxLanes];
  HWY_ALIGN std::int32_t cs[kMaxLanes];
  hn::Store(x, df, xl);
  for (std::size_t l = 0; l < hn::Lanes(df); ++l) {
    vec<double, D> q{};  // band_position's axis a depends on coordinate a only
    q[a] = static_cast<double>(xl[l]);
    const lattice_coord<float> c =
        lattice_split<float>(w.band_position(band, q)[a], w.split_period());
    fs[l] = c.f;
    cs[l] = static_cast<std::int32_t>(c.i0);
  }
  f = hn::Load(df, fs);
  cell = hn::Load(di, cs);
}

// The band's D axes with the plain B-spline.
template <bool kGradient, int D>
HWY_INLINE void band_axes(const wavelet<D>& w, int band, const VF* xs, axis* ax) {
  const int n = w.parameters().tile_size;
  for (int a = 0; a < D; ++a) {
    VI cell;
    VF f;
    band_split<D>(w, band, a, xs[a], cell, f);
    tap_indices(cell, n, w.tile().stride(a), ax[a].idx);
    weights<kGradient>(f, ax[a]);
  }
}

// wavelet_separable in 3D over gathered coefficients, any tap counts per axis (x
// outermost, z innermost): value and gradient (coefficient units).
template <bool kGradient, class AX, class AY, class AZ>
HWY_INLINE void separable3(const float* tile, const AX& ax, const AY& ay, const AZ& az, VF& v,
                           VF* g) {
  const DF df;
  v = hn::Zero(df);
  for (int a = 0; a < 3; ++a) g[a] = hn::Zero(df);
  for (int a = 0; a < AX::kTaps; ++a) {
    VF t = hn::Zero(df), ty = hn::Zero(df), tz = hn::Zero(df);
    for (int b = 0; b < AY::kTaps; ++b) {
      const VI xy = hn::Add(ax.idx[a], ay.idx[b]);
      VF s = hn::Zero(df), sz = hn::Zero(df);
      for (int c = 0; c < AZ::kTaps; ++c) {
        const VF cf = hn::GatherIndex(df, tile, hn::Add(xy, az.idx[c]));
        s = mul_add(az.w[c], cf, s);
        if constexpr (kGradient) sz = mul_add(az.dw[c], cf, sz);
      }
      t = mul_add(ay.w[b], s, t);
      if constexpr (kGradient) {
        ty = mul_add(ay.dw[b], s, ty);
        tz = mul_add(ay.w[b], sz, tz);
      }
    }
    v = mul_add(ax.w[a], t, v);
    if constexpr (kGradient) {
      g[0] = mul_add(ax.dw[a], t, g[0]);
      g[1] = mul_add(ax.w[a], ty, g[1]);
      g[2] = mul_add(ax.w[a], tz, g[2]);
    }
  }
}

#undef HUSH_WAVELET_ROW_LOADS  // per target (this file is included once per target)
#if HWY_TARGET != HWY_SCALAR && !HWY_HAVE_SCALABLE
#define HUSH_WAVELET_ROW_LOADS 1
// A vector of 4-float rows of the 3D tile (padded rows, wavelet_tile::coefficients): its
// 128-bit block j holds rows[o[4 j]], ..., rows[o[4 j] + 3].
template <class D>
HWY_INLINE hn::Vec<D> row_blocks(D d, const float* rows, const std::int32_t* o) {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  if constexpr (hn::MaxLanes(D()) == 16) {
    // One load and three inserts from memory (Highway 1.0's Combine of halves also
    // moves the halves between registers: 7 instructions per vector of rows, not 4).
    __m512 v = _mm512_castps128_ps512(_mm_loadu_ps(rows + o[0]));
    v = _mm512_insertf32x4(v, _mm_loadu_ps(rows + o[4]), 1);
    v = _mm512_insertf32x4(v, _mm_loadu_ps(rows + o[8]), 2);
    v = _mm512_insertf32x4(v, _mm_loadu_ps(rows + o[12]), 3);
    return hn::Vec<D>{v};
  }
#endif
  if constexpr (hn::MaxLanes(D()) <= 4) {
    return hn::LoadU(d, rows + o[0]);
  } else {
    const hn::Half<D> dh;
    return hn::Combine(d, row_blocks(dh, rows, o + hn::MaxLanes(dh)), row_blocks(dh, rows, o));
  }
}

// The x taps of each lane's row (lane l's row starts at rows + o[l]): t[j] holds
// rows[o[l] + j] in lane l. One unaligned load per lane and a 4x4 transpose per
// block in place of three gathers.
HWY_INLINE void row_taps(const float* rows, const std::int32_t* o, VF (&t)[3]) {
  const DF df;
  const hn::Repartition<std::uint64_t, DF> d64;
  const VF a = row_blocks(df, rows, o), b = row_blocks(df, rows, o + 1);
  const VF c = row_blocks(df, rows, o + 2), d = row_blocks(df, rows, o + 3);
  const auto ab_lo = hn::BitCast(d64, hn::InterleaveLower(df, a, b));  // a0 b0 a1 b1
  const auto cd_lo = hn::BitCast(d64, hn::InterleaveLower(df, c, d));  // c0 d0 c1 d1
  const auto ab_hi = hn::BitCast(d64, hn::InterleaveUpper(df, a, b));  // a2 b2 a3 b3
  const auto cd_hi = hn::BitCast(d64, hn::InterleaveUpper(df, c, d));  // c2 d2 c3 d3
  t[0] = hn::BitCast(df, hn::InterleaveLower(d64, ab_lo, cd_lo));
  t[1] = hn::BitCast(df, hn::InterleaveUpper(d64, ab_lo, cd_lo));
  t[2] = hn::BitCast(df, hn::InterleaveLower(d64, ab_hi, cd_hi));
}

// separable3 with 3 x taps over the padded rows (wavelet_tile::coefficients; ay's and
// az's indices scaled by the strides m = row_length() and m n): the
// same sums in the same order (per lane and element the same operations, so the
// same bits), each (y, z) row's x taps from row_taps, z innermost, then y, then x.
template <bool kGradient, class AY, class AZ>
HWY_INLINE void rows3(const float* rows, VI x0, const axis& ax, const AY& ay, const AZ& az, VF& v,
                      VF* g) {
  const DF df;
  const DI di;
  constexpr int kY = AY::kTaps, kZ = AZ::kTaps;
  HWY_ALIGN std::int32_t o[kY * kZ][kMaxLanes];
  for (int b = 0; b < kY; ++b)
    for (int c = 0; c < kZ; ++c)
      hn::Store(hn::Add(x0, hn::Add(ay.idx[b], az.idx[c])), di, o[b * kZ + c]);
  VF t[3], ty[3], tz[3];
  for (int a = 0; a < 3; ++a) t[a] = ty[a] = tz[a] = hn::Zero(df);
  for (int b = 0; b < kY; ++b) {
    VF s[3], sz[3];
    for (int a = 0; a < 3; ++a) s[a] = sz[a] = hn::Zero(df);
    for (int c = 0; c < kZ; ++c) {
      VF r[3];
      row_taps(rows, o[b * kZ + c], r);
      for (int a = 0; a < 3; ++a) {
        s[a] = mul_add(az.w[c], r[a], s[a]);
        if constexpr (kGradient) sz[a] = mul_add(az.dw[c], r[a], sz[a]);
      }
    }
    for (int a = 0; a < 3; ++a) {
      t[a] = mul_add(ay.w[b], s[a], t[a]);
      if constexpr (kGradient) {
        ty[a] = mul_add(ay.dw[b], s[a], ty[a]);
        tz[a] = mul_add(ay.w[b], sz[a], tz[a]);
      }
    }
  }
  v = hn::Zero(df);
  for (int a = 0; a < 3; ++a) g[a] = hn::Zero(df);
  for (int a = 0; a < 3; ++a) {
    v = mul_add(ax.w[a], t[a], v);
    if constexpr (kGradient) {
      g[0] = mul_add(ax.dw[a], t[a], g[0]);
      g[1] = mul_add(ax.w[a], ty[a], g[1]);
      g[2] = mul_add(ax.w[a], tz[a], g[2]);
    }
  }
}

// One plain band of a vector of 3D points over the padded rows (rows3).
template <bool kGradient>
HWY_INLINE void plain3_rows(const wavelet<3>& w, int band, const VF* xs, VF& v, VF* g) {
  const int n = w.parameters().tile_size;
  axis ax[3];
  VI x0;
  for (int a = 0; a < 3; ++a) {
    VI cell;
    VF f;
    band_split<3>(w, band, a, xs[a], cell, f);
    weights<kGradient>(f, ax[a]);
    if (a == 0)
      x0 = cell;
    else
      tap_indices(cell, n, w.tile().stride(a), ax[a].idx);
  }
  rows3<kGradient>(w.tile().coefficients(), x0, ax[0], ax[1], ax[2], v, g);
}
#endif

// wavelet_separable over gathered coefficients: value and gradient (coefficient units).
template <bool kGradient, int D>
HWY_INLINE void separable(const float* tile, const axis* ax, VF& v, VF* g) {
  const DF df;
  v = hn::Zero(df);
  for (int a = 0; a < D; ++a) g[a] = hn::Zero(df);
  if constexpr (D == 2) {
    for (int a = 0; a < 3; ++a) {
      VF s = hn::Zero(df), sy = hn::Zero(df);
      for (int b = 0; b < 3; ++b) {
        const VF c = hn::GatherIndex(df, tile, hn::Add(ax[0].idx[a], ax[1].idx[b]));
        s = mul_add(ax[1].w[b], c, s);
        if constexpr (kGradient) sy = mul_add(ax[1].dw[b], c, sy);
      }
      v = mul_add(ax[0].w[a], s, v);
      if constexpr (kGradient) {
        g[0] = mul_add(ax[0].dw[a], s, g[0]);
        g[1] = mul_add(ax[0].w[a], sy, g[1]);
      }
    }
  } else {
    separable3<kGradient>(tile, ax[0], ax[1], ax[2], v, g);
  }
}

}  // namespace wavelet_simd
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_WAVELET_SEPARABLE_INL_H_ toggle
