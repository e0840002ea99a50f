// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Numerical integration for the statistics hush computes at construction
// (a noise's exact variance and power spectrum when no closed form exists),
// in double, from the C library's cos only, so results are the same wherever
// that is correctly rounded (glibc).
//
//   gauss_legendre_rule()          the 16-point Gauss-Legendre rule on [-1, 1]
//   integrate(f, lo, hi, panels)   composite 16-point rule: exact for polynomials
//                                  of degree 31 per panel; for smooth f the error
//                                  falls geometrically with the panel count
//   integrate_ends(f, lo, hi, panels)  the same rule after v = mid + half sin(pi t / 2):
//                                  exact to the rule's order for f smooth inside
//                                  but with square-root endpoint behaviour
//   chebyshev_table                piecewise Chebyshev interpolation of a smooth f
//   bessel_j0(z)                   J0 by the trapezoidal rule on its integral
//                                  representation (periodic integrand: the error is
//                                  below 2 |J_N(z)|, under 1e-15 with N = 2|z| + 40)
#ifndef HUSH_DETAIL_QUADRATURE_HPP
#define HUSH_DETAIL_QUADRATURE_HPP

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

constexpr int kGaussPoints = 16;

struct gauss_rule {
  std::array<double, kGaussPoints> node, weight;
};

// Nodes (roots of P_16) by Newton's iteration from Tricomi's initial guesses,
// weights 2 / ((1 - x^2) P_16'(x)^2). Computed once.
inline const gauss_rule& gauss_legendre_rule() {
  static const gauss_rule rule = [] {
    gauss_rule g{};
    constexpr int n = kGaussPoints;
    for (int i = 0; i < n; ++i) {
      double x = std::cos(constants::kPi * (i + 0.75) / (n + 0.5));
      double dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = x;  // P_0, P_1, then the recurrence up to P_n
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::fabs(dx) < 1e-16) break;
      }
      g.node[static_cast<std::size_t>(i)] = x;
      g.weight[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    return g;
  }();
  return rule;
}

// The integral of f over [lo, hi] by the 16-point rule on `panels` equal panels.
template <class F>
double integrate(F f, double lo, double hi, int panels) {
  const gauss_rule& g = gauss_legendre_rule();
  const double h = (hi - lo) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = lo + (p + 0.5) * h, half = 0.5 * h;
    double s = 0.0;
    for (int i = 0; i < kGaussPoints; ++i)
      s += g.weight[static_cast<std::size_t>(i)] *
           f(mid + half * g.node[static_cast<std::size_t>(i)]);
    sum += s * half;
  }
  return sum;
}

// The integral of f over [lo, hi] where f is smooth inside but behaves like
// sqrt(v - lo) or sqrt(hi - v) at an end (an arc's length where a circle
// touches a cap's rim): with v = mid + half sin(pi t / 2), t in [-1, 1],
// sqrt(1 -+ sin(pi t / 2)) = sqrt 2 |sin(pi / 4 -+ pi t / 4)| is analytic on
// [-1, 1], so the composite rule in t converges geometrically again (in v it
// falls only as panels^-3). dv / dt <= half pi / 2: `panels` panels in t cover
// at most (hi - lo) pi / (2 panels) of v each.
template <class F>
double integrate_ends(F f, double lo, double hi, int panels) {
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo), q = 0.5 * constants::kPi;
  return integrate([&](double t) { return f(mid + half * std::sin(q * t)) * half * q * std::cos(q * t); },
                   -1.0, 1.0, panels);
}

// f on [lo, hi] interpolated on panels of width <= `width`, each through f at
// its n Chebyshev-Lobatto points (shared with the neighbours, so (n - 1)
// panels + 1 calls of f), evaluated by the barycentric formula (stable). For
// f analytic in a strip around the panel the error falls like (width / (2 d))^n
// (d: the strip's half-width; e.g. e^{i w v} with w width / 2 = 0.8, n = 12:
// ~2e-14 of its amplitude); tests measure it for the functions hush tabulates.
// x outside [lo, hi] is clamped.
class chebyshev_table {
 public:
  template <class F>
  chebyshev_table(F f, double lo, double hi, double width, int n)
      : lo_(lo), n_(static_cast<std::size_t>(std::max(n, 2))) {
    const int panels = std::max(1, static_cast<int>(std::ceil((hi - lo) / width)));
    panels_ = static_cast<std::size_t>(panels);
    width_ = (hi - lo) / panels;
    values_.resize(panels_ * (n_ - 1) + 1);
    node_.resize(n_);
    for (std::size_t j = 0; j < n_; ++j)  // ascending on [0, 1]
      node_[j] = 0.5 - 0.5 * std::cos(constants::kPi * static_cast<double>(j) / static_cast<double>(n_ - 1));
    for (std::size_t p = 0; p < panels_; ++p)
      for (std::size_t j = p == 0 ? 0 : 1; j < n_; ++j)
        values_[p * (n_ - 1) + j] = f(lo_ + width_ * (static_cast<double>(p) + node_[j]));
  }

  double operator()(double x) const {
    const double t = std::clamp((x - lo_) / width_, 0.0, static_cast<double>(panels_));
    const std::size_t p = std::min(static_cast<std::size_t>(t), panels_ - 1);
    const double s = t - static_cast<double>(p);
    double num = 0, den = 0;
    for (std::size_t j = 0; j < n_; ++j) {
      const double v = values_[p * (n_ - 1) + j], d = s - node_[j];
      if (d == 0.0) return v;
      // Lobatto weights (-1)^j, halved at the ends.
      const double w = ((j % 2 == 0) ? 1.0 : -1.0) * ((j == 0 || j + 1 == n_) ? 0.5 : 1.0) / d;
      num += w * v;
      den += w;
    }
    return num / den;
  }

  // Calls of f the table made.
  std::size_t calls() const { return values_.size(); }

 private:
  double lo_ = 0, width_ = 1;
  std::size_t n_ = 2, panels_ = 1;
  std::vector<double> node_, values_;
};

// J0(z) to ~1e-15 absolute: the power series for |z| < 8 (terms up to 113:
// two digits of cancellation); the trapezoidal rule on
// J0(z) = (1/2pi) int_0^2pi cos(z cos t) dt for 8 <= |z| < 25 (periodic
// integrand: error below 2 |J_n(z)| with n = 2 ceil(|z|) + 40 points); Hankel's
// asymptotic expansion beyond (Abramowitz and Stegun 9.2.5, summed while its
// terms fall, the smallest below e^-2|z| < 2e-22).
inline double bessel_j0(double z) {
  const double x = std::fabs(z);
  if (x < 8.0) {
    const double q = -0.25 * x * x;
    double term = 1.0, sum = 1.0;
    for (int k = 1; k < 60 && std::fabs(term) > 1e-18; ++k) {
      term *= q / (static_cast<double>(k) * k);
      sum += term;
    }
    return sum;
  }
  if (x < 25.0) {
    const int n = 2 * static_cast<int>(std::ceil(x)) + 40;
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += std::cos(x * std::cos(constants::kTwoPi * i / n));
    return s / n;
  }
  double p = 0.0, q = 0.0, term = 1.0, last = 2.0;
  for (int k = 0; k < 60; ++k) {
    if (k > 0) {
      const double odd = 2.0 * k - 1.0;
      term *= -odd * odd / (k * 8.0 * x);
    }
    if (std::fabs(term) >= last) break;  // the asymptotic series starts to diverge
    last = std::fabs(term);
    // Terms alternate between P (even k, signs + - + ...) and Q (odd k).
    const double sign = (k / 2) % 2 == 0 ? 1.0 : -1.0;
    if (k % 2 == 0)
      p += sign * term;
    else
      q += sign * term;
  }
  const double chi = x - 0.25 * constants::kPi;
  return std::sqrt(2.0 / (constants::kPi * x)) * (p * std::cos(chi) - q * std::sin(chi));
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_DETAIL_QUADRATURE_HPP
