// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Improved Perlin noise (Ken Perlin, "Improving Noise", SIGGRAPH 2002) in 2D
// and 3D: gradient noise on the integer lattice with the quintic fade, seeded
// through hush's lattice hash (any 32-bit seed gives an independent field, not
// a reshuffle of one 256-entry table), optionally periodic per axis.
//
//   hush::perlin<3> p{7};                        // seed 7
//   float v = p(hush::vec3{x, y, z});            // in [-1, 1]
//   auto [v2, g] = p.gradient(hush::vec3{x, y, z});
//   double r = p(hush::dvec3{x, y, z});          // the double-precision reference
//
// Contract (both dimensions, float and double):
//  - range: [-1, 1]; the bound is attained (constants.hpp, docs/design.md).
//    Float results may exceed it by the float error budget below.
//  - mean 0 and variance variance() over space and seeds (0.0931 in 2D,
//    0.0679 in 3D; derived in docs/design.md, measured in the tests).
//  - C2 in position; gradient() returns the exact analytic derivative.
//  - zero at every lattice point.
//  - float evaluation is within 2^-16 (1.5e-5, a forward error bound) of the
//    double reference at the same position; measured max 2.4e-6, RMS 1.9e-7
//    (tests/perlin/perlin_test.cpp).
//  - domain: every finite coordinate (core/lattice.hpp); NaN or +-Inf in any
//    coordinate gives NaN (value and gradient). Evaluation never throws.
//  - periodic mode: with period[a] = p > 0, noise(x + p e_a) == noise(x)
//    exactly (bit for bit where x and x + p are both representable).
#ifndef HUSH_PERLIN_HPP
#define HUSH_PERLIN_HPP

#include <array>
#include <climits>
#include <cstdint>
#include <string>
#include <vector>

#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/point_noise.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

// Quintic fade s(t) and its derivative, from the coefficients in constants.hpp.
template <class T>
HUSH_INLINE T fade(T t) {
  namespace c = constants;
  return t * t * t * (t * (t * T(c::kFade5) + T(c::kFade4)) + T(c::kFade3));
}
template <class T>
HUSH_INLINE T fade_derivative(T t) {
  namespace c = constants;
  return t * t * (t * (t * T(5 * c::kFade5) + T(4 * c::kFade4)) + T(3 * c::kFade3));
}
template <class T>
HUSH_INLINE T lerp(T a, T b, T t) {
  return a + t * (b - a);
}

// Gradient tables in T, converted at compile time from the double constants.
template <class T, std::size_t N>
constexpr std::array<T, N> table_cast(const double (&src)[N]) {
  std::array<T, N> r{};
  for (std::size_t i = 0; i < N; ++i) r[i] = static_cast<T>(src[i]);
  return r;
}
template <class T>
struct perlin_tables {
  static constexpr auto g2x = table_cast<T>(constants::kPerlin2GradX);
  static constexpr auto g2y = table_cast<T>(constants::kPerlin2GradY);
  static constexpr auto g3x = table_cast<T>(constants::kPerlin3GradX);
  static constexpr auto g3y = table_cast<T>(constants::kPerlin3GradY);
  static constexpr auto g3z = table_cast<T>(constants::kPerlin3GradZ);
};

// Gradient index of a lattice hash: 2D takes the top 3 bits (uniform over 8);
// 3D maps the top 16 bits onto 12 buckets by a fixed-point multiply. Both
// read only bits 16 ... 31, so lattice_hash_high serves (core/hash.hpp).
static_assert(constants::kPerlin2GradShift >= 16 && constants::kPerlin3IndexShift >= 16,
              "the gradient index may read only the bits lattice_hash_high shares");
HUSH_INLINE constexpr std::uint32_t perlin2_grad_index(std::uint32_t h) {
  return h >> constants::kPerlin2GradShift;
}
HUSH_INLINE constexpr std::uint32_t perlin3_grad_index(std::uint32_t h) {
  return ((h >> constants::kPerlin3IndexShift) * std::uint32_t(constants::kPerlin3GradCount)) >>
         constants::kPerlin3IndexShift;
}

// 3D grid rows with gradients (docs/design.md, "Grid gradients, affine in x"):
// within one row (fixed y, z) and one x cell, each gradient component is
// lerp(P(f_x), Q(f_x), u) (plus u' (Q_v - P_v) for d/dx) with P, Q affine in
// the x fraction f_x. The coefficients, per (row, cell), by index:
//   kEA, kEB      slope and intercept of V1 - V0 (the value's x-lerp ends)
//   kX0           d/dx's interpolated gradient at a = 0 (its a = 1 - a = 0 is kEA),
//                 which is also the slope of V0; kV0B: V0's intercept
//   kY0A, kY0B    d/dy at a = 0, slope and intercept; kDYA, kDYB: a = 1 minus a = 0
//   kZ0A ... kDZB the same for d/dz.
enum row_gradient_coef : int {
  kEA,
  kEB,
  kX0,
  kV0B,
  kY0A,
  kY0B,
  kDYA,
  kDYB,
  kZ0A,
  kZ0B,
  kDZA,
  kDZB,
  kRowGradientCoefs
};
// They are formed from per-(slice, cell) data, blended in z once for all the
// rows of a z slice and y cell (the corner gradients and the slice's z
// fraction are fixed there), then in y per row. For corner (a, b, c), split
// its dot product's x-free part as gy (f_y - b) + e with e = gz (f_z - c) -
// a gx; per side a and y offset b, blended in z with the slice's fade w and
// slope w':
//   kZgx, kZgy, kZgz, kZe   lerp(q_ab0, q_ab1, w) of q = gx, gy, gz, e
//   kWgx, kWgy, kWe         w' (q_ab1 - q_ab0) of q = gx, gy, e
// at index slice_gradient_coef_index(q, a, b).
enum slice_gradient_coef : int { kZgx, kZgy, kZgz, kZe, kWgx, kWgy, kWe, kSliceGradientKinds };
constexpr int kSliceGradientCoefs = 4 * kSliceGradientKinds;
HUSH_INLINE constexpr int slice_gradient_coef_index(int q, int a, int b) {
  return 4 * q + 2 * a + b;
}
// Rows take the per-cell path (shared corner data) when cells hold at least
// two columns on average; scalar and SIMD grids decide alike, so both use the
// same gradient algorithm on every grid.
HUSH_INLINE constexpr bool grid_cells_shared(std::size_t cells, std::size_t columns) {
  return 2 * cells <= columns;
}

}  // namespace detail

template <int D>
class perlin : public point_noise<perlin<D>, D> {
  static_assert(D == 2 || D == 3, "hush::perlin is 2D or 3D");

 public:
  struct params {
    std::uint32_t seed = 0;
    // Per-axis period in lattice units: 0 = not periodic, p in 1 ... INT_MAX =
    // the noise repeats every p units along that axis (tileable noise).
    std::array<int, std::size_t{D}> period{};
  };

  perlin() : perlin(params{}) {}
  explicit perlin(std::uint32_t seed) : perlin(params{seed, {}}) {}
  // Throws hush::invalid_argument when a period is negative.
  explicit perlin(const params& prm) : prm_(prm), key_(seed_key(prm.seed)) {
    for (std::size_t a = 0; a < D; ++a)
      if (prm.period[a] < 0)
        detail::throw_out_of_range("hush::perlin", "period[" + std::to_string(a) + "]",
                                   prm.period[a], "0 (not periodic) or 1 ... 2147483647");
  }

  const params& parameters() const { return prm_; }

  // Output bound and variance of the noise over space and seeds (see header comment).
  static constexpr double bound() { return 1.0; }
  static constexpr double variance() {
    return D == 2 ? detail::constants::kPerlin2Variance : detail::constants::kPerlin3Variance;
  }

  // p(vec) -> value and p.gradient(vec) -> value and analytic gradient, in
  // float or double (the reference), come from core/point_noise.hpp.

  // Evaluation at a double-precision position with arithmetic in T: the
  // position is split into cell and fraction in double, the rest runs in T.
  // This is what grids far from the origin use.
  template <class T>
  T value(const vec<double, D>& p) const {
    return eval<T, false>(p).value;
  }
  template <class T>
  value_gradient<T, D> value_and_gradient(const vec<double, D>& p) const {
    return eval<T, true>(p);
  }

  // The samples of `g` with slowest-axis index (j in 2D, k in 3D) in
  // [first, first + count), in C order, into out (and gradients into grad
  // unless null); out starts at the slab's first sample. exec::scalar calls
  // this for grids (exec.hpp). The x axis is split once per column, y and z
  // once per row, and a row hashes its lattice points once per cell, not
  // once per sample. Values alone, and 2D values with gradients, are what
  // value<float> / value_and_gradient<float> give at g.position(...), bit for
  // bit (unless the compiler contracts multiply-adds, which HUSH_STRICT_FP
  // forbids). 3D values with gradients on rows whose cells hold two or more
  // columns on average take the affine-in-x form (docs/design.md, "Grid
  // gradients, affine in x"): within 2^-17 (values) and 2^-15 (gradients) of
  // point evaluation, and within the float budget of the double reference
  // (tests/perlin/perlin_test.cpp); hush/simd computes the same, bit for bit under
  // HUSH_STRICT_FP.
  void grid_values(const grid<D>& g, std::size_t first, std::size_t count, float* out,
                   vec<float, D>* grad) const {
    auto at = [&g](int a) {
      return [&g, a](std::size_t index) { return g.coordinate(a, index); };
    };
    const std::size_t j0 = D == 2 ? first : 0, j1 = D == 2 ? first + count : g.size[1];
    const std::size_t k0 = D == 3 ? first : 0, k1 = D == 3 ? first + count : 1;
    grid_rows_at(g.size[0], at(0), j0, j1, at(1), k0, k1, at(D - 1), out, grad);
  }

  // grid_values over positions given per axis: column i at x_at(i), row j at
  // y_at(j), slice k at z_at(k) (doubles; 2D: z_at unused, k in [0, 1)), for
  // rows j in [j0, j1) and slices k in [k0, k1), in C order into out (and
  // grad unless null). fractal.hpp runs its bands' grids (positions f x + o)
  // through it. 3D gradients of rows whose cells hold two or more columns on
  // average take the affine-in-x form (docs/design.md); everything else is
  // point evaluation's result, as grid_values states.
  template <class X, class Y, class Z>
  void grid_rows_at(std::size_t nx, const X& x_at, std::size_t j0, std::size_t j1, const Y& y_at,
                    std::size_t k0, std::size_t k1, const Z& z_at, float* out,
                    vec<float, D>* grad) const {
    if (grad)
      grid_rows<true>(nx, x_at, j0, j1, y_at, k0, k1, z_at, out, grad);
    else
      grid_rows<false>(nx, x_at, j0, j1, y_at, k0, k1, z_at, out, nullptr);
  }

 private:
  static constexpr int kCorners = 1 << D;

  // One axis of a lookup as the blend needs it: the fraction f, f - 1, the
  // fade s(f) and, for gradients, its derivative.
  template <class T>
  struct axis {
    T f, f1, s, ds;
  };
  template <class T, bool WithGradient>
  static axis<T> make_axis(T f) {
    return {f, f - T(1), detail::fade(f), WithGradient ? detail::fade_derivative(f) : T(0)};
  }
  // Per corner n = a + 2b + 4c (offset (a, b, c) from the cell's origin):
  // the gradient g and the dot product d = g . (x - corner).
  template <class T>
  struct corners {
    T d[std::size_t{kCorners}], gx[std::size_t{kCorners}], gy[std::size_t{kCorners}],
        gz[std::size_t{kCorners}];
  };

  // Corner n's gradient from the top half of its lattice hash, and the part
  // of its dot product that does not depend on x:
  //   2D: k = gy f_y;   3D: k = gy f_y + gz f_z,
  // so that d = gx f_x + k. In 3D every product is exact (components 0 or
  // +-1): d is the single rounding of +-f_p +- f_q however it is summed.
  template <class T>
  static void corner_gradient(std::uint32_t h, T fy, T fz, corners<T>& c, int n, T& k) {
    using tab = detail::perlin_tables<T>;
    if constexpr (D == 2) {
      (void)fz;
      const std::uint32_t i = detail::perlin2_grad_index(h);
      c.gx[n] = tab::g2x[i];
      c.gy[n] = tab::g2y[i];
      k = c.gy[n] * fy;
    } else {
      const std::uint32_t i = detail::perlin3_grad_index(h);
      c.gx[n] = tab::g3x[i];
      c.gy[n] = tab::g3y[i];
      c.gz[n] = tab::g3z[i];
      k = c.gy[n] * fy + c.gz[n] * fz;
    }
  }

  template <class T, bool WithGradient>
  value_gradient<T, D> eval(const vec<double, D>& p) const {
    lattice_coord<T> lc[std::size_t{D}];
    for (std::size_t a = 0; a < D; ++a)
      lc[a] = lattice_split<T>(p[a], static_cast<std::uint32_t>(prm_.period[a]));
    axis<T> ax[3]{};
    for (int a = 0; a < D; ++a) ax[a] = make_axis<T, WithGradient>(lc[a].f);
    corners<T> c;
    for (int n = 0; n < kCorners; ++n) {
      const int a = n & 1, b = (n >> 1) & 1, cc = n >> 2;
      const std::uint32_t i = a ? lc[0].i1 : lc[0].i0, j = b ? lc[1].i1 : lc[1].i0;
      std::uint32_t h;
      if constexpr (D == 2)
        h = lattice_hash_high(key_, i, j);
      else
        h = lattice_hash_high(key_, i, j, cc ? lc[2].i1 : lc[2].i0);
      T k;
      corner_gradient<T>(h, b ? ax[1].f1 : ax[1].f, cc ? ax[2].f1 : ax[2].f, c, n, k);
      c.d[n] = c.gx[n] * (a ? ax[0].f1 : ax[0].f) + k;
    }
    return blend<T, WithGradient>(c, ax);
  }

  // The fade-weighted blend of the corners' dot products, and its analytic
  // derivative (product rule on the fade weights).
  template <class T, bool WithGradient>
  static value_gradient<T, D> blend(const corners<T>& c, const axis<T>* ax) {
    const T* d = c.d;
    const T u = ax[0].s, v = ax[1].s;
    if constexpr (D == 2) {
      const T x0 = detail::lerp(d[0], d[1], u), x1 = detail::lerp(d[2], d[3], u);
      constexpr T kScale = T(detail::constants::kPerlin2Scale);
      value_gradient<T, 2> r{kScale * detail::lerp(x0, x1, v), {}};
      if constexpr (WithGradient) {
        // d/dx: interpolated gradients plus the fade's derivative times the
        // difference of the contributions it blends.
        const T gx =
            detail::lerp(detail::lerp(c.gx[0], c.gx[1], u), detail::lerp(c.gx[2], c.gx[3], u), v) +
            ax[0].ds * detail::lerp(d[1] - d[0], d[3] - d[2], v);
        const T gy =
            detail::lerp(detail::lerp(c.gy[0], c.gy[1], u), detail::lerp(c.gy[2], c.gy[3], u), v) +
            ax[1].ds * (x1 - x0);
        r.gradient = {kScale * gx, kScale * gy};
      }
      return r;
    } else {
      const T w = ax[2].s;
      const T x00 = detail::lerp(d[0], d[1], u), x10 = detail::lerp(d[2], d[3], u);
      const T x01 = detail::lerp(d[4], d[5], u), x11 = detail::lerp(d[6], d[7], u);
      const T y0 = detail::lerp(x00, x10, v), y1 = detail::lerp(x01, x11, v);
      constexpr T kScale = T(detail::constants::kPerlin3Scale);
      // "+ 0" turns a zero result into +0: kernels that form the same dot
      // products another way (sign flips instead of products) can differ only
      // in the sign of zeros, and this makes every backend agree bit for bit.
      value_gradient<T, 3> r{kScale * detail::lerp(y0, y1, w) + T(0), {}};
      if constexpr (WithGradient) {
        // Trilinear blend of a per-corner quantity q[n] with the fade weights.
        auto trilinear = [&](const T* q) {
          return detail::lerp(
              detail::lerp(detail::lerp(q[0], q[1], u), detail::lerp(q[2], q[3], u), v),
              detail::lerp(detail::lerp(q[4], q[5], u), detail::lerp(q[6], q[7], u), v), w);
        };
        // d/dx of the lerp over x: ds_x * (d[a=1] - d[a=0]), blended in y and z.
        const T ex = detail::lerp(detail::lerp(d[1] - d[0], d[3] - d[2], v),
                                  detail::lerp(d[5] - d[4], d[7] - d[6], v), w);
        const T ey = detail::lerp(x10 - x00, x11 - x01, w);
        const T ez = y1 - y0;
        r.gradient = {kScale * (trilinear(c.gx) + ax[0].ds * ex) + T(0),
                      kScale * (trilinear(c.gy) + ax[1].ds * ey) + T(0),
                      kScale * (trilinear(c.gz) + ax[2].ds * ez) + T(0)};
      }
      return r;
    }
  }

  // The slice_gradient_coef data of one cell (corner gradients c) in the
  // slice of z axis az. Mirrored op for op by perlin/simd-inl.h.
  template <class T>
  static void slice_gradient_coefs(const corners<T>& c, const axis<T>& az, T* out) {
    namespace d = detail;
    const T w = az.s, dw = az.ds;
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const int n0 = a + 2 * b, n1 = n0 + 4;
        // gz (f_z - c) is exact (components are 0 or +-1): one rounding.
        auto e = [&](int n, T fz) { return c.gz[n] * fz - (a ? c.gx[n] : T(0)); };
        const T e0 = e(n0, az.f), e1 = e(n1, az.f1);
        auto at = [&](int q) -> T& { return out[d::slice_gradient_coef_index(q, a, b)]; };
        at(d::kZgx) = detail::lerp(c.gx[n0], c.gx[n1], w);
        at(d::kZgy) = detail::lerp(c.gy[n0], c.gy[n1], w);
        at(d::kZgz) = detail::lerp(c.gz[n0], c.gz[n1], w);
        at(d::kZe) = detail::lerp(e0, e1, w);
        at(d::kWgx) = dw * (c.gx[n1] - c.gx[n0]);
        at(d::kWgy) = dw * (c.gy[n1] - c.gy[n0]);
        at(d::kWe) = dw * (e1 - e0);
      }
  }
  // The row_gradient_coef coefficients of one cell from its slice data sc and
  // the row's y axis ay (fade v, slope v'). Per side a, with Z_b(q) the slice
  // data: L(q) = lerp(Z_0, Z_1, v) is q's bilinear blend, Z_1 - Z_0 its v
  // slope, and the dot products' x-free parts c_b = Z_b(gy) (f_y - b) + Z_b(e).
  // Mirrored op for op by perlin/simd-inl.h.
  template <class T>
  static void row_gradient_coefs(const T* sc, const axis<T>& ay, T* out) {
    namespace d = detail;
    const T v = ay.s, dv = ay.ds, fy0 = ay.f, fy1 = ay.f1;
    T lgx[2], lc[2], ya[2], yb[2], za[2], zb[2];
    for (int a = 0; a < 2; ++a) {
      auto q = [&](int kind, int b) { return sc[d::slice_gradient_coef_index(kind, a, b)]; };
      lgx[a] = detail::lerp(q(d::kZgx, 0), q(d::kZgx, 1), v);
      const T mygx = q(d::kZgx, 1) - q(d::kZgx, 0);
      const T zc0 = q(d::kZgy, 0) * fy0 + q(d::kZe, 0), zc1 = q(d::kZgy, 1) * fy1 + q(d::kZe, 1);
      lc[a] = detail::lerp(zc0, zc1, v);
      const T myc = zc1 - zc0;
      const T lgy = detail::lerp(q(d::kZgy, 0), q(d::kZgy, 1), v);
      const T lgz = detail::lerp(q(d::kZgz, 0), q(d::kZgz, 1), v);
      za[a] = detail::lerp(q(d::kWgx, 0), q(d::kWgx, 1), v);
      const T wc0 = q(d::kWgy, 0) * fy0 + q(d::kWe, 0), wc1 = q(d::kWgy, 1) * fy1 + q(d::kWe, 1);
      zb[a] = detail::lerp(wc0, wc1, v) + lgz;
      ya[a] = dv * mygx;
      yb[a] = dv * myc + lgy;
    }
    out[d::kEA] = lgx[1] - lgx[0];
    out[d::kEB] = lc[1] - lc[0];
    out[d::kX0] = lgx[0];
    out[d::kV0B] = lc[0];
    out[d::kY0A] = ya[0];
    out[d::kY0B] = yb[0];
    out[d::kDYA] = ya[1] - ya[0];
    out[d::kDYB] = yb[1] - yb[0];
    out[d::kZ0A] = za[0];
    out[d::kZ0B] = zb[0];
    out[d::kDZA] = za[1] - za[0];
    out[d::kDZB] = zb[1] - zb[0];
  }
  // A sample's value and gradient from its cell's coefficients: u = s(f_x),
  // u' = s'(f_x).
  template <class T>
  static value_gradient<T, 3> row_gradient(const T* co, const axis<T>& x) {
    namespace d = detail;
    const T f = x.f, u = x.s, du = x.ds;
    const T delta = co[d::kEA] * f + co[d::kEB];
    const T gx = du * delta + (u * co[d::kEA] + co[d::kX0]);
    const T gy = u * (co[d::kDYA] * f + co[d::kDYB]) + (co[d::kY0A] * f + co[d::kY0B]);
    const T gz = u * (co[d::kDZA] * f + co[d::kDZB]) + (co[d::kZ0A] * f + co[d::kZ0B]);
    const T value = u * delta + (co[d::kX0] * f + co[d::kV0B]);
    constexpr T kScale = T(detail::constants::kPerlin3Scale);
    return {kScale * value + T(0), {kScale * gx + T(0), kScale * gy + T(0), kScale * gz + T(0)}};
  }

  // grid_values: the columns' splits are kept; a row walks them, taking new
  // corner gradients (and their x-free parts k) where the cell changes.
  template <bool WithGradient, class X, class Y, class Z>
  void grid_rows(std::size_t nx, const X& x_at, std::size_t j0, std::size_t j1, const Y& y_at,
                 std::size_t k0, std::size_t k1, const Z& z_at, float* out,
                 vec<float, D>* grad) const {
    using T = float;
    std::vector<lattice_coord<T>> cells(nx);
    std::vector<axis<T>> cols(nx);
    std::size_t cell_count = 0;
    for (std::size_t i = 0; i < nx; ++i) {
      cells[i] = lattice_split<T>(x_at(i), static_cast<std::uint32_t>(prm_.period[0]));
      cols[i] = make_axis<T, WithGradient>(cells[i].f);
      if (i == 0 || cells[i].i0 != cells[i - 1].i0) ++cell_count;
    }
    // 3D gradients of rows with shared cells: the affine-in-x form.
    const bool affine = D == 3 && WithGradient && detail::grid_cells_shared(cell_count, nx);
    T coef[detail::kRowGradientCoefs]{};
    std::size_t idx = 0;
    axis<T> ax[3]{};
    for (std::size_t kk = k0; kk < k1; ++kk) {
      lattice_coord<T> cz{};
      if constexpr (D == 3) {
        cz = lattice_split<T>(z_at(kk), static_cast<std::uint32_t>(prm_.period[D - 1]));
        ax[2] = make_axis<T, WithGradient>(cz.f);
      }
      for (std::size_t j = j0; j < j1; ++j) {
        const lattice_coord<T> cy =
            lattice_split<T>(y_at(j), static_cast<std::uint32_t>(prm_.period[1]));
        ax[1] = make_axis<T, WithGradient>(cy.f);
        // key ^ word_y ^ word_z per corner offset (b, c): lattice_hash_high's fold.
        std::uint32_t kyz[4];
        for (int m = 0; m < 4; ++m)
          kyz[m] = key_ ^ lattice_word_y((m & 1) ? cy.i1 : cy.i0) ^
                   (D == 3 ? lattice_word_z((m & 2) ? cz.i1 : cz.i0) : 0u);
        corners<T> c{};
        T k[std::size_t{kCorners}]{};
        for (std::size_t i = 0; i < nx; ++i, ++idx) {
          const lattice_coord<T>& cx = cells[i];
          if (i == 0 || cx.i0 != cells[i - 1].i0) {
            for (int n = 0; n < kCorners; ++n) {
              const std::uint32_t h =
                  hash32_high(kyz[n >> 1] ^ lattice_word_x((n & 1) ? cx.i1 : cx.i0));
              corner_gradient<T>(h, ((n >> 1) & 1) ? ax[1].f1 : ax[1].f,
                                 (n >> 2) ? ax[2].f1 : ax[2].f, c, n, k[n]);
            }
            if constexpr (D == 3)
              if (affine) {
                T slice[detail::kSliceGradientCoefs];
                slice_gradient_coefs<T>(c, ax[2], slice);
                row_gradient_coefs<T>(slice, ax[1], coef);
              }
          }
          ax[0] = cols[i];
          if constexpr (D == 3 && WithGradient) {
            if (affine) {
              const value_gradient<T, 3> r = row_gradient<T>(coef, ax[0]);
              out[idx] = r.value;
              grad[idx] = r.gradient;
              continue;
            }
          }
          for (int n = 0; n < kCorners; ++n)
            c.d[n] = c.gx[n] * ((n & 1) ? ax[0].f1 : ax[0].f) + k[n];
          const value_gradient<T, D> r = blend<T, WithGradient>(c, ax);
          out[idx] = r.value;
          if constexpr (WithGradient) grad[idx] = r.gradient;
        }
      }
    }
  }

  params prm_;
  std::uint32_t key_;
};

}  // namespace hush

// The SIMD backend's entry points and exec::simd binding, after the class they use.
#include "hush/perlin/simd_kernel.hpp"  // IWYU pragma: export

#endif  // HUSH_PERLIN_HPP
