// hush::wavelet (include/hush/wavelet.hpp): evaluation against the definitions it states.
// Every statistical tolerance is derived from the sample size (formula beside it); fixed
// seeds. Band values are checked against an independent textbook evaluator of
// N(y) = sum_i n_i B(y - i) over the tile's coefficients.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "hush/hush.hpp"

namespace {

using hush::dvec2;
using hush::dvec3;

double textbook_b(double x) {
  x = std::fabs(x);
  if (x < 0.5) return 0.75 - x * x;
  if (x < 1.5) return 0.5 * (1.5 - x) * (1.5 - x);
  return 0;
}
int wrap(long long i, int n) {
  const long long r = i % n;
  return static_cast<int>(r < 0 ? r + n : r);
}
// N(y) over the periodic tile, 3D.
double band3(const hush::wavelet_tile<3>& t, const double (&y)[3]) {
  const int n = t.size();
  int lo[3];
  for (int a = 0; a < 3; ++a) lo[a] = static_cast<int>(std::floor(y[a] - 1.5));
  double s = 0;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const double w = textbook_b(y[0] - (lo[0] + i)) * textbook_b(y[1] - (lo[1] + j)) *
                         textbook_b(y[2] - (lo[2] + k));
        if (w == 0) continue;
        const std::size_t idx =
            static_cast<std::size_t>(wrap(lo[0] + i, n)) +
            static_cast<std::size_t>(n) *
                (static_cast<std::size_t>(wrap(lo[1] + j, n)) +
                 static_cast<std::size_t>(n) * static_cast<std::size_t>(wrap(lo[2] + k, n)));
        s += w * t.coefficient(idx);
      }
  return s;
}

template <int D>
hush::vec<double, D> random_point(hush::rng& r, double extent) {
  hush::vec<double, D> p;
  for (int a = 0; a < D; ++a) p[a] = r.uniform<double>(-extent, extent);
  return p;
}

template <int D>
typename hush::wavelet<D>::params small(std::uint32_t seed, int tile) {
  typename hush::wavelet<D>::params prm;
  prm.seed = seed;
  prm.tile_size = tile;
  return prm;
}

// Mean and variance of f over n random points in [-extent, extent)^D.
template <int D, class F>
std::pair<double, double> moments(F f, int n, double extent, std::uint32_t seed) {
  hush::rng r(seed, 77);
  double s = 0, s2 = 0;
  for (int i = 0; i < n; ++i) {
    const double v = f(random_point<D>(r, extent));
    s += v;
    s2 += v * v;
  }
  const double mean = s / n;
  return {mean, s2 / n - mean * mean};
}

// Central differences in double against the analytic gradient, relative tolerance tol.
template <int D, class F>
void check_gradient(F f, const hush::vec<double, D>& p, double tol) {
  const auto vg = f(p);
  const double h = 1e-6;
  for (int a = 0; a < D; ++a) {
    hush::vec<double, D> lo = p, hi = p;
    lo[a] -= h;
    hi[a] += h;
    const double fd = (f(hi).value - f(lo).value) / (2 * h);
    CAPTURE(a);
    CHECK(vg.gradient[a] == doctest::Approx(fd).epsilon(tol).scale(1.0));
  }
}

}  // namespace

TEST_CASE("wavelet: every bad parameter throws naming it and its valid range") {
  using P = hush::wavelet<2>::params;
  auto refuse = [](const P& p, const char* name) {
    CAPTURE(name);
    try {
      hush::wavelet<2> w{p};
      FAIL("accepted a bad " << name);
    } catch (const hush::invalid_argument& e) {
      const std::string m = e.what();
      CHECK(m.find(std::string("hush::wavelet: ") + name) == 0);
      CHECK(m.find("valid") != std::string::npos);
    }
  };
  P p;
  p.tile_size = 31;
  refuse(p, "tile_size");
  p = P{};
  p.first_band = 33;
  refuse(p, "first_band");
  p.first_band = 30;
  p.weights = {1, 1, 1, 1};
  refuse(p, "first_band");
  p = P{};
  p.weights = {};
  refuse(p, "weights.size()");
  p.weights.assign(33, 1.0);
  refuse(p, "weights.size()");
  p.weights = {1, std::nan("")};
  refuse(p, "weights[1]");
  p.weights = {0, 0};
  refuse(p, "weights are all zero");
  p = P{};
  p.offsets = {{0, 0}, {0, 0}};
  refuse(p, "offsets.size()");
  p.offsets = {{0, HUGE_VAL}};
  refuse(p, "offsets[0][1]");
  p = P{};
  p.gaussian_scale = 0;
  refuse(p, "gaussian_scale");
  p = P{};
  p.distribution = hush::wavelet_distribution::table;
  refuse(p, "table.size()");
  p.table = {0, std::nan("")};
  refuse(p, "table[1]");
  p = P{};
  p.relative_weights = true;
  p.relative_bands = 0;
  refuse(p, "relative_bands");
  p = P{};
  p.variant_overlap = 33;  // tile 128: at most 32
  refuse(p, "variant_overlap");
  p.variant_overlap = -1;
  refuse(p, "variant_overlap");
}

TEST_CASE("wavelet: the band is sum n_i B(y - i) over the tile, scaled to unit variance") {
  // With explicit zero offsets band 0 sits at y = x: noise(x) sqrt(sigma^2) = N(x).
  auto prm = small<3>(5, 16);
  prm.offsets = {{0, 0, 0}};
  const hush::wavelet<3> w{prm};
  hush::rng r(1);
  for (int i = 0; i < 200; ++i) {
    const dvec3 p = random_point<3>(r, 40);
    const double y[3] = {p[0], p[1], p[2]};
    CHECK(w(p) * std::sqrt(w.tile().variance()) ==
          doctest::Approx(band3(w.tile(), y)).epsilon(1e-13).scale(1e-13));
  }
}

TEST_CASE("wavelet: unit variance and zero mean over space, within 5 standard errors") {
  // N = 1e5 points spread over many tile periods are nearly independent; the sample
  // variance then has standard error sqrt(2 / N) = 0.45 %, the mean 1 / sqrt(N) = 0.32 %.
  // The spatial variance over a tile period is exactly 1 for one band; bands at other
  // scales add cross terms that average out over the tile.
  const int n = 100000;
  const double tol_var = 5 * std::sqrt(2.0 / n), tol_mean = 5 / std::sqrt(double(n));
  const hush::wavelet<2> w2{small<2>(1, 64)};
  auto m2 = moments<2>([&](const dvec2& p) { return w2(p); }, n, 512, 1);
  CHECK(m2.second == doctest::Approx(1).epsilon(tol_var));
  CHECK(std::fabs(m2.first) < tol_mean);
  const hush::wavelet<3> w3{small<3>(1, 32)};
  auto m3 = moments<3>([&](const dvec3& p) { return w3(p); }, n, 128, 2);
  CHECK(m3.second == doctest::Approx(1).epsilon(tol_var));
  CHECK(std::fabs(m3.first) < tol_mean);
  auto multi = small<2>(2, 64);
  multi.weights = {1, 0.5, 0.25, 0.125};
  multi.first_band = -1;
  const hush::wavelet<2> wm{multi};
  auto mm = moments<2>([&](const dvec2& p) { return wm(p); }, n, 1024, 3);
  CHECK(mm.second == doctest::Approx(1).epsilon(0.03));
  CHECK(std::fabs(mm.first) < tol_mean);
}

TEST_CASE("wavelet: analytic gradients match central differences in every mode") {
  hush::rng r(9);
  const double tol = 2e-4;  // central differences of a C1 piecewise quadratic, h = 1e-6
  {
    auto prm = small<2>(3, 32);
    prm.weights = {1, -0.5, 0.25};
    const hush::wavelet<2> w{prm};
    for (int i = 0; i < 50; ++i)
      check_gradient<2>([&](const dvec2& p) { return w.gradient(p); }, random_point<2>(r, 50), tol);
  }
  hush::footprint<3> fp = hush::footprint<3>::isotropic(0.7);
  for (auto proj : {hush::wavelet_projection::exact, hush::wavelet_projection::approximate})
    for (bool widen : {false, true}) {
      auto prm = small<3>(4, 16);
      prm.weights = {1, 0.5};
      prm.projection = proj;
      prm.widen = widen;
      const hush::wavelet<3> w{prm};
      for (const dvec3 nrm : {dvec3{0, 0, 1}, dvec3{0.3, -0.5, 0.8}, dvec3{1, 1, 1}})
        for (int i = 0; i < 6; ++i) {
          CAPTURE(nrm[0]);
          CAPTURE(widen);
          check_gradient<3>([&](const dvec3& p) { return w.sample_gradient(p, nrm, fp); },
                            random_point<3>(r, 20), tol);
        }
    }
  for (auto dist : {hush::wavelet_distribution::uniform, hush::wavelet_distribution::table}) {
    auto prm = small<3>(4, 16);
    prm.distribution = dist;
    prm.table = {-2, -1, 0.5, 3};
    prm.variant_overlap = 2;
    const hush::wavelet<3> w{prm};
    for (int i = 0; i < 20; ++i)
      check_gradient<3>([&](const dvec3& p) { return w.gradient(p); }, random_point<3>(r, 40), tol);
  }
}

TEST_CASE("wavelet: float evaluation stays within float_budget() of the double reference") {
  hush::rng r(11);
  auto prm = small<3>(6, 32);
  prm.weights = {1, 0.5, 0.25};
  const hush::wavelet<3> w{prm};
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const hush::vec3 p{r.uniform(-1000.0f, 1000.0f), r.uniform(-1000.0f, 1000.0f),
                       r.uniform(-1000.0f, 1000.0f)};
    worst = std::max(worst, std::fabs(double(w(p)) - w(hush::vec_cast<double>(p))));
  }
  MESSAGE("3D, 3 bands: max |float - double| = " << worst << ", budget " << w.float_budget());
  CHECK(worst <= w.float_budget());
  const hush::footprint<3> fp = hush::footprint<3>::isotropic(0.6);
  prm.widen = true;
  const hush::wavelet<3> ww{prm};
  worst = 0;
  for (int i = 0; i < 2000; ++i) {
    const hush::vec3 p{r.uniform(-100.0f, 100.0f), r.uniform(-100.0f, 100.0f),
                       r.uniform(-100.0f, 100.0f)};
    const hush::vec3 n{r.uniform(-1.0f, 1.0f), r.uniform(-1.0f, 1.0f), r.uniform(-1.0f, 1.0f)};
    worst = std::max(
        worst, std::fabs(double(ww.sample(p, n, fp)) -
                         ww.sample(hush::vec_cast<double>(p), hush::vec_cast<double>(n), fp)));
  }
  MESSAGE("projected + widened: max |float - double| = " << worst << ", budget "
                                                         << ww.float_budget(false));
  CHECK(worst <= ww.float_budget(false));
}

TEST_CASE("wavelet: far coordinates wrap on the tile exactly") {
  // One band repeats every tile_size / 2^first_band units, bit for bit where x and the
  // shifted x are both exact (float inputs far from the origin included).
  for (int first : {0, 2, -1}) {
    auto prm = small<2>(8, 32);
    prm.first_band = first;
    const hush::wavelet<2> w{prm};
    const float period = std::ldexp(32.0f, -first);
    hush::rng r(first + 20);
    for (int i = 0; i < 200; ++i) {
      // Far from the origin (1.5 * 2^20, 1/8 apart), every shift staying in the binade.
      const float far = 1.5f * std::ldexp(1.0f, 20);
      const float xs = far + std::round(r.uniform(0.0f, 256.0f) * 8) / 8;
      const float ys = std::round(r.uniform(-8.0f, 8.0f) * 16) / 16;
      CHECK(w(hush::vec2{xs, ys}) == w(hush::vec2{xs + period, ys}));
      CHECK(w(hush::vec2{xs, ys}) == w(hush::vec2{xs - 3 * period, ys + 5 * period}));
    }
  }
  // 3D, double positions near 2^27.
  const hush::wavelet<3> w3{small<3>(8, 16)};
  const double base = std::ldexp(1.0, 27);
  hush::rng r(5);
  for (int i = 0; i < 100; ++i) {
    const dvec3 p{base + std::round(r.uniform<double>(0, 1) * 256) / 256, 0.25, -3.5};
    CHECK(w3(p) == w3(dvec3{p[0] - 16 * 1024, p[1] + 16, p[2] - 160}));
  }
}

TEST_CASE("wavelet: NaN and infinite input, footprints and normals have their documented results") {
  const hush::wavelet<3> w{small<3>(1, 16)};
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = HUGE_VAL;
  for (const dvec3 p : {dvec3{nan, 0, 0}, dvec3{0, inf, 0}, dvec3{0, 0, -inf}}) {
    CHECK(std::isnan(w(p)));
    const auto g = w.gradient(p);
    CHECK(std::isnan(g.value));
    CHECK(std::isnan(g.gradient[0]));
    CHECK(std::isnan(w.sample(p, dvec3{0, 0, 1}, hush::footprint<3>::isotropic(0.5))));
  }
  const dvec3 p{1.25, -3.5, 7.75};
  // A footprint that covers everything (NaN, Inf, huge) gives the mean, 0.
  for (double width : {nan, inf, 1e300}) {
    CHECK(w.sample(p, hush::footprint<3>::isotropic(width)) == 0.0);
    CHECK(w.sample(p, dvec3{0, 0, 1}, hush::footprint<3>::isotropic(width)) == 0.0);
  }
  // A zero, NaN or infinite normal: the unprojected noise.
  const hush::footprint<3> none;
  for (const dvec3 n : {dvec3{0, 0, 0}, dvec3{nan, 0, 1}, dvec3{inf, 0, 0}})
    CHECK(w.sample(p, n, none) == w(p));
  // Any length: normalised (a power-of-two scale normalises to the same bits).
  for (const dvec3 n : {dvec3{0, 0, 1}, dvec3{0.25, -0.5, 1.5}}) {
    const double a = w.sample(p, n, none);
    CHECK(w.sample(p, dvec3{n[0] * 1024, n[1] * 1024, n[2] * 1024}, none) == a);
    CHECK(w.sample(p, dvec3{n[0] * 1e-200, n[1] * 1e-200, n[2] * 1e-200}, none) ==
          doctest::Approx(a).epsilon(1e-14));
    CHECK(w.sample(p, dvec3{-n[0], -n[1], -n[2]}, none) == doctest::Approx(a).epsilon(1e-14));
  }
  // A point footprint is point evaluation, bit for bit.
  CHECK(w.sample(p, none) == w(p));
}

TEST_CASE("wavelet: the exact projection is the line integral of the band along the normal") {
  // Brute force: integral N(y + t u) B2(t) dt by the midpoint rule over 6000 cells, with
  // the textbook band; B2(t) = B(t / 2) / 2. Then scaled like the noise.
  auto prm = small<3>(2, 16);
  prm.offsets = {{0, 0, 0}};
  const hush::wavelet<3> w{prm};
  hush::rng r(4);
  for (int i = 0; i < 12; ++i) {
    dvec3 u{r.uniform<double>(-1, 1), r.uniform<double>(-1, 1), r.uniform<double>(-1, 1)};
    if (i == 0) u = {0, 0, 1};
    if (i == 1) u = {1e-3, 0, 1};
    const double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (int a = 0; a < 3; ++a) u[a] /= len;
    const dvec3 p = random_point<3>(r, 30);
    double ref = 0;
    const int steps = 6000;
    for (int q = 0; q < steps; ++q) {
      const double t = -3 + 6.0 * (q + 0.5) / steps;
      const double y[3] = {p[0] + t * u[0], p[1] + t * u[1], p[2] + t * u[2]};
      ref += band3(w.tile(), y) * 0.5 * textbook_b(t / 2) * 6.0 / steps;
    }
    double sigma2 = 0;
    for (int a = 0; a < 3; ++a) sigma2 += u[a] * u[a] * w.tile().projected_variance(a, true);
    const double uu[3] = {u[0], u[1], u[2]};
    sigma2 *= hush::detail::wavelet_oblique_variance_ratio(uu);
    CAPTURE(i);
    CHECK(w.sample(p, u, hush::footprint<3>{}) * std::sqrt(sigma2) ==
          doctest::Approx(ref).scale(1.0).epsilon(2e-6));
  }
}

TEST_CASE("wavelet: projection is continuous as the normal leaves an axis") {
  // Axis-aligned normals take the separable kernels (beta, or the double-width B-spline),
  // others the general ones: at a tilt of 1e-9 both must agree.
  for (auto proj : {hush::wavelet_projection::exact, hush::wavelet_projection::approximate}) {
    auto prm = small<3>(3, 16);
    prm.projection = proj;
    const hush::wavelet<3> w{prm};
    hush::rng r(6);
    for (int i = 0; i < 50; ++i) {
      const dvec3 p = random_point<3>(r, 30);
      const auto a = w.sample_gradient(p, dvec3{0, 1, 0}, hush::footprint<3>{});
      const auto b = w.sample_gradient(p, dvec3{1e-9, 1, -1e-9}, hush::footprint<3>{});
      CHECK(b.value == doctest::Approx(a.value).scale(1.0).epsilon(1e-7));
      for (int c = 0; c < 3; ++c)
        CHECK(b.gradient[c] == doctest::Approx(a.gradient[c]).scale(1.0).epsilon(1e-6));
    }
  }
}

TEST_CASE("wavelet: the footprint keeps bands with c = 2^b w <= 1 and drops those with c >= 2") {
  auto prm = small<2>(7, 32);
  prm.weights = {1, 1, 1, 1};  // bands 0 ... 3
  const hush::wavelet<2> all{prm};
  std::vector<hush::wavelet<2>> single;
  for (int b = 0; b < 4; ++b) {
    auto one = prm;
    one.weights = {0, 0, 0, 0};
    one.weights[static_cast<std::size_t>(b)] = 1;
    single.emplace_back(one);
  }
  hush::rng r(8);
  // w = 1/4: bands 0 ... 2 have c <= 1, band 3 has c = 2.
  const auto fp = hush::footprint<2>::isotropic(0.25);
  for (int i = 0; i < 100; ++i) {
    const dvec2 p = random_point<2>(r, 100);
    // The single-band noises have scale 1/sigma, the sum 1/(2 sigma): compare raw sums.
    double kept = 0;
    for (int b = 0; b < 3; ++b) kept += single[static_cast<std::size_t>(b)](p);
    CHECK(all.sample(p, fp) * 2 == doctest::Approx(kept).epsilon(1e-12).scale(1e-12));
  }
  // Weights fade continuously in between: the value is continuous in the width.
  const dvec2 p{3.3, -7.1};
  double prev = all.sample(p, hush::footprint<2>::isotropic(0.1));
  double worst = 0;
  for (int s = 1; s <= 4000; ++s) {
    const double width = 0.1 * std::pow(2.0, 4.0 * s / 4000);  // 0.1 ... 1.6: 4 octaves
    const double v = all.sample(p, hush::footprint<2>::isotropic(width));
    worst = std::max(worst, std::fabs(v - prev));
    prev = v;
  }
  MESSAGE("largest step over 4000 width steps of 1/1000 octave: " << worst);
  CHECK(worst < 0.01);  // the quintic fade's slope (15/8 per octave) times 1/1000 octave
                        // times the band's range (~4): <= 0.0075
  CHECK(all.sample(p, hush::footprint<2>::isotropic(2.0)) == 0.0);  // every band dropped
}

TEST_CASE("wavelet: an anisotropic footprint is judged by its largest width") {
  const hush::wavelet<3> w{small<3>(2, 16)};
  const auto thin = hush::footprint<3>::from_derivatives(dvec3{0.6, 0, 0}, dvec3{0, 0.001, 0});
  const auto round = hush::footprint<3>::isotropic(0.6);
  hush::rng r(3);
  for (int i = 0; i < 20; ++i) {
    const dvec3 p = random_point<3>(r, 20);
    CHECK(w.sample(p, thin) == doctest::Approx(w.sample(p, round)).epsilon(1e-12));
  }
}

TEST_CASE("wavelet: infinite noise keeps unit variance at every zoom and is continuous") {
  auto prm = small<2>(4, 64);
  prm.relative_weights = true;
  prm.weights = {1, 0.7, 0.5, 0.35};
  prm.first_band = -6;
  prm.relative_bands = 16;
  const hush::wavelet<2> w{prm};
  const int n = 40000;
  const double tol = 5 * std::sqrt(2.0 / n) + 0.02;  // sampling + band cross terms
  for (double width : {0.013, 0.37, 5.0}) {
    const auto fp = hush::footprint<2>::isotropic(width);
    auto m = moments<2>([&](const dvec2& p) { return w.sample(p, fp); }, n, 4096 * width, 5);
    CAPTURE(width);
    CHECK(m.second == doctest::Approx(1).epsilon(tol));
  }
  double prev = w.sample(dvec2{1.5, 2.5}, hush::footprint<2>::isotropic(0.5)), worst = 0;
  for (int s = 1; s <= 2000; ++s) {
    const double v =
        w.sample(dvec2{1.5, 2.5}, hush::footprint<2>::isotropic(0.5 * std::pow(2.0, s / 1000.0)));
    worst = std::max(worst, std::fabs(v - prev));
    prev = v;
  }
  CHECK(worst < 0.05);
}

TEST_CASE("wavelet: tile variants remove the repetition and keep variance and smoothness") {
  auto prm = small<2>(3, 32);
  const hush::wavelet<2> plain{prm};
  prm.variant_overlap = 4;
  const hush::wavelet<2> varied{prm};
  hush::rng r(12);
  double cp = 0, cv = 0, vv = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const dvec2 p = random_point<2>(r, 2000);
    const dvec2 q{p[0] + 32, p[1]};
    cp += plain(p) * plain(q);
    cv += varied(p) * varied(q);
    vv += varied(p) * varied(p);
  }
  CHECK(cp / n == doctest::Approx(1).epsilon(5 * std::sqrt(2.0 / n)));  // the plain tile repeats
  // With variants the correlation at the tile period is that of independent fields:
  // |rho| < 5 / sqrt(n) (a few cells repeat a variant: 1 in 8 in 2D, so allow 1/8 + that).
  CHECK(std::fabs(cv / n) < 0.125 + 5 / std::sqrt(double(n)));
  CHECK(vv / n == doctest::Approx(1).epsilon(0.05));
  // C1 across cell borders (x = 28 k is a border): gradients match differences there.
  for (int k = -3; k <= 3; ++k)
    check_gradient<2>([&](const dvec2& p) { return varied.gradient(p); },
                      dvec2{28.0 * k + 0.01, 3.3}, 2e-4);
}

TEST_CASE("wavelet: distributions: uniform through erf, a user table, a Gaussian scale") {
  auto prm = small<2>(5, 64);
  prm.distribution = hush::wavelet_distribution::uniform;
  const hush::wavelet<2> u{prm};
  prm.distribution = hush::wavelet_distribution::table;
  prm.table = {-1, 1};  // the inverse CDF of U(-1, 1): the same as erf
  const hush::wavelet<2> t{prm};
  prm.distribution = hush::wavelet_distribution::gaussian;
  prm.gaussian_scale = 2.5;
  const hush::wavelet<2> g{prm};
  const hush::wavelet<2> base{small<2>(5, 64)};
  hush::rng r(14);
  const int n = 50000, bins = 10;
  int hist[bins] = {};
  for (int i = 0; i < n; ++i) {
    const dvec2 p = random_point<2>(r, 3000);
    const double v = u(p);
    REQUIRE(v > -1);
    REQUIRE(v < 1);
    CHECK(t(p) == doctest::Approx(v).scale(1.0).epsilon(1e-12));  // 2 Phi - 1 = erf(v / sqrt 2)
    CHECK(g(p) == doctest::Approx(2.5 * base(p)).epsilon(1e-15));
    ++hist[std::min(bins - 1, static_cast<int>((v + 1) / 2 * bins))];
  }
  // Each bin holds n / 10 in expectation; binomial sd sqrt(n 0.1 0.9) = 67; 5 sd = 335,
  // plus 2 % of n/10 for the tile's own deviation from a Gaussian distribution.
  for (int b = 0; b < bins; ++b) CHECK(std::fabs(hist[b] - n / bins) < 335 + 100);
}

TEST_CASE("wavelet: outputs never exceed bound() (HARD_CASES row 6)") {
  auto prm = small<3>(1, 16);
  prm.weights = {1, -0.5, 0.25};
  const hush::wavelet<3> w{prm};
  hush::rng r(15);
  double worst = 0;
  for (int i = 0; i < 100000; ++i) worst = std::max(worst, std::fabs(w(random_point<3>(r, 1e4))));
  MESSAGE("max |value| " << worst << " of bound " << w.bound());
  CHECK(worst <= w.bound());
}

TEST_CASE(
    "wavelet: hush::evaluate over samples is the scalar sample evaluation, element by element") {
  auto prm = small<3>(2, 16);
  prm.widen = true;
  const hush::wavelet<3> w{prm};
  std::vector<hush::vec3> pos, nrm;
  std::vector<hush::footprint<3>> fps;
  hush::rng r(16);
  for (int i = 0; i < 64; ++i) {
    pos.push_back({r.uniform(-9.0f, 9.0f), r.uniform(-9.0f, 9.0f), r.uniform(-9.0f, 9.0f)});
    nrm.push_back({r.uniform(-1.0f, 1.0f), r.uniform(-1.0f, 1.0f), r.uniform(-1.0f, 1.0f)});
    fps.push_back(hush::footprint<3>::isotropic(r.uniform(0.0, 1.5)));
  }
  std::vector<float> out(pos.size());
  std::vector<hush::vec3> grad(pos.size());
  hush::samples<3> s{pos, fps, nrm};
  hush::evaluate(w, hush::exec::scalar, s, out, grad);
  for (std::size_t i = 0; i < pos.size(); ++i) {
    const auto e = w.sample_gradient(pos[i], nrm[i], fps[i]);
    CHECK(out[i] == e.value);
    CHECK(grad[i][2] == e.gradient[2]);
  }
}

TEST_CASE("wavelet: weights beyond what a float evaluation carries are refused, naming them") {
  auto refused = [](std::vector<double> weights, const char* names) {
    hush::wavelet<2>::params prm;
    prm.tile_size = 16;
    prm.weights = std::move(weights);
    try {
      const hush::wavelet<2> w{prm};
      FAIL("accepted");
    } catch (const hush::invalid_argument& e) {
      CHECK(std::string(e.what()).find(names) != std::string::npos);
    }
  };
  refused({1e308, 1e308}, "weights[0]");
  refused({1, 1.01e30}, "weights[1]");
  refused({1e-200, -0.99e-30}, "weights are all below 1e-30");
  refused({0, 0}, "weights are all zero");
  hush::wavelet<2>::params prm;
  prm.tile_size = 16;
  // The extremes of the range: finite output in double and in float.
  for (const std::vector<double>& ws : {std::vector<double>{1e30, -1e30}, {1e-30, 1e-40}}) {
    prm.weights = ws;
    const hush::wavelet<2> w{prm};
    CHECK(std::isfinite(w(hush::dvec2{0.3, 0.7})));
    CHECK(std::isfinite(w(hush::vec2{0.3f, 0.7f})));
  }
}

TEST_CASE("wavelet: a normal's length never matters; zero and NaN normals give plain 3D noise") {
  const hush::wavelet<3> w{small<3>(5, 16)};
  const hush::dvec3 p{1.3, -2.1, 0.4};
  const hush::footprint<3> fp{};
  CHECK(w.sample(p, hush::dvec3{1e-300, 0, 0}, fp) == w.sample(p, hush::dvec3{1, 0, 0}, fp));
  CHECK(w.sample(p, hush::dvec3{1e300, 1e300, 0}, fp) == w.sample(p, hush::dvec3{1, 1, 0}, fp));
  CHECK(w.sample(p, hush::dvec3{0, -1e-310, 0}, fp) == w.sample(p, hush::dvec3{0, -1, 0}, fp));
  // float normals (hush::samples): denormal and near-FLT_MAX lengths
  CHECK(w.sample(hush::vec3{1.3f, -2.1f, 0.4f}, hush::vec3{1e-40f, 0, 0}) ==
        w.sample(hush::vec3{1.3f, -2.1f, 0.4f}, hush::vec3{1, 0, 0}));
  CHECK(w.sample(hush::vec3{1.3f, -2.1f, 0.4f}, hush::vec3{3e38f, 3e38f, 0}) ==
        w.sample(hush::vec3{1.3f, -2.1f, 0.4f}, hush::vec3{1, 1, 0}));
  const double plain = w.sample(p, fp);
  CHECK(w.sample(p, hush::dvec3{0, 0, 0}, fp) == plain);
  CHECK(w.sample(p, hush::dvec3{std::nan(""), 1, 0}, fp) == plain);
  CHECK(w.sample(p, hush::dvec3{HUGE_VAL, 1, 0}, fp) == plain);
}
