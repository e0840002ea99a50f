// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernels for wavelet noise (include/hush/wavelet.hpp), 2D and 3D:
// batches of points, uniform grids, and samples with footprints and normals;
// values and optionally analytic gradients. Compiled once per SIMD target (the
// "-inl.h" convention); reached through hush/simd/dispatch.hpp.
//
// The kernels repeat wavelet.hpp's float algorithm operation by operation, so
// under HUSH_STRICT_FP every value and gradient is bit for bit the scalar
// result (tests/wavelet/wavelet_simd_test.cpp, every compiled target):
//  - band positions 2^b x + o_b - 1/2 are formed in double and split into cell
//    and fraction as lattice_split<float> does (in f64 lanes; lanes that are
//    not finite or beyond 2^31 take core/lattice.hpp lane by lane);
//  - the B-spline weights by the same Horner steps, the same nested sums
//    (z innermost), the same band accumulation, scale and gradient chain;
//  - the distribution remapping (erf, the table) runs lane by lane through
//    wavelet::remap, the scalar code itself.
// 3D points: a 4-float row load per lane and (y, z) row (rows3). Grids use the separability
// of the basis (the 3D single-band fast path): per slice the
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
//
// Its parts: hush/wavelet/separable-inl.h (the bands in lanes, separable),
// hush/wavelet/projected-inl.h (projection onto a surface) and hush/wavelet/grid-inl.h
// (grids); this file holds the points and samples kernels and the entry points.
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

#include <hwy/highway.h>

#include "hush/core/samples.hpp"
#include "hush/core/views.hpp"
#include "hush/simd/lanes-inl.h"
#include "hush/wavelet/grid-inl.h"
#include "hush/wavelet/projected-inl.h"
#include "hush/wavelet/separable-inl.h"

// The noise class comes first, not from here: hush/wavelet.hpp includes these
// kernels at its end (hush/wavelet/simd_kernel.hpp), as src/simd/wavelet.cpp does.
HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace wavelet_simd {

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
