// Tests for hush/fractal.hpp: fBm and turbulence over Perlin bands.
// Includes only the umbrella header so the same file also runs against the
// single header (tests/single_header).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hush/hush.hpp"
#include "test_util.hpp"

namespace {

template <int D>
using fractal = hush::fractal<hush::perlin<D>>;

using hush_test::random_point;

template <int D>
typename fractal<D>::params make_params(std::uint32_t seed, int octaves) {
  typename fractal<D>::params prm;
  prm.seed = seed;
  prm.octaves = octaves;
  return prm;
}

}  // namespace

TEST_CASE_TEMPLATE("fractal: unit_variance fBm has mean 0 and variance 1 over space and seeds", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Bands are independent fields, so Var = sigma^2 sum w_i^2 exactly, and the
  // normalisation divides it out. Points uniform in a large box are nearly
  // independent (correlation length: one band-0 cell); the tolerances are five
  // standard errors: mean sqrt(m2/n), second moment sqrt((m4 - m2^2)/n).
  struct setup {
    int octaves;
    double gain;
    std::vector<double> weights;
  };
  const setup setups[] = {{1, 0.5, {}}, {4, 0.5, {}}, {8, 0.7, {}}, {3, 0.5, {1.0, -2.0, 0.5}}};
  for (const setup& su : setups) {
    const int seeds = 100, per_seed = 1000;
    const double n = double(seeds) * per_seed;
    double s1 = 0, s2 = 0, s4 = 0;
    hush::rng r(3, static_cast<std::uint32_t>(su.octaves));
    for (int s = 0; s < seeds; ++s) {
      auto prm = make_params<D>(static_cast<std::uint32_t>(s), su.octaves);
      prm.gain = su.gain;
      prm.weights = std::vector<double>(su.weights);  // a move: GCC 12 warns falsely on copy
      const fractal<D> f(prm);
      CHECK(f.variance() == doctest::Approx(1.0));
      for (int i = 0; i < per_seed; ++i) {
        const double v = f.template value<float>(random_point<D>(r, 1e4));
        s1 += v, s2 += v * v, s4 += v * v * v * v;
      }
    }
    const double mean = s1 / n, m2 = s2 / n, m4 = s4 / n;
    INFO("octaves " << su.octaves << " gain " << su.gain);
    CHECK(std::fabs(mean) <= 5 * std::sqrt(m2 / n));
    CHECK(std::fabs(m2 - 1.0) <= 5 * std::sqrt((m4 - m2 * m2) / n));
  }
}

TEST_CASE_TEMPLATE("fractal: outputs stay within bound(), unit_range within -1 ... 1", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  const double float_slack = std::ldexp(1.0, -15);  // 2^-16 per band, summed weights <= 2
  auto prm = make_params<D>(5, 6);
  const fractal<D> fbm_var(prm);
  prm.norm = hush::normalization::unit_range;
  const fractal<D> fbm_range(prm);
  prm.kind = hush::fractal_kind::turbulence;
  const fractal<D> turb(prm);
  CHECK(fbm_range.bound() == doctest::Approx(1.0));
  CHECK(turb.bound() == doctest::Approx(1.0));
  // unit_variance bound: sum|w| / (sigma sqrt(sum w^2)).
  double sa = 0, sq = 0;
  for (int i = 0; i < 6; ++i) sa += std::pow(0.5, i), sq += std::pow(0.25, i);
  CHECK(fbm_var.bound() == doctest::Approx(sa / std::sqrt(hush::perlin<D>::variance() * sq)));
  hush::rng r(7, D);
  double max_var = 0, max_range = 0, min_turb = 1, max_turb = 0;
  for (int i = 0; i < 1000000; ++i) {
    const auto x = random_point<D>(r, 1000.0);
    max_var = std::max(max_var, std::fabs(double(fbm_var.template value<float>(x))));
    max_range = std::max(max_range, std::fabs(double(fbm_range.template value<float>(x))));
    const double t = turb.template value<float>(x);
    min_turb = std::min(min_turb, t), max_turb = std::max(max_turb, t);
  }
  MESSAGE("fractal" << D << "d over 1e6 points: max |fbm| " << max_var << " (bound "
                    << fbm_var.bound() << "), max |fbm unit_range| " << max_range
                    << ", turbulence in [" << min_turb << ", " << max_turb << "]");
  CHECK(max_var <= fbm_var.bound() * (1 + float_slack));
  CHECK(max_range <= 1.0 + float_slack);
  CHECK(min_turb >= 0.0);
  CHECK(max_turb <= 1.0 + float_slack);
}

TEST_CASE_TEMPLATE("fractal: band weights act linearly and zero-weight bands contribute nothing", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  auto one = make_params<D>(9, 1);
  one.norm = hush::normalization::none;
  const fractal<D> band0(one);
  auto three = make_params<D>(9, 3);
  three.norm = hush::normalization::none;
  three.weights = {2.5, 0.0, 0.0};
  const fractal<D> weighted(three);
  hush::rng r(11, D);
  for (int i = 0; i < 1000; ++i) {
    const auto x = random_point<D>(r, 100.0);
    CHECK(weighted(x) == doctest::Approx(2.5 * band0(x)).epsilon(1e-14));
  }
  CHECK(weighted.band_frequency(2) == 4.0);
  CHECK(weighted.band_weight(1) == 0.0);
}

TEST_CASE_TEMPLATE("fractal: gradient() matches central differences", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // fBm is C2: central differences with h = 1e-6 at band frequencies up to 32
  // have truncation error ~ h^2 f^3 |n'''| / 6 < 1e-5 and rounding 2 eps B / h < 1e-8.
  auto prm = make_params<D>(13, 6);
  const fractal<D> f(prm);
  prm.kind = hush::fractal_kind::turbulence;
  prm.norm = hush::normalization::unit_range;
  const fractal<D> t(prm);
  hush::rng r(17, D);
  const double h = 1e-6;
  double worst_fbm = 0, worst_turb = 0;
  for (int i = 0; i < 5000; ++i) {
    const auto x = random_point<D>(r, 50.0);
    const auto g = f.gradient(x), gt = t.gradient(x);
    CHECK(g.value == f(x));
    CHECK(gt.value == doctest::Approx(t(x)).epsilon(1e-15));
    for (int a = 0; a < D; ++a) {
      auto lo = x, hi = x;
      lo[a] -= h, hi[a] += h;
      worst_fbm = std::max(worst_fbm, std::fabs((f(hi) - f(lo)) / (2 * h) - g.gradient[a]));
      // Turbulence has creases where a band crosses zero; a crease inside
      // [x - h, x + h] is rare (probability ~ h * density) and shows as a large
      // mismatch, so compare with the one-sided differences too.
      const double c = (t(hi) - t(lo)) / (2 * h), l = (t(x) - t(lo)) / h, u = (t(hi) - t(x)) / h;
      const double e = std::min({std::fabs(c - gt.gradient[a]), std::fabs(l - gt.gradient[a]),
                                 std::fabs(u - gt.gradient[a])});
      worst_turb = std::max(worst_turb, e);
    }
  }
  CHECK(worst_fbm <= 1e-5);
  CHECK(worst_turb <= 1e-3);
}

TEST_CASE_TEMPLATE("fractal: periodic sums repeat every period / frequency", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  auto prm = make_params<D>(21, 4);
  prm.frequency = 0.25;  // band 0 has 4 units per cell
  prm.period[0] = 3;     // so the sum repeats every 12 units along x
  const fractal<D> f(prm);
  hush::rng r(23, D);
  for (int i = 0; i < 2000; ++i) {
    hush::vec<double, D> x;  // dyadic, so x and x + 12 are exact
    for (int a = 0; a < D; ++a) x[a] = std::ldexp(std::floor(r.uniform<double>(-8192, 8192)), -7);
    auto y = x;
    y[0] += 12.0;
    CHECK(f(x) == doctest::Approx(f(y)).epsilon(1e-12));
  }
}

TEST_CASE("fractal: bad parameters are rejected with a message naming them") {
  using F = fractal<2>;
  auto expect = [](F::params prm, const char* fragment) {
    CHECK_THROWS_AS(F{prm}, hush::invalid_argument);
    CHECK_THROWS_WITH(F{prm}, doctest::Contains(fragment));
  };
  auto prm = make_params<2>(0, 5);
  prm.octaves = 0;
  expect(prm, "octaves = 0 is out of range; valid: 1 ... 32");
  prm.octaves = 33;
  expect(prm, "octaves = 33");
  prm = make_params<2>(0, 5);
  prm.lacunarity = 1.0;
  expect(prm, "lacunarity = 1 is out of range; valid: 1 < lacunarity <= 16");
  prm.lacunarity = std::nan("");
  expect(prm, "lacunarity = nan");
  prm = make_params<2>(0, 5);
  prm.frequency = 0;
  expect(prm, "frequency = 0");
  prm.frequency = INFINITY;
  expect(prm, "frequency = inf");
  prm = make_params<2>(0, 5);
  prm.gain = -0.5;
  expect(prm, "gain = -0.5");
  prm.gain = 1e-80;  // gain^4 underflows below 1e-300
  expect(prm, "gain^(octaves-1)");
  prm = make_params<2>(0, 3);
  prm.weights = {1.0, 2.0};
  expect(prm, "weights.size() = 2");
  prm.weights = {0.0, 0.0, 0.0};
  expect(prm, "weights are all zero");
  prm.weights = {1.0, NAN, 0.0};
  expect(prm, "weights[1] = nan");
  prm.weights = {1.0, 2e30, 0.0};  // beyond what a float evaluation carries
  expect(prm, "weights[1]");
  prm = make_params<2>(0, 21);
  prm.gain = 256;  // gain^20 = 1.5e48
  expect(prm, "gain = 256");
  prm = make_params<2>(0, 3);
  prm.kind = hush::fractal_kind::turbulence;
  expect(prm, "unit_variance is not available for turbulence");
  prm = make_params<2>(0, 3);
  prm.period = {4, -1};
  expect(prm, "period[1] = -1");
  prm.period = {4, 0};
  prm.lacunarity = 2.5;
  expect(prm, "an integer (2 ... 16) when a period is set");
  prm.lacunarity = 16;
  prm.octaves = 8;
  prm.period = {1 << 20, 0};
  expect(prm, "period * lacunarity^(octaves-1) <= 2147483647");
}

// The weights' range (detail/constants.hpp kMaxBandWeight, kMinLargestBandWeight) is what a
// float evaluation carries: at its ends, under every normalisation, values stay finite.
TEST_CASE("fractal: band weights at the ends of their range give finite values in float") {
  for (hush::normalization norm :
       {hush::normalization::unit_variance, hush::normalization::unit_range,
        hush::normalization::none})
    for (const std::vector<double>& ws :
         {std::vector<double>{1e30, -1e30, 1e30}, {1e-30, 1e-45, 0.0}}) {
      auto prm = make_params<2>(3, 3);
      prm.weights = ws;
      prm.norm = norm;
      const fractal<2> f(prm);
      CHECK(std::isfinite(f.bound()));
      hush::rng r(31);
      for (int i = 0; i < 200; ++i) {
        const auto x = random_point<2>(r, 100.0);
        const float v = f(hush::vec_cast<float>(x));
        INFO("norm " << int(norm) << " weights[0] " << ws[0] << " at " << x[0] << ", " << x[1]);
        CHECK(std::isfinite(v));
        CHECK(std::fabs(double(v)) <= f.bound() * (1 + 1e-5));
      }
    }
}

TEST_CASE(
    "fractal: a value type: default-constructible, copies evaluate identically, seeds differ") {
  const fractal<2> d;  // the documented defaults
  CHECK(d.parameters().octaves == 5);
  CHECK(d.variance() == doctest::Approx(1.0));
  const fractal<3> a(make_params<3>(1, 5));
  const fractal<3> b = a;
  const fractal<3> c(make_params<3>(2, 5));
  int differ = 0;
  hush::rng r(29);
  for (int i = 0; i < 100; ++i) {
    const auto x = random_point<3>(r, 10.0);
    CHECK(a(x) == b(x));
    differ += a(x) != c(x);
  }
  CHECK(differ == 100);
}
