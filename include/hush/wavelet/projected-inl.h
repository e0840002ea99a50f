// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Wavelet noise projected onto a surface (wavelet.hpp band_kernel, unwidened) in
// lanes: the kinds of lanes a vector may hold, and per kind its kernel: the fixed
// kernel along a tile axis for a normal along it, the exact projection
// (general_exact) or the paper's approximation (general_approx) for any other.
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/wavelet/simd-inl.h, never included directly by users.
#if defined(HUSH_WAVELET_PROJECTED_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_WAVELET_PROJECTED_INL_H_
#undef HUSH_WAVELET_PROJECTED_INL_H_
#else
#define HUSH_WAVELET_PROJECTED_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <limits>

#include <hwy/highway.h>

#include "hush/wavelet/separable-inl.h"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace wavelet_simd {

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

}  // namespace wavelet_simd
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_WAVELET_PROJECTED_INL_H_ toggle
