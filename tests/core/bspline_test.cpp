// The wavelet-noise kernels of core/bspline.hpp, each checked against the property that
// defines it, computed here independently of the truncated-power derivation (midpoint
// quadrature of the defining integrals, the refinement relation, partitions of unity).
#include <doctest/doctest.h>

#include <cmath>

#include "hush/core/bspline.hpp"

namespace {

using namespace hush::detail;

// The quadratic B-spline from its textbook pieces, independent of the header.
double textbook_b(double x) {
  x = std::fabs(x);
  if (x < 0.5) return 0.75 - x * x;
  if (x < 1.5) return 0.5 * (1.5 - x) * (1.5 - x);
  return 0;
}

// Midpoint rule with `steps` cells over [lo, hi] (exact to ~1e-10 for these smooth kernels).
template <class F>
double integrate(F f, double lo, double hi, int steps) {
  double s = 0, h = (hi - lo) / steps;
  for (int i = 0; i < steps; ++i) s += f(lo + (i + 0.5) * h);
  return s * h;
}

}  // namespace

TEST_CASE("bspline: B is the textbook quadratic B-spline, and its derivative is B'") {
  for (double x = -2.0; x <= 2.0; x += 0.0625) {
    CHECK(kernel_at(kBspline, x) == doctest::Approx(textbook_b(x)).epsilon(1e-15));
    const double h = 1e-6;
    const double fd = (textbook_b(x + h) - textbook_b(x - h)) / (2 * h);
    if (std::fabs(std::fabs(x) - 0.5) > 1e-3 && std::fabs(std::fabs(x) - 1.5) > 1e-3)
      CHECK(kernel_at(kBsplineDerivative, x) == doctest::Approx(fd).epsilon(1e-8));
  }
}

TEST_CASE("bspline: B, B2 and beta are partitions of unity and integrate to 1") {
  for (double y = 0; y < 1; y += 0.03125) {
    double sb = 0, sb2 = 0, sbeta = 0;
    for (int i = -10; i <= 10; ++i) {
      sb += kernel_at(kBspline, y - i);
      sb2 += kernel_at(kBspline2, y - i);
      sbeta += kernel_at(kBeta, y - i);
    }
    CHECK(sb == doctest::Approx(1).epsilon(1e-15));
    CHECK(sb2 == doctest::Approx(1).epsilon(1e-15));
    CHECK(sbeta == doctest::Approx(1).epsilon(1e-15));
  }
  CHECK(integrate([](double x) { return kernel_at(kBeta, x); }, -5, 5, 100000) ==
        doctest::Approx(1).epsilon(1e-9));
}

TEST_CASE("bspline: the plain 3-tap weights are B at the three distances f + 1/2 - j") {
  for (double f = 0; f < 1; f += 0.0625) {
    double w[3], dw[3];
    bspline_weights(f, w);
    bspline_derivative_weights(f, dw);
    for (int j = 0; j < 3; ++j) {
      CHECK(w[j] == doctest::Approx(textbook_b(f + 0.5 - j)).epsilon(1e-15));
      CHECK(dw[j] == doctest::Approx(kernel_at(kBsplineDerivative, f + 0.5 - j)).epsilon(1e-15));
    }
  }
}

TEST_CASE("bspline: refinement B((y - 1/2) / 2) = sum_k p_k B(y - k), p = (1, 3, 3, 1) / 4") {
  namespace c = hush::detail::constants;
  for (double y = -4; y <= 4; y += 0.0625) {
    double s = 0;
    for (int i = 0; i < 4; ++i)
      s += c::kWaveletRefine[i] * textbook_b(y - (c::kWaveletRefineFirst + i));
    CHECK(textbook_b((y - 0.5) / 2) == doctest::Approx(s).epsilon(1e-15));
  }
}

TEST_CASE("bspline: B2 is B stretched by 2, beta is B convolved with B2 (the exact projection)") {
  for (double x = -5; x <= 5; x += 0.1875) {
    CHECK(kernel_at(kBspline2, x) == doctest::Approx(0.5 * textbook_b(x / 2)).epsilon(1e-15));
    const double conv = integrate(
        [x](double t) { return textbook_b(x - t) * 0.5 * textbook_b(t / 2); }, -3, 3, 60000);
    CHECK(kernel_at(kBeta, x) == doctest::Approx(conv).epsilon(1e-9).scale(1e-12));
  }
  // beta is C4: its pieces join with matching value and derivative at every knot.
  for (int k = 1; k < kBeta.pieces; ++k) {
    const double left = piece_value(kBeta, k - 1, 1.0), right = piece_value(kBeta, k, 0.0);
    CHECK(left == doctest::Approx(right).epsilon(1e-14).scale(1e-15));
    const double dl = piece_value(kBetaDerivative, k - 1, 1.0);
    const double dr = piece_value(kBetaDerivative, k, 0.0);
    CHECK(dl == doctest::Approx(dr).epsilon(1e-13).scale(1e-15));
  }
}

TEST_CASE("bspline: Gram entries are B's autocorrelation (66, 26, 1) / 120, and beta's, B2's") {
  CHECK(bspline_gram(0) == doctest::Approx(66.0 / 120).epsilon(1e-16));
  CHECK(bspline_gram(1) == doctest::Approx(26.0 / 120).epsilon(1e-16));
  CHECK(bspline_gram(2) == doctest::Approx(1.0 / 120).epsilon(1e-16));
  CHECK(bspline_gram(3) == 0.0);
  for (int d = 0; d < kBetaGramReach + 1; ++d) {
    const double b2 =
        integrate([d](double t) { return kernel_at(kBspline2, t) * kernel_at(kBspline2, t + d); },
                  -3, 3, 60000);
    const double beta = integrate(
        [d](double t) { return kernel_at(kBeta, t) * kernel_at(kBeta, t + d); }, -4.5, 4.5, 90000);
    if (d < kBspline2GramReach + 1) CHECK(bspline2_gram(d) == doctest::Approx(b2).scale(1e-11));
    CHECK(beta_gram(d) == doctest::Approx(beta).scale(1e-11));
  }
}
