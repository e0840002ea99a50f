// Tests for hush/perlin.hpp: improved Perlin noise in 2D and 3D.
// Includes only the umbrella header so the same file also runs against the
// single header (tests/single_header).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "hush/hush.hpp"
#include "test_util.hpp"

namespace {

using hush_test::kDoubleBudget;
using hush_test::kFloatBudget;
using hush_test::lipschitz_bound;

constexpr double kPi = 3.14159265358979323846;

using hush_test::random_point;

template <int D>
hush::vec<double, D> offset(hush::vec<double, D> p, int axis, double h) {
  p[axis] += h;
  return p;
}

// sup over gradient choices of sum_i w_i(f) g_i.(f - c_i) at a position f in
// the unit cell: each corner independently takes the gradient that maximises
// its term. This is the adversarial bound the output scale is derived from.
template <int D>
double adversarial_sum(const hush::vec<double, D>& f) {
  namespace c = hush::detail::constants;
  double total = 0;
  for (int n = 0; n < (1 << D); ++n) {
    double w = 1, best = -1e300;
    double d[3] = {0, 0, 0};
    for (int a = 0; a < D; ++a) {
      const int bit = (n >> a) & 1;
      const double s = hush::detail::fade(f[a]);
      w *= bit ? s : 1 - s;
      d[a] = f[a] - bit;
    }
    const int count = D == 2 ? c::kPerlin2GradCount : c::kPerlin3GradCount;
    for (int k = 0; k < count; ++k) {
      const double dot = D == 2 ? c::kPerlin2GradX[k] * d[0] + c::kPerlin2GradY[k] * d[1]
                                : c::kPerlin3GradX[k] * d[0] + c::kPerlin3GradY[k] * d[1] +
                                      c::kPerlin3GradZ[k] * d[2];
      best = std::max(best, dot);
    }
    total += w * best;
  }
  return total * (D == 2 ? c::kPerlin2Scale : c::kPerlin3Scale);
}

}  // namespace

TEST_CASE_TEMPLATE("perlin: the scale maps the adversarial bound onto exactly 1", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // The output scale is 1/B with B the maximum over the cell of the adversarial
  // sum (constants.hpp). Re-derive B: scan the octant [0, 1/2]^D (the sum is
  // symmetric under x -> 1 - x per axis), then refine the best point by a
  // shrinking pattern search. The scaled maximum must be 1 to 1e-12, and no
  // scanned point may exceed it.
  const int steps = D == 2 ? 200 : 40;
  double peak = 0;
  hush::vec<double, D> arg{};
  hush::vec<double, D> f{};
  int total = 1;
  for (int a = 0; a < D; ++a) total *= steps + 1;
  for (int idx = 0; idx < total; ++idx) {
    int rest = idx;
    for (int a = 0; a < D; ++a, rest /= steps + 1) f[a] = 0.5 * (rest % (steps + 1)) / steps;
    const double v = adversarial_sum<D>(f);
    if (v > peak) peak = v, arg = f;
  }
  CHECK(peak <= 1.0 + 1e-12);
  for (double h = 0.5 / steps; h > 1e-13;) {
    bool improved = false;
    for (int m = 0; m < (D == 2 ? 9 : 27); ++m) {
      auto q = arg;
      for (int a = 0, rest = m; a < D; ++a, rest /= 3) q[a] += (rest % 3 - 1) * h;
      const double v = adversarial_sum<D>(q);
      if (v > peak) peak = v, arg = q, improved = true;
    }
    if (!improved) h *= 0.5;
  }
  CHECK(peak == doctest::Approx(1.0).epsilon(1e-12));
  if (D == 2) {  // 2D: the maximum is the cell centre
    for (int a = 0; a < D; ++a) CHECK(arg[a] == doctest::Approx(0.5).epsilon(1e-6));
  }
}

TEST_CASE_TEMPLATE("perlin: |noise| <= 1 over 1e6 random points", N, std::integral_constant<int, 2>,
                   std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Float rounding may exceed the exact bound slightly; the contract allows
  // the float error budget (see the float-vs-double test).
  hush::rng r(2024, D);
  double max_f = 0, max_d = 0;
  for (int s = 0; s < 100; ++s) {
    const hush::perlin<D> p(static_cast<std::uint32_t>(s * 7919));
    for (int i = 0; i < 10000; ++i) {
      const auto x = random_point<D>(r, 1000.0);
      max_d = std::max(max_d, std::fabs(p(x)));
      max_f = std::max(max_f, double(std::fabs(p.template value<float>(x))));
    }
  }
  MESSAGE("perlin" << D << "d max |noise| over 1e6 points: " << max_d);
  CHECK(max_d <= 1.0);
  CHECK(max_f <= 1.0 + kFloatBudget);
}

TEST_CASE("perlin: the 2D bound is reached where all four gradients aim at the centre") {
  // With probability 8^-4 per cell all corner gradients point at the centre;
  // there the noise is exactly +-1. 2e5 cells contain ~50 such cells.
  const hush::perlin<2> p(1);
  double max_centre = 0;
  for (int i = 0; i < 200000; ++i)
    max_centre = std::max(max_centre, std::fabs(p(hush::dvec2{i % 512 + 0.5, i / 512 + 0.5})));
  CHECK(max_centre == doctest::Approx(1.0).epsilon(1e-12));
}

TEST_CASE_TEMPLATE("perlin: mean 0 and variance() over space and seeds", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Points uniform over a large box: pairs closer than one cell (the noise's
  // correlation length) are rare, so samples are close to independent and the
  // standard errors below hold.
  const int kSeeds = 200, kPerSeed = 2000;
  const double n = double(kSeeds) * kPerSeed;
  hush::rng r(99, D);
  double s1 = 0, s2 = 0, s4 = 0;
  for (int s = 0; s < kSeeds; ++s) {
    const hush::perlin<D> p(static_cast<std::uint32_t>(s));
    for (int i = 0; i < kPerSeed; ++i) {
      const double v = p.template value<float>(random_point<D>(r, 1e4));
      s1 += v, s2 += v * v, s4 += v * v * v * v;
    }
  }
  const double mean = s1 / n, m2 = s2 / n, m4 = s4 / n;
  const double sigma2 = hush::perlin<D>::variance();
  // Standard errors: mean sqrt(m2 / n); second moment sqrt((m4 - m2^2) / n).
  CHECK(std::fabs(mean) <= 5 * std::sqrt(m2 / n));
  CHECK(std::fabs(m2 - sigma2) <= 5 * std::sqrt((m4 - m2 * m2) / n));
}

TEST_CASE_TEMPLATE("perlin: float evaluation is within 2^-16 of the double reference", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // |float - double| <= kFloatBudget for values; gradients' terms reach the
  // Lipschitz bound, so their budget is kFloatBudget * (1 + lipschitz).
  const double kValueBudget = kFloatBudget;
  const double kGradBudget = kFloatBudget * (1 + lipschitz_bound<D>());
  hush::rng r(5, D);
  double max_v = 0, max_g = 0, sum_sq = 0;
  const int count = 1000000;
  const hush::perlin<D> p(3);
  for (int i = 0; i < count; ++i) {
    const auto x = random_point<D>(r, i < count / 2 ? 100.0 : 1e6);
    const double err = std::fabs(double(p.template value<float>(x)) - p.template value<double>(x));
    max_v = std::max(max_v, err);
    sum_sq += err * err;
    if (i % 10 == 0) {
      const auto gf = p.template value_and_gradient<float>(x);
      const auto gd = p.template value_and_gradient<double>(x);
      for (int a = 0; a < D; ++a)
        max_g = std::max(max_g, std::fabs(double(gf.gradient[a]) - gd.gradient[a]));
    }
  }
  MESSAGE("perlin" << D << "d float vs double: max " << max_v << ", rms "
                   << std::sqrt(sum_sq / count) << ", gradient max " << max_g);
  CHECK(max_v <= kValueBudget);
  CHECK(max_g <= kGradBudget);
}

TEST_CASE_TEMPLATE("perlin: gradient() matches central differences of the double reference", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Central difference error: h^2/6 * |n'''| + 2 eps / h. The noise is C2 with
  // a bounded third derivative (< 1e3 for the quintic fade), so with h = 1e-5
  // the truncation is < 2e-8 and the rounding < 1e-10: tolerance 1e-7.
  const double h = 1e-5, tol = 1e-7;
  const hush::perlin<D> p(11);
  hush::rng r(17, D);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto x = random_point<D>(r, 50.0);
    const auto vg = p.gradient(x);
    CHECK(vg.value == p(x));
    for (int a = 0; a < D; ++a) {
      const double fd = (p(offset<D>(x, a, h)) - p(offset<D>(x, a, -h))) / (2 * h);
      worst = std::max(worst, std::fabs(fd - vg.gradient[a]));
    }
  }
  CHECK(worst <= tol);
}

TEST_CASE_TEMPLATE("perlin: value and gradient are continuous across lattice planes", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Just below and at each plane x_a = k (k negative, zero and positive), value
  // and gradient must agree up to the Lipschitz bound times the step (C1);
  // a wrong floor for negative k would pick a different cell and jump by O(1).
  const hush::perlin<D> p(5);
  hush::rng r(23, D);
  const double lip = lipschitz_bound<D>();
  for (int k = -4; k <= 4; ++k) {
    for (int a = 0; a < D; ++a) {
      for (int t = 0; t < 50; ++t) {
        auto x = random_point<D>(r, 10.0);
        x[a] = k;
        auto below = x;
        below[a] = std::nextafter(double(k), -1e9);
        const double step = x[a] - below[a];
        const auto at = p.gradient(x), lo = p.gradient(below);
        // Plus rounding: each double evaluation is within kDoubleBudget of exact.
        CHECK(std::fabs(at.value - lo.value) <= lip * step + 2 * kDoubleBudget);
        for (int b = 0; b < D; ++b) CHECK(std::fabs(at.gradient[b] - lo.gradient[b]) <= 1e-9);
        // Float path: the cell split must agree with the double one.
        auto xf = hush::vec_cast<float>(below);
        CHECK(std::fabs(double(p(xf)) - p(hush::vec_cast<double>(xf))) <= kFloatBudget);
      }
    }
  }
}

TEST_CASE_TEMPLATE("perlin: lines through the origin and the diagonal have no jumps", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // HARD_CASES row 2: along x = y (= z) and the axes through the origin, the
  // difference between consecutive samples never exceeds the Lipschitz bound.
  const hush::perlin<D> p(8);
  const double lip = lipschitz_bound<D>();
  const double step = 1.0 / 1024;
  for (int dir = 0; dir <= D; ++dir) {  // dir < D: axis dir; dir == D: the diagonal
    hush::vec<double, D> u{};
    for (int a = 0; a < D; ++a) u[a] = (dir == D || dir == a) ? 1.0 : 0.0;
    double norm = 0;
    for (int a = 0; a < D; ++a) norm += u[a] * u[a];
    norm = std::sqrt(norm);
    double prev = 0, worst_ratio = 0;
    for (int i = -8192; i <= 8192; ++i) {
      hush::vec<double, D> x;
      for (int a = 0; a < D; ++a) x[a] = u[a] * i * step;
      const double v = p(x);
      if (i > -8192) worst_ratio = std::max(worst_ratio, std::fabs(v - prev) / (step * norm));
      prev = v;
      if (i == 0) CHECK(v == 0.0);  // the origin is a lattice point
    }
    CHECK(worst_ratio <= lip);
  }
}

TEST_CASE_TEMPLATE("perlin: |gradient| never exceeds the analytic Lipschitz bound", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  const hush::perlin<D> p(13);
  hush::rng r(29, D);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const auto g = p.gradient(random_point<D>(r, 500.0)).gradient;
    double n2 = 0;
    for (int a = 0; a < D; ++a) n2 += g[a] * g[a];
    worst = std::max(worst, std::sqrt(n2));
  }
  MESSAGE("perlin" << D << "d max |gradient| " << worst << " <= bound " << lipschitz_bound<D>());
  CHECK(worst <= lipschitz_bound<D>());
}

TEST_CASE_TEMPLATE("perlin: zero at every lattice point", N, std::integral_constant<int, 2>,
                   std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  const hush::perlin<D> p(21);
  hush::rng r(31, D);
  for (int i = 0; i < 10000; ++i) {
    hush::vec<float, D> x;
    for (int a = 0; a < D; ++a) x[a] = std::floor(r.uniform<float>(-1e6f, 1e6f));
    CHECK(p(x) == 0.0f);
  }
}

TEST_CASE_TEMPLATE("perlin: different seeds give uncorrelated fields", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Pearson correlation of nearly independent samples has standard error
  // 1/sqrt(n); five of them is the tolerance.
  const int n = 100000;
  const std::uint32_t pairs[][2] = {{0, 1}, {7, 8}, {1, 0xffffffffu}, {0x80000000u, 0}};
  for (const auto& pr : pairs) {
    const hush::perlin<D> a(pr[0]), b(pr[1]);
    hush::rng r(37, pr[0]);
    double sab = 0, saa = 0, sbb = 0;
    for (int i = 0; i < n; ++i) {
      const auto x = random_point<D>(r, 1e4);
      const double va = a(x), vb = b(x);
      sab += va * vb, saa += va * va, sbb += vb * vb;
    }
    CHECK(std::fabs(sab / std::sqrt(saa * sbb)) <= 5 / std::sqrt(double(n)));
  }
}

TEST_CASE_TEMPLATE("perlin: no repetition at lags 256, 289, 2^k or along diagonals", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // HARD_CASES row 7: a 256-entry permutation table repeats at lag 256; hush's
  // lattice hash must not repeat at any lag below 2^32 cells. Correlation of
  // n(x) and n(x + lag * u) over near-independent x: |rho| <= 5 / sqrt(n).
  const hush::perlin<D> p(42);
  const int n = 20000;
  const double lags[] = {256, 289, 512, 1024, 4096, 65536, 1 << 20, 1 << 24, 1u << 31};
  for (double lag : lags) {
    for (int dir = 0; dir <= D; ++dir) {
      hush::rng r(41, static_cast<std::uint32_t>(lag) + dir);
      double sab = 0, saa = 0, sbb = 0;
      for (int i = 0; i < n; ++i) {
        const auto x = random_point<D>(r, 1e4);
        auto y = x;
        for (int a = 0; a < D; ++a) y[a] += (dir == D || dir == a) ? lag : 0.0;
        const double va = p(x), vb = p(y);
        sab += va * vb, saa += va * va, sbb += vb * vb;
      }
      INFO("lag " << lag << " direction " << dir);
      CHECK(std::fabs(sab / std::sqrt(saa * sbb)) <= 5 / std::sqrt(double(n)));
    }
  }
  // The lattice is 2^32 cells wide (documented): there it repeats exactly.
  hush::rng r(43, D);
  for (int i = 0; i < 100; ++i) {
    auto x = random_point<D>(r, 100.0);
    auto y = x;
    y[0] += 4294967296.0;
    CHECK(p(x) == doctest::Approx(p(y)).epsilon(1e-6));
  }
}

TEST_CASE_TEMPLATE("perlin: periodic mode repeats exactly, only along periodic axes", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Odd, tiny and huge periods included (HARD_CASES row 14 for tiles).
  const int periods[] = {1, 2, 3, 5, 64, 255, 2147483647};
  hush::rng r(47, D);
  for (int period : periods) {
    typename hush::perlin<D>::params prm;
    prm.seed = 9;
    prm.period[0] = period;  // axis 0 periodic, the others not
    const hush::perlin<D> p(prm);
    int differs_on_free_axis = 0;
    for (int i = 0; i < 2000; ++i) {
      // Dyadic coordinates: x and x + period are both exact in double and float.
      hush::vec<double, D> x;
      for (int a = 0; a < D; ++a) x[a] = std::ldexp(std::floor(r.uniform<double>(-4096, 4096)), -6);
      const auto shifted = offset<D>(x, 0, double(period));
      CHECK(p(x) == p(shifted));
      CHECK(p.template value<float>(x) == p.template value<float>(shifted));
      const auto g0 = p.gradient(x), g1 = p.gradient(shifted);
      for (int a = 0; a < D; ++a) CHECK(g0.gradient[a] == g1.gradient[a]);
      if (p(x) != p(offset<D>(x, 1, double(period)))) ++differs_on_free_axis;
    }
    // Axis 1 is not periodic: shifting along it changes the value almost everywhere
    // (it is equal only where both are lattice points, i.e. x on the lattice).
    CHECK(differs_on_free_axis > 1000);
  }
  // A non-periodic field is not periodic at small integer periods.
  const hush::perlin<D> plain(9);
  int same = 0;
  for (int i = 0; i < 1000; ++i) {
    const auto x = random_point<D>(r, 100.0);
    if (plain(x) == plain(offset<D>(x, 0, 64.0))) ++same;
  }
  CHECK(same == 0);
}

TEST_CASE("perlin: parameters are validated with a message naming them") {
  hush::perlin<3>::params prm;
  prm.period = {4, -3, 0};
  CHECK_THROWS_AS(hush::perlin<3>{prm}, hush::invalid_argument);
  CHECK_THROWS_WITH(hush::perlin<3>{prm}, doctest::Contains("period[1] = -3"));
  CHECK_THROWS_WITH(hush::perlin<3>{prm},
                    doctest::Contains("0 (not periodic) or 1 ... 2147483647"));
}

TEST_CASE_TEMPLATE("perlin: gradient directions are uniform over the table", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // Chi-square of gradient indices over 64^D cells against uniform: with k
  // buckets, the statistic has mean k - 1 and sd sqrt(2(k - 1)); bound mean + 5 sd.
  const int k = D == 2 ? 8 : 12;
  std::vector<double> counts(k, 0.0);
  const std::uint32_t key = hush::seed_key(3);
  const int side = D == 2 ? 512 : 64;
  double total = 0;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int l = 0; l < (D == 2 ? 1 : side); ++l) {
        const std::uint32_t h =
            D == 2 ? hush::lattice_hash(key, i, j) : hush::lattice_hash(key, i, j, l);
        counts[D == 2 ? hush::detail::perlin2_grad_index(h)
                      : hush::detail::perlin3_grad_index(h)] += 1;
        total += 1;
      }
  double chi2 = 0;
  for (double c : counts) chi2 += (c - total / k) * (c - total / k) / (total / k);
  CHECK(chi2 <= (k - 1) + 5 * std::sqrt(2.0 * (k - 1)));
}

TEST_CASE("perlin: 2D gradients are unit vectors 45 degrees apart, 3D ones cube edges") {
  namespace c = hush::detail::constants;
  for (int k = 0; k < c::kPerlin2GradCount; ++k) {
    CHECK(c::kPerlin2GradX[k] == doctest::Approx(std::cos(k * kPi / 4)).epsilon(1e-15));
    CHECK(c::kPerlin2GradY[k] == doctest::Approx(std::sin(k * kPi / 4)).epsilon(1e-15));
  }
  double cov[3][3] = {};
  for (int k = 0; k < c::kPerlin3GradCount; ++k) {
    const double g[3] = {c::kPerlin3GradX[k], c::kPerlin3GradY[k], c::kPerlin3GradZ[k]};
    CHECK(g[0] * g[0] + g[1] * g[1] + g[2] * g[2] == 2.0);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) cov[a][b] += g[a] * g[b] / c::kPerlin3GradCount;
  }
  // E[g g^T] = (2/3) I: the variance derivation and isotropy rely on it.
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) CHECK(cov[a][b] == doctest::Approx(a == b ? 2.0 / 3 : 0.0));
}

TEST_CASE_TEMPLATE("perlin: exec::scalar grids equal point evaluation at every sample", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  // The scalar grid path (perlin::grid_values) shares splits and corner
  // gradients between samples. Values alone, and 2D values with gradients,
  // must still be what point evaluation gives at g.position(...), bit for bit
  // unless the build lets the compiler fuse multiply-adds (then it may fuse
  // the two paths' sums differently: within the float budget).
  //
  // 3D with gradients, rows whose cells hold two or more columns take the
  // affine-in-x form (docs/design.md): the same exact polynomial of the same
  // float fractions, rounded along another path. Forward bound per path:
  // at most n = 16 roundings in a chain, so gamma_n <= 16 * 2^-24 = 2^-20,
  // times the sum of the magnitudes of the terms combined: S <= 4 for the
  // value (corner dot products split as gx f + c, |gx f| <= 1, |c| <= 3,
  // blended with convex weights) and S <= 16 for a gradient component (a
  // blended gradient <= 1 plus the fade's slope <= 15/8 times a difference
  // of blended dot products <= 8). Two paths, scale < 1: values within
  // 2^-17, gradients within 2^-15. A wrong coefficient is off by O(0.1).
#if defined(__FMA__) && !HUSH_CONFIG_STRICT_FP
  const double tolerance = kFloatBudget;
#else
  const double tolerance = 0;
#endif
  const double affine_value = D == 3 ? std::ldexp(1.0, -17) : tolerance;
  const double affine_gradient = D == 3 ? std::ldexp(1.0, -15) : tolerance;
  typename hush::perlin<D>::params periodic;
  periodic.seed = 31;
  for (int a = 0; a < D; ++a) periodic.period[a] = 2 + a;
  const hush::perlin<D> noises[] = {hush::perlin<D>(30), hush::perlin<D>(periodic)};
  // Near, negative steps, far from the origin, steps above one cell, cells
  // wrapping modulo 2^32.
  const double grids[][3] = {{0.3, 1.0 / 37, 1}, {-4.5, -0.25, 1},  {1e9 + 0.5, 1.0 / 3, 1},
                             {-7.1, 1.7, 1},     {1e300, 1e290, 1}, {-1.0, 0.5, 1}};
  double worst_value = 0, worst_gradient = 0;
  for (const auto& noise : noises)
    for (const auto& spec : grids) {
      hush::grid<D> g;
      for (int a = 0; a < D; ++a) {
        g.origin[a] = spec[0] + 0.37 * a;
        g.step[a] = spec[1] * (1 + 0.1 * a);
        g.size[a] = 9 + 4 * std::size_t(a);
      }
      std::vector<float> out(g.count()), alone(g.count());
      std::vector<hush::vec<float, D>> grad(g.count());
      hush::evaluate_grid(noise, hush::exec::scalar, g, out, grad);
      hush::evaluate_grid(noise, hush::exec::scalar, g, alone);
      std::size_t idx = 0;
      for (std::size_t k = 0; k < (D == 3 ? g.size[2] : 1); ++k)
        for (std::size_t j = 0; j < g.size[1]; ++j)
          for (std::size_t i = 0; i < g.size[0]; ++i, ++idx) {
            std::array<std::size_t, D> ijk{};
            ijk[0] = i;
            ijk[1] = j;
            if constexpr (D == 3) ijk[2] = k;
            const auto want = noise.template value_and_gradient<float>(g.position(ijk));
            INFO("grid origin " << spec[0] << " step " << spec[1] << ", sample " << idx);
            if (tolerance == 0) {
              REQUIRE(std::memcmp(&alone[idx], &want.value, sizeof(float)) == 0);
            } else {
              REQUIRE(std::fabs(alone[idx] - want.value) <= tolerance);
            }
            if (D == 2 && tolerance == 0) {
              REQUIRE(std::memcmp(&out[idx], &want.value, sizeof(float)) == 0);
              REQUIRE(std::memcmp(&grad[idx], &want.gradient, sizeof(grad[idx])) == 0);
              continue;
            }
            worst_value = std::max(worst_value, double(std::fabs(out[idx] - want.value)));
            REQUIRE(std::fabs(out[idx] - want.value) <= affine_value);
            for (int a = 0; a < D; ++a) {
              const double e = std::fabs(grad[idx][a] - want.gradient[a]);
              worst_gradient = std::max(worst_gradient, e);
              REQUIRE(e <= affine_gradient);
            }
          }
    }
  MESSAGE("perlin " << D << "D scalar grid with gradients against point evaluation: max |value| "
                    << worst_value << ", max |gradient| " << worst_gradient);
}

TEST_CASE("perlin: 3D grid gradients (affine in x) are within the float budget of the double "
          "reference") {
  // The affine-in-x path is a float algorithm like point evaluation and must
  // keep its budget: values within 2^-16, gradients within 2^-16 (1 + L)
  // (the budgets of the point tests above). A dense grid: ~37 columns per
  // cell, so every row takes the affine path.
  const hush::perlin<3> noise(33);
  hush::grid<3> g;
  g.origin = {-3.1, 0.4, 2.2};
  g.step = {1.0 / 37, 1.0 / 29, 1.0 / 31};
  g.size = {75, 31, 17};
  std::vector<float> out(g.count());
  std::vector<hush::vec3> grad(g.count());
  hush::evaluate_grid(noise, hush::exec::scalar, g, out, grad);
  const double grad_budget = kFloatBudget * (1 + lipschitz_bound<3>());
  double worst_value = 0, worst_gradient = 0;
  std::size_t idx = 0;
  for (std::size_t k = 0; k < g.size[2]; ++k)
    for (std::size_t j = 0; j < g.size[1]; ++j)
      for (std::size_t i = 0; i < g.size[0]; ++i, ++idx) {
        const auto ref = noise.value_and_gradient<double>(g.position({i, j, k}));
        worst_value = std::max(worst_value, std::fabs(out[idx] - ref.value));
        for (int a = 0; a < 3; ++a)
          worst_gradient = std::max(worst_gradient, std::fabs(grad[idx][a] - ref.gradient[a]));
      }
  MESSAGE("3D grid against double: max |value| " << worst_value << ", max |gradient| "
                                                 << worst_gradient);
  CHECK(worst_value <= kFloatBudget);
  CHECK(worst_gradient <= grad_budget);
}
