// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Scalar Gabor noise in batches (gabor<D>::point_values, grid_values' tiles): the impulses of
// a block of 3^D cells are decoded once and reused by every sample in the block, then summed
// per sample in exactly the order and form of the point evaluation (for_each_pair and
// solid_sum), so batches give noise(p) bit for bit. Member definitions of hush::gabor<D>
// (gabor.hpp declares them and includes this file after the class).
#ifndef HUSH_GABOR_BATCH_HPP
#define HUSH_GABOR_BATCH_HPP

#include <cstddef>
#include <cstdint>
#include <vector>

// Part of hush/gabor.hpp, which includes it after the class it completes.
#ifndef HUSH_GABOR_HPP
#error "hush/gabor/batch.hpp is part of hush/gabor.hpp: include <hush/gabor.hpp>"
#endif

namespace hush {

template <int D>
template <class T>
void gabor<D>::fill_block(const std::uint32_t (&centre)[std::size_t{D}],
                          std::vector<block_impulse<T>>& out) const {
  out.clear();
  constexpr int kCells = D == 2 ? 9 : 27;
  for (int n = 0; n < kCells; ++n) {
    int o[std::size_t{D}];
    std::uint32_t cell[std::size_t{D}];
    for (int ax = 0, m = n; ax < D; ++ax, m /= 3) {
      o[ax] = m % 3 - 1;
      cell[ax] = centre[ax] + static_cast<std::uint32_t>(o[ax]);
    }
    for_each_impulse(cell, [&](const std::uint32_t* words) {
      block_impulse<T> b;
      for (int ax = 0; ax < D; ++ax) b.ou[ax] = T(o[ax]) + impulse_position<T>(words, ax);
      T u[4] = {};
      mark_values<T>(words, u);
      marks_.template draw<T>(u, b.w, b.phi);
      out.push_back(b);
    });
  }
}

template <int D>
void gabor<D>::point_values(const vec<float, D>* pts, std::size_t count, float* out,
                            vec<float, D>* grad) const {
  std::vector<block_impulse<float>> block;
  std::vector<kept_impulse> kept;
  std::uint32_t centre[std::size_t{D}] = {};
  bool filled = false;
  for (std::size_t i = 0; i < count; ++i) {
    const vec<double, D> p = vec_cast<double>(pts[i]);
    lattice_coord<float> c[std::size_t{D}];
    bool finite = true;
    for (int a = 0; a < D; ++a) {
      c[a] = lattice_split<float>(p[a] * inv_cell_);
      if (std::isnan(c[a].f)) finite = false;
    }
    value_gradient<float, D> r;
    if (!finite) {
      r = nan_result<float>();
    } else {
      bool same = filled;
      for (int a = 0; a < D; ++a) same = same && centre[a] == c[a].i0;
      if (!same) {
        for (int a = 0; a < D; ++a) centre[a] = c[a].i0;
        fill_block<float>(centre, block);
        filled = true;
      }
      r = grad ? block_eval<true>(block, c, kept) : block_eval<false>(block, c, kept);
    }
    out[i] = r.value;
    if (grad) grad[i] = r.gradient;
  }
}

template <int D>
template <bool G>
value_gradient<float, D> gabor<D>::block_eval(const std::vector<block_impulse<float>>& block,
                                              const lattice_coord<float>* c,
                                              std::vector<kept_impulse>& kept) const {
  kept.resize(block.size());
  std::size_t n = 0;
  for (const block_impulse<float>& b : block) {
    kept_impulse& k = kept[n];
    float d2[std::size_t{D}];
    for (int ax = 0; ax < D; ++ax) {
      k.d[ax] = c[ax].f - b.ou[ax];
      d2[ax] = k.d[ax] * k.d[ax];
    }
    k.s = D == 2 ? d2[0] + d2[1] : d2[0] + (d2[1] + d2[2]);
    k.b = &b;
    n += k.s < 1.0f ? 1 : 0;
  }
  solid_sum<float, G, false> acc(*this);
  for (std::size_t m = 0; m < n; ++m) acc.add(kept[m].d, kept[m].s, kept[m].b->w, kept[m].b->phi);
  return acc.result(*this);
}

template <int D>
template <bool G>
void gabor<D>::grid_tiles(const grid<D>& g, std::size_t first, std::size_t count, float* out,
                          vec<float, D>* grad) const {
  std::size_t lo[std::size_t{D}] = {}, hi[std::size_t{D}] = {};
  std::vector<lattice_coord<float>> coord[std::size_t{D}];
  std::vector<grid_run> runs[std::size_t{D}];
  for (int a = 0; a < D; ++a) {
    lo[a] = a == D - 1 ? first : 0;
    hi[a] = a == D - 1 ? first + count : g.size[a];
    for (std::size_t i = lo[a]; i < hi[a]; ++i) {
      // grid::position's coordinate, split as for_each_pair splits it.
      const double x = g.coordinate(a, i);
      const lattice_coord<float> c = lattice_split<float>(x * inv_cell_);
      coord[a].push_back(c);
      const bool nan = std::isnan(c.f);
      if (runs[a].empty()) runs[a].push_back(grid_run{i, i, nan});
      const grid_run& last = runs[a].back();
      if (last.end > last.begin && (nan || last.nan || coord[a][last.begin - lo[a]].i0 != c.i0 ||
                                    last.end - last.begin == kGridTile))
        runs[a].push_back(grid_run{i, i, nan});
      runs[a].back().end = i + 1;
    }
  }
  std::vector<block_impulse<float>> block;
  std::vector<grid_column> cols;
  std::vector<grid_row> rows;
  const std::size_t nx = g.size[0], ny = g.size[1];
  auto index = [&](std::size_t i, std::size_t j, std::size_t k) {
    return D == 2 ? (j - first) * nx + i : ((k - first) * ny + j) * nx + i;
  };
  const std::size_t kruns = D == 3 ? runs[std::size_t{D} - 1].size() : 1;
  for (std::size_t rk = 0; rk < kruns; ++rk)
    for (const grid_run& ry : runs[1])
      for (const grid_run& rx : runs[0]) {
        const grid_run rz = D == 3 ? runs[std::size_t{D} - 1][rk] : grid_run{0, 1, false};
        const std::size_t ncol = rx.end - rx.begin;
        const std::size_t nrow = (ry.end - ry.begin) * (rz.end - rz.begin);
        if (rx.nan || ry.nan || rz.nan || ncol * nrow < 2 * (ncol + nrow)) {
          for (std::size_t k = rz.begin; k < rz.end; ++k)
            for (std::size_t j = ry.begin; j < ry.end; ++j)
              for (std::size_t i = rx.begin; i < rx.end; ++i) {
                std::array<std::size_t, std::size_t{D}> ijk{};
                ijk[0] = i;
                ijk[1] = j;
                if constexpr (D == 3) ijk[2] = k;
                const auto r = eval<float, G, true>(g.position(ijk));
                out[index(i, j, k)] = r.value;
                if constexpr (G) grad[index(i, j, k)] = r.gradient;
              }
          continue;
        }
        std::uint32_t centre[std::size_t{D}];
        centre[0] = coord[0][rx.begin - lo[0]].i0;
        centre[1] = coord[1][ry.begin - lo[1]].i0;
        if constexpr (D == 3) centre[2] = coord[2][rz.begin - lo[2]].i0;
        fill_block<float>(centre, block);
        auto put = [&](std::size_t i, std::size_t j, std::size_t k,
                       const value_gradient<float, D>& r) {
          out[index(i, j, k)] = r.value;
          if constexpr (G) grad[index(i, j, k)] = r.gradient;
        };
        grid_tile<G>(block, coord, lo, rx, ry, rz, cols, rows, put);
      }
}

template <int D>
template <bool G, class Put>
void gabor<D>::grid_tile(const std::vector<block_impulse<float>>& block,
                         const std::vector<lattice_coord<float>> (&coord)[std::size_t{D}],
                         const std::size_t (&lo)[std::size_t{D}], const grid_run& rx,
                         const grid_run& ry, const grid_run& rz, std::vector<grid_column>& cols,
                         std::vector<grid_row>& rows, Put put) const {
  const float neg_a = float(-kernel_.envelope_exponent()), a = float(kernel_.envelope_exponent());
  const float taper_k = taper_k_<float>();
  const std::size_t nk = block.size();
  cols.resize((rx.end - rx.begin) * nk);
  rows.resize((ry.end - ry.begin) * (rz.end - rz.begin) * nk);
  for (std::size_t i = rx.begin; i < rx.end; ++i) {
    const float f = coord[0][i - lo[0]].f;
    grid_column* col = &cols[(i - rx.begin) * nk];
    for (std::size_t m = 0; m < nk; ++m) {
      const float d = f - block[m].ou[0];
      col[m].d = d;
      col[m].d2 = d * d;
      if (!(col[m].d2 < 1.0f)) continue;
      const detail::gabor_axis<float> x = detail::gabor_axis_factors(d, neg_a, block[m].phi[0]);
      col[m].ec = x.e * x.c;
      col[m].es = x.e * x.s;
    }
  }
  std::size_t nr = 0;
  for (std::size_t k = rz.begin; k < rz.end; ++k)
    for (std::size_t j = ry.begin; j < ry.end; ++j, ++nr) {
      float f[std::size_t{D} - 1];
      f[0] = coord[1][j - lo[1]].f;
      if constexpr (D == 3) f[1] = coord[2][k - lo[2]].f;
      grid_row* row = &rows[nr * nk];
      for (std::size_t m = 0; m < nk; ++m) {
        float d[std::size_t{D} - 1], d2[std::size_t{D} - 1];
        for (int e = 0; e < D - 1; ++e) {
          d[e] = f[e] - block[m].ou[e + 1];
          d2[e] = d[e] * d[e];
          row[m].d[e] = d[e];
        }
        row[m].d2 = D == 2 ? d2[0] : d2[0] + d2[D - 2];
        if (!(row[m].d2 < 1.0f)) continue;
        detail::gabor_axis<float> ax[std::size_t{D} - 1];
        for (int e = 0; e < D - 1; ++e)
          ax[e] = detail::gabor_axis_factors(d[e], neg_a, block[m].phi[e + 1]);
        detail::gabor_row<float> r;
        if constexpr (D == 2)
          r = detail::gabor_row_of(block[m].w, ax[0]);
        else
          r = detail::gabor_row_of(block[m].w, ax[0], ax[D - 2]);
        row[m].b = r.we * r.c;
        row[m].q = r.we * r.s;
      }
    }
  nr = 0;
  for (std::size_t k = rz.begin; k < rz.end; ++k)
    for (std::size_t j = ry.begin; j < ry.end; ++j, ++nr) {
      const grid_row* row = &rows[nr * nk];
      for (std::size_t i = rx.begin; i < rx.end; ++i) {
        const grid_column* col = &cols[(i - rx.begin) * nk];
        float sum = 0, gs[std::size_t{D}] = {};
        for (std::size_t m = 0; m < nk; ++m) {
          // for_each_pair's test: s = d2_x + (d2_y [+ d2_z]) < 1.
          const float s = col[m].d2 + row[m].d2;
          if (!(s < 1.0f)) continue;
          if constexpr (G) {
            const auto pg = detail::gabor_pair_gradient_of_products(col[m].ec, col[m].es, row[m].b,
                                                                    row[m].q, s, taper_k, a);
            sum += pg.value;
            float d[std::size_t{D}];
            d[0] = col[m].d;
            for (int e = 1; e < D; ++e) d[e] = row[m].d[e - 1];
            for (int e = 0; e < D; ++e) gs[e] += pg.u * d[e] - pg.v * block[m].phi[e];
          } else {
            sum += detail::gabor_pair_of_products(col[m].ec, col[m].es, row[m].b, row[m].q, s,
                                                  taper_k);
          }
        }
        put(i, j, k, finish<float, G>(sum, gs, float(scale_), float(scale_ * inv_cell_)));
      }
    }
}

}  // namespace hush

#endif  // HUSH_GABOR_BATCH_HPP
