// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The SIMD backend against scalar evaluation and the double reference, on
// every SIMD target compiled into this test and supported by this CPU
// (Highway's SupportedAndGeneratedTargets). The same source builds three
// suites (tests/simd/CMakeLists.txt):
//  - simd_test:        hush::simd (dynamic dispatch, contraction allowed):
//                      within the float budget of the double reference, and
//                      within 2 budgets of scalar;
//  - simd_strict_test: HUSH_STRICT_FP (-ffp-contract=off): bit-identical to
//                      scalar, values and gradients;
//  - simd_static_test: HUSH_SIMD_STATIC (the compiler's baseline target, no
//                      dispatch): bit-identical under strict FP too.
// Covered: grids and point batches, 2D and 3D, values and gradients, every
// tail length up to three vectors, periodic noise, and the hard cases
// (NaN, Inf, |x| >= 2^31, -1, -0, tiny negatives, FLT_MAX, far grids).
#include <doctest/doctest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"
#include "test_util.hpp"

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
#include <hwy/targets.h>
#endif

namespace {

using hush_test::kFloatBudget;
using hush_test::lipschitz_bound;

static_assert(HUSH_CONFIG_SIMD, "the SIMD suites need HUSH_SIMD_DYNAMIC or HUSH_SIMD_STATIC");
#if defined(HUSH_TEST_EXPECT_SINGLE_HEADER)
static_assert(HUSH_SINGLE_HEADER == 1, "this suite must compile against single_include/ only");
#endif

// Runs `check` once per SIMD target this program can run (dynamic dispatch),
// or once (static route), with the target's name in every failure message.
template <class Check>
void for_each_target(Check check) {
#if HUSH_CONFIG_SIMD_STATIC
  INFO("static target " << hush::simd::chosen_target());
  check();
#else
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  REQUIRE(!targets.empty());
  for (std::int64_t t : targets) {
    hwy::SetSupportedTargetsForTest(t);
    INFO("target " << hwy::TargetName(t));
    REQUIRE(hush::simd::chosen_target() == hwy::TargetName(t));
    check();
  }
  hwy::SetSupportedTargetsForTest(0);
#endif
}

// The largest vector has 16 floats (AVX-512); three vectors of tails cover
// every remainder on every x86 target.
constexpr std::size_t kMaxTail = 3 * 16 + 1;

bool same_bits(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Compares SIMD output with scalar output element by element: bit for bit
// under strict FP, else within `budget`. Returns the largest difference.
double compare(const std::vector<float>& simd, const std::vector<float>& scalar, double budget) {
  REQUIRE(simd.size() == scalar.size());
  double worst = 0;
  for (std::size_t i = 0; i < simd.size(); ++i) {
    INFO("element " << i << ": simd " << simd[i] << ", scalar " << scalar[i]);
    if (std::isnan(simd[i]) || std::isnan(scalar[i])) {
      REQUIRE(same_bits(std::isnan(simd[i]) ? NAN : 0.f, std::isnan(scalar[i]) ? NAN : 0.f));
      continue;
    }
#if HUSH_CONFIG_STRICT_FP
    (void)budget;
    REQUIRE(same_bits(simd[i], scalar[i]));
#else
    REQUIRE(std::fabs(double(simd[i]) - scalar[i]) <= budget);
#endif
    worst = std::max(worst, std::fabs(double(simd[i]) - scalar[i]));
  }
  return worst;
}

template <int D>
std::vector<float> flatten(const std::vector<hush::vec<float, D>>& g) {
  std::vector<float> r;
  for (const auto& v : g)
    for (int a = 0; a < D; ++a) r.push_back(v[a]);
  return r;
}

// Non-strict budgets against scalar: both sides are within the float budget
// of the double reference (perlin.hpp), so they are within twice it of each
// other; gradients likewise with the gradient budget of tests/perlin/perlin_test.cpp.
template <int D>
double value_budget() {
  return 2 * kFloatBudget;
}
template <int D>
double gradient_budget() {
  return 2 * kFloatBudget * (1 + lipschitz_bound<D>());
}

// SIMD against scalar for any noise with SIMD kernels: values alone, values with gradients,
// and gradients. evaluate(policy, values[, gradients]) evaluates the noise on the n points or
// grid samples under test. Returns the largest differences {values, gradients}.
struct worst_difference {
  double value = 0, gradient = 0;
  void merge(const worst_difference& o) {
    value = std::max(value, o.value);
    gradient = std::max(gradient, o.gradient);
  }
};
template <int D, class Evaluate>
worst_difference check_against_scalar(std::size_t n, Evaluate evaluate, double vbudget,
                                      double gbudget) {
  std::vector<float> vs(n), va(n), vv(n), vg(n);
  std::vector<hush::vec<float, D>> gs(n), gv(n);
  evaluate(hush::exec::scalar, vs, gs);
  evaluate(hush::exec::scalar, va);
  evaluate(hush::exec::simd, vv);
  worst_difference w;
  w.value = compare(vv, va, vbudget);
  // Values with gradients against scalar values with gradients: on 3D grids
  // both take the affine-in-x form (perlin.hpp), not the value kernel's path.
  evaluate(hush::exec::simd, vg, gv);
  w.value = std::max(w.value, compare(vg, vs, vbudget));
  w.gradient = compare(flatten<D>(gv), flatten<D>(gs), gbudget);
  return w;
}

// ... at points (hush::evaluate) and on a grid (hush::evaluate_grid).
template <class Noise>
worst_difference check_points(const Noise& p,
                              const std::vector<hush::vec<float, Noise::dimension>>& pts,
                              double vbudget = value_budget<Noise::dimension>(),
                              double gbudget = gradient_budget<Noise::dimension>()) {
  return check_against_scalar<Noise::dimension>(
      pts.size(), [&](auto policy, auto&... out) { hush::evaluate(p, policy, pts, out...); },
      vbudget, gbudget);
}

template <class Noise>
worst_difference check_grid(const Noise& p, const hush::grid<Noise::dimension>& g,
                            double vbudget = value_budget<Noise::dimension>(),
                            double gbudget = gradient_budget<Noise::dimension>()) {
  return check_against_scalar<Noise::dimension>(
      g.count(), [&](auto policy, auto&... out) { hush::evaluate_grid(p, policy, g, out...); },
      vbudget, gbudget);
}

template <int D>
std::vector<hush::vec<float, D>> random_points(std::size_t n, double extent, std::uint32_t seed) {
  hush::rng r(seed, D);
  std::vector<hush::vec<float, D>> pts(n);
  for (auto& q : pts)
    for (int a = 0; a < D; ++a) q[a] = static_cast<float>(r.uniform<double>(-extent, extent));
  return pts;
}

template <int D>
hush::grid<D> make_grid(double origin, double step, std::size_t nx, std::size_t ny,
                        std::size_t nz = 1) {
  hush::grid<D> g;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = origin + 0.37 * a;
    g.step[a] = step * (1 + 0.1 * a);
  }
  g.size[0] = nx;
  g.size[1] = ny;
  if constexpr (D == 3) g.size[2] = nz;
  return g;
}

}  // namespace

TEST_CASE_TEMPLATE("simd perlin: random point batches agree with scalar evaluation", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  const hush::perlin<D> p(11);
  for_each_target([&] {
    check_points(p, random_points<D>(4096, 50.0, 1));
    check_points(p, random_points<D>(4096, 3e6, 2));  // fractions with few bits
  });
}

TEST_CASE_TEMPLATE("simd perlin: every batch length up to three vectors, tails included", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  const hush::perlin<D> p(12);
  for_each_target([&] {
    for (std::size_t n = 0; n <= kMaxTail; ++n) {
      INFO("points " << n);
      check_points(p, random_points<D>(n, 20.0, static_cast<std::uint32_t>(n)));
      if (n == 0) continue;
      INFO("grid width " << n);
      check_grid(p, make_grid<D>(-1.3, 1.0 / 7, n, 3, 2));
    }
  });
}

TEST_CASE_TEMPLATE("simd perlin: grids agree with scalar evaluation, near and far", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  const hush::perlin<D> p(13);
  worst_difference w;
  for_each_target([&] {
    w.merge(check_grid(p, make_grid<D>(0.0, 1.0 / 37, 67, 33, 5)));
    // Every row of every slice in one y and z cell: 3D gradient rows keep the
    // corner gradients from slice to slice, and their z-blended slice data
    // must still follow the slice's z fraction.
    w.merge(check_grid(p, make_grid<D>(0.0, 1.0 / 37, 67, 3, 5)));
    w.merge(check_grid(p, make_grid<D>(-4.5, -0.25, 40, 9, 4)));         // negative steps
    w.merge(check_grid(p, make_grid<D>(1e9 + 0.5, 1.0 / 3, 35, 7, 3)));  // far from the origin
    w.merge(check_grid(p, make_grid<D>(-3e15, 0.125, 21, 5, 3)));        // beyond float's integers
    w.merge(check_grid(p, make_grid<D>(1e300, 1e290, 19, 4, 2)));        // cells wrap modulo 2^32
  });
  MESSAGE("perlin " << D << "D grids, every target: max |simd - scalar| = " << w.value
                    << " (values), " << w.gradient << " (gradients)");
}

TEST_CASE_TEMPLATE("simd perlin: periodic noise agrees with scalar and repeats", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  typename hush::perlin<D>::params prm;
  prm.seed = 14;
  for (int a = 0; a < D; ++a) prm.period[a] = 3 + 2 * a;
  const hush::perlin<D> p(prm);
  for_each_target([&] {
    check_points(p, random_points<D>(1000, 40.0, 3));
    check_grid(p, make_grid<D>(-7.25, 0.3, 41, 6, 3));
    // One period apart along x: the same values, bit for bit.
    hush::grid<D> g = make_grid<D>(0.5, 0.25, 33, 4, 2), h = g;
    h.origin[0] += prm.period[0];
    std::vector<float> a(g.count()), b(g.count());
    hush::evaluate_grid(p, hush::exec::simd, g, a);
    hush::evaluate_grid(p, hush::exec::simd, h, b);
    for (std::size_t i = 0; i < a.size(); ++i) REQUIRE(same_bits(a[i], b[i]));
  });
}

TEST_CASE_TEMPLATE("simd perlin: hard-case coordinates behave as in scalar evaluation", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  const hush::perlin<D> p(15);
  const float inf = std::numeric_limits<float>::infinity(), nan = NAN;
  const float specials[] = {nan,     inf,    -inf,        2147483648.0f, -2147483648.0f,
                            3e9f,    -3e9f,  -1.0f,       -0.0f,         0.0f,
                            -1e-30f, -1e-9f, 1e30f,       FLT_MAX,       -FLT_MAX,
                            FLT_MIN, 1e-45f, 16777217.0f, -16777215.5f,  0.99999994f};
  for_each_target([&] {
    // Each special value in each lane position, on each axis, amid ordinary
    // lanes: a bad lane must not disturb its neighbours.
    std::vector<hush::vec<float, D>> pts = random_points<D>(kMaxTail, 10.0, 4);
    for (float s : specials)
      for (int a = 0; a < D; ++a)
        for (std::size_t lane = 0; lane < 17; ++lane) {
          std::vector<hush::vec<float, D>> q = pts;
          q[lane][a] = s;
          INFO("value " << s << " on axis " << a << " in lane " << lane);
          check_points(p, q);
          std::vector<float> out(q.size());
          hush::evaluate(p, hush::exec::simd, q, out);
          CHECK(std::isnan(out[lane]) == !std::isfinite(s));
        }
  });
}

TEST_CASE("simd perlin: wrong output sizes are rejected before any work") {
  const hush::perlin<2> p(1);
  std::vector<hush::vec2> pts(5);
  std::vector<float> out(4, 7.0f);
  CHECK_THROWS_AS(hush::evaluate(p, hush::exec::simd, pts, out), hush::invalid_argument);
  CHECK(out[0] == 7.0f);
  std::vector<float> out5(5);
  std::vector<hush::vec2> grad(3);
  CHECK_THROWS_WITH_AS(hush::evaluate(p, hush::exec::simd, pts, out5, grad),
                       doctest::Contains("gradients"), hush::invalid_argument);
  hush::grid<2> g{{0, 0}, {0, 1}, {{2, 2}}};
  std::vector<float> out4(4);
  CHECK_THROWS_WITH_AS(hush::evaluate_grid(p, hush::exec::simd, g, out4),
                       doctest::Contains("grid.step[0]"), hush::invalid_argument);
}

TEST_CASE("simd perlin: the target list names what this build compiled and chose") {
  const std::vector<std::string> compiled = hush::simd::compiled_targets();
  REQUIRE(!compiled.empty());
  const std::string chosen = hush::simd::chosen_target();
  CHECK(std::find(compiled.begin(), compiled.end(), chosen) != compiled.end());
  CHECK(std::string(hush::simd::dispatch_mode()) ==
        (HUSH_CONFIG_SIMD_STATIC ? "static" : "dynamic"));
}

TEST_CASE_TEMPLATE("simd fractal: fBm and turbulence agree with scalar evaluation", N,
                   std::integral_constant<int, 2>, std::integral_constant<int, 3>) {
  constexpr int D = N::value;
  using fractal = hush::fractal<hush::perlin<D>>;
  std::vector<typename fractal::params> configs(5);
  configs[0].seed = 21;  // default: 5 octaves of fBm, unit variance
  configs[1].seed = 22;
  configs[1].kind = hush::fractal_kind::turbulence;
  configs[1].norm = hush::normalization::unit_range;
  configs[1].octaves = 7;
  configs[2].seed = 23;  // explicit weights, a zero and a negative one, no normalisation
  configs[2].octaves = 4;
  configs[2].weights = {1.0, 0.0, -0.75, 0.3};
  configs[2].norm = hush::normalization::none;
  configs[2].frequency = 0.37;
  configs[2].lacunarity = 2.7;
  configs[3].seed = 24;  // periodic
  configs[3].octaves = 3;
  for (int a = 0; a < D; ++a) configs[3].period[a] = 2 + a;
  configs[4].seed = 25;  // a single octave
  configs[4].octaves = 1;
  for (const auto& prm : configs) {
    const fractal fr(prm);
    // Per band the float budget, scaled by the band's normalised weight (and
    // frequency for gradients), on each side of the comparison.
    double wsum = 0, wfsum = 0;
    for (int b = 0; b < fr.band_count(); ++b) {
      wsum += std::fabs(fr.band_weight(b));
      wfsum += std::fabs(fr.band_weight(b)) * fr.band_frequency(b);
    }
    const double vbudget = 2 * kFloatBudget * (wsum + 1);
    const double gbudget = 2 * kFloatBudget * (1 + lipschitz_bound<D>()) * (wfsum + 1);
    INFO("octaves " << prm.octaves << ", seed " << prm.seed);
    for_each_target([&] {
      check_points(fr, random_points<D>(700, 30.0, 5), vbudget, gbudget);
      check_points(fr, random_points<D>(kMaxTail, 1e5, 6), vbudget, gbudget);
      for (std::size_t w : {1, 7, 16, 33})
        check_grid(fr, make_grid<D>(-2.2, 0.173, w, 5, 3), vbudget, gbudget);
      check_grid(fr, make_grid<D>(4e8, -0.31, 19, 4, 2), vbudget, gbudget);
    });
  }
}

TEST_CASE("simd fractal: hard-case coordinates behave as in scalar evaluation") {
  const hush::fractal<hush::perlin<3>> fr{};
  std::vector<hush::vec3> pts = random_points<3>(40, 5.0, 7);
  const float specials[] = {NAN, INFINITY, -INFINITY, 3e9f, -1.0f, -0.0f, -1e-30f, FLT_MAX};
  for_each_target([&] {
    for (float s : specials)
      for (std::size_t lane = 0; lane < 17; ++lane) {
        std::vector<hush::vec3> q = pts;
        q[lane].y = s;
        INFO("value " << s << " in lane " << lane);
        check_points(fr, q, 2 * kFloatBudget * (fr.bound() + 1),
                     2 * kFloatBudget * (1 + lipschitz_bound<3>()) * 64);
      }
  });
}
