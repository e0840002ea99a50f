// hush::gabor (gabor.hpp): sparse Gabor convolution noise. Parameters, exact
// statistics (mean, unit variance, for every kind, 2D, 3D and on surfaces),
// the analytic gradient, the float budget, filtering and the hard cases.
// Tolerances come from the sample sizes (formulas beside each test). The long
// spectral sweeps are in gabor_slow_test.cpp (label slow).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "gabor_test_util.hpp"
#include "hush/hush.hpp"

using namespace gabor_test_util;  // NOLINT(google-build-using-namespace): the suites' helpers

// ---- Parameters.

TEST_CASE("gabor: every parameter out of range is refused, naming it and its range") {
  auto refused = [](auto mutate, const char* name) {
    hush::gabor<2>::params p;
    mutate(p);
    try {
      const hush::gabor<2> g(p);
      return false;
    } catch (const hush::invalid_argument& e) {
      const std::string m = e.what();
      return m.find(std::string("hush::gabor: ") + name + " = ") != std::string::npos &&
             m.find("valid: ") != std::string::npos;
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using P = hush::gabor<2>::params;
  CHECK(refused([](P& p) { p.frequency = -0.1; }, "frequency"));
  CHECK(refused([&](P& p) { p.frequency = nan; }, "frequency"));
  CHECK(refused([](P& p) { p.frequency = 2e6; }, "frequency"));
  CHECK(refused([](P& p) { p.bandwidth = 0; }, "bandwidth"));
  CHECK(refused([&](P& p) { p.bandwidth = inf; }, "bandwidth"));
  CHECK(refused([](P& p) { p.truncation = 0.7; }, "truncation"));
  CHECK(refused([](P& p) { p.truncation = 0; }, "truncation"));
  CHECK(refused([](P& p) { p.impulses = 0; }, "impulses"));
  // So few kernels that the Poisson table holds no impulse: refused, not a NaN field.
  CHECK(refused([](P& p) { p.impulses = 1e-10; }, "impulses"));
  CHECK(refused([](P& p) { p.impulses = 257; }, "impulses"));
  CHECK(refused([&](P& p) { p.impulses = nan; }, "impulses"));
  CHECK(refused([&](P& p) { p.orientation = inf; }, "orientation"));
  CHECK(refused([&](P& p) { p.elevation = nan; }, "elevation"));
  CHECK(refused([](P& p) { p.orientation_spread = 7; }, "orientation_spread"));
  CHECK(refused([](P& p) { p.orientation_spread = -1; }, "orientation_spread"));
  CHECK(refused([](P& p) { p.frequency_spread = 2.5; }, "frequency_spread"));  // > 2 F0
  CHECK(refused([](P& p) { p.kind = static_cast<gabor_kind>(9); }, "kind"));
  // The extremes of every range are accepted, in 2D and 3D.
  hush::gabor<3>::params p3;
  p3.impulses = 256;
  p3.truncation = 1e-9;
  p3.kind = gabor_kind::hybrid;
  p3.orientation_spread = 2 * kPi;
  p3.frequency_spread = 2.0;
  CHECK_NOTHROW(hush::gabor<3>{p3});
  hush::gabor<2>::params p2;
  p2.frequency = 0;
  p2.impulses = 1e-3;
  CHECK_NOTHROW(hush::gabor<2>{p2});
}

// ---- Statistics.

TEST_CASE("gabor: the sparsest accepted noise (impulses 1e-6) is finite everywhere") {
  for (auto kind : {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic}) {
    hush::gabor<2>::params p2;
    p2.kind = kind;
    p2.impulses = 1e-6;
    hush::gabor<3>::params p3;
    p3.kind = kind;
    p3.impulses = 1e-6;
    const hush::gabor<2> g2(p2);
    const hush::gabor<3> g3(p3);
    CHECK(std::isfinite(g2.scale()));
    CHECK(std::isfinite(g3.scale()));
    CHECK(std::isfinite(g3.surface_scale()));
    for (double x : {0.5, 1e3, 6e293}) {
      CHECK(std::isfinite(g2(hush::dvec2{0.5, x})));
      CHECK(std::isfinite(g3(hush::dvec3{0.5, x, -x})));
    }
  }
}

// Hybrid noise's normalisation averages the kernel energy over |Phi| in [F0 -+ spread / 2]: a
// spread too narrow for doubles to separate the ends (or a few ulps of F0) is the single
// frequency F0, so the noise equals spread 0's, not infinite or off by the ends' rounding.
TEST_CASE("gabor: hybrid noise with a vanishing frequency spread is the spread-0 noise") {
  hush::gabor<3>::params p;
  p.kind = hush::gabor_kind::hybrid;
  p.frequency = 256;
  p.bandwidth = 2;
  p.orientation_spread = 0.5;
  const hush::gabor<3> none(p);
  hush::gabor<2>::params p2;
  p2.kind = hush::gabor_kind::hybrid;
  p2.frequency = 7;
  p2.orientation_spread = 1;
  const hush::gabor<2> none2(p2);
  for (double spread : {1e-300, 1e-100, 1e-10}) {
    CAPTURE(spread);
    p.frequency_spread = spread;
    p2.frequency_spread = spread;
    const hush::gabor<3> g(p);
    const hush::gabor<2> g2(p2);
    CHECK(g.scale() == doctest::Approx(none.scale()).epsilon(1e-12));
    CHECK(g2.scale() == doctest::Approx(none2.scale()).epsilon(1e-12));
    for (double x : {0.3, -539.0, 1e10}) {
      CHECK(g(hush::dvec3{x, 0.4, 0.5}) == doctest::Approx(none(hush::dvec3{x, 0.4, 0.5})).epsilon(1e-6));
      CHECK(g2(hush::dvec2{x, 0.4}) == doctest::Approx(none2(hush::dvec2{x, 0.4})).epsilon(1e-6));
    }
  }
}

TEST_CASE("gabor: any finite orientation is the noise of its angle within one turn, float and double") {
  // Hybrid 2D noise draws each impulse's angle around omega0 in turns: an orientation far beyond
  // one turn must give the noise of its reduced angle, and float evaluation must stay within the
  // float budget (see the float test below), not lose the fraction or overflow to NaN.
  hush::gabor<2>::params p;
  p.kind = gabor_kind::hybrid;
  p.frequency = 4;
  p.frequency_spread = 2;
  p.orientation_spread = 0.5;
  for (const double w : {7.5, -40.0, 1e10, 1e39, -8.2864457291795643e+307, 1.7e308}) {
    CAPTURE(w);
    p.orientation = w;
    const hush::gabor<2> g(p);
    p.orientation = std::atan2(std::sin(w), std::cos(w));
    const hush::gabor<2> reduced(p);
    const double phi = g.marks().phi0() + 0.5 * g.marks().dphi();
    const double budget =
        g.scale() * std::ldexp(1.0, -21) * (1 + 2 * kPi * phi) * (g.parameters().impulses + 1);
    for (const double x : {0.3, -53.9, 1e4, 1e30}) {
      const hush::dvec2 pd{x, 0.25 * x + 0.4};
      // theta0 of the two differs by at most an ulp of a turn: far below the float budget.
      CHECK(std::fabs(g(pd) - reduced(pd)) <= 1e-9);
      const hush::vec2 pf = hush::vec_cast<float>(pd);
      const double f = g(pf);
      REQUIRE(std::isfinite(f));
      CHECK(std::fabs(f - g(hush::vec_cast<double>(pf))) <= budget);
    }
  }
}

TEST_CASE("gabor: mean 0 and variance 1 over space and seeds, every kind, 2D and 3D") {
  // 20000 i.i.d. samples per configuration: |mean| <= 5 SE(mean) and
  // |var - 1| <= 5 SE(var), the SEs from the samples (moments_of).
  for (const gabor_kind kind :
       {gabor_kind::isotropic, gabor_kind::anisotropic, gabor_kind::hybrid}) {
    const hush::gabor<2> g2(make_params<2>(kind, 3));
    std::vector<double> v2;
    for (const auto& p : independent_points<2>(g2.kernel().radius(), 20000, 1)) v2.push_back(g2(p));
    const moments m2 = moments_of(v2);
    INFO("2D kind " << static_cast<int>(kind) << ": mean " << m2.mean << " var " << m2.var);
    CHECK(std::fabs(m2.mean) <= 5 * m2.se_mean);
    CHECK(std::fabs(m2.var - 1) <= 5 * m2.se_var);
    const hush::gabor<3> g3(make_params<3>(kind, 4));
    std::vector<double> v3;
    for (const auto& p : independent_points<3>(g3.kernel().radius(), 8000, 2)) v3.push_back(g3(p));
    const moments m3 = moments_of(v3);
    INFO("3D kind " << static_cast<int>(kind) << ": mean " << m3.mean << " var " << m3.var);
    CHECK(std::fabs(m3.mean) <= 5 * m3.se_mean);
    CHECK(std::fabs(m3.var - 1) <= 5 * m3.se_var);
  }
}

TEST_CASE("gabor: surface noise has mean 0 and variance 1 on planes of any orientation") {
  // The projection of the slab's impulses is a 2D Poisson process: on a plane
  // the variance is exactly 1 whatever the normal (isotropic noise). 8000
  // i.i.d. samples per plane (surface cells 3 apart), 5 SE.
  const hush::gabor<3> g(make_params<3>(gabor_kind::isotropic, 5));
  const double cell = 1.0 / g.inverse_surface_cell();
  for (const hush::dvec3 n :
       {hush::dvec3{0, 0, 1}, hush::dvec3{1, 1, 1}, hush::dvec3{-0.2, 0.9, -0.1}}) {
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    const hush::dvec3 u{n.x / len, n.y / len, n.z / len};
    hush::dvec3 t, b;
    hush::detail::orthonormal_basis(u, t, b);
    std::vector<double> v;
    hush::rng r(6);
    for (int i = 0; i < 8000; ++i) {
      const double s = (3.0 * (i % 100) + r.uniform<double>()) * 2 * cell;
      const double q = (3.0 * (i / 100) + r.uniform<double>()) * 2 * cell;
      const hush::dvec3 p{s * t.x + q * b.x + 0.37, s * t.y + q * b.y - 5.2,
                          s * t.z + q * b.z + 1.1};
      v.push_back(g.sample(p, u));
    }
    const moments m = moments_of(v);
    INFO("normal " << u.x << ", " << u.y << ", " << u.z << ": mean " << m.mean << " var " << m.var);
    CHECK(std::fabs(m.mean) <= 5 * m.se_mean);
    CHECK(std::fabs(m.var - 1) <= 5 * m.se_var);
  }
}

TEST_CASE("gabor: gradient is the derivative of the value (2D, 3D, filtered, surface)") {
  hush::rng r(8);
  const hush::gabor<2> g2(make_params<2>(gabor_kind::hybrid));
  const hush::gabor<3> g3(make_params<3>(gabor_kind::isotropic));
  const auto fp2 =
      hush::footprint<2>::from_derivatives(hush::dvec2{0.1, 0.05}, hush::dvec2{0, 0.2});
  const auto fp3 =
      hush::footprint<3>::from_derivatives(hush::dvec3{0.1, 0.05, 0}, hush::dvec3{0, 0.2, 0.1});
  const hush::dvec3 nrm{0.3, -0.5, 0.8};
  double worst = 0;
  auto fd_check = [&](auto value, auto analytic, auto p) {
    constexpr int D = static_cast<int>(sizeof(p) / sizeof(double));
    for (int a = 0; a < D; ++a) {
      const double h = 1e-6;
      auto pp = p, pm = p;
      pp[a] += h;
      pm[a] -= h;
      const double fd = (value(pp) - value(pm)) / (2 * h);
      worst = std::fmax(worst, std::fabs(fd - analytic.gradient[a]) / (1 + std::fabs(fd)));
    }
  };
  for (int i = 0; i < 300; ++i) {
    const hush::dvec2 p2{r.uniform<double>(-50, 50), r.uniform<double>(-50, 50)};
    const hush::dvec3 p3{r.uniform<double>(-50, 50), r.uniform<double>(-50, 50),
                         r.uniform<double>(-50, 50)};
    fd_check([&](const hush::dvec2& p) { return g2(p); }, g2.gradient(p2), p2);
    fd_check([&](const hush::dvec2& p) { return g2.sample(p, fp2); }, g2.sample_gradient(p2, fp2),
             p2);
    fd_check([&](const hush::dvec3& p) { return g3(p); }, g3.gradient(p3), p3);
    fd_check([&](const hush::dvec3& p) { return g3.sample(p, fp3); }, g3.sample_gradient(p3, fp3),
             p3);
    fd_check([&](const hush::dvec3& p) { return g3.sample(p, nrm, fp3); },
             g3.sample_gradient(p3, nrm, fp3), p3);
  }
  // Central differences with h = 1e-6: O(h^2 |n'''|) ~ 1e-10 plus rounding 1e-16 / h.
  CHECK(worst < 1e-6);
}

TEST_CASE("gabor: float evaluation stays within the stated budget of the double reference") {
  // Budget (gabor.hpp, docs/gabor.md): each of the <= 3^D max_count kernels
  // is within 2^-21 (1 + 2 pi |Phi|) of its double value (gabor_kernel_test);
  // their float sum adds one rounding of the running sum per term; times the
  // scale. The kernels' errors are independent, so the RMS grows like the
  // square root of the count; the stated bound is the worst case over the
  // ~N' kernels within reach of a point: scale 2^-21 (1 + 2 pi Phi) (N' + 1).
  hush::rng r(12);
  for (const gabor_kind kind : {gabor_kind::isotropic, gabor_kind::anisotropic}) {
    const hush::gabor<2> g(make_params<2>(kind));
    const double phi = g.marks().phi0();
    const double budget =
        g.scale() * std::ldexp(1.0, -21) * (1 + 2 * kPi * phi) * (g.parameters().impulses + 1);
    double worst = 0, sum2 = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double extent = i % 2 ? 100.0 : 1e6;
      const hush::vec2 pf{r.uniform<float>(-1, 1) * float(extent),
                          r.uniform<float>(-1, 1) * float(extent)};
      const double e = std::fabs(g(pf) - g(hush::vec_cast<double>(pf)));
      worst = std::fmax(worst, e);
      sum2 += e * e;
    }
    MESSAGE("kind " << static_cast<int>(kind) << ": max |float - double| " << worst << ", RMS "
                    << std::sqrt(sum2 / n) << ", budget " << budget);
    CHECK(worst <= budget);
  }
}

namespace {
// Each form's error per kernel, relative to its weight (|w| < 1), against the
// exact kernel at the same float offsets d (u = 2^-24; gabor_kernel.hpp; the
// offsets' own rounding is in the budget above, the same for both forms):
// point form w e^{-A s} cos(2 pi theta) tau: s = |d|^2 in D roundings and -A s
// in one move exp's argument by <= (D + 1) A u (a relative error of e), exp
// 2^-22, theta = <phi, d> in 2D - 1 roundings moves the cos by <= 2 pi D |Phi| u,
// cos 2^-23, the taper and the three products <= 6 u. Grid form: D exps (2^-22
// each, arguments moved by <= 2 A u together) and D sin/cos (2^-23 each, phases
// by <= 2 pi D |Phi| u), the products of the factors <= 4 D u.
double point_form_error(int dim, double a, double phi) {
  const double u = std::ldexp(1.0, -24);
  return std::ldexp(1.0, -22) + std::ldexp(1.0, -23) + u * ((dim + 1) * a + 2 * kPi * dim * phi + 6);
}
double grid_form_error(int dim, double a, double phi) {
  const double u = std::ldexp(1.0, -24);
  return dim * (std::ldexp(1.0, -22) + std::ldexp(1.0, -23)) +
         u * (2 * a + 2 * kPi * dim * phi + 4 * dim);
}

template <int D>
void check_forms(const hush::gabor<D>& g, std::uint32_t seed) {
  const double phi = g.marks().phi0() + g.marks().dphi(), a = g.kernel().envelope_exponent();
  const double kernels = g.parameters().impulses + 1;  // as the budget above counts them
  const double budget = g.scale() * std::ldexp(1.0, -21) * (1 + 2 * kPi * phi) * kernels;
  const double apart =
      g.scale() * (point_form_error(D, a, phi) + grid_form_error(D, a, phi)) * kernels;
  hush::rng r(seed);
  double worst_point = 0, worst_grid = 0, worst_apart = 0;
  for (int i = 0; i < 3000; ++i) {
    const double extent = i % 2 ? 50.0 : 1e5;
    hush::vec<float, D> pf;
    for (int k = 0; k < D; ++k) pf[k] = r.uniform<float>(-1, 1) * float(extent);
    const hush::vec<double, D> pd = hush::vec_cast<double>(pf);
    const double ref = g.template value<double>(pd);
    const double point = g.template value<float>(pd);
    const double grid = g.template grid_sample<float>(pd).value;
    worst_point = std::fmax(worst_point, std::fabs(point - ref));
    worst_grid = std::fmax(worst_grid, std::fabs(grid - ref));
    worst_apart = std::fmax(worst_apart, std::fabs(grid - point));
  }
  MESSAGE(D << "D kind " << static_cast<int>(g.marks().kind()) << ": max |point - double| "
            << worst_point << ", |grid - double| " << worst_grid << " (budget " << budget
            << "), |grid - point| " << worst_apart << " (bound " << apart << ")");
  CHECK(worst_point <= budget);
  CHECK(worst_grid <= budget);
  CHECK(worst_apart <= apart);
  CHECK(worst_apart > 0.0);  // two forms indeed: the bound is not vacuous
}
}  // namespace

TEST_CASE("gabor: points (point form) and grid samples (separable form) stay within their bounds") {
  for (const gabor_kind kind : {gabor_kind::isotropic, gabor_kind::hybrid}) {
    check_forms(hush::gabor<2>(make_params<2>(kind)), 31);
    check_forms(hush::gabor<3>(make_params<3>(kind)), 32);
  }
}

TEST_CASE("gabor: a point footprint evaluates the unfiltered noise, filtering is continuous") {
  const hush::gabor<2> g(make_params<2>(gabor_kind::isotropic));
  hush::rng r(13);
  for (int i = 0; i < 200; ++i) {
    const hush::dvec2 p{r.uniform<double>(-20, 20), r.uniform<double>(-20, 20)};
    CHECK(g.sample(p, hush::footprint<2>{}) == doctest::Approx(g(p)).epsilon(1e-13).scale(1.0));
    // Shrinking footprints converge to the point value; growing ones to the mean 0.
    const double v = g(p);
    CHECK(std::fabs(g.sample(p, hush::footprint<2>::isotropic(1e-6)) - v) < 1e-6);
    CHECK(std::fabs(g.sample(p, hush::footprint<2>::isotropic(1e-3)) - v) < 1e-3 * 10);
    CHECK(std::fabs(g.sample(p, hush::footprint<2>::isotropic(1e3))) < 1e-3);
  }
}

TEST_CASE(
    "gabor: NaN and infinite positions give NaN, huge ones stay finite (HARD_CASES 1, 3, 5)") {
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  const hush::gabor<2> g2(make_params<2>(gabor_kind::isotropic));
  const hush::gabor<3> g3(make_params<3>(gabor_kind::anisotropic));
  for (const float bad : {nan, inf, -inf}) {
    CHECK(std::isnan(g2(hush::vec2{bad, 0.5f})));
    CHECK(std::isnan(g2(hush::vec2{0.5f, bad})));
    const auto vg = g3.gradient(hush::vec3{0.5f, 0.25f, bad});
    CHECK(std::isnan(vg.value));
    CHECK(std::isnan(vg.gradient.x));
    CHECK(std::isnan(g3.sample(hush::vec3{bad, 0, 0}, hush::vec3{0, 0, 1})));
    CHECK(std::isnan(g2.sample(hush::vec2{bad, 0}, hush::footprint<2>::isotropic(0.1f))));
  }
  CHECK(std::isnan(g3.sample(hush::vec3{1, 2, 3}, hush::vec3{nan, 0, 1})));
  const float big = std::numeric_limits<float>::max();
  for (const float x : {-1.0f, -0.0f, std::nextafter(-1.0f, 0.0f), 4.9999998f, 8388607.5f,
                        8388608.5f, 16777216.0f, -16777216.0f, 1e6f, 1e20f, big, -big, 1e-40f}) {
    const float v = g2(hush::vec2{x, 0.3f});
    CHECK(std::isfinite(v));
    CHECK(std::fabs(v) <= g2.bound());
    CHECK(std::isfinite(g3(hush::vec3{x, x, 0.3f})));
  }
  for (const double x : {2147483648.0, 9007199254740992.0, 1e300, -1e300})
    CHECK(std::isfinite(g2(hush::dvec2{x, -x})));
  // A zero normal evaluates the solid noise.
  CHECK(g3.sample(hush::vec3{1, 2, 3}, hush::vec3{0, 0, 0}) ==
        g3.sample(hush::vec3{1, 2, 3}, hush::footprint<3>{}));
}

TEST_CASE("gabor: continuous across cell boundaries and truncation circles (HARD_CASES row 2)") {
  // Along lines through the origin, across cell planes: consecutive values
  // 1e-7 apart differ by the derivative times the step, to second order.
  const hush::gabor<2> g(make_params<2>(gabor_kind::anisotropic));
  const double r = g.kernel().radius(), h = 1e-7;
  double worst = 0;
  for (int k = -20; k <= 20; ++k)
    for (const double dir : {0.0, 0.25 * kPi, 1.0}) {
      const hush::dvec2 u{std::cos(dir), std::sin(dir)};
      const double t = k * r;  // crosses the cell planes x = k r (dir 0) and others
      const hush::dvec2 a{t * u.x - 0.5 * h * u.x, t * u.y - 0.5 * h * u.y};
      const hush::dvec2 b{a.x + h * u.x, a.y + h * u.y};
      const auto ga = g.gradient(a);
      const double slope = ga.gradient.x * u.x + ga.gradient.y * u.y;
      worst = std::fmax(worst, std::fabs(g(b) - g(a) - slope * h));
    }
  CHECK(worst < 1e-11);  // O(h^2 |n''|) with |n''| ~ 100
}

TEST_CASE(
    "gabor: degenerate footprints give finite values tending to the mean (HARD_CASES row 12)") {
  const hush::gabor<2> g2(make_params<2>(gabor_kind::isotropic));
  const hush::gabor<3> g3(make_params<3>(gabor_kind::hybrid));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const hush::footprint<3> fps[] = {
      hush::footprint<3>{},
      hush::footprint<3>::from_derivatives(hush::dvec3{0.2, 0.1, 0}, hush::dvec3{0, 0, 0}),
      hush::footprint<3>::from_derivatives(hush::dvec3{1e-15, 0, 0}, hush::dvec3{0, 1e-15, 0}),
      hush::footprint<3>::from_derivatives(hush::dvec3{1e15, 0, 0}, hush::dvec3{0, 1e15, 0}),
      hush::footprint<3>::from_derivatives(hush::dvec3{nan, 0, 0}, hush::dvec3{0, 1, 0})};
  hush::rng r(16);
  for (int i = 0; i < 50; ++i) {
    const hush::dvec3 p{r.uniform<double>(-9, 9), r.uniform<double>(-9, 9),
                        r.uniform<double>(-9, 9)};
    for (const auto& fp : fps) {
      const auto v = g3.sample_gradient(hush::vec_cast<float>(p), fp);
      CHECK(std::isfinite(v.value));
      CHECK(std::isfinite(v.gradient.x));
      const auto s = g3.sample_gradient(hush::vec_cast<float>(p), hush::vec3{0.f, 0.6f, 0.8f}, fp);
      CHECK(std::isfinite(s.value));
      CHECK(std::isfinite(s.gradient.z));
    }
    // The widest footprints filter everything: the mean.
    CHECK(std::fabs(g3.sample(p, fps[3])) < 1e-12);
    CHECK(std::fabs(g3.sample(p, fps[4])) < 1e-12);
    CHECK(std::fabs(g2.sample(hush::dvec2{p.x, p.y}, hush::footprint<2>::isotropic(nan))) < 1e-12);
  }
}

TEST_CASE("gabor: the observed range stays within bound() (HARD_CASES row 6)") {
  const hush::gabor<2> g(make_params<2>(gabor_kind::anisotropic));
  hush::rng r(17);
  double worst = 0;
  for (int i = 0; i < 100000; ++i)
    worst = std::fmax(
        worst,
        std::fabs(g(hush::vec2{r.uniform<float>(-1e4f, 1e4f), r.uniform<float>(-1e4f, 1e4f)})));
  MESSAGE("max |n| over 1e5 points: " << worst << " (bound " << g.bound() << ")");
  CHECK(worst <= g.bound());
  CHECK(worst > 3.0);  // unit variance: 1e5 samples reach beyond 3 sigma
}

TEST_CASE(
    "gabor: every seed gives a field, nearby seeds are uncorrelated (HARD_CASES rows 4, 10)") {
  // Seed 1 against seed 0 over 500 independent points: |rho| <= 5 / sqrt(500).
  const hush::gabor<2> g0(make_params<2>(gabor_kind::isotropic, 0));
  double prev = 0;
  for (const std::uint32_t seed : {0U, 1U, 2U, 0x7FFFFFFFU, 0x80000000U, 0xFFFFFFFFU}) {
    const hush::gabor<2> g(make_params<2>(gabor_kind::isotropic, seed));
    double s = 0, sxy = 0;
    for (int i = 0; i < 500; ++i) {
      const hush::dvec2 x{i * 3.7, 0.5};
      const double v = g(x);
      s += v * v;
      if (seed == 1U) sxy += v * g0(x);
    }
    CHECK(s > 0);
    if (seed == 1U) CHECK(std::fabs(sxy / s) < 5.0 / std::sqrt(500.0));
    CHECK(s != prev);
    prev = s;
  }
}
