// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Wavelet noise on uniform grids in lanes, by the separability of the basis: per
// band the x axis split once per column, y once per row, z once per slice, and the
// contraction in the scalar code's order (hush/wavelet/simd-inl.h says how).
// Compiled once per SIMD target (the "-inl.h" convention: toggle include guard
// below); a part of hush/wavelet/simd-inl.h, never included directly by users.
#if defined(HUSH_WAVELET_GRID_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_WAVELET_GRID_INL_H_
#undef HUSH_WAVELET_GRID_INL_H_
#else
#define HUSH_WAVELET_GRID_INL_H_
#endif

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <hwy/highway.h>

#include "hush/core/views.hpp"
#include "hush/wavelet/separable-inl.h"
#include "hush/simd/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

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

template <bool kGradient, int D>
column_table make_columns(std::size_t nx, int n, std::uint32_t period, double freq, double off,
                          const grid<D>& g) {
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
    double x = g.coordinate(0, i) * freq;
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
                                           w.band_position(b, zero)[0], g));
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
                               g.coordinate(1, j)));
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
                                 g.coordinate(2, k));
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
}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_WAVELET_GRID_INL_H_ toggle
