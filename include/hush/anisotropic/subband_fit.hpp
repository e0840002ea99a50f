// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::subband_fit: weights w of a steerable bank's filters (anisotropic/steerable.hpp)
// such that sum_j w_j D_j(w) approximates a target amplitude response t(w)
// (Goldberg, Zwicker & Durand 2008: distortion compensation, sec. 3.1,
// weights gamma; anisotropic filtering, sec. 4.2, weights lambda):
//
//   weight_rule::centre         w_j = t(c_j), c_j the subband's centre (t's
//                               even part: (t(c) + t(-c)) / 2, as the filters are even)
//                               f_s (cos theta_i, sin theta_i) (sec. 3.1 / 4.2
//                               "heuristic"); exact for targets that are
//                               isotropic within each scale (B vanishes at
//                               the other scales' centres and the G_i sum to 1)
//   weight_rule::three_point    sec. 5's variant: t read at the centre and at
//                               -1/2 and +1/2 octave along the same direction,
//                               averaged 1/4, 1/2, 1/4 (the radial profile's
//                               weights there, constants.hpp)
//   weight_rule::least_squares  min over w of the integral of (t - sum w D)^2
//                               over the frequency plane (sec. 3.1), by
//                               quadrature: midpoint nodes, 16 per octave of
//                               radius, 12 K over a half turn (the integrand
//                               is even), and a Cholesky solve of the normal
//                               equations. The Gram matrix is the bank's and
//                               is factored once, here.
// The basis is the K S subbands (index i + K s) and, when residuals are asked
// for (image filtering), the low- and high-pass residuals after them. The
// quadrature domain is the annulus the subbands cover, [f_0 / 2, 2 f_{S-1}],
// extended with residuals to [0, r_max] (r_max: e.g. the corner of an
// image's spectrum, sqrt(2) / 2 cycles per pixel).
// Targets are callables double(const dvec2& w), w in cycles per unit; they
// should be finite and even. Construction allocates the node table (nodes x
// basis doubles; 4 MB for K = 8, S = 5 with residuals); fits are const and
// thread-safe. A least-squares fit costs one target evaluation per node plus
// a nodes x basis product (about 1 ms for K = 4, S = 3 here: hush bench).
#ifndef HUSH_ANISOTROPIC_SUBBAND_FIT_HPP
#define HUSH_ANISOTROPIC_SUBBAND_FIT_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/vec.hpp"
#include "hush/detail/approx_math.hpp"  // detail::index
#include "hush/detail/constants.hpp"
#include "hush/anisotropic/steerable.hpp"

namespace hush {

enum class weight_rule { centre, three_point, least_squares };

// "centre", "three_point", "least_squares".
inline const char* weight_rule_name(weight_rule r) {
  switch (r) {
    case weight_rule::centre:
      return "centre";
    case weight_rule::three_point:
      return "three_point";
    case weight_rule::least_squares:
      return "least_squares";
  }
  return "?";
}

class subband_fit {
 public:
  // residuals: include the low- and high-pass residuals in the basis.
  // r_max: outer radius of the quadrature domain with residuals (cycles per
  // unit; at least 2 f_{S-1}; ignored without residuals).
  explicit subband_fit(const steerable_bank& bank, bool residuals = false, double r_max = 0.0)
      : bank_(bank), residuals_(residuals) {
    namespace c = detail::constants;
    const int k = bank.orientations(), s_count = bank.scales();
    n_ = bank.subbands() + (residuals ? 2 : 0);
    // Radial segments: octaves [f_0 2^{j-1}, f_0 2^j] for j = 0 ... S, plus,
    // with residuals, [0, f_0 / 2] and octaves beyond 2 f_{S-1} up to r_max.
    std::vector<std::pair<double, double>> segments;
    const double f0 = bank.centre_frequency(0), top = 2.0 * bank.centre_frequency(s_count - 1);
    if (residuals) segments.emplace_back(0.0, 0.5 * f0);
    for (int j = 0; j <= s_count; ++j)
      segments.emplace_back(std::ldexp(f0, j - 1), std::ldexp(f0, j));
    if (residuals)
      for (int j = 0; std::ldexp(top, j) < r_max; ++j)
        segments.emplace_back(std::ldexp(top, j), std::min(std::ldexp(top, j + 1), r_max));
    const int nr = c::kAnisoRadialNodesPerOctave, nt = c::kAnisoAngularNodesPerOrientation * k;
    const double dt = c::kPi / nt;
    for (const auto& seg : segments) {
      const double dr = (seg.second - seg.first) / nr;
      for (int a = 0; a < nr; ++a) {
        const double r = seg.first + (a + 0.5) * dr;
        for (int b = 0; b < nt; ++b) {
          const double t = (b + 0.5) * dt;
          nodes_.push_back({r * std::cos(t), r * std::sin(t)});
          area_.push_back(2.0 * r * dr * dt);  // both half-planes
        }
      }
    }
    basis_.resize(nodes_.size() * static_cast<std::size_t>(n_));
    for (std::size_t q = 0; q < nodes_.size(); ++q) {
      double* row = &basis_[q * static_cast<std::size_t>(n_)];
      for (int s = 0; s < s_count; ++s)
        for (int i = 0; i < k; ++i) row[i + k * s] = bank.subband(i, s, nodes_[q]);
      if (residuals) {
        row[bank.subbands()] = bank.low_residual(nodes_[q]);
        row[bank.subbands() + 1] = bank.high_residual(nodes_[q]);
      }
    }
    // Gram matrix G = Q^T diag(area) Q and its Cholesky factor (lower, in place).
    chol_.assign(at(n_, 0), 0.0);
    for (std::size_t q = 0; q < nodes_.size(); ++q) {
      const double* row = &basis_[q * static_cast<std::size_t>(n_)];
      for (int a = 0; a < n_; ++a) {
        if (row[a] == 0.0) continue;
        const double wa = area_[q] * row[a];
        for (int b = 0; b <= a; ++b) chol_[at(a, b)] += wa * row[b];
      }
    }
    for (int j = 0; j < n_; ++j) {
      double d = chol_[at(j, j)];
      for (int m = 0; m < j; ++m) d -= chol_[at(j, m)] * chol_[at(j, m)];
      // G is positive definite (the filters are linearly independent on the
      // nodes); the guard only keeps a degenerate case finite.
      d = std::sqrt(std::max(d, 1e-300));
      chol_[at(j, j)] = d;
      for (int i = j + 1; i < n_; ++i) {
        double v = chol_[at(i, j)];
        for (int m = 0; m < j; ++m) v -= chol_[at(i, m)] * chol_[at(j, m)];
        chol_[at(i, j)] = v / d;
      }
    }
  }

  const steerable_bank& bank() const { return bank_; }
  bool has_residuals() const { return residuals_; }
  // Number of weights: K S, plus 2 with residuals (low at K S, high at K S + 1).
  int basis_size() const { return n_; }
  // The quadrature: node q's frequency, its area weight, and the basis there.
  std::size_t quadrature_nodes() const { return nodes_.size(); }
  const dvec2& node(std::size_t q) const { return nodes_[q]; }
  double node_area(std::size_t q) const { return area_[q]; }
  const double* node_basis(std::size_t q) const {
    return &basis_[q * static_cast<std::size_t>(n_)];
  }

  // The weights of `target` under `rule` into w[0 ... basis_size() - 1].
  template <class Target>
  void fit(weight_rule rule, const Target& target, double* w) const {
    switch (rule) {
      case weight_rule::centre:
        return sample_rule(target, w, false);
      case weight_rule::three_point:
        return sample_rule(target, w, true);
      case weight_rule::least_squares:
        return least_squares(target, w);
    }
  }
  template <class Target>
  std::vector<double> fit(weight_rule rule, const Target& target) const {
    std::vector<double> w(static_cast<std::size_t>(n_));
    fit(rule, target, w.data());
    return w;
  }

  // sum_j w_j D_j(x): the response the weights give at frequency x.
  double response(const double* w, const dvec2& x) const {
    double r = 0;
    for (int s = 0; s < bank_.scales(); ++s)
      for (int i = 0; i < bank_.orientations(); ++i)
        r += w[i + bank_.orientations() * s] * bank_.subband(i, s, x);
    if (residuals_)
      r += w[bank_.subbands()] * bank_.low_residual(x) +
           w[bank_.subbands() + 1] * bank_.high_residual(x);
    return r;
  }

  // sqrt(integral (t - sum w D)^2 / integral t^2) over the quadrature domain.
  template <class Target>
  double relative_error(const Target& target, const double* w) const {
    double num = 0, den = 0;
    for (std::size_t q = 0; q < nodes_.size(); ++q) {
      const double* row = &basis_[q * static_cast<std::size_t>(n_)];
      double r = 0;
      for (int a = 0; a < n_; ++a) r += w[a] * row[a];
      const double t = target(nodes_[q]);
      num += area_[q] * (t - r) * (t - r);
      den += area_[q] * t * t;
    }
    return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
  }

 private:
  std::size_t at(int r, int c) const { return detail::index(r * n_ + c); }

  template <class Target>
  void sample_rule(const Target& target, double* w, bool three) const {
    namespace c = detail::constants;
    const int k = bank_.orientations();
    // The even part of the target (the filters are even) at x.
    auto even = [&](const dvec2& x) { return 0.5 * (target(x) + target(dvec2{-x.x, -x.y})); };
    // Read at radius r along direction d (centre rule), or averaged around it (three-point).
    auto read = [&](const dvec2& d, double r) {
      const dvec2 x{d.x * r, d.y * r};
      if (!three) return even(x);
      const double lo = std::exp2(-c::kAnisoThreePointOffset),
                   hi = std::exp2(c::kAnisoThreePointOffset);
      return c::kAnisoThreePointSide * even(dvec2{x.x * lo, x.y * lo}) +
             c::kAnisoThreePointCentre * even(x) +
             c::kAnisoThreePointSide * even(dvec2{x.x * hi, x.y * hi});
    };
    for (int s = 0; s < bank_.scales(); ++s)
      for (int i = 0; i < k; ++i)
        w[i + k * s] = read(bank_.direction(i), bank_.centre_frequency(s));
    if (residuals_) {
      w[bank_.subbands()] = target(dvec2{0.0, 0.0});
      // The high residual's "centre": one octave above the top scale, averaged over directions.
      const double r = 2.0 * bank_.centre_frequency(bank_.scales() - 1);
      double h = 0;
      for (int i = 0; i < k; ++i) h += read(bank_.direction(i), r);
      w[bank_.subbands() + 1] = h / k;
    }
  }

  template <class Target>
  void least_squares(const Target& target, double* w) const {
    std::vector<double> b(static_cast<std::size_t>(n_), 0.0);
    for (std::size_t q = 0; q < nodes_.size(); ++q) {
      const double t = area_[q] * target(nodes_[q]);
      if (t == 0.0) continue;
      const double* row = &basis_[q * static_cast<std::size_t>(n_)];
      for (int a = 0; a < n_; ++a) b[static_cast<std::size_t>(a)] += t * row[a];
    }
    // Solve L L^T w = b.
    for (int i = 0; i < n_; ++i) {
      double v = b[static_cast<std::size_t>(i)];
      for (int m = 0; m < i; ++m) v -= chol_[at(i, m)] * w[m];
      w[i] = v / chol_[at(i, i)];
    }
    for (int i = n_ - 1; i >= 0; --i) {
      double v = w[i];
      for (int m = i + 1; m < n_; ++m) v -= chol_[at(m, i)] * w[m];
      w[i] = v / chol_[at(i, i)];
    }
  }

  steerable_bank bank_;
  bool residuals_;
  int n_ = 0;
  std::vector<dvec2> nodes_;
  std::vector<double> area_;
  std::vector<double> basis_;  // nodes x basis, row-major
  std::vector<double> chol_;   // n x n, lower Cholesky factor of the Gram matrix
};

}  // namespace hush

#endif  // HUSH_ANISOTROPIC_SUBBAND_FIT_HPP
