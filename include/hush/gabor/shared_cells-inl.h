// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise's shared-cell path, its cells: a call's points counting-sorted by
// cell within a box of cells, each cell's impulses drawn once per call (draw_box),
// and the workspace each thread keeps between calls. The kernels that run over
// them are in hush/gabor/shared_points-inl.h.
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/gabor/simd-inl.h, never included directly by users.
#if defined(HUSH_GABOR_SHARED_CELLS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_GABOR_SHARED_CELLS_INL_H_
#undef HUSH_GABOR_SHARED_CELLS_INL_H_
#else
#define HUSH_GABOR_SHARED_CELLS_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <hwy/highway.h>

#include "hush/detail/constants.hpp"
#include "hush/gabor/lockstep-inl.h"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace gabor_simd {

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

}  // namespace gabor_simd
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_GABOR_SHARED_CELLS_INL_H_ toggle
