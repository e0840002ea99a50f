// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise's lockstep path (one lane per point): per cell and impulse the lanes
// draw in lockstep, the impulses within each lane's support are compressed into a
// list, and the unfiltered, filtered or surface kernel runs over it in full
// vectors; each lane sums its terms in stream order (finish). It evaluates points
// and filtered samples that the shared-cell path leaves, and samples with normals.
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/gabor/simd-inl.h, never included directly by users.
#if defined(HUSH_GABOR_LOCKSTEP_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_GABOR_LOCKSTEP_INL_H_
#undef HUSH_GABOR_LOCKSTEP_INL_H_
#else
#define HUSH_GABOR_LOCKSTEP_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/samples.hpp"
#include "hush/detail/constants.hpp"
#include "hush/gabor/kernel-inl.h"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace gabor_simd {

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

}  // namespace gabor_simd
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_GABOR_LOCKSTEP_INL_H_ toggle
