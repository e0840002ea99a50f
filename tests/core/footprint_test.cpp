// Tests for hush/core/footprint.hpp: the footprint matrix S = J J^T (or w^2 I),
// its widths and eigenvalues, and its robustness to degenerate, huge and
// non-finite Jacobians (HARD_CASES row 12).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "hush/core/footprint.hpp"
#include "hush/core/rng.hpp"

namespace {

const double kCap = hush::detail::constants::kFootprintMaxWidth;

// Every stored entry finite.
template <int D>
bool finite(const hush::footprint<D>& f) {
  for (int e = 0; e < hush::footprint<D>::kEntries; ++e)
    if (!std::isfinite(f.data()[e])) return false;
  return true;
}

// Largest eigenvalue of a symmetric 3x3 matrix by power iteration on S + c I
// (shifted to be positive definite): an independent check of the closed form.
double power_iteration_max(const hush::footprint<3>& f) {
  double shift = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) shift += std::fabs(double(f.covariance(r, c)));
  double v[3] = {0.6, 0.5, 0.62}, lambda = 0;
  for (int it = 0; it < 5000; ++it) {
    double w[3] = {shift * v[0], shift * v[1], shift * v[2]};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) w[r] += double(f.covariance(r, c)) * v[c];
    const double n = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (double& x : w) x /= n;
    lambda = n - shift;
    for (int a = 0; a < 3; ++a) v[a] = w[a];
  }
  return lambda;
}

}  // namespace

TEST_CASE("footprint: the default is a point and filters nothing") {
  const hush::footprint<2> f2;
  const hush::footprint<3> f3;
  CHECK(f2.is_point());
  CHECK(f3.is_point());
  CHECK(f2.max_width() == 0.0);
  CHECK(f3.max_width() == 0.0);
}

TEST_CASE("footprint: isotropic width w stores w^2 I, a negative width its magnitude") {
  const auto f = hush::footprint<3>::isotropic(0.25);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(f.covariance(r, c) == (r == c ? 0.0625f : 0.0f));
  CHECK(f.max_width() == doctest::Approx(0.25).epsilon(1e-12));
  CHECK(f.min_width() == doctest::Approx(0.25).epsilon(1e-12));
  CHECK(hush::footprint<2>::isotropic(-3.0) == hush::footprint<2>::isotropic(3.0));
}

TEST_CASE("footprint: from derivatives, S = J J^T and width_along(u) = |J^T u|") {
  hush::rng r(5, 0);
  for (int t = 0; t < 200; ++t) {
    const hush::dvec3 dx{r.uniform(-2.0, 2.0), r.uniform(-2.0, 2.0), r.uniform(-2.0, 2.0)};
    const hush::dvec3 dy{r.uniform(-2.0, 2.0), r.uniform(-2.0, 2.0), r.uniform(-2.0, 2.0)};
    const auto f = hush::footprint<3>::from_derivatives(dx, dy);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        CHECK(double(f.covariance(a, b)) ==
              doctest::Approx(dx[a] * dx[b] + dy[a] * dy[b]).epsilon(1e-6).scale(1));
    hush::dvec3 u{r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0)};
    const double n = std::sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
    u = {u.x / n, u.y / n, u.z / n};
    const double jx = dx.x * u.x + dx.y * u.y + dx.z * u.z,
                 jy = dy.x * u.x + dy.y * u.y + dy.z * u.z;
    CHECK(f.width_along(u) == doctest::Approx(std::hypot(jx, jy)).epsilon(1e-5));
    // Rank 2 in 3D: the smallest extent is 0 (up to the float rounding of S).
    CHECK(f.min_width() <= 1e-3 * f.max_width());
    CHECK(f.max_width() * f.max_width() == doctest::Approx(power_iteration_max(f)).epsilon(1e-9));
  }
}

TEST_CASE("footprint: 2D eigenvalues are the squared semi-axes of the pixel ellipse") {
  // J = R diag(a, b) with a rotation R: the semi-axes are a and b.
  const double a = 3.0, b = 0.5, th = 0.7;
  const hush::dvec2 dx{a * std::cos(th), a * std::sin(th)};
  const hush::dvec2 dy{-b * std::sin(th), b * std::cos(th)};
  const auto f = hush::footprint<2>::from_derivatives(dx, dy);
  CHECK(f.max_width() == doctest::Approx(a).epsilon(1e-6));
  CHECK(f.min_width() == doctest::Approx(b).epsilon(1e-5));
}

TEST_CASE("footprint: 3D eigenvalues of rotated diagonal matrices are the diagonal") {
  hush::rng r(11, 0);
  for (int t = 0; t < 100; ++t) {
    // Columns of a random rotation (Gram-Schmidt), scaled by widths w0 >= w1 >= w2.
    hush::dvec3 q[3];
    for (auto& v : q) v = {r.gaussian<double>(), r.gaussian<double>(), r.gaussian<double>()};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < i; ++j) {
        const double d = q[i].x * q[j].x + q[i].y * q[j].y + q[i].z * q[j].z;
        q[i] = {q[i].x - d * q[j].x, q[i].y - d * q[j].y, q[i].z - d * q[j].z};
      }
      const double n = std::sqrt(q[i].x * q[i].x + q[i].y * q[i].y + q[i].z * q[i].z);
      q[i] = {q[i].x / n, q[i].y / n, q[i].z / n};
    }
    const double w[3] = {r.uniform(1.0, 4.0), r.uniform(0.5, 1.0), r.uniform(0.0, 0.5)};
    float upper[6];
    int e = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j, ++e) {
        double s = 0;
        for (int k = 0; k < 3; ++k) s += w[k] * w[k] * q[k][std::size_t(i)] * q[k][std::size_t(j)];
        upper[e] = float(s);
      }
    const auto f = hush::footprint<3>::from_covariance(upper);
    const hush::dvec3 ev = f.eigenvalues();
    CHECK(ev.z == doctest::Approx(w[0] * w[0]).epsilon(1e-5));
    CHECK(ev.y == doctest::Approx(w[1] * w[1]).epsilon(1e-5).scale(w[0] * w[0]));
    CHECK(ev.x == doctest::Approx(w[2] * w[2]).epsilon(1e-5).scale(w[0] * w[0]));
  }
}

TEST_CASE("footprint: degenerate, huge and non-finite Jacobians give finite footprints (row 12)") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  // Zero: a point. Rank 1: one axis only.
  CHECK(hush::footprint<2>::from_derivatives(hush::dvec2{0, 0}, hush::dvec2{0, 0}).is_point());
  const auto rank1 = hush::footprint<2>::from_derivatives(hush::dvec2{2, 0}, hush::dvec2{0, 0});
  CHECK(rank1.max_width() == doctest::Approx(2.0));
  CHECK(rank1.min_width() == 0.0);
  // det 1e-30: stored as it is; det 1e30 (widths 1e15, beyond the cap): capped, finite.
  const auto tiny =
      hush::footprint<2>::from_derivatives(hush::dvec2{1e-15, 0}, hush::dvec2{0, 1e-15});
  const auto huge =
      hush::footprint<2>::from_derivatives(hush::dvec2{1e15, 0}, hush::dvec2{0, 1e15});
  CHECK(finite(tiny));
  CHECK(finite(huge));
  CHECK(tiny.max_width() == doctest::Approx(1e-15).epsilon(1e-6));
  CHECK(huge.max_width() == doctest::Approx(kCap).epsilon(1e-6));
  CHECK(huge.min_width() == doctest::Approx(kCap).epsilon(1e-6));
  // NaN, Inf: "everything", the widest footprint, isotropic.
  for (double bad : {nan, inf, -inf}) {
    const auto f =
        hush::footprint<3>::from_derivatives(hush::dvec3{1, bad, 0}, hush::dvec3{0, 1, 0});
    CHECK(finite(f));
    CHECK(f == hush::footprint<3>::isotropic(kCap));
    CHECK(hush::footprint<2>::isotropic(bad) == hush::footprint<2>::isotropic(kCap));
  }
  // Beyond the cap: scaled down to it, the shape (width ratio) kept.
  const auto wide =
      hush::footprint<2>::from_derivatives(hush::dvec2{1e300, 0}, hush::dvec2{0, 1e299});
  CHECK(finite(wide));
  CHECK(wide.max_width() == doctest::Approx(kCap).epsilon(1e-6));
  CHECK(wide.min_width() == doctest::Approx(kCap / 10).epsilon(1e-6));
}

TEST_CASE("footprint: scaled(s) multiplies S by s^2, capped; non-finite s gives everything") {
  const auto f = hush::footprint<2>::from_derivatives(hush::dvec2{0.5, 0.25}, hush::dvec2{0, 0.5});
  const auto g = f.scaled(4.0);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) CHECK(g.covariance(r, c) == 16.0f * f.covariance(r, c));
  // Capped: the largest entry is W^2, so the largest width is in [W, sqrt(2) W].
  CHECK(f.scaled(1e30).max_width() >= kCap * (1 - 1e-6));
  CHECK(f.scaled(1e30).max_width() <= std::sqrt(2.0) * kCap);
  CHECK(f.scaled(std::numeric_limits<double>::infinity()) == hush::footprint<2>::isotropic(kCap));
  CHECK(f.scaled(0.0).is_point());
}
