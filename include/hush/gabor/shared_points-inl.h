// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise's shared-cell path, its kernels: per point the candidate impulses
// of its cells (hush/gabor/shared_cells-inl.h) tested in full vectors and the kept
// ones compressed into a pair list; the unfiltered and filtered kernels over the
// list (shared_unfiltered, shared_filtered; filters_2d computes 2D filters in lanes
// of doubles); and shared_points, which runs them and sends the box's outliers to
// the lockstep path.
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/gabor/simd-inl.h, never included directly by users.
#if defined(HUSH_GABOR_SHARED_POINTS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_GABOR_SHARED_POINTS_INL_H_
#undef HUSH_GABOR_SHARED_POINTS_INL_H_
#else
#define HUSH_GABOR_SHARED_POINTS_INL_H_
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <hwy/cache_control.h>
#include <hwy/highway.h>

#include "hush/core/samples.hpp"
#include "hush/detail/constants.hpp"
#include "hush/gabor/shared_cells-inl.h"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace gabor_simd {

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

}  // namespace gabor_simd
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_GABOR_SHARED_POINTS_INL_H_ toggle
