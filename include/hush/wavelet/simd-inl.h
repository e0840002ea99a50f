// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernels for wavelet noise (include/hush/wavelet.hpp), 2D and 3D:
// batches of points, uniform grids, and samples with footprints and normals;
// values and optionally analytic gradients. Compiled once per SIMD target (the
// "-inl.h" convention); reached through hush/simd/dispatch.hpp.
//
// The kernels repeat wavelet.hpp's float algorithm operation by operation, so
// under HUSH_STRICT_FP every value and gradient is bit for bit the scalar
// result (tests/simd/wavelet_simd_test.cpp, every compiled target):
//  - band positions 2^b x + o_b - 1/2 are formed in double and split into cell
//    and fraction as lattice_split<float> does (in f64 lanes; lanes that are
//    not finite or beyond 2^31 take core/lattice.hpp lane by lane);
//  - the B-spline weights by the same Horner steps, the same nested sums
//    (z innermost), the same band accumulation, scale and gradient chain;
//  - the distribution remapping (erf, the table) runs lane by lane through
//    wavelet::remap, the scalar code itself.
// 3D points: a 4-float row load per lane and (y, z) row (rows3). Grids use the separability
// of the basis (the "3D single band" fast path of the issue): per slice the
// z contraction S(x, y) = sum_c wz_c n(x, y, z_c) for the coefficients the grid
// touches, per row T(x) = sum_b wy_b S(x, y_b), per sample sum_a wx_a T(x_a):
// three reads of a small table per sample and band, whatever D is; where a
// vector of columns spans less than a vector of cells (grids with at least
// ~1 sample per coefficient) one load and three lane lookups, else gathers.
// The scalar code sums in exactly this order, so the shortcut changes no bit.
// Samples with footprints take the points path with per-lane band weights and
// scales (wavelet::make_plan, computed in double per lane as scalar code does).
// Samples projected onto a surface run vector kernels too, one pass per kind of
// lane in a vector (lane_kind): a normal along a tile axis reads beta's (or
// B2's) taps along it (rows3 along y, z); any other normal runs the exact projection (each lane's
// knots from detail::wavelet_exact_knots, 5 Gauss-Legendre nodes per piece,
// masked past its own pieces) or the paper's approximation (the lanes' column
// and slab ranges united, each lane adding only the taps its scalar loop adds).
// Lanes that widen the basis or see a footprint that filters everything are
// evaluated lane by lane by the scalar code, and so is any batch of a noise with
// tile variants (variant_overlap > 0): correct everywhere but not vectorised.
#if defined(HUSH_WAVELET_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_WAVELET_SIMD_INL_H_
#undef HUSH_WAVELET_SIMD_INL_H_
#else
#define HUSH_WAVELET_SIMD_INL_H_
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <hwy/highway.h>

#include "hush/core/lattice.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/lanes-inl.h"

// The noise class comes first, not from here: hush/wavelet.hpp includes these
// kernels at its end (hush/wavelet/simd_kernel.hpp), as src/simd/wavelet.cpp does.
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

// ---- Projection onto a surface (wavelet.hpp band_kernel, unwidened): the kinds
// of lanes a vector may hold, each with its kernel.
enum lane_kind : int {
  kAlongX = 0,    // normal along tile axis 0, 1, 2: beta (exact) or B2 along it
  kGeneral = 3,   // any other normal: detail::wavelet_general_exact / _approx
  kPlain = 4,     // no projection: the B-spline on every axis
  kScalarLane = 5 // widened, "everything", not finite: the scalar code
};
constexpr int kLaneKinds = kPlain + 1;  // the kinds the vector kernels take

// One axis for the projection along tile axis A: the fixed kernel k along A (N taps,
// wavelet_axis_fixed), the B-spline elsewhere (3 taps).
template <bool kGradient, int N, int P, int O>
HWY_INLINE void axis_taps(VI cell, VF f, int n, int stride, const detail::piecewise_kernel<P, O>& k,
                          const detail::piecewise_kernel<P, O - 1>& dk, axis_n<N>& ax) {
  if constexpr (N == 3) {
    tap_indices(cell, n, stride, ax.idx);
    weights<kGradient>(f, ax);
  } else {
    tap_indices<N>(cell, hn::Set(DI(), detail::fixed_kernel_first_tap<P>()), n, stride, ax.idx);
    fixed_weights<kGradient>(f, k, dk, ax);
  }
}
template <bool kGradient, int A, int P, int O>
HWY_INLINE void projected_axis(const wavelet_tile<3>& tile, int n, const VI* cell, const VF* f,
                               const detail::piecewise_kernel<P, O>& k,
                               const detail::piecewise_kernel<P, O - 1>& dk, VF& v, VF* g) {
  constexpr int N = detail::fixed_kernel_taps<P>();
#ifdef HUSH_WAVELET_ROW_LOADS
  if constexpr (A != 0) {  // 3 x taps: rows (along x, N x taps: gathers)
    axis ax;
    weights<kGradient>(f[0], ax);
    axis_n<A == 1 ? N : 3> ay;
    axis_n<A == 2 ? N : 3> az;
    axis_taps<kGradient>(cell[1], f[1], n, tile.stride(1), k, dk, ay);
    axis_taps<kGradient>(cell[2], f[2], n, tile.stride(2), k, dk, az);
    rows3<kGradient>(tile.coefficients(), cell[0], ax, ay, az, v, g);
    return;
  }
#endif
  axis_n<A == 0 ? N : 3> ax;
  axis_n<A == 1 ? N : 3> ay;
  axis_n<A == 2 ? N : 3> az;
  axis_taps<kGradient>(cell[0], f[0], n, 1, k, dk, ax);
  axis_taps<kGradient>(cell[1], f[1], n, tile.stride(1), k, dk, ay);
  axis_taps<kGradient>(cell[2], f[2], n, tile.stride(2), k, dk, az);
  separable3<kGradient>(tile.coefficients(), ax, ay, az, v, g);
}

// The one lane of m0, m1, m2 (exactly one set per lane) picks v0, v1 or v2.
template <class M, class V>
HWY_INLINE V pick(const M (&m)[3], const V (&v)[3]) {
  return hn::IfThenElse(m[0], v[0], hn::IfThenElse(m[1], v[1], v[2]));
}

HWY_INLINE int max_lane(VI v) {
  const DI di;
  return hn::GetLane(hn::MaxOfLanes(di, v));
}

// detail::wavelet_general_approx (s = 1) in lanes. Each lane visits its own
// coefficients in its own order (columns along the axis other than its dominant
// one w, then along w over the slab where the three B-spline factors are non-zero);
// the vector loops run over the union of the lanes' ranges, and a lane adds a tap
// only where its scalar loop would (masked sums: the same operations, bit for bit).
// y: positions relative to the cells, u: the unit normals.
template <bool kGradient>
HWY_INLINE void general_approx(const wavelet_tile<3>& tl, const VI* cell, const VF* y, const VF* u,
                               VF& v, VF* g) {
  const DF df;
  const DI di;
  const float* tile = tl.coefficients();
  const int n = tl.size();
  const VF half = hn::Set(df, static_cast<float>(detail::kBspline.half_support()));
  const VF stretch = hn::Set(df, static_cast<float>(1.0 / detail::constants::kWaveletProjectionStretch));
  const VF one = hn::Set(df, 1.0f);
  const VF au[3] = {hn::Abs(u[0]), hn::Abs(u[1]), hn::Abs(u[2])};
  // w: the first axis of largest |u|; U < V the others (the scalar ax_u, ax_v).
  const MF w1 = hn::Gt(au[1], au[0]);
  const MF w2 = hn::Gt(au[2], hn::IfThenElse(w1, au[1], au[0]));
  const MF none = hn::Lt(one, hn::Zero(df));  // all false
  const MF is_w[3] = {hn::Not(hn::Or(w1, w2)), hn::AndNot(w2, w1), w2};
  const MF is_u[3] = {hn::Not(is_w[0]), is_w[0], none};
  const MF is_v[3] = {none, is_w[2], hn::Not(is_w[2])};
  const int strides[3] = {tl.stride(0), tl.stride(1), tl.stride(2)};
  const VI sv[3] = {hn::Set(di, strides[0]), hn::Set(di, strides[1]), hn::Set(di, strides[2])};
  const auto frame = [&](const MF (&m)[3], const VF (&x)[3]) { return pick(m, x); };
  const VF yv[3] = {y[0], y[1], y[2]}, uv[3] = {u[0], u[1], u[2]};
  const VF y_u = frame(is_u, yv), y_v = frame(is_v, yv), y_w = frame(is_w, yv);
  const VF u_u = frame(is_u, uv), u_v = frame(is_v, uv), u_w = frame(is_w, uv);
  const hn::Mask<DI> iu[3] = {hn::RebindMask(di, is_u[0]), hn::RebindMask(di, is_u[1]),
                              hn::RebindMask(di, is_u[2])};
  const hn::Mask<DI> iv[3] = {hn::RebindMask(di, is_v[0]), hn::RebindMask(di, is_v[1]),
                              hn::RebindMask(di, is_v[2])};
  const hn::Mask<DI> iw[3] = {hn::RebindMask(di, is_w[0]), hn::RebindMask(di, is_w[1]),
                              hn::RebindMask(di, is_w[2])};
  const VI cv[3] = {cell[0], cell[1], cell[2]};
  const VI c_u = pick(iu, cv), c_v = pick(iv, cv), c_w = pick(iw, cv);
  const VI s_u = pick(iu, sv), s_v = pick(iv, sv), s_w = pick(iw, sv);
  // reach_a = half (s_a + |u_a| l1), l1 = sum |u_a| s_a (s = 1).
  const VF l1 = hn::Add(hn::Add(au[0], au[1]), au[2]);
  VF reach[3];
  for (int a = 0; a < 3; ++a) reach[a] = hn::Mul(half, mul_add(au[a], l1, one));
  const VF r_u = frame(is_u, reach), r_v = frame(is_v, reach);
  const VI u_lo = hn::ConvertTo(di, hn::Ceil(hn::Sub(y_u, r_u)));
  const VI u_n = hn::Sub(hn::ConvertTo(di, hn::Floor(hn::Add(y_u, r_u))), u_lo);
  const VI v_lo = hn::ConvertTo(di, hn::Ceil(hn::Sub(y_v, r_v)));
  const VI v_n = hn::Sub(hn::ConvertTo(di, hn::Floor(hn::Add(y_v, r_v))), v_lo);
  const int nu = max_lane(u_n), nv = max_lane(v_n);
  VF sw = hn::Zero(df), sval = hn::Zero(df), sdw[3], sg[3];
  for (int a = 0; a < 3; ++a) sdw[a] = sg[a] = hn::Zero(df);
  const VF inf = hn::Set(df, std::numeric_limits<float>::infinity());
  for (int i = 0; i <= nu; ++i) {
    const VI ku = hn::Add(u_lo, hn::Set(di, i));
    const auto in_u = hn::Lt(hn::Set(di, i - 1), u_n);
    const VF d_u = hn::Sub(y_u, hn::ConvertTo(df, ku));
    const VI row_u = hn::Mul(wrap_add(c_u, hn::IfThenElseZero(in_u, ku), n), s_u);
    for (int j = 0; j <= nv; ++j) {
      const VI kv = hn::Add(v_lo, hn::Set(di, j));
      const auto in_uv = hn::And(in_u, hn::Lt(hn::Set(di, j - 1), v_n));
      if (hn::AllFalse(di, in_uv)) continue;
      const VF d_v = hn::Sub(y_v, hn::ConvertTo(df, kv));
      const VI row = hn::Add(row_u, hn::Mul(wrap_add(c_v, hn::IfThenElseZero(in_uv, kv), n), s_v));
      // e_a = A_a + C_a d_w: the slab of d_w where every |e_a| < half.
      const VF pp = hn::Add(hn::Mul(u_u, d_u), hn::Mul(u_v, d_v));
      const VF dz = hn::Zero(df);
      const VF dn[3] = {hn::IfThenElse(is_u[0], d_u, hn::IfThenElse(is_v[0], d_v, dz)),
                        hn::IfThenElse(is_u[1], d_u, hn::IfThenElse(is_v[1], d_v, dz)),
                        hn::IfThenElse(is_u[2], d_u, hn::IfThenElse(is_v[2], d_v, dz))};
      VF lo = hn::Neg(inf), hi = inf;
      MF empty = none;
      for (int a = 0; a < 3; ++a) {
        const VF A = hn::Sub(hn::IfThenElseZero(hn::Not(is_w[a]), dn[a]),
                             hn::Mul(hn::Mul(u[a], pp), stretch));
        const VF C = hn::Sub(hn::IfThenElseZero(is_w[a], one), hn::Mul(hn::Mul(u[a], u_w), stretch));
        const MF flat = hn::Eq(C, hn::Zero(df));
        empty = hn::Or(empty, hn::AndNot(hn::Lt(hn::Abs(A), half), flat));
        const VF e0 = hn::Div(hn::Sub(hn::Neg(half), A), C), e1 = hn::Div(hn::Sub(half, A), C);
        lo = hn::IfThenElse(flat, lo, hn::Max(lo, hn::Min(e0, e1)));
        hi = hn::IfThenElse(flat, hi, hn::Min(hi, hn::Max(e0, e1)));
      }
      const MF ok = hn::AndNot(empty, hn::And(hn::RebindMask(df, in_uv), hn::Lt(lo, hi)));
      if (hn::AllFalse(df, ok)) continue;
      const auto oki = hn::RebindMask(di, ok);
      const VI w_lo = hn::IfThenElseZero(oki, hn::ConvertTo(di, hn::Floor(hn::Sub(y_w, hi))));
      const VI w_n = hn::IfThenElse(
          oki, hn::Sub(hn::ConvertTo(di, hn::Ceil(hn::Sub(y_w, lo))), w_lo), hn::Set(di, -1));
      const int nw = max_lane(w_n);
      for (int m = 0; m <= nw; ++m) {
        const auto in_w = hn::Lt(hn::Set(di, m - 1), w_n);
        const VI kw = hn::IfThenElseZero(in_w, hn::Add(w_lo, hn::Set(di, m)));
        const VF d_w = hn::Sub(y_w, hn::ConvertTo(df, kw));
        VF d[3];
        for (int a = 0; a < 3; ++a) d[a] = hn::IfThenElse(is_w[a], d_w, dn[a]);
        const VF ud = hn::Add(hn::Add(hn::Mul(u[0], d[0]), hn::Mul(u[1], d[1])), hn::Mul(u[2], d[2]));
        VF e[3], b[3];
        for (int a = 0; a < 3; ++a) {
          e[a] = hn::Sub(d[a], hn::Mul(hn::Mul(u[a], ud), stretch));
          b[a] = kernel_lanes(detail::kBspline, e[a], 0, 2);
        }
        const VF weight = hn::Mul(hn::Mul(b[0], b[1]), b[2]);
        const MF take = hn::And(hn::RebindMask(df, in_w), hn::Ne(weight, hn::Zero(df)));
        if (hn::AllFalse(df, take)) continue;
        const VI idx = hn::Add(row, hn::Mul(wrap_add(c_w, kw, n), s_w));
        const VF c = hn::GatherIndex(df, tile, idx);
        sw = hn::IfThenElse(take, hn::Add(sw, weight), sw);
        sval = hn::IfThenElse(take, mul_add(weight, c, sval), sval);
        if constexpr (kGradient) {
          VF q[3];
          for (int a = 0; a < 3; ++a)
            q[a] = hn::Mul(hn::Mul(kernel_lanes(detail::kBsplineDerivative, e[a], 0, 2),
                                   b[(a + 1) % 3]),
                           b[(a + 2) % 3]);
          const VF uq = hn::Add(hn::Add(hn::Mul(u[0], q[0]), hn::Mul(u[1], q[1])), hn::Mul(u[2], q[2]));
          for (int a = 0; a < 3; ++a) {
            const VF gw = hn::Sub(q[a], hn::Mul(hn::Mul(u[a], uq), stretch));
            sdw[a] = hn::IfThenElse(take, hn::Add(sdw[a], gw), sdw[a]);
            sg[a] = hn::IfThenElse(take, mul_add(gw, c, sg[a]), sg[a]);
          }
        }
      }
    }
  }
  const MF some = hn::Gt(sw, hn::Zero(df));
  const VF inv = hn::Div(one, sw);
  v = hn::IfThenElseZero(some, hn::Mul(sval, inv));
  if constexpr (kGradient)
    for (int a = 0; a < 3; ++a)
      g[a] = hn::IfThenElseZero(some, hn::Mul(hn::Sub(sg[a], hn::Mul(v, sdw[a])), inv));
}

// detail::wavelet_general_exact (s = 1) in lanes: each lane's knots (the scalar
// detail::wavelet_exact_knots), padded with its last knot so that the pieces past
// its own count are empty; per piece the 5 Gauss-Legendre nodes, each a full
// 27-tap B-spline evaluation at y + t u (wavelet_axis_at), summed in the scalar order.
template <bool kGradient>
HWY_INLINE void general_exact(const wavelet_tile<3>& tl, const VI* cell, const VF* y, const VF* u,
                              VF& v, VF* g) {
  namespace c = detail::constants;
  const DF df;
  const DI di;
  const float* tile = tl.coefficients();
  const int n = tl.size();
  const std::size_t lanes = hn::Lanes(df);
  HWY_ALIGN float ys[3][kMaxLanes], us[3][kMaxLanes];
  for (int a = 0; a < 3; ++a) {
    hn::Store(y[a], df, ys[a]);
    hn::Store(u[a], df, us[a]);
  }
  HWY_ALIGN float knots[c::kWaveletMaxKnots][kMaxLanes];
  int count[kMaxLanes], most = 0;
  for (std::size_t l = 0; l < lanes; ++l) {
    const float yl[3] = {ys[0][l], ys[1][l], ys[2][l]}, ul[3] = {us[0][l], us[1][l], us[2][l]};
    const float sl[3] = {1.0f, 1.0f, 1.0f};
    float k[c::kWaveletMaxKnots];
    count[l] = detail::wavelet_exact_knots<float>(yl, ul, sl, k);
    for (int i = 0; i < count[l]; ++i) knots[i][l] = k[i];
    most = std::max(most, count[l]);
  }
  for (std::size_t l = 0; l < lanes; ++l)
    for (int i = count[l]; i < most; ++i) knots[i][l] = knots[count[l] - 1][l];
  v = hn::Zero(df);
  for (int a = 0; a < 3; ++a) g[a] = hn::Zero(df);
  const VF two = hn::Set(df, 2.0f), cell_offset = hn::Set(df, float(c::kWaveletCellOffset));
  const int strides[3] = {tl.stride(0), tl.stride(1), tl.stride(2)};
  for (int i = 0; i + 1 < most; ++i) {
    const VF t0 = hn::Load(df, knots[i]), t1 = hn::Load(df, knots[i + 1]);
    const auto piece_ok = hn::Gt(t1, t0);
    if (hn::AllFalse(df, piece_ok)) continue;
    const VF mid = hn::Div(hn::Add(t0, t1), two), h = hn::Div(hn::Sub(t1, t0), two);
    for (int q = 0; q < c::kGaussLegendreOrder; ++q) {
      const VF t = mul_add(h, hn::Set(df, float(c::kGaussLegendreNode[q])), mid);
      const VF wq = hn::Mul(hn::Mul(h, hn::Set(df, float(c::kGaussLegendreWeight[q]))),
                            kernel_lanes(detail::kBspline2, t, 0, detail::kBspline2.pieces - 1));
      axis ax[3];
      for (int a = 0; a < 3; ++a) {
        const VF ya = hn::Sub(mul_add(t, u[a], y[a]), cell_offset);
        const VF fl = hn::Floor(ya);
        tap_indices<3>(cell[a], hn::ConvertTo(di, fl), n, strides[a], ax[a].idx);
        weights<kGradient>(hn::Sub(ya, fl), ax[a]);
      }
      VF nv, ng[3];
      separable3<kGradient>(tile, ax[0], ax[1], ax[2], nv, ng);
      v = hn::IfThenElse(piece_ok, mul_add(wq, nv, v), v);
      if constexpr (kGradient)
        for (int a = 0; a < 3; ++a) g[a] = hn::IfThenElse(piece_ok, mul_add(wq, ng[a], g[a]), g[a]);
    }
  }
}

// One band of one vector of points with the lanes' kernel `kind` (lane_kind; u: the
// lanes' unit normals for kGeneral): value and gradient in coefficient units.
template <bool kGradient, int D>
HWY_INLINE void band_value(const wavelet<D>& w, int band, int kind, const VF* xs,
                           const VF* u, VF& v, VF* g) {
  const float* tile = w.tile().coefficients();
  if constexpr (D == 3) {
    if (kind != kPlain) {
      const int n = w.parameters().tile_size;
      VI cell[3];
      VF f[3];
      for (int a = 0; a < 3; ++a) band_split<3>(w, band, a, xs[a], cell[a], f[a]);
      const bool exact = w.parameters().projection == wavelet_projection::exact;
      if (kind == kGeneral) {
        const VF half = hn::Set(DF(), float(detail::constants::kWaveletCellOffset));
        const VF y[3] = {hn::Add(f[0], half), hn::Add(f[1], half), hn::Add(f[2], half)};
        if (exact)
          general_exact<kGradient>(w.tile(), cell, y, u, v, g);
        else
          general_approx<kGradient>(w.tile(), cell, y, u, v, g);
        return;
      }
      const auto along = [&](const auto& k, const auto& dk) {
        if (kind == 0) projected_axis<kGradient, 0>(w.tile(), n, cell, f, k, dk, v, g);
        if (kind == 1) projected_axis<kGradient, 1>(w.tile(), n, cell, f, k, dk, v, g);
        if (kind == 2) projected_axis<kGradient, 2>(w.tile(), n, cell, f, k, dk, v, g);
      };
      if (exact)
        along(detail::kBeta, detail::kBetaDerivative);
      else
        along(detail::kBspline2, detail::kBspline2Derivative);
      return;
    }
  }
  (void)kind;
  (void)u;
#ifdef HUSH_WAVELET_ROW_LOADS
  if constexpr (D == 3) {
    plain3_rows<kGradient>(w, band, xs, v, g);
    return;
  }
#endif
  axis ax[D];
  band_axes<kGradient, D>(w, band, xs, ax);
  separable<kGradient, D>(tile, ax, v, g);
}

// The lanes' band weights, chains (weight x band frequency) and scales (their plans,
// in double) as the floats points_vector multiplies by; made once per batch where
// every lane has the same plan, not per vector.
struct lane_weights {
  HWY_ALIGN float weight[detail::constants::kWaveletMaxBands][kMaxLanes];
  HWY_ALIGN float chain[detail::constants::kWaveletMaxBands][kMaxLanes];
  HWY_ALIGN float scale[kMaxLanes];
  bool any[detail::constants::kWaveletMaxBands];  // some lane's weight is not 0
  template <int D>
  void set(const wavelet<D>& w, const double (*wd)[kMaxLanes], const double* sd) {
    const std::size_t lanes = hn::Lanes(DF());
    for (int b = 0; b < w.band_count(); ++b) {
      any[b] = false;
      for (std::size_t l = 0; l < lanes; ++l) {
        const double wb = wd[b][l];
        any[b] = any[b] || wb != 0.0;
        weight[b][l] = static_cast<float>(wb);
        chain[b][l] = static_cast<float>(wb * w.band_frequency(b));
      }
    }
    for (std::size_t l = 0; l < lanes; ++l) scale[l] = static_cast<float>(sd[l]);
  }
};

// The sum over bands, scale and remapping of wavelet::eval for one vector of points
// with per-lane band weights, chains and scales (plans, lane_weights), into value
// and interleaved gradients, every lane with the kernel `kind` (lane_kind; normal:
// the lanes' unit normals for kGeneral). Lanes of weight 0 come out 0 for the
// caller to overwrite.
template <bool kGradient, int D>
HWY_INLINE void points_vector(const wavelet<D>& w, const float* HWY_RESTRICT pts,
                              const lane_weights& lw, float* HWY_RESTRICT value,
                              float* HWY_RESTRICT grad, int kind = kPlain,
                              const float (*normal)[kMaxLanes] = nullptr) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  VF xs[3];
  if constexpr (D == 2)
    hn::LoadInterleaved2(df, pts, xs[0], xs[1]);
  else
    hn::LoadInterleaved3(df, pts, xs[0], xs[1], xs[2]);
  VF acc = hn::Zero(df), gacc[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
  VF u[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
  if (normal)
    for (int a = 0; a < 3; ++a) u[a] = hn::Load(df, normal[a]);
  for (int b = 0; b < w.band_count(); ++b) {
    if (!lw.any[b]) continue;
    VF v, g[3];
    band_value<kGradient, D>(w, b, kind, xs, u, v, g);
    acc = mul_add(hn::Load(df, lw.weight[b]), v, acc);
    if constexpr (kGradient) {
      const VF chain = hn::Load(df, lw.chain[b]);
      for (int a = 0; a < D; ++a) gacc[a] = mul_add(chain, g[a], gacc[a]);
    }
  }
  const VF sv = hn::Load(df, lw.scale);
  acc = hn::Mul(acc, sv);
  if constexpr (kGradient)
    for (int a = 0; a < D; ++a) gacc[a] = hn::Mul(gacc[a], sv);
  const auto& prm = w.parameters();
  if (prm.distribution == wavelet_distribution::gaussian) {
    const VF gs = hn::Set(df, static_cast<float>(prm.gaussian_scale));
    hn::StoreU(hn::Mul(acc, gs), df, value);
    if constexpr (kGradient) {
      for (int a = 0; a < D; ++a) gacc[a] = hn::Mul(gacc[a], gs);
      store_interleaved<D>(gacc, grad);
    }
    return;
  }
  // Other distributions: the scalar remap, lane by lane.
  hn::StoreU(acc, df, value);
  if constexpr (kGradient) store_interleaved<D>(gacc, grad);
  for (std::size_t l = 0; l < lanes; ++l) {
    float dv = 1.0f;
    w.template remap<float>(value[l], kGradient ? &dv : nullptr);
    if constexpr (kGradient)
      for (int a = 0; a < D; ++a) grad[l * D + a] *= dv;
  }
}

// Whether the D vectors of floats at p are all finite.
template <int D>
HWY_INLINE bool all_finite(const float* HWY_RESTRICT p) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  auto ok = hn::IsFinite(hn::LoadU(df, p));
  for (int a = 1; a < D; ++a) ok = hn::And(ok, hn::IsFinite(hn::LoadU(df, p + a * lanes)));
  return hn::AllTrue(df, ok);
}

// The scalar evaluation of one sample (the lane-by-lane path).
template <int D>
HWY_INLINE void scalar_sample(const wavelet<D>& w, const sample_input<D>& s, float* value,
                              float* grad) {
  if (grad) {
    const value_gradient<float, D> r = w.template sample_value_and_gradient<float>(s);
    *value = r.value;
    for (int a = 0; a < D; ++a) grad[a] = r.gradient[a];
  } else {
    *value = w.template sample_value<float>(s);
  }
}

// Whether two normals are the same bits (NaN and signed zeros included).
HWY_INLINE bool same_bits(const vec<float, 3>& a, const vec<float, 3>& b) {
  for (int i = 0; i < 3; ++i) {
    std::uint32_t x = 0, y = 0;
    std::memcpy(&x, &a[i], sizeof x);
    std::memcpy(&y, &b[i], sizeof y);
    if (x != y) return false;
  }
  return true;
}

// The kernel a sample's plan asks for (lane_kind): finite position, not "everything",
// no widening: vectorised; else the scalar code.
template <int D>
HWY_INLINE int lane_kind_of(const wavelet<D>& w, const typename wavelet<D>::plan& pl,
                            bool finite) {
  if (!finite || pl.everything) return kScalarLane;
  for (int b = 0; b < w.band_count(); ++b)
    for (int a = 0; a < 3; ++a)
      if (pl.widen[b][a] != 1.0) return kScalarLane;
  if (!pl.project) return kPlain;
  return pl.normal_axis >= 0 ? kAlongX + pl.normal_axis : kGeneral;
}

}  // namespace wavelet_simd

// Wavelet noise at n interleaved points; values into value[n], interleaved
// gradients into grad[D n] unless grad is null.
template <int D>
void wavelet_points(const wavelet<D>& w, const float* pts, std::size_t n, float* value,
                    float* grad) {
  namespace ws = wavelet_simd;
  if (w.parameters().variant_overlap > 0) {
    for (std::size_t i = 0; i < n; ++i) {
      sample_input<D> s;
      for (int a = 0; a < D; ++a) s.position[a] = static_cast<double>(pts[i * D + a]);
      ws::scalar_sample<D>(w, s, value + i, grad ? grad + i * D : nullptr);
    }
    return;
  }
  const typename wavelet<D>::plan pl = w.make_plan(sample_input<D>{});
  const std::size_t lanes = hn::Lanes(ws::DF());
  double weight[wavelet<D>::kMaxBands][lanes::kMaxLanes], scale[lanes::kMaxLanes];
  for (int b = 0; b < w.band_count(); ++b)
    for (std::size_t l = 0; l < lanes; ++l) weight[b][l] = pl.weight[b];
  for (std::size_t l = 0; l < lanes; ++l) scale[l] = pl.scale;
  ws::lane_weights lw;
  lw.set(w, weight, scale);
  lanes::for_each_vector<D>(n, pts, value, grad,
                            [&](std::size_t first, const float* p, float* v, float* g) {
                              // Non-finite lanes: the scalar code (its NaN, exactly).
                              const bool finite = ws::all_finite<D>(p);
                              if (g)
                                ws::points_vector<true, D>(w, p, lw, v, g);
                              else
                                ws::points_vector<false, D>(w, p, lw, v, nullptr);
                              if (finite) return;
                              for (std::size_t l = 0; l < lanes && first + l < n; ++l) {
                                sample_input<D> s;
                                bool lane_finite = true;
                                for (int a = 0; a < D; ++a) {
                                  s.position[a] = static_cast<double>(p[l * D + a]);
                                  lane_finite = lane_finite && std::isfinite(s.position[a]);
                                }
                                if (!lane_finite)
                                  ws::scalar_sample<D>(w, s, v + l, g ? g + l * D : nullptr);
                              }
                            });
}

// Samples with footprints and normals (core/samples.hpp).
template <int D>
void wavelet_samples(const wavelet<D>& w, const samples<D>& s, float* value, float* grad) {
  namespace ws = wavelet_simd;
  const std::size_t n = s.size(), lanes = hn::Lanes(ws::DF());
  if (w.parameters().variant_overlap > 0) {
    for (std::size_t i = 0; i < n; ++i)
      ws::scalar_sample<D>(w, s.at(i), value + i, grad ? grad + i * D : nullptr);
    return;
  }
  const float* pts = reinterpret_cast<const float*>(s.positions.data());
  const int nb = w.band_count();
  double weight[wavelet<D>::kMaxBands][lanes::kMaxLanes], scale[lanes::kMaxLanes];
  double kind_weight[wavelet<D>::kMaxBands][lanes::kMaxLanes];
  double kind_scale[lanes::kMaxLanes];
  int kind[lanes::kMaxLanes];
  HWY_ALIGN float normal[3][lanes::kMaxLanes];
  ws::lane_weights lw;
  // Without footprints the bands' part of the plan is every sample's: made once; per
  // sample only its surface part (wavelet::plan_normal, plan_variance, plan_scale,
  // the scalar code's own steps), redone only when the normal changes.
  const bool shared = !s.has_footprints() && !s.has_surface_maps();
  typename wavelet<D>::plan base;
  if (shared) base = w.make_plan(sample_input<D>{});
  vec<float, 3> last_normal{};
  bool have_last = false;
  int last_kind = ws::kPlain;
  double last_scale = 0;
  float last_u[3] = {0, 0, 1};
  // The weights and scales lw was last set from (lw.set converts them per lane and band:
  // skipped while a run of vectors repeats them, the usual case without footprints).
  double set_weight[wavelet<D>::kMaxBands][lanes::kMaxLanes], set_scale[lanes::kMaxLanes];
  bool lw_set = false;
  const std::size_t row_bytes = lanes * sizeof(double);
  lanes::for_each_vector<D>(
      n, pts, value, grad, [&](std::size_t first, const float* p, float* v, float* g) {
        unsigned present = 0;  // bit k: some lane has kind k
        unsigned seen = 0;     // the same, scalar lanes and lanes past n included
        for (std::size_t l = 0; l < lanes; ++l) {
          kind[l] = ws::kScalarLane;
          for (int a = 0; a < 3; ++a) normal[a][l] = a == 2 ? 1.0f : 0.0f;
          if (first + l >= n) {
            seen |= 1u << ws::kScalarLane;
            continue;
          }
          // p holds the lane's position (for_each_vector): finite as s.at's doubles are.
          bool finite = true;
          for (int a = 0; a < D; ++a) finite = finite && std::isfinite(p[l * D + a]);
          if (shared) {
            const bool same =
                have_last && (!s.has_normals() || ws::same_bits(s.normals[first + l], last_normal));
            if (!same) {  // only here the sample itself is needed
              w.plan_normal(s.at(first + l), base);
              last_scale = w.plan_scale(base, w.plan_variance(base));
              last_kind = ws::lane_kind_of<D>(w, base, true);
              for (int a = 0; a < 3; ++a) last_u[a] = static_cast<float>(base.normal[a]);
              if (s.has_normals()) last_normal = s.normals[first + l];
              have_last = true;
            }
            kind[l] = finite ? last_kind : ws::kScalarLane;
          } else {
            const typename wavelet<D>::plan pl = w.make_plan(s.at(first + l));
            kind[l] = ws::lane_kind_of<D>(w, pl, finite);
            last_scale = pl.scale;
            for (int b = 0; b < nb; ++b) base.weight[b] = pl.weight[b];
            for (int a = 0; a < 3; ++a) last_u[a] = static_cast<float>(pl.normal[a]);
          }
          seen |= 1u << kind[l];
          const bool vectorised = kind[l] != ws::kScalarLane;
          if (vectorised) present |= 1u << kind[l];
          for (int b = 0; b < nb; ++b) weight[b][l] = vectorised ? base.weight[b] : 0.0;
          scale[l] = vectorised ? last_scale : 0.0;
          if (kind[l] == ws::kGeneral)
            for (int a = 0; a < 3; ++a) normal[a][l] = last_u[a];
        }
        // One pass per kind present (usually one); with several, each pass writes the
        // lanes of its kind only.
        for (int k = 0; k < ws::kLaneKinds; ++k) {
          if (((present >> k) & 1u) == 0) continue;
          const bool alone = present == (1u << k);
          // Every lane of kind k (the usual case): the lanes' own points, weights and
          // scales; else copies with the other lanes' zeroed.
          const bool all = seen == (1u << k);
          const double(*kw)[lanes::kMaxLanes] = weight;
          const double* ks = scale;
          const float* pk = p;
          HWY_ALIGN float pv[lanes::kMaxLanes * 3];
          if (!all) {
            std::fill(pv, pv + lanes * D, 0.0f);
            for (std::size_t l = 0; l < lanes; ++l) {
              const bool mine = kind[l] == k;
              for (int b = 0; b < nb; ++b) kind_weight[b][l] = mine ? weight[b][l] : 0.0;
              kind_scale[l] = mine ? scale[l] : 0.0;
              if (mine)
                for (int a = 0; a < D; ++a) pv[l * D + a] = p[l * D + a];
            }
            kw = kind_weight;
            ks = kind_scale;
            pk = pv;
          }
          bool repeat = lw_set && std::memcmp(ks, set_scale, row_bytes) == 0;
          for (int b = 0; b < nb && repeat; ++b)
            repeat = std::memcmp(kw[b], set_weight[b], row_bytes) == 0;
          if (!repeat) {
            lw.set(w, kw, ks);
            for (int b = 0; b < nb; ++b) std::memcpy(set_weight[b], kw[b], row_bytes);
            std::memcpy(set_scale, ks, row_bytes);
            lw_set = true;
          }
          HWY_ALIGN float vt[lanes::kMaxLanes], gt[lanes::kMaxLanes * 3];
          float* vo = alone ? v : vt;
          float* go = g == nullptr ? nullptr : (alone ? g : gt);
          if (g)
            ws::points_vector<true, D>(w, pk, lw, vo, go, k, normal);
          else
            ws::points_vector<false, D>(w, pk, lw, vo, nullptr, k, normal);
          if (alone) continue;
          for (std::size_t l = 0; l < lanes; ++l) {
            if (kind[l] != k) continue;
            v[l] = vt[l];
            if (g)
              for (int a = 0; a < D; ++a) g[l * D + a] = gt[l * D + a];
          }
        }
        for (std::size_t l = 0; l < lanes && first + l < n; ++l)
          if (kind[l] == ws::kScalarLane)
            ws::scalar_sample<D>(w, s.at(first + l), v + l, g ? g + l * D : nullptr);
      });
}

namespace wavelet_simd {

// ---- Grids: per band, the x axis split once per column (lattice_split<float> in
// double, as scalar evaluation does), y once per row, z once per slice; the
// contraction follows the separable order (file comment).
// Two layouts of the row's contraction T that columns read:
//  - unwrapped (the grid spans at most max(n, nx) + 3 cells): T[r] is x cell
//    (first + r) mod n, r = 0 ... span - 1, so a vector of columns reads a few
//    consecutive T values: when they fit in one vector (lane0 + 2 < lanes, i.e.
//    at least ~1 column per cell), one load and three in-register lane lookups
//    (TableLookupLanes) replace the three gathers;
//  - wrapped (sparse grids): T[x cell], gathered.
// Either way the same T values meet the same weights in the same order.
struct column_table {
  std::vector<std::int32_t> idx[3];  // T index of each tap
  std::vector<float> w[3], dw[3];
  std::vector<char> needed;  // x cells some column reads
  std::size_t padded = 0;
  bool unwrapped = false;
  int first = 0;          // unwrapped: the x cell of T[0]
  std::size_t span = 0;   // unwrapped: T's length
  std::vector<std::int32_t> lane0;  // unwrapped: idx[0] - base of the column's vector
  std::vector<std::int32_t> base;   // per vector: the smallest idx[0] of its columns
  std::vector<char> fits;           // per vector: every tap within one vector of T
};

template <bool kGradient>
column_table make_columns(std::size_t nx, int n, std::uint32_t period, double freq, double off,
                          double origin, double step) {
  column_table t;
  const std::size_t lanes = hn::Lanes(DF());
  t.padded = (nx + lanes - 1) / lanes * lanes;
  for (int j = 0; j < 3; ++j) {
    t.idx[j].assign(t.padded, 0);
    t.w[j].assign(t.padded, 0.0f);
    if (kGradient) t.dw[j].assign(t.padded, 0.0f);
  }
  t.needed.assign(static_cast<std::size_t>(n), 0);
  // rel: tap 0's cell, unwrapped column to column (any representative of the cell
  // modulo n serves: T's index only has to name the right cell).
  std::vector<long long> rel(t.padded, 0);
  long long prev = 0, lo = 0, hi = 0;
  const auto un = static_cast<std::uint32_t>(n);
  for (std::size_t i = 0; i < nx; ++i) {
    double x = (origin + step * static_cast<double>(i)) * freq;
    if (!std::isfinite(x)) x = 0.0;  // as wavelet::band::position for finite input
    const lattice_coord<float> c = lattice_split<float>(x + off, period);
    detail::wavelet_axis<float> ax;
    detail::wavelet_axis_plain<float, kGradient>(c.f, ax);
    const long long cell0 = static_cast<long long>(c.i0 % un);
    if (i == 0) {
      rel[i] = cell0;
    } else {
      long long d = (cell0 - prev % n + n) % n;  // in [0, n): the step modulo n
      if (2 * d > n) d -= n;
      rel[i] = rel[i - 1] + d;
    }
    prev = cell0;
    lo = i == 0 ? rel[i] : std::min(lo, rel[i]);
    hi = i == 0 ? rel[i] : std::max(hi, rel[i]);
    for (int j = 0; j < 3; ++j) {
      const int cell = static_cast<int>((c.i0 + static_cast<std::uint32_t>(j)) % un);
      t.idx[j][i] = cell;
      t.needed[static_cast<std::size_t>(cell)] = 1;
      t.w[j][i] = ax.w[j];
      if (kGradient) t.dw[j][i] = ax.dw[j];
    }
  }
  for (std::size_t i = nx; i < t.padded; ++i) rel[i] = nx ? rel[nx - 1] : 0;  // weight 0
  const auto limit = static_cast<long long>(std::max(static_cast<std::size_t>(n), nx));
  if (nx == 0 || hi - lo > limit) return t;
  t.unwrapped = true;
  t.first = static_cast<int>(((lo % n) + n) % n);
  t.span = static_cast<std::size_t>(hi - lo) + 3;
  t.lane0.assign(t.padded, 0);
  for (std::size_t v = 0; v < t.padded; v += lanes) {
    long long b = rel[v] - lo, top = b;
    for (std::size_t l = 0; l < lanes; ++l) {
      b = std::min(b, rel[v + l] - lo);
      top = std::max(top, rel[v + l] - lo);
    }
    t.base.push_back(static_cast<std::int32_t>(b));
    t.fits.push_back(top - b + 2 < static_cast<long long>(lanes) ? 1 : 0);
    for (std::size_t l = 0; l < lanes; ++l) {
      const auto r = static_cast<std::int32_t>(rel[v + l] - lo);
      t.lane0[v + l] = static_cast<std::int32_t>(r - b);
      for (int j = 0; j < 3; ++j) t.idx[j][v + l] = r + j;
    }
  }
  return t;
}

// One row or slice coordinate of a band: three wrapped cells and their weights.
struct line_axis {
  int cell[3];
  detail::wavelet_axis<float> ax;
};
template <bool kGradient>
line_axis make_line(int n, std::uint32_t period, double freq, double off, double coordinate) {
  line_axis r;
  double x = coordinate * freq;
  if (!std::isfinite(x)) x = 0.0;
  const lattice_coord<float> c = lattice_split<float>(x + off, period);
  detail::wavelet_axis_plain<float, kGradient>(c.f, r.ax);
  for (int j = 0; j < 3; ++j)
    r.cell[j] =
        static_cast<int>((c.i0 + static_cast<std::uint32_t>(j)) % static_cast<std::uint32_t>(n));
  return r;
}

template <bool kGradient, int D>
void wavelet_grid(const wavelet<D>& w, const grid<D>& g, float* value, float* grad) {
  const DF df;
  const DI di;
  const std::size_t lanes = hn::Lanes(df);
  const int n = w.parameters().tile_size;
  const std::size_t un = static_cast<std::size_t>(n);
  const auto um = static_cast<std::size_t>(w.tile().row_length());  // row stride of the tile
  const std::uint32_t period = w.split_period();
  const typename wavelet<D>::plan pl = w.make_plan(sample_input<D>{});
  const std::size_t nx = g.size[0], ny = g.size[1], nz = D == 3 ? g.size[D - 1] : 1;
  const float* tile = w.tile().coefficients();
  std::vector<int> bands;
  for (int b = 0; b < w.band_count(); ++b)
    if (pl.weight[b] != 0.0) bands.push_back(b);
  const vec<double, D> zero{};
  std::vector<column_table> cols;
  cols.reserve(bands.size());
  for (int b : bands)
    cols.push_back(make_columns<kGradient>(nx, n, period, w.band_frequency(b),
                                           w.band_position(b, zero)[0], g.origin[0], g.step[0]));
  const std::size_t padded = cols.empty() ? nx : cols[0].padded;
  // Per band: S (3D: the z contraction per (x, y) cell, and its z derivative) and T
  // (the row's contraction per x cell: value, d/dy, d/dz).
  std::vector<std::vector<float>> S(bands.size()), Sz(bands.size());
  std::size_t t_len = un;
  for (const column_table& ct : cols) t_len = std::max(t_len, ct.span + lanes);
  std::vector<float> T(t_len), Ty(t_len), Tz(t_len);
  std::vector<float> acc(padded), gacc[3];
  for (int a = 0; a < D; ++a) gacc[a].assign(kGradient ? padded : 0, 0.0f);
  // Per band: the row lines (the same in every slice) and, in 3D, the x and y
  // cells some sample reads (the slice contraction S is needed there only).
  std::vector<std::vector<line_axis>> ylines(bands.size());
  std::vector<std::vector<std::size_t>> xcells(bands.size()), ycells(bands.size());
  for (std::size_t q = 0; q < bands.size(); ++q) {
    const int b = bands[q];
    std::vector<char> yneeded(un, 0);
    for (std::size_t j = 0; j < ny; ++j) {
      ylines[q].push_back(
          make_line<kGradient>(n, period, w.band_frequency(b), w.band_position(b, zero)[1],
                               g.origin[1] + g.step[1] * static_cast<double>(j)));
      for (int c : ylines[q].back().cell) yneeded[static_cast<std::size_t>(c)] = 1;
    }
    for (std::size_t c = 0; c < un; ++c) {
      if (yneeded[c]) ycells[q].push_back(c);
      if (cols[q].needed[c]) xcells[q].push_back(c);
    }
    if constexpr (D == 3) {
      S[q].assign(un * un, 0.0f);
      if (kGradient) Sz[q].assign(un * un, 0.0f);
    }
  }
  for (std::size_t k = 0; k < nz; ++k) {
    if constexpr (D == 3) {
      for (std::size_t q = 0; q < bands.size(); ++q) {
        const int b = bands[q];
        const line_axis z =
            make_line<kGradient>(n, period, w.band_frequency(b), w.band_position(b, zero)[2],
                                 g.origin[2] + g.step[2] * static_cast<double>(k));
        for (const std::size_t yc : ycells[q]) {
          for (const std::size_t xc : xcells[q]) {
            float s = 0, sz = 0;
            for (int c = 0; c < 3; ++c) {
              const float v = tile[xc + um * (yc + un * static_cast<std::size_t>(z.cell[c]))];
              s += z.ax.w[c] * v;
              if (kGradient) sz += z.ax.dw[c] * v;
            }
            S[q][yc * un + xc] = s;
            if (kGradient) Sz[q][yc * un + xc] = sz;
          }
        }
      }
    }
    for (std::size_t j = 0; j < ny; ++j) {
      std::fill(acc.begin(), acc.end(), 0.0f);
      for (int a = 0; a < D; ++a) std::fill(gacc[a].begin(), gacc[a].end(), 0.0f);
      for (std::size_t q = 0; q < bands.size(); ++q) {
        const int b = bands[q];
        const line_axis& y = ylines[q][j];
        // T(x) = sum_b wy_b S(x, y_b) (2D: S(x, y) is the coefficient itself), at T
        // index r: x cell (first + r) mod n unwrapped, x cell r wrapped.
        const column_table& ct = cols[q];
        const std::size_t t_count = ct.unwrapped ? ct.span : un;
        for (std::size_t r = 0; r < t_count; ++r) {
          const std::size_t xc = ct.unwrapped ? (static_cast<std::size_t>(ct.first) + r) % un : r;
          if (!ct.unwrapped && !ct.needed[xc]) continue;
          float t = 0, ty = 0, tz = 0;
          for (int bb = 0; bb < 3; ++bb) {
            const std::size_t yc = static_cast<std::size_t>(y.cell[bb]);
            const float s = D == 3 ? S[q][yc * un + xc] : tile[xc + um * yc];
            t += y.ax.w[bb] * s;
            if (kGradient) {
              ty += y.ax.dw[bb] * s;
              if (D == 3) tz += y.ax.w[bb] * Sz[q][yc * un + xc];
            }
          }
          T[r] = t;
          if (kGradient) {
            Ty[r] = ty;
            Tz[r] = tz;
          }
        }
        const float wb = static_cast<float>(pl.weight[b]);
        const float chain = static_cast<float>(pl.weight[b] * w.band_frequency(b));
        for (std::size_t i = 0; i < nx; i += lanes) {
          VF v = hn::Zero(df), gx = hn::Zero(df), gy = hn::Zero(df), gz = hn::Zero(df);
          const std::size_t vec = i / lanes;
          if (ct.unwrapped && ct.fits[vec]) {
            // The taps of these columns lie in T[base, base + lanes): lane lookups.
            const auto base = static_cast<std::size_t>(ct.base[vec]);
            const VF tv = hn::LoadU(df, T.data() + base);
            const VF tyv = kGradient ? hn::LoadU(df, Ty.data() + base) : tv;
            const VF tzv = kGradient && D == 3 ? hn::LoadU(df, Tz.data() + base) : tv;
            const VI l0 = hn::LoadU(di, ct.lane0.data() + i);
            for (int a = 0; a < 3; ++a) {
              const auto ind = hn::IndicesFromVec(df, hn::Add(l0, hn::Set(di, a)));
              const VF wa = hn::LoadU(df, ct.w[a].data() + i);
              const VF t = hn::TableLookupLanes(tv, ind);
              v = mul_add(wa, t, v);
              if constexpr (kGradient) {
                gx = mul_add(hn::LoadU(df, ct.dw[a].data() + i), t, gx);
                gy = mul_add(wa, hn::TableLookupLanes(tyv, ind), gy);
                if (D == 3) gz = mul_add(wa, hn::TableLookupLanes(tzv, ind), gz);
              }
            }
          } else {
            for (int a = 0; a < 3; ++a) {
              const VI idx = hn::LoadU(di, ct.idx[a].data() + i);
              const VF wa = hn::LoadU(df, ct.w[a].data() + i);
              const VF t = hn::GatherIndex(df, T.data(), idx);
              v = mul_add(wa, t, v);
              if constexpr (kGradient) {
                gx = mul_add(hn::LoadU(df, ct.dw[a].data() + i), t, gx);
                gy = mul_add(wa, hn::GatherIndex(df, Ty.data(), idx), gy);
                if (D == 3) gz = mul_add(wa, hn::GatherIndex(df, Tz.data(), idx), gz);
              }
            }
          }
          hn::StoreU(mul_add(hn::Set(df, wb), v, hn::LoadU(df, acc.data() + i)), df,
                     acc.data() + i);
          if constexpr (kGradient) {
            const VF cv = hn::Set(df, chain);
            const VF gs[3] = {gx, gy, gz};
            for (int a = 0; a < D; ++a)
              hn::StoreU(mul_add(cv, gs[a], hn::LoadU(df, gacc[a].data() + i)), df,
                         gacc[a].data() + i);
          }
        }
      }
      // Scale and remap, as wavelet::eval.
      const std::size_t row = k * ny + j;
      float* out = value + row * nx;
      float* gout = kGradient ? grad + row * nx * D : nullptr;
      const float scale = static_cast<float>(pl.scale);
      const auto& prm = w.parameters();
      std::size_t done = 0;
      if (prm.distribution == wavelet_distribution::gaussian) {  // whole vectors in lanes
        const VF sv = hn::Set(df, scale), gv = hn::Set(df, static_cast<float>(prm.gaussian_scale));
        for (; done + lanes <= nx; done += lanes) {
          hn::StoreU(hn::Mul(hn::Mul(hn::LoadU(df, acc.data() + done), sv), gv), df, out + done);
          if constexpr (kGradient) {
            VF gs[3];
            for (int a = 0; a < D; ++a)
              gs[a] = hn::Mul(hn::Mul(hn::LoadU(df, gacc[a].data() + done), sv), gv);
            store_interleaved<D>(gs, gout + done * D);
          }
        }
      }
      for (std::size_t i = done; i < nx; ++i) {
        float v = acc[i] * scale;
        float gr[3];
        for (int a = 0; a < D; ++a) gr[a] = kGradient ? gacc[a][i] * scale : 0.0f;
        if (prm.distribution == wavelet_distribution::gaussian) {
          const float gs = static_cast<float>(prm.gaussian_scale);
          v = v * gs;
          for (int a = 0; a < D; ++a) gr[a] = gr[a] * gs;
        } else {
          float dv = 1.0f;
          w.template remap<float>(v, kGradient ? &dv : nullptr);
          for (int a = 0; a < D; ++a) gr[a] = gr[a] * dv;
        }
        out[i] = v;
        if (kGradient)
          for (int a = 0; a < D; ++a) gout[i * D + a] = gr[a];
      }
    }
  }
}

}  // namespace wavelet_simd

// Wavelet noise on a uniform grid (C order, i fastest); interleaved gradients unless
// grad is null.
template <int D>
void wavelet_grid(const wavelet<D>& w, const grid<D>& g, float* value, float* grad) {
  if (w.parameters().variant_overlap > 0) {
    const std::size_t nx = g.size[0], ny = g.size[1], nz = D == 3 ? g.size[D - 1] : 1;
    std::size_t idx = 0;
    for (std::size_t k = 0; k < nz; ++k)
      for (std::size_t j = 0; j < ny; ++j)
        for (std::size_t i = 0; i < nx; ++i, ++idx) {
          std::array<std::size_t, D> ijk{};
          ijk[0] = i;
          ijk[1] = j;
          if constexpr (D == 3) ijk[D - 1] = k;
          sample_input<D> s;
          s.position = g.position(ijk);
          wavelet_simd::scalar_sample<D>(w, s, value + idx, grad ? grad + idx * D : nullptr);
        }
    return;
  }
  if (grad)
    wavelet_simd::wavelet_grid<true, D>(w, g, value, grad);
  else
    wavelet_simd::wavelet_grid<false, D>(w, g, value, nullptr);
}

inline void wavelet2_points(const wavelet<2>& w, const float* xy, std::size_t n, float* value,
                            float* grad) {
  wavelet_points<2>(w, xy, n, value, grad);
}
inline void wavelet3_points(const wavelet<3>& w, const float* xyz, std::size_t n, float* value,
                            float* grad) {
  wavelet_points<3>(w, xyz, n, value, grad);
}
inline void wavelet2_grid(const wavelet<2>& w, const grid<2>& g, float* value, float* grad) {
  wavelet_grid<2>(w, g, value, grad);
}
inline void wavelet3_grid(const wavelet<3>& w, const grid<3>& g, float* value, float* grad) {
  wavelet_grid<3>(w, g, value, grad);
}
inline void wavelet2_samples(const wavelet<2>& w, const samples<2>& s, float* value, float* grad) {
  wavelet_samples<2>(w, s, value, grad);
}
inline void wavelet3_samples(const wavelet<3>& w, const samples<3>& s, float* value, float* grad) {
  wavelet_samples<3>(w, s, value, grad);
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_WAVELET_SIMD_INL_H_ toggle
