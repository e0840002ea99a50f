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
//    (tests/perlin_test.cpp).
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

#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/point_noise.hpp"
#include "hush/core/vec.hpp"
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
template <class T, int N>
constexpr std::array<T, N> table_cast(const double (&src)[N]) {
  std::array<T, N> r{};
  for (int i = 0; i < N; ++i) r[i] = static_cast<T>(src[i]);
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

}  // namespace detail

template <int D>
class perlin : public point_noise<perlin<D>, D> {
  static_assert(D == 2 || D == 3, "hush::perlin is 2D or 3D");

 public:
  struct params {
    std::uint32_t seed = 0;
    // Per-axis period in lattice units: 0 = not periodic, p in 1 ... INT_MAX =
    // the noise repeats every p units along that axis (tileable noise).
    std::array<int, D> period{};
  };

  perlin() : perlin(params{}) {}
  explicit perlin(std::uint32_t seed) : perlin(params{seed, {}}) {}
  // Throws hush::invalid_argument when a period is negative.
  explicit perlin(const params& prm) : prm_(prm), key_(seed_key(prm.seed)) {
    for (int a = 0; a < D; ++a)
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

 private:
  template <class T, bool WithGradient>
  value_gradient<T, D> eval(const vec<double, D>& p) const {
    lattice_coord<T> c[D];
    for (int a = 0; a < D; ++a)
      c[a] = lattice_split<T>(p[a], static_cast<std::uint32_t>(prm_.period[a]));
    if constexpr (D == 2)
      return eval2<T, WithGradient>(c[0], c[1]);
    else
      return eval3<T, WithGradient>(c[0], c[1], c[2]);
  }

  template <class T, bool WithGradient>
  value_gradient<T, 2> eval2(const lattice_coord<T>& cx, const lattice_coord<T>& cy) const {
    using tab = detail::perlin_tables<T>;
    const T fx = cx.f, fy = cy.f, fx1 = fx - T(1), fy1 = fy - T(1);
    const std::uint32_t g00 = detail::perlin2_grad_index(lattice_hash_high(key_, cx.i0, cy.i0));
    const std::uint32_t g10 = detail::perlin2_grad_index(lattice_hash_high(key_, cx.i1, cy.i0));
    const std::uint32_t g01 = detail::perlin2_grad_index(lattice_hash_high(key_, cx.i0, cy.i1));
    const std::uint32_t g11 = detail::perlin2_grad_index(lattice_hash_high(key_, cx.i1, cy.i1));
    // Corner contributions g . (x - corner).
    const T d00 = tab::g2x[g00] * fx + tab::g2y[g00] * fy;
    const T d10 = tab::g2x[g10] * fx1 + tab::g2y[g10] * fy;
    const T d01 = tab::g2x[g01] * fx + tab::g2y[g01] * fy1;
    const T d11 = tab::g2x[g11] * fx1 + tab::g2y[g11] * fy1;
    const T u = detail::fade(fx), v = detail::fade(fy);
    const T x0 = detail::lerp(d00, d10, u), x1 = detail::lerp(d01, d11, u);
    constexpr T kScale = T(detail::constants::kPerlin2Scale);
    value_gradient<T, 2> r{kScale * detail::lerp(x0, x1, v), {}};
    if constexpr (WithGradient) {
      // d/dx: interpolated gradients plus the fade's derivative times the
      // difference of the contributions it blends (product rule).
      const T du = detail::fade_derivative(fx), dv = detail::fade_derivative(fy);
      const T gx = detail::lerp(detail::lerp(tab::g2x[g00], tab::g2x[g10], u),
                                detail::lerp(tab::g2x[g01], tab::g2x[g11], u), v) +
                   du * detail::lerp(d10 - d00, d11 - d01, v);
      const T gy = detail::lerp(detail::lerp(tab::g2y[g00], tab::g2y[g10], u),
                                detail::lerp(tab::g2y[g01], tab::g2y[g11], u), v) +
                   dv * (x1 - x0);
      r.gradient = {kScale * gx, kScale * gy};
    }
    return r;
  }

  template <class T, bool WithGradient>
  value_gradient<T, 3> eval3(const lattice_coord<T>& cx, const lattice_coord<T>& cy,
                             const lattice_coord<T>& cz) const {
    using tab = detail::perlin_tables<T>;
    const T f[2][3] = {{cx.f, cy.f, cz.f}, {cx.f - T(1), cy.f - T(1), cz.f - T(1)}};
    const std::uint32_t ix[2] = {cx.i0, cx.i1}, iy[2] = {cy.i0, cy.i1}, iz[2] = {cz.i0, cz.i1};
    // Corner n = a + 2b + 4c is at offset (a, b, c) from the cell's origin.
    T d[8];
    std::uint32_t g[8];
    for (int n = 0; n < 8; ++n) {
      const int a = n & 1, b = (n >> 1) & 1, cc = n >> 2;
      g[n] = detail::perlin3_grad_index(lattice_hash_high(key_, ix[a], iy[b], iz[cc]));
      // g . f with the y and z terms summed first: every product is exact (the
      // components are 0 or +-1), so this is the single rounding of +-f_p +-
      // f_q, the form grid kernels split into a per-row part (y, z) and an x
      // term (hush/simd/perlin-inl.h).
      d[n] = tab::g3x[g[n]] * f[a][0] + (tab::g3y[g[n]] * f[b][1] + tab::g3z[g[n]] * f[cc][2]);
    }
    const T u = detail::fade(f[0][0]), v = detail::fade(f[0][1]), w = detail::fade(f[0][2]);
    const T x00 = detail::lerp(d[0], d[1], u), x10 = detail::lerp(d[2], d[3], u);
    const T x01 = detail::lerp(d[4], d[5], u), x11 = detail::lerp(d[6], d[7], u);
    const T y0 = detail::lerp(x00, x10, v), y1 = detail::lerp(x01, x11, v);
    constexpr T kScale = T(detail::constants::kPerlin3Scale);
    // "+ 0" turns a zero result into +0: kernels that form the same dot
    // products another way (sign flips instead of products) can differ only in
    // the sign of zeros, and this makes every backend agree bit for bit.
    value_gradient<T, 3> r{kScale * detail::lerp(y0, y1, w) + T(0), {}};
    if constexpr (WithGradient) {
      // Trilinear blend of a per-corner quantity q[n] with the fade weights.
      auto blend = [&](const T* q) {
        return detail::lerp(
            detail::lerp(detail::lerp(q[0], q[1], u), detail::lerp(q[2], q[3], u), v),
            detail::lerp(detail::lerp(q[4], q[5], u), detail::lerp(q[6], q[7], u), v), w);
      };
      T gxs[8], gys[8], gzs[8], ddx[4], ddy[4];
      for (int n = 0; n < 8; ++n) {
        gxs[n] = tab::g3x[g[n]];
        gys[n] = tab::g3y[g[n]];
        gzs[n] = tab::g3z[g[n]];
      }
      for (int m = 0; m < 4; ++m) ddx[m] = d[2 * m + 1] - d[2 * m];  // along x, per (b, c)
      const T du = detail::fade_derivative(f[0][0]);
      const T dv = detail::fade_derivative(f[0][1]);
      const T dw = detail::fade_derivative(f[0][2]);
      // d/dx of lerp over x: du * (d[a=1] - d[a=0]), then blended in y and z.
      const T ex =
          detail::lerp(detail::lerp(ddx[0], ddx[1], v), detail::lerp(ddx[2], ddx[3], v), w);
      ddy[0] = x10 - x00;
      ddy[1] = x11 - x01;
      const T ey = detail::lerp(ddy[0], ddy[1], w);
      const T ez = y1 - y0;
      r.gradient = {kScale * (blend(gxs) + du * ex) + T(0), kScale * (blend(gys) + dv * ey) + T(0),
                    kScale * (blend(gzs) + dw * ez) + T(0)};
    }
    return r;
  }

  params prm_;
  std::uint32_t key_;
};

}  // namespace hush

#endif  // HUSH_PERLIN_HPP
