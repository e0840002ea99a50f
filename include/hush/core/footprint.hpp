// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::footprint<D>: a sample's filter footprint in noise space, built from
// what a shader has at that sample (DESIGN.md "Per-sample inputs").
//
// A renderer knows, per sample, how noise-space position changes from one
// pixel to the next: the screen-to-noise Jacobian J = [dP/dx  dP/dy] (D x 2;
// in GLSL, dFdx(P) and dFdy(P)), or at least a width w, the noise-space size
// of one pixel. The footprint stores the one quantity every filtering noise
// needs from that, the symmetric positive semi-definite D x D matrix
//
//   S = J J^T = dP/dx dP/dx^T + dP/dy dP/dy^T     (from derivatives), or
//   S = w^2 I                                      (isotropic width w),
//
// in squared noise units per pixel: a screen offset d (in pixels) moves the
// noise position by J d, and |J^T u|^2 = u^T S u is the squared pixel extent
// along unit direction u. A Gaussian pixel filter of standard deviation sigma
// pixels maps to the noise-space Gaussian of covariance sigma^2 S, and its
// frequency response at noise frequency k is exp(-2 pi^2 sigma^2 k^T S k).
// hush's noises filter with sigma = constants::kPixelFilterSigma (1/2 pixel)
// unless they say otherwise; each states which bands or kernels it keeps.
//
// The default footprint is a point (S = 0): nothing is filtered.
//
// Robustness (HARD_CASES row 12; footprints are per-sample data, so nothing
// here throws): every input gives a finite footprint.
//  - NaN or +-Inf in a derivative or width: the footprint is "everything",
//    S = W^2 I with W = constants::kFootprintMaxWidth (2^32, the lattice's
//    period: nothing narrower survives filtering), so filtering noises return
//    their mean (0) there, the limit of an ever larger footprint.
//  - a footprint wider than W is scaled down (same shape) until its largest
//    entry is W^2 (for derivatives: until no component exceeds W), so its
//    largest width lies in [W, sqrt(D) W]: again everything is filtered.
//  - zero, rank 1 (e.g. dP/dy = 0, an edge-on surface) and nearly singular
//    footprints are stored as they are; consumers must accept singular S.
//  - a negative width means its magnitude.
// S is formed in double and rounded to float once; entries lie in
// [-2^64, 2^64], so consumers compute determinants and inverses in double,
// or scale first (float overflows beyond 2^128).
#ifndef HUSH_CORE_FOOTPRINT_HPP
#define HUSH_CORE_FOOTPRINT_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "hush/core/vec.hpp"
#include "hush/detail/constants.hpp"

namespace hush {

template <int D>
class footprint {
  static_assert(D == 2 || D == 3, "hush::footprint is 2D or 3D");

 public:
  static constexpr int dimension = D;
  // Stored entries: the upper triangle of S, row by row
  // (2D: xx, xy, yy; 3D: xx, xy, xz, yy, yz, zz).
  static constexpr int kEntries = D * (D + 1) / 2;

  // A point sample: S = 0.
  constexpr footprint() = default;

  // One pixel spans `width` noise units in every direction: S = width^2 I.
  static footprint isotropic(double width) {
    footprint f;
    double w = std::fabs(width);
    if (!(w <= kMaxWidth())) w = kMaxWidth();  // NaN, Inf and beyond the cap
    for (int a = 0; a < D; ++a) f.s_[index(a, a)] = static_cast<float>(w * w);
    return f;
  }

  // From the screen-space derivatives of the noise-space position (noise
  // units per pixel): S = dpdx dpdx^T + dpdy dpdy^T.
  static footprint from_derivatives(const vec<double, D>& dpdx, const vec<double, D>& dpdy) {
    if (!finite(dpdx) || !finite(dpdy)) return isotropic(kMaxWidth());
    double m = 0;  // largest magnitude: both columns are scaled by one factor to the cap
    for (int a = 0; a < D; ++a) m = std::max({m, std::fabs(dpdx[a]), std::fabs(dpdy[a])});
    const double k = m > kMaxWidth() ? kMaxWidth() / m : 1.0;
    double upper[std::size_t{kEntries}];
    for (int r = 0; r < D; ++r)
      for (int c = r; c < D; ++c)
        upper[index(r, c)] = (k * dpdx[r]) * (k * dpdx[c]) + (k * dpdy[r]) * (k * dpdy[c]);
    return from_upper(upper);
  }
  static footprint from_derivatives(const vec<float, D>& dpdx, const vec<float, D>& dpdy) {
    return from_derivatives(vec_cast<double>(dpdx), vec_cast<double>(dpdy));
  }

  // From a symmetric matrix S given by its upper triangle (the stored layout).
  // Non-finite entries give "everything"; a matrix with an entry beyond W^2
  // is scaled down until its largest entry is W^2. Not checked for positive
  // semi-definiteness: pass one.
  static footprint from_covariance(const float (&upper)[std::size_t{kEntries}]) {
    double u[std::size_t{kEntries}];
    for (int e = 0; e < kEntries; ++e) u[e] = static_cast<double>(upper[e]);
    return from_upper(u);
  }

  // S(r, c), r and c in 0 ... D-1.
  float covariance(int r, int c) const { return s_[r <= c ? index(r, c) : index(c, r)]; }
  // The stored upper triangle (kEntries floats; batch layouts copy it as is).
  const float* data() const { return s_; }

  // True when S = 0 (nothing to filter).
  bool is_point() const {
    for (float v : s_)
      if (v != 0.0f) return false;
    return true;
  }

  // The pixel's extent along unit direction u: sqrt(u^T S u), in noise units.
  double width_along(const vec<double, D>& u) const {
    double q = 0;
    for (int r = 0; r < D; ++r)
      for (int c = 0; c < D; ++c) q += u[r] * static_cast<double>(covariance(r, c)) * u[c];
    return std::sqrt(std::max(q, 0.0));
  }

  // The largest and smallest extent: the square roots of the largest and
  // smallest eigenvalues of S (the footprint ellipse's semi-axes), computed in
  // double in closed form (2D: the quadratic; 3D: the trigonometric solution
  // of the characteristic cubic), to within 1e-12 relative of the largest.
  double max_width() const { return std::sqrt(std::max(eigenvalues()[D - 1], 0.0)); }
  double min_width() const { return std::sqrt(std::max(eigenvalues()[0], 0.0)); }

  // The footprint of the same pixel for a noise evaluated at s * P (a band of
  // frequency s): S s^2, capped like every footprint.
  footprint scaled(double s) const {
    double u[std::size_t{kEntries}];
    for (int e = 0; e < kEntries; ++e) u[e] = static_cast<double>(s_[e]) * s * s;
    return from_upper(u);
  }

  // Eigenvalues of S in ascending order (double; clamped below at 0 is up to the caller).
  vec<double, D> eigenvalues() const {
    if constexpr (D == 2) {
      const double a = s_[0], b = s_[1], c = s_[2];
      const double mean = 0.5 * (a + c), half = 0.5 * (a - c);
      const double r = std::hypot(half, b);
      return {mean - r, mean + r};
    } else {
      return symmetric3_eigenvalues();
    }
  }

  friend bool operator==(const footprint& x, const footprint& y) {
    for (int e = 0; e < kEntries; ++e)
      if (!(x.s_[e] == y.s_[e])) return false;
    return true;
  }
  friend bool operator!=(const footprint& x, const footprint& y) { return !(x == y); }

 private:
  static constexpr double kMaxWidth() { return detail::constants::kFootprintMaxWidth; }
  static constexpr double kMaxVariance() { return kMaxWidth() * kMaxWidth(); }
  // Position of S(r, c), r <= c, in the upper triangle stored row by row.
  static constexpr int index(int r, int c) { return r * D - r * (r - 1) / 2 + (c - r); }
  static bool finite(const vec<double, D>& v) {
    for (int a = 0; a < D; ++a)
      if (!std::isfinite(v[a])) return false;
    return true;
  }
  // The footprint of upper triangle u (double): "everything" when an entry is
  // not finite, scaled down (shape kept) when an entry exceeds W^2, then
  // rounded to float once.
  static footprint from_upper(const double (&u)[std::size_t{kEntries}]) {
    double m = 0;
    for (int e = 0; e < kEntries; ++e) {
      if (!std::isfinite(u[e])) return isotropic(kMaxWidth());
      m = std::max(m, std::fabs(u[e]));
    }
    const double k = m > kMaxVariance() ? kMaxVariance() / m : 1.0;
    footprint f;
    for (int e = 0; e < kEntries; ++e) f.s_[e] = static_cast<float>(k * u[e]);
    return f;
  }

  // Smith's closed form for a symmetric 3x3 matrix (Smith 1961, "Eigenvalues of a
  // symmetric 3 x 3 matrix", CACM 4(4)): the trigonometric roots of the
  // characteristic cubic of B = (S - q I) / p.
  vec<double, 3> symmetric3_eigenvalues() const {
    const double a00 = s_[0], a01 = s_[1], a02 = s_[2], a11 = s_[3], a12 = s_[4], a22 = s_[5];
    const double off = a01 * a01 + a02 * a02 + a12 * a12;
    const double q = (a00 + a11 + a22) / 3.0;
    const double d0 = a00 - q, d1 = a11 - q, d2 = a22 - q;
    const double p2 = d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * off;
    if (p2 <= 0.0) return {q, q, q};  // a multiple of I
    const double p = std::sqrt(p2 / 6.0);
    // det(B) / 2 with B = (S - q I) / p.
    const double b00 = d0 / p, b11 = d1 / p, b22 = d2 / p, b01 = a01 / p, b02 = a02 / p,
                 b12 = a12 / p;
    const double det = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) +
                       b02 * (b01 * b12 - b11 * b02);
    const double r = std::clamp(det / 2.0, -1.0, 1.0);
    const double phi = std::acos(r) / 3.0;
    const double hi = q + 2.0 * p * std::cos(phi);
    const double lo = q + 2.0 * p * std::cos(phi + detail::constants::kTwoPiOver3);
    const double mid = 3.0 * q - hi - lo;
    return {lo, mid, hi};
  }

  float s_[std::size_t{kEntries}] = {};
};

}  // namespace hush

#endif  // HUSH_CORE_FOOTPRINT_HPP
