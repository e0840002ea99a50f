// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Gabor noise on uniform grids: samples in blocks that share their cell along y
// (and z), each impulse's factors along y (and z) computed once per row, along x
// once per column, and per sample only their products; each cell's impulses
// drawn once into a cache for the blocks that see it. Grids too sparse for blocks
// take the lockstep path (hush/gabor/lockstep-inl.h).
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/gabor/simd-inl.h, never included directly by users.
#if defined(HUSH_GABOR_GRID_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_GABOR_GRID_INL_H_
#undef HUSH_GABOR_GRID_INL_H_
#else
#define HUSH_GABOR_GRID_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <hwy/highway.h>

#include "hush/core/views.hpp"
#include "hush/gabor/lockstep-inl.h"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace gabor_simd {

// Grids with fewer samples per cell along x than this (cell / |step x|) take the points path.
constexpr double kMinRun = 8.0;
// Grid blocks' width along x (2D, 3D): several cells, so that an impulse's
// factors along y (and z) serve that many samples; the block's sums stay in
// L1/L2 (2D: rows of one cell, ~64 x 256 floats; 3D: 32 x 16 rows).
constexpr std::size_t kBlockX[2] = {256, 64};

// ---- Grids: blocks of samples that share their cell.

// One axis of a grid, split as scalar evaluation splits grid.position(): the
// cell and fraction of g.coordinate(axis, first + i) * inverse cell for i in
// [0, n), and runs of equal cells (at most `cap` long).
struct grid_axis {
  std::vector<std::uint32_t> cell;
  std::vector<float> frac;
  std::vector<char> bad;
  std::vector<std::size_t> run_start;  // runs [run_start[r], run_start[r + 1])
  template <int D>
  grid_axis(const hush::grid<D>& g, int axis, std::size_t first, std::size_t n, double inv,
            std::size_t cap)
      : cell(n), frac(n), bad(n) {
    for (std::size_t i = 0; i < n; ++i) {
      const lattice_coord<float> c =
          lattice_split<float>(g.coordinate(axis, first + i) * inv);
      cell[i] = c.i0;
      frac[i] = c.f;
      bad[i] = std::isnan(c.f) ? 1 : 0;
    }
    for (std::size_t i = 0; i < n; ++i)
      if (i == 0 || cell[i] != cell[i - 1] || i - run_start.back() == cap) run_start.push_back(i);
    run_start.push_back(n);
  }
  std::size_t runs() const { return run_start.size() - 1; }
  std::size_t longest_run() const {
    std::size_t m = 0;
    for (std::size_t r = 0; r + 1 < run_start.size(); ++r)
      m = std::max(m, run_start[r + 1] - run_start[r]);
    return m;
  }
};

// The factors of one impulse along one axis of a block: for the block's
// samples [from, n) (padded to whole vectors with fractions far outside), offset
// d = frac - (o + u) (detail::gabor_offset), d^2 and the axis factors; `lo`, `hi`: the range of
// samples with d^2 < 1 (contiguous: frac is monotonic within a cell); along
// x (`ox`: each sample's o, the impulse's cell relative to the sample's) also
// the products e c and e s (gabor_pair_of_products' x side).
struct block_factors {
  std::vector<float> d, d2, e, s, c, ec, es;
  // Along x, per vector: the least d^2 of its lanes (a NaN lane counts as 0:
  // such a vector is never skipped).
  std::vector<float> vmin;
  std::size_t lo = 0, hi = 0;
  explicit block_factors(std::size_t cap)
      : d(cap), d2(cap), e(cap), s(cap), c(cap), ec(cap), es(cap), vmin(cap) {}
  void compute(const float* frac, std::size_t n_pad, float o, float u, VF neg_a, VF phi,
               const float* ox = nullptr, std::size_t from = 0) {
    const DF df;
    const std::size_t lanes = hn::Lanes(df);
    const VF ou = hn::Set(df, o), uu = hn::Set(df, u);
    lo = n_pad;
    hi = 0;
    for (std::size_t i = from; i < n_pad; i += lanes) {
      const VF dv = hn::Sub(hn::LoadU(df, frac + i), hn::Add(ox ? hn::LoadU(df, ox + i) : ou, uu));
      const VF d2v = hn::Mul(dv, dv);
      hn::StoreU(dv, df, d.data() + i);
      hn::StoreU(d2v, df, d2.data() + i);
      if (ox)
        vmin[i / lanes] = hn::GetLane(hn::MinOfLanes(df, hn::IfThenZeroElse(hn::IsNaN(d2v), d2v)));
      if (hn::AllFalse(df, hn::Lt(d2v, hn::Set(df, 1.0f)))) continue;
      lo = std::min(lo, i);
      hi = i + lanes;
      const axis f = axis_factors(dv, neg_a, phi);
      hn::StoreU(f.e, df, e.data() + i);
      hn::StoreU(f.s, df, s.data() + i);
      hn::StoreU(f.c, df, c.data() + i);
      hn::StoreU(hn::Mul(f.e, f.c), df, ec.data() + i);
      hn::StoreU(hn::Mul(f.e, f.s), df, es.data() + i);
    }
  }
};

template <int D, bool G>
struct grid_kernel {
  const gabor<D>& g;
  const consts<D> c;
  std::size_t cap[3];
  std::vector<float> acc, gacc[3];
  std::size_t stride = 0;  // floats per block row
  // The block's fractions per axis, padded (x to whole vectors).
  std::vector<float> frac[3];
  block_factors fx, fy, fz;
  // Along x: each sample's cell relative to the block's first (padded), the
  // runs of equal cells, the cells to visit, and o per sample for one of them.
  struct xrun {
    std::int32_t rel;
    std::size_t begin, end;
  };
  std::vector<std::int32_t> rel;
  static constexpr std::int32_t kFar = 1 << 20;  // rel of non-finite samples and padding
  std::vector<float> ox;
  std::vector<xrun> xruns;
  std::vector<std::int32_t> visits;

  // Each cell's impulses (positions, weight, frequency: stream order) drawn
  // once for the blocks that see it, in a direct-mapped cache keyed by the
  // cell (the low bits of its indices pick the slot: blocks go along x, so the
  // cells in use stay apart); a slot shared by two cells in use only repeats
  // a draw.
  struct drawn {
    float u[3], wt, phi[3];
  };
  struct slot {
    bool used = false;
    std::uint32_t key[3] = {};
    std::vector<drawn> imp;
  };
  static constexpr std::uint32_t kSlotsX = 64, kSlotsYZ = 4;
  std::vector<slot> cache{kSlotsX * kSlotsYZ * (D == 3 ? kSlotsYZ : 1)};
  const std::vector<drawn>& impulses(const std::uint32_t (&cell)[D]) {
    std::size_t i = cell[0] % kSlotsX + kSlotsX * (cell[1] % kSlotsYZ);
    if (D == 3) i += kSlotsX * kSlotsYZ * (cell[D - 1] % kSlotsYZ);
    slot& sl = cache[i];
    bool hit = sl.used;
    for (int a = 0; a < D; ++a) hit = hit && sl.key[a] == cell[a];
    if (hit) return sl.imp;
    sl.used = true;
    for (int a = 0; a < D; ++a) sl.key[a] = cell[a];
    sl.imp.clear();
    g.for_each_impulse(cell, [&](const std::uint32_t* w) {
      drawn d{};
      for (int a = 0; a < D; ++a) d.u[a] = gabor<D>::template impulse_position<float>(w, a);
      float mv[4] = {};
      vec<float, D> phi;
      g.template mark_values<float>(w, mv);
      g.marks().template draw<float>(mv, d.wt, phi);
      for (int a = 0; a < D; ++a) d.phi[a] = phi[a];
      sl.imp.push_back(d);
    });
    return sl.imp;
  }

  explicit grid_kernel(const gabor<D>& noise, std::size_t cx, std::size_t cy, std::size_t cz)
      : g(noise),
        c(noise),
        cap{cx, cy, cz},
        fx(cx + kMaxLanes),
        fy(cy + kMaxLanes),
        fz(cz + kMaxLanes) {
    stride = cx + kMaxLanes;
    const std::size_t cells = stride * cy * cz;
    acc.resize(cells);
    if (G)
      for (int a = 0; a < D; ++a) gacc[a].resize(cells);
    for (int a = 0; a < 3; ++a) frac[a].resize(cap[a] + kMaxLanes);
    rel.resize(stride);
    ox.resize(stride);
  }

  // Adds one impulse's terms (factors along each axis in fx, fy, fz) to the
  // block's sums: per row the row's side of gabor_pair_of_products, per
  // sample only the products and the taper, which is 0 outside the support
  // (no mask: adding +-0 leaves every sum as the scalar path's).
  void add_impulse(const float* phi, float wt, std::size_t ny, std::size_t nz) {
    const DF df;
    const std::size_t lanes = hn::Lanes(df);
    const VF phx = hn::Set(df, phi[0]);
    for (std::size_t kk = 0; kk < nz; ++kk) {
      if constexpr (D == 3)
        if (!(fz.d2[kk] < 1.0f)) continue;
      for (std::size_t jj = std::min(fy.lo, ny); jj < std::min(fy.hi, ny); ++jj) {
        if (!(fy.d2[jj] < 1.0f)) continue;
        detail::gabor_row<float> r;
        if constexpr (D == 2) {
          r = detail::gabor_row_of(
              wt, detail::gabor_axis<float>{fy.d[jj], fy.d2[jj], fy.e[jj], fy.s[jj], fy.c[jj]});
        } else {
          r = detail::gabor_row_of(
              wt, detail::gabor_axis<float>{fy.d[jj], fy.d2[jj], fy.e[jj], fy.s[jj], fy.c[jj]},
              detail::gabor_axis<float>{fz.d[kk], fz.d2[kk], fz.e[kk], fz.s[kk], fz.c[kk]});
        }
        const VF b = hn::Set(df, r.we * r.c), q = hn::Set(df, r.we * r.s);
        const VF rd2 = hn::Set(df, r.d2);
        // Local restrict pointers: the sums' stores alias no factor, so the
        // loop keeps them in registers.
        float* HWY_RESTRICT arow = acc.data() + (kk * ny + jj) * stride;
        const float* HWY_RESTRICT xec = fx.ec.data();
        const float* HWY_RESTRICT xes = fx.es.data();
        const float* HWY_RESTRICT xd2 = fx.d2.data();
        // The row's chord of the support, by whole vectors: a vector whose
        // least d^2 plus the row's is >= 1 only adds +-0 (float addition and
        // the taper's steps are monotonic), so skipping it changes nothing.
        std::size_t ib = fx.lo, ie = fx.hi;
        while (ib < ie && !(fx.vmin[ib / lanes] + r.d2 < 1.0f)) ib += lanes;
        while (ie > ib && !(fx.vmin[ie / lanes - 1] + r.d2 < 1.0f)) ie -= lanes;
        for (std::size_t ii = ib; ii < ie; ii += lanes) {
          const VF ec = hn::LoadU(df, xec + ii), es = hn::LoadU(df, xes + ii);
          const VF s2 = hn::Add(hn::LoadU(df, xd2 + ii), rd2);
          if constexpr (G) {
            VF v, uu, vv;
            pair_gradient_of_products(ec, es, b, q, s2, c.k, c.a, v, uu, vv);
            hn::StoreU(hn::Add(hn::LoadU(df, arow + ii), v), df, arow + ii);
            const VF dd[3] = {hn::LoadU(df, fx.d.data() + ii), hn::Set(df, fy.d[jj]),
                              hn::Set(df, D == 3 ? fz.d[kk] : 0.0f)};
            const VF ph[3] = {phx, hn::Set(df, phi[1]), hn::Set(df, D == 3 ? phi[D - 1] : 0.0f)};
            for (int a = 0; a < D; ++a) {
              float* grow = gacc[a].data() + (kk * ny + jj) * stride;
              const VF term = hn::Sub(hn::Mul(uu, dd[a]), hn::Mul(vv, ph[a]));
              hn::StoreU(hn::Add(hn::LoadU(df, grow + ii), term), df, grow + ii);
            }
          } else {
            hn::StoreU(hn::Add(hn::LoadU(df, arow + ii), pair_of_products(ec, es, b, q, s2, c.k)),
                       df, arow + ii);
          }
        }
      }
    }
  }

  // One block: samples [i0, i0 + nx) x [j0, j0 + ny) x [k0, k0 + nz) of the
  // axes, along y (and z) all in the cell (ay.cell[j0], az.cell[k0]), along x
  // in any cells: each impulse's factors along y (and z) are computed once for
  // the whole width, and its chord of each row is cut by no block edge but the
  // block's.
  void block(const grid_axis* axes, std::size_t i0, std::size_t nx, std::size_t j0, std::size_t ny,
             std::size_t k0, std::size_t nz, const hush::grid<D>& gr, float* value, float* grad) {
    const DF df;
    const DI di;
    const std::size_t lanes = hn::Lanes(df);
    const std::size_t nx_pad = (nx + lanes - 1) / lanes * lanes;
    const std::size_t n[3] = {nx, ny, nz}, first[3] = {i0, j0, k0};
    for (int a = 0; a < D; ++a) {
      std::copy(axes[a].frac.begin() + static_cast<std::ptrdiff_t>(first[a]),
                axes[a].frac.begin() + static_cast<std::ptrdiff_t>(first[a] + n[a]),
                frac[a].begin());
      std::fill(frac[a].begin() + static_cast<std::ptrdiff_t>(n[a]), frac[a].end(),
                4.0f);  // d^2 > 1
    }
    const std::size_t rows = ny * nz;
    std::fill(acc.begin(), acc.begin() + static_cast<std::ptrdiff_t>(rows * stride), 0.0f);
    if constexpr (G)
      for (int a = 0; a < D; ++a)
        std::fill(gacc[a].begin(), gacc[a].begin() + static_cast<std::ptrdiff_t>(rows * stride),
                  0.0f);
    // Along x: each sample's cell relative to the first finite sample's (a
    // non-finite sample, or padding, far away: its value is NaN or unused),
    // the runs of equal cells, and the cells to visit (each run's and its
    // neighbours, ascending: per sample the scalar order o = -1, 0, 1).
    std::size_t f0 = 0;
    while (f0 < nx && axes[0].bad[i0 + f0]) ++f0;
    const std::uint32_t ref = f0 < nx ? axes[0].cell[i0 + f0] : 0u;
    xruns.clear();
    visits.clear();
    for (std::size_t i = 0; i < nx_pad; ++i) {
      if (i >= nx || axes[0].bad[i0 + i]) {
        rel[i] = kFar;
        continue;
      }
      rel[i] = static_cast<std::int32_t>(axes[0].cell[i0 + i] - ref);
      if (xruns.empty() || xruns.back().rel != rel[i] || xruns.back().end != i)
        xruns.push_back({rel[i], i, i + 1});
      else
        xruns.back().end = i + 1;
    }
    for (const xrun& x : xruns)
      for (std::int32_t o = -1; o <= 1; ++o) visits.push_back(x.rel + o);
    std::sort(visits.begin(), visits.end());
    visits.erase(std::unique(visits.begin(), visits.end()), visits.end());
    const std::uint32_t base[3] = {ref, axes[1].cell[j0], D == 3 ? axes[D - 1].cell[k0] : 0u};
    for (int oz = D == 3 ? -1 : 0; oz <= (D == 3 ? 1 : 0); ++oz)
      for (int oy = -1; oy <= 1; ++oy)
        for (const std::int32_t X : visits) {
          // The samples within one cell of X (contiguous: cells are monotonic
          // along x), by whole vectors, and their o = X - rel (clamped: from 2
          // on, d^2 >= 1 exactly).
          std::size_t lo = nx_pad, hi = 0;
          for (const xrun& x : xruns)
            if (x.rel >= X - 1 && x.rel <= X + 1) {
              lo = std::min(lo, x.begin);
              hi = std::max(hi, x.end);
            }
          if (lo >= hi) continue;
          lo = lo / lanes * lanes;
          hi = (hi + lanes - 1) / lanes * lanes;
          const VI xv = hn::Set(di, X), two = hn::Set(di, 2);
          for (std::size_t i = lo; i < hi; i += lanes) {
            const VI o = hn::Sub(xv, hn::LoadU(di, rel.data() + i));
            hn::StoreU(hn::ConvertTo(df, hn::Min(hn::Max(o, hn::Neg(two)), two)), df,
                       ox.data() + i);
          }
          std::uint32_t cell[D];
          cell[0] = ref + static_cast<std::uint32_t>(X);
          cell[1] = base[1] + static_cast<std::uint32_t>(oy);
          if constexpr (D == 3) cell[2] = base[2] + static_cast<std::uint32_t>(oz);
          for (const drawn& im : impulses(cell)) {
            const float* u = im.u;
            const float* phi = im.phi;
            const float wt = im.wt;
            fy.compute(frac[1].data(), (ny + lanes - 1) / lanes * lanes, float(oy), u[1], c.neg_a,
                       hn::Set(df, phi[1]));
            if (fy.lo >= fy.hi) continue;
            if constexpr (D == 3) {
              fz.compute(frac[2].data(), (nz + lanes - 1) / lanes * lanes, float(oz), u[2], c.neg_a,
                         hn::Set(df, phi[2]));
              if (fz.lo >= fz.hi) continue;
            }
            fx.compute(frac[0].data(), hi, 0.0f, u[0], c.neg_a, hn::Set(df, phi[0]), ox.data(), lo);
            if (fx.lo >= fx.hi) continue;
            add_impulse(phi, wt, ny, nz);
          }
        }
    // Out: value = sum * scale, gradient = sum * (scale / cell); NaN where a
    // coordinate of the sample is not finite.
    const float scale = float(g.scale()), gscale = float(g.scale() * g.inverse_cell());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::size_t gx = gr.size[0], gy = gr.size[1];
    const VF vscale = hn::Set(df, scale), vnan = hn::Set(df, nan);
    const VI far = hn::Set(di, kFar);
    for (std::size_t kk = 0; kk < nz; ++kk)
      for (std::size_t jj = 0; jj < ny; ++jj) {
        const bool row_bad = axes[1].bad[j0 + jj] || (D == 3 && axes[D - 1].bad[k0 + kk]);
        const std::size_t out_row = ((k0 + kk) * gy + (j0 + jj)) * gx + i0;
        const float* arow = acc.data() + (kk * ny + jj) * stride;
        std::size_t ii = 0;
        if (!row_bad)  // whole vectors; rel marks the non-finite samples
          for (; ii + lanes <= nx; ii += lanes) {
            const MF bad = hn::RebindMask(df, hn::Eq(hn::LoadU(di, rel.data() + ii), far));
            hn::StoreU(hn::IfThenElse(bad, vnan, hn::Mul(hn::LoadU(df, arow + ii), vscale)), df,
                       value + out_row + ii);
          }
        for (; ii < nx; ++ii)
          value[out_row + ii] = row_bad || axes[0].bad[i0 + ii] ? nan : arow[ii] * scale;
        if constexpr (G)
          for (ii = 0; ii < nx; ++ii) {
            const bool bad = row_bad || axes[0].bad[i0 + ii];
            for (int a = 0; a < D; ++a)
              grad[(out_row + ii) * D + static_cast<std::size_t>(a)] =
                  bad ? nan : gacc[a][(kk * ny + jj) * stride + ii] * gscale;
          }
      }
  }
};

// The slab [first, first + count) of a grid's slowest axis (value and grad
// start at its first sample): blocks of shared cells when there are enough
// samples per cell along x, else the points path on the grid's positions.
template <int D, bool G>
void grid(const gabor<D>& g, const hush::grid<D>& whole, std::size_t first, std::size_t count,
          float* value, float* grad) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const double inv = g.inverse_cell();
  const std::size_t caps[3] = {64, D == 2 ? 64u : 32u, 16};
  hush::grid<D> gr = whole;  // the slab's sizes (output indexing); positions from `whole`
  gr.size[D - 1] = count;
  std::vector<grid_axis> axes;
  axes.reserve(D);
  for (int a = 0; a < D; ++a)
    axes.emplace_back(whole, a, a == D - 1 ? first : 0, gr.size[a], inv, caps[a]);
  // Samples per cell along x from the step, not from this slab's size: a block of a grid
  // (hush::grid::block) and every parallel slab take the path the whole grid takes, so each
  // sample meets the same arithmetic (the two paths contract differently).
  const double per_cell = 1.0 / (std::fabs(whole.step[0]) * inv);
  const std::size_t nx = gr.size[0], ny = gr.size[1];
  if (!(per_cell >= kMinRun)) {
    lanes_split sp;
    auto split = [&](std::size_t batch, std::size_t used) {
      for (std::size_t l = 0; l < lanes; ++l) {
        if (l >= used) {
          clear_lane<D>(sp, l);
          continue;
        }
        const std::size_t idx = batch + l, i = idx % nx, j = (idx / nx) % ny, k = idx / (nx * ny);
        const std::size_t ijk[3] = {i, j, k};
        bool bad = false;
        for (int a = 0; a < D; ++a) {
          sp.cell[a][l] = axes[a].cell[ijk[a]];
          sp.frac[a][l] = axes[a].frac[ijk[a]];
          bad = bad || axes[a].bad[ijk[a]];
        }
        sp.bad[l] = bad;
      }
    };
    points<D, G, true>(g, gr.count(), sp, split, value, grad);
    return;
  }
  // Block buffers sized by the longest runs, not the caps: small grids do not pay for
  // (and page-fault in) buffers they never fill.
  // Along x, blocks of kBlockX samples whatever their cells (see block()) where
  // the finite samples' cells step by at most one (so a block's cells relative to
  // its first are small and ascend or descend); else (only where coordinates are
  // so large that a double's spacing exceeds a cell) blocks of one cell's run.
  bool steps_of_one = true;
  for (std::size_t i = 0, last = nx; i < nx && steps_of_one; ++i) {
    if (axes[0].bad[i]) continue;
    if (last < nx) {
      const auto step = static_cast<std::int32_t>(axes[0].cell[i] - axes[0].cell[last]);
      steps_of_one = step >= -1 && step <= 1;
    }
    last = i;
  }
  const std::size_t bx = std::min(nx, kBlockX[D - 2]);
  grid_kernel<D, G> kernel(g, bx, axes[1].longest_run(), D == 3 ? axes[D - 1].longest_run() : 1);
  auto each_block = [&](auto&& f) {
    if (steps_of_one)
      for (std::size_t i0 = 0; i0 < nx; i0 += bx) f(i0, std::min(bx, nx - i0));
    else
      for (std::size_t xr = 0; xr < axes[0].runs(); ++xr)
        f(axes[0].run_start[xr], axes[0].run_start[xr + 1] - axes[0].run_start[xr]);
  };
  const std::size_t zruns = D == 3 ? axes[D - 1].runs() : 1;
  for (std::size_t zr = 0; zr < zruns; ++zr) {
    const std::size_t k0 = D == 3 ? axes[D - 1].run_start[zr] : 0;
    const std::size_t k1 = D == 3 ? axes[D - 1].run_start[zr + 1] : 1;
    for (std::size_t yr = 0; yr < axes[1].runs(); ++yr) {
      const std::size_t j0 = axes[1].run_start[yr], j1 = axes[1].run_start[yr + 1];
      each_block([&](std::size_t i0, std::size_t n) {
        kernel.block(axes.data(), i0, n, j0, j1 - j0, k0, k1 - k0, gr, value, grad);
      });
    }
  }
}

}  // namespace gabor_simd
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_GABOR_GRID_INL_H_ toggle
