// Fitting subband weights to a target spectrum (include/hush/subband_fit.hpp):
// the heuristic rules read the target where the paper says, least squares
// minimises the stated integral (checked against a target the basis spans,
// against Eigen's least-squares solver, and against the heuristics' error).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "hush/hush.hpp"

#if HUSH_TEST_HAVE_EIGEN
#include <Eigen/Dense>
#endif

namespace {

hush::steerable_bank make_bank(int k, int s, double f0) {
  hush::steerable_bank::params p;
  p.orientations = k;
  p.scales = s;
  p.base_frequency = f0;
  return hush::steerable_bank(p);
}

// The pixel filter of footprint S = [a b; b c] (covariance, sigma 1/2): exp(-2 pi^2 sigma^2 w^T S
// w).
struct gaussian_target {
  double a, b, c;
  double operator()(const hush::dvec2& w) const {
    const double k = 2 * 3.14159265358979323846 * 3.14159265358979323846 * 0.25;
    return std::exp(-k * (a * w.x * w.x + 2 * b * w.x * w.y + c * w.y * w.y));
  }
};

}  // namespace

TEST_CASE("subband fit: least squares recovers the weights of a target the basis spans") {
  hush::rng r(7);
  for (bool residuals : {false, true})
    for (int k : {2, 4, 7}) {
      const hush::subband_fit fit(make_bank(k, 3, 0.05), residuals, 0.7);
      std::vector<double> truth(static_cast<std::size_t>(fit.basis_size()));
      for (double& v : truth) v = r.uniform<double>(-1, 1);
      const std::vector<double> w =
          fit.fit(hush::weight_rule::least_squares,
                  [&](const hush::dvec2& x) { return fit.response(truth.data(), x); });
      double worst = 0;
      for (std::size_t j = 0; j < w.size(); ++j)
        worst = std::max(worst, std::fabs(w[j] - truth[j]));
      CAPTURE(k);
      CAPTURE(residuals);
      CHECK(worst < 1e-9);
    }
}

#if HUSH_TEST_HAVE_EIGEN
TEST_CASE("subband fit: least squares equals Eigen's solution of the weighted system") {
  const hush::subband_fit fit(make_bank(4, 3, 0.05), true, 0.7);
  const gaussian_target t{30.0, 12.0, 9.0};
  const auto q = static_cast<Eigen::Index>(fit.quadrature_nodes());
  const auto n = static_cast<Eigen::Index>(fit.basis_size());
  Eigen::MatrixXd a(q, n);
  Eigen::VectorXd b(q);
  for (Eigen::Index i = 0; i < q; ++i) {
    const double sw = std::sqrt(fit.node_area(static_cast<std::size_t>(i)));
    const double* row = fit.node_basis(static_cast<std::size_t>(i));
    for (Eigen::Index j = 0; j < n; ++j) a(i, j) = sw * row[j];
    b(i) = sw * t(fit.node(static_cast<std::size_t>(i)));
  }
  const Eigen::VectorXd x = a.colPivHouseholderQr().solve(b);
  const std::vector<double> w = fit.fit(hush::weight_rule::least_squares, t);
  double worst = 0;
  for (Eigen::Index j = 0; j < n; ++j)
    worst = std::max(worst, std::fabs(x(j) - w[static_cast<std::size_t>(j)]));
  CHECK(worst < 1e-9);
}
#endif

TEST_CASE("subband fit: the centre rule reads the target at each subband's centre") {
  const hush::steerable_bank bank = make_bank(5, 3, 0.3);
  const hush::subband_fit fit(bank, true, 4.0);
  // An even target whose value tells the frequency: t(w) = w.x^2 + 2 w.y^2 + w.x w.y + 5.
  auto t = [](const hush::dvec2& x) { return x.x * x.x + 2 * x.y * x.y + x.x * x.y + 5; };
  const auto w = fit.fit(hush::weight_rule::centre, t);
  for (int s = 0; s < 3; ++s)
    for (int i = 0; i < 5; ++i) {
      const hush::dvec2 c{bank.direction(i).x * bank.centre_frequency(s),
                          bank.direction(i).y * bank.centre_frequency(s)};
      CHECK(w[static_cast<std::size_t>(i + 5 * s)] == doctest::Approx(t(c)));
    }
  // An odd part is dropped (the filters are even).
  const auto odd = fit.fit(hush::weight_rule::centre, [](const hush::dvec2& x) { return x.x; });
  for (double v : odd) CHECK(v == doctest::Approx(0.0));
  CHECK(w[15] == doctest::Approx(5.0));  // low residual: the target at 0
  // High residual: the mean over directions at 2 f_{S-1} = 2.4: 5 + mean(x^2 + 2 y^2 + x y)
  // = 5 + 2.4^2 (1/2 + 2/2 + 0) over K = 5 equally spaced directions.
  CHECK(w[16] == doctest::Approx(5 + 2.4 * 2.4 * 1.5));
  // Exact for a scale's isotropic band: weights 1 on that scale, 0 elsewhere,
  // and the response reproduces the target.
  const auto iso = fit.fit(hush::weight_rule::centre,
                           [&](const hush::dvec2& x) { return bank.scale_band(1, x); });
  CHECK(fit.relative_error([&](const hush::dvec2& x) { return bank.scale_band(1, x); },
                           iso.data()) < 1e-12);
}

TEST_CASE("subband fit: the three-point rule averages -1/2, 0, +1/2 octave with 1/4, 1/2, 1/4") {
  const hush::steerable_bank bank = make_bank(4, 2, 1.0);
  const hush::subband_fit fit(bank);
  // t = (log2 |w|)^2: the rule gives L^2 + 1/8 at a centre of log2-radius L.
  const auto w = fit.fit(hush::weight_rule::three_point, [](const hush::dvec2& x) {
    const double l = std::log2(std::hypot(x.x, x.y));
    return l * l;
  });
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < 4; ++i)
      CHECK(w[static_cast<std::size_t>(i + 4 * s)] == doctest::Approx(s * s + 0.125));
}

TEST_CASE("subband fit: least squares fits anisotropic pixel filters better than the heuristics") {
  // Image filtering: scales at 1/64 ... 1/4 cycles per pixel, the spectrum to its corner.
  const hush::subband_fit fit(make_bank(8, 5, 1.0 / 64), true, 0.7071);
  for (const gaussian_target t : {gaussian_target{16, 0, 16}, gaussian_target{40, 0, 4},
                                  gaussian_target{30, 14, 12}, gaussian_target{200, -10, 2}}) {
    const double lsq = fit.relative_error(t, fit.fit(hush::weight_rule::least_squares, t).data());
    const double centre = fit.relative_error(t, fit.fit(hush::weight_rule::centre, t).data());
    const double three = fit.relative_error(t, fit.fit(hush::weight_rule::three_point, t).data());
    CAPTURE(t.a);
    CAPTURE(lsq);
    CAPTURE(centre);
    CAPTURE(three);
    CHECK(lsq <= centre);
    CHECK(lsq <= three);
    MESSAGE("relative L2 error: least squares " << lsq << ", centre " << centre << ", three-point "
                                                << three);
  }
}
