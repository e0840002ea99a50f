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
//    result (tests/gabor/gabor_simd_test.cpp, every compiled target);
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
//    (gabor/kernel.hpp's separable form), unmasked (the float taper is exactly 0 outside the
//    support) over the x-vectors that reach the impulse's disk in that row (the row skip);
//    each cell's impulses drawn once into a small cache for the blocks that see it (the draw
//    cache). Grids with fewer than kMinRun samples per cell along x (by their step, so that
//    blocks and slabs of a grid take its path) go through the points path instead.
//
// Its parts, one per path: hush/gabor/kernel-inl.h (the kernel and the constants in
// lanes), hush/gabor/lockstep-inl.h, hush/gabor/shared_cells-inl.h and
// hush/gabor/shared_points-inl.h (the shared-cell path), hush/gabor/grid-inl.h; this
// file holds the entry points.

#if defined(HUSH_GABOR_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_GABOR_SIMD_INL_H_
#undef HUSH_GABOR_SIMD_INL_H_
#else
#define HUSH_GABOR_SIMD_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <hwy/highway.h>

#include "hush/config.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/views.hpp"
#include "hush/gabor/grid-inl.h"
#include "hush/gabor/lockstep-inl.h"
#include "hush/gabor/shared_points-inl.h"
#include "hush/simd/lanes-inl.h"

// The noise class comes first, not from here: hush/gabor.hpp includes these
// kernels at its end (hush/gabor/simd_kernel.hpp), as src/simd/gabor.cpp does.
HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

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
