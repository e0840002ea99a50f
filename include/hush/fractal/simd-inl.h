// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Highway kernels for fractal sums of Perlin noise (hush/fractal.hpp over
// hush::perlin<D>): batches of points and uniform grids, values and optionally
// gradients. Compiled once per SIMD target (the "-inl.h" convention: toggle
// include guard below, no normal guard); reached through
// hush/fractal/simd_kernel.hpp, never included directly by users.
//
// Each band is a Perlin field evaluated by perlin/simd-inl.h's vector code at the
// band position, formed as scalar evaluation forms it, and the bands are
// summed in the same order with the same operations: under HUSH_STRICT_FP
// every value and gradient is bit for bit the scalar result
// (tests/perlin/perlin_simd_test.cpp, every compiled target); otherwise within
// fractal.hpp's float budget of the double reference.

// Toggle guard: included once per target by foreach_target.h (Highway's
// hwy/examples/skeleton-inl.h pattern).
#if defined(HUSH_FRACTAL_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef HUSH_FRACTAL_SIMD_INL_H_
#undef HUSH_FRACTAL_SIMD_INL_H_
#else
#define HUSH_FRACTAL_SIMD_INL_H_
#endif

#include <cstddef>
#include <vector>

#include <hwy/highway.h>

#include "hush/core/views.hpp"
#include "hush/simd/lanes-inl.h"
#include "hush/perlin/simd-inl.h"  // the bands' Perlin vectors and rows

// The classes come first, not from here: hush/fractal.hpp includes these
// kernels at its end (hush/fractal/simd_kernel.hpp, after hush/perlin.hpp), as
// src/simd/fractal.cpp does.
HWY_BEFORE_NAMESPACE();
namespace hush {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace perlin_simd {

// ---- Fractal sums of Perlin bands (fractal.hpp): each band is a Perlin
// field evaluated by the code above at the band position f_i x + o_i, which
// fractal::band_position forms in double exactly as scalar evaluation does;
// the weighted sum is accumulated band by band in the same order and with
// the same operations as fractal::value / value_and_gradient.
template <int D>
struct band_config {
  std::uint32_t key;
  std::uint32_t period[3];
  float weight;      // T(w_i)
  float chain;       // T(w_i f_i): the band gradient's factor
  double frequency;  // f_i and o_i of the band position f_i x + o_i
  double offset[3];
  bool plain;  // no axis periodic: the vector split may take the band
};

template <int D>
std::vector<band_config<D>> band_configs(const fractal<perlin<D>>& fr) {
  std::vector<band_config<D>> r(static_cast<std::size_t>(fr.band_count()));
  for (int b = 0; b < fr.band_count(); ++b) {
    const auto& prm = fr.band_noise(b).parameters();
    band_config<D>& c = r[static_cast<std::size_t>(b)];
    c.key = seed_key(prm.seed);
    for (int a = 0; a < 3; ++a)
      c.period[a] = a < D ? static_cast<std::uint32_t>(prm.period[a]) : 0u;
    c.weight = float(fr.band_raw_weight(b));
    c.chain = float(fr.band_raw_weight(b) * fr.band_frequency(b));
    c.frequency = fr.band_frequency(b);
    // f_i 0 + o_i = o_i exactly: the band's offset as the scalar code adds it.
    const vec<double, D> o = fr.band_position(b, vec<double, D>{});
    c.plain = true;
    for (int a = 0; a < 3; ++a) {
      c.offset[a] = a < D ? o[a] : 0.0;
      c.plain = c.plain && c.period[a] == 0;
    }
  }
  return r;
}

// The vector split of one axis of a band position, q = x f + o, formed in
// double as fractal's band position is and split as lattice_split<float>
// splits it, bit for bit, when every lane's q is finite with |q| < 2^31
// (the cell then fits an int32, whose two's complement low word is the cell
// modulo 2^32). Returns false, writing nothing, otherwise: the caller splits
// lane by lane. The per-lane path cost ~40 ns per point for 4 bands.
template <bool kGradient, int kAxis>
HWY_INLINE bool split_band(VF x, double f, double o, axis& a) {
#if HWY_HAVE_FLOAT64 && HWY_TARGET != HWY_SCALAR
  const DF df;
  const hn::Half<DF> dh;
  const hn::Repartition<double, DF> dd;
  const hn::Rebind<float, decltype(dd)> df_of_d;
  const hn::Rebind<std::int32_t, decltype(dd)> di_of_d;
  const auto vf = hn::Set(dd, f), vo = hn::Set(dd, o);
  const auto position = [&](hn::Vec<decltype(dd)> p) HWY_ATTR { return mul_add(p, vf, vo); };
  const auto lo = position(hn::PromoteTo(dd, hn::LowerHalf(dh, x)));
  const auto hi = position(hn::PromoteTo(dd, hn::UpperHalf(dh, x)));
  const auto limit = hn::Set(dd, 2147483648.0);  // 2^31; false for NaN
  if (!hn::AllTrue(dd, hn::Lt(hn::Abs(lo), limit)) || !hn::AllTrue(dd, hn::Lt(hn::Abs(hi), limit)))
    return false;
  const auto flo = hn::Floor(lo), fhi = hn::Floor(hi);
  const VF frac = hn::Combine(df, hn::DemoteTo(df_of_d, hn::Sub(hi, fhi)),
                              hn::DemoteTo(df_of_d, hn::Sub(lo, flo)));
  const DI di;
  const VU i0 =
      hn::BitCast(DU(), hn::Combine(di, hn::DemoteTo(di_of_d, fhi), hn::DemoteTo(di_of_d, flo)));
  a.w0 = word<kAxis>(i0);
  a.w1 = word<kAxis>(hn::Add(i0, hn::Set(DU(), 1u)));
  fill_axis<kGradient>(hn::Min(frac, hn::Set(df, detail::one_minus_ulp<float>())), a);
  return true;
#else
  (void)x;
  (void)f;
  (void)o;
  (void)a;
  return false;
#endif
}

// acc += band value (and gradient) with fractal.hpp's operations.
template <bool kGradient, int D>
HWY_INLINE void accumulate(bool turbulence, const band_config<D>& c, VF v, const VF* g, VF& acc,
                           VF* gacc) {
  const DF df;
  const VF w = hn::Set(df, c.weight);
  if constexpr (kGradient) {
    // sign = -1 where turbulence folds a negative value; w sign v, chain sign g.
    const VF sign =
        turbulence ? hn::IfThenElse(hn::Lt(v, hn::Zero(df)), hn::Set(df, -1.0f), hn::Set(df, 1.0f))
                   : hn::Set(df, 1.0f);
    acc = hn::Add(acc, hn::Mul(hn::Mul(w, sign), v));
    const VF chain = hn::Mul(hn::Set(df, c.chain), sign);
    for (int a = 0; a < D; ++a) gacc[a] = hn::Add(gacc[a], hn::Mul(chain, g[a]));
  } else {
    (void)g;
    (void)gacc;
    acc = hn::Add(acc, hn::Mul(w, turbulence ? hn::Abs(v) : v));
  }
}

// One vector of fractal points: band positions split by the vector where
// split_band can, else per lane in double (NaN, Inf, huge, periodic bands).
template <bool kGradient, int D>
HWY_INLINE void fractal_points_vector(const fractal<perlin<D>>& fr,
                                      const std::vector<band_config<D>>& bands,
                                      const float* HWY_RESTRICT pts, float* HWY_RESTRICT value,
                                      float* HWY_RESTRICT grad) {
  const DF df;
  const std::size_t lanes = hn::Lanes(df);
  const bool turbulence = fr.parameters().kind == fractal_kind::turbulence;
  VF acc = hn::Zero(df), gacc[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
  VF xs[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
  if constexpr (D == 2)
    hn::LoadInterleaved2(df, pts, xs[0], xs[1]);
  else
    hn::LoadInterleaved3(df, pts, xs[0], xs[1], xs[2]);
  vec<double, D> p[kMaxLanes];  // the lanes' points in double, once, when a band needs them
  bool have_p = false;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const band_config<D>& c = bands[b];
    axis ax{}, ay{}, az{};
    bool split = c.plain && split_band<kGradient, 0>(xs[0], c.frequency, c.offset[0], ax) &&
                 split_band<kGradient, 1>(xs[1], c.frequency, c.offset[1], ay);
    if constexpr (D == 3)
      split = split && split_band<kGradient, 2>(xs[2], c.frequency, c.offset[2], az);
    if (HWY_UNLIKELY(!split)) {
      if (!have_p) {
        for (std::size_t l = 0; l < lanes; ++l)
          for (int a = 0; a < D; ++a) p[l][a] = double(pts[l * D + a]);
        have_p = true;
      }
      double q[3][kMaxLanes];
      for (std::size_t l = 0; l < lanes; ++l) {
        const vec<double, D> qb = fr.band_position(static_cast<int>(b), p[l]);
        for (int a = 0; a < D; ++a) q[a][l] = qb[a];
      }
      ax = split_doubles<kGradient, 0>(q[0], c.period[0]);
      ay = split_doubles<kGradient, 1>(q[1], c.period[1]);
      if constexpr (D == 3) az = split_doubles<kGradient, 2>(q[2], c.period[2]);
    }
    VU kyz[4];
    key_words<D>(hn::Set(DU(), c.key), ay, az, kyz);
    corners k;
    hashed_corners<kGradient, D>(ax, kyz, ay, az, k);
    VF v, g[3];
    finish<kGradient, D>(k, ax, ay, az, v, g);
    accumulate<kGradient, D>(turbulence, c, v, g, acc, gacc);
  }
  const VF scale = hn::Set(df, float(fr.scale()));
  if constexpr (kGradient) {
    hn::StoreU(hn::Mul(acc, scale), df, value);
    for (int a = 0; a < D; ++a) gacc[a] = hn::Mul(gacc[a], scale);
    store_interleaved<D>(gacc, grad);
  } else {
    hn::StoreU(hn::Mul(scale, acc), df, value);
  }
}

// A fractal on a grid: per band, the column layout of the band's x positions
// and a per-row split of its y (and z) positions, evaluated like a Perlin
// grid row and accumulated into the row's sums.
template <bool kGradient, int D>
void fractal_grid(const fractal<perlin<D>>& fr, const grid<D>& g, std::size_t first,
                  std::size_t count, float* value, float* grad) {
  const DF df;
  const std::vector<band_config<D>> bands = band_configs(fr);
  const bool turbulence = fr.parameters().kind == fractal_kind::turbulence;
  const std::size_t nx = g.size[0];
  const std::size_t lanes = hn::Lanes(df);
  auto position = [&](int b, int axis_index, double coordinate) {
    vec<double, D> p;  // axes are independent in f x + o: the other coordinates do not matter
    p[axis_index] = coordinate;
    return fr.band_position(b, p)[axis_index];
  };
  std::vector<grid_columns> cols;
  cols.reserve(bands.size());
  for (std::size_t b = 0; b < bands.size(); ++b)
    cols.emplace_back(nx, bands[b].period[0], kGradient, [&](std::size_t i) {
      return position(static_cast<int>(b), 0, g.coordinate(0, i));
    });
  std::vector<row_evaluator<kGradient, D>> rows;
  rows.reserve(bands.size());
  for (const grid_columns& c : cols) rows.emplace_back(c);
  // Per band, the current row's words and fractions (z kept while the slice
  // is). On the stack: grid_row holds vectors, whose alignment a
  // std::vector's storage need not have.
  grid_row band_rows[fractal<perlin<D>>::kMaxOctaves];
  std::size_t split_k = ~std::size_t(0);
  const VF scale = hn::Set(df, float(fr.scale()));
  for_each_row<D>(
      g, first, count, [&](std::size_t j, std::size_t k, std::size_t row_index) HWY_ATTR {
        for (std::size_t b = 0; b < bands.size(); ++b) {
          const band_config<D>& c = bands[b];
          const int bi = static_cast<int>(b);
          grid_row& row = band_rows[b];
          row.key = c.key;
          row.y = broadcast_axis<kGradient, 1>(position(bi, 1, g.coordinate(1, j)),
                                               c.period[1]);
          if constexpr (D == 3)
            if (k != split_k)
              row.z = broadcast_axis<kGradient, 2>(
                  position(bi, 2, g.coordinate(2, k)), c.period[2]);
          rows[b].prepare(row);
        }
        split_k = k;
        // Per vector of columns, the bands in order, summed in registers.
        for (std::size_t i = 0; i < nx; i += lanes) {
          VF a = hn::Zero(df), ga[3] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
          for (std::size_t b = 0; b < bands.size(); ++b)
            rows[b].vector(band_rows[b], i, [&](VF v, const VF* gr) HWY_ATTR {
              accumulate<kGradient, D>(turbulence, bands[b], v, gr, a, ga);
            });
          VF gs[3];
          if constexpr (kGradient)
            for (int d = 0; d < D; ++d) gs[d] = hn::Mul(ga[d], scale);
          store_row<D>(i, nx, kGradient ? hn::Mul(a, scale) : hn::Mul(scale, a), gs,
                       value + row_index * nx, kGradient ? grad + row_index * nx * D : nullptr);
        }
      });
}

}  // namespace perlin_simd

// Fractal sums of Perlin (fBm, turbulence) at interleaved points or on a
// grid; same layout conventions as the Perlin entry points above.
template <int D>
void fractal_points(const fractal<perlin<D>>& fr, const float* pts, std::size_t n, float* value,
                    float* grad) {
  const std::vector<perlin_simd::band_config<D>> bands = perlin_simd::band_configs(fr);
  if (grad)
    perlin_simd::for_each_point_vector<true, D>(
        n, pts, value, grad, [&](const float* p, float* v, float* g) HWY_ATTR {
          perlin_simd::fractal_points_vector<true, D>(fr, bands, p, v, g);
        });
  else
    perlin_simd::for_each_point_vector<false, D>(
        n, pts, value, nullptr, [&](const float* p, float* v, float*) HWY_ATTR {
          perlin_simd::fractal_points_vector<false, D>(fr, bands, p, v, nullptr);
        });
}
inline void fractal2_points(const fractal<perlin<2>>& fr, const float* xy, std::size_t n,
                            float* value, float* grad) {
  fractal_points<2>(fr, xy, n, value, grad);
}
inline void fractal3_points(const fractal<perlin<3>>& fr, const float* xyz, std::size_t n,
                            float* value, float* grad) {
  fractal_points<3>(fr, xyz, n, value, grad);
}
inline void fractal2_grid(const fractal<perlin<2>>& fr, const grid<2>& g, std::size_t first,
                          std::size_t count, float* value, float* grad) {
  if (grad)
    perlin_simd::fractal_grid<true, 2>(fr, g, first, count, value, grad);
  else
    perlin_simd::fractal_grid<false, 2>(fr, g, first, count, value, nullptr);
}
inline void fractal3_grid(const fractal<perlin<3>>& fr, const grid<3>& g, std::size_t first,
                          std::size_t count, float* value, float* grad) {
  if (grad)
    perlin_simd::fractal_grid<true, 3>(fr, g, first, count, value, grad);
  else
    perlin_simd::fractal_grid<false, 3>(fr, g, first, count, value, nullptr);
}

}  // namespace HWY_NAMESPACE
}  // namespace hush
HWY_AFTER_NAMESPACE();

#endif  // HUSH_FRACTAL_SIMD_INL_H_ toggle
