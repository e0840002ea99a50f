// HARD_CASES.md rows 1, 3, 5 and 14, checked on every noise hush offers (Perlin
// 2D/3D, fBm, turbulence, wavelet 2D/3D) in float and double; row 12's
// indefinite footprint for anisotropic noise (its other row-12 cases live in
// anisotropic_test.cpp). Rows 2, 6 and 7 live in
// perlin_test.cpp, row 10 in golden_test.cpp, row 11 in core/rng_test.cpp,
// row 1 for the lattice split itself in core/lattice_test.cpp. Row 4 (no
// signed overflow) is this whole suite run under UBSan in CI.
#include <doctest/doctest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"

namespace {

// One noise under test, type-erased to "evaluate at (x, y, z)" in float and
// double (2D noises ignore z), with its analytic output bound.
struct subject {
  std::string name;
  std::function<float(float, float, float)> f;
  std::function<double(double, double, double)> d;
  std::function<hush::vec3(float, float, float)> grad;  // gradient in float; z = 0 for 2D
  double bound;
  double lipschitz;  // a bound on |gradient| (perlin_test derives Perlin's)
};

template <class Noise>
subject make_subject(const std::string& name, const Noise& n, double bound, double lipschitz) {
  constexpr int D = Noise::dimension;
  subject s;
  s.name = name;
  s.bound = bound;
  s.lipschitz = lipschitz;
  if constexpr (D == 2) {
    s.f = [n](float x, float y, float) { return n(hush::vec2{x, y}); };
    s.d = [n](double x, double y, double) { return n(hush::dvec2{x, y}); };
    s.grad = [n](float x, float y, float) {
      const auto g = n.gradient(hush::vec2{x, y}).gradient;
      return hush::vec3{g.x, g.y, 0.0f};
    };
  } else {
    s.f = [n](float x, float y, float z) { return n(hush::vec3{x, y, z}); };
    s.d = [n](double x, double y, double z) { return n(hush::dvec3{x, y, z}); };
    s.grad = [n](float x, float y, float z) { return n.gradient(hush::vec3{x, y, z}).gradient; };
  }
  return s;
}

template <int D>
hush::fractal<hush::perlin<D>> make_fractal(hush::fractal_kind kind) {
  typename hush::fractal<hush::perlin<D>>::params prm;
  prm.seed = 77;
  prm.octaves = 5;
  prm.kind = kind;
  prm.norm = hush::normalization::unit_range;
  return hush::fractal<hush::perlin<D>>(prm);
}

// Wavelet noise (hush/wavelet.hpp), 3 bands: its bound() is analytic; per axis a band's
// derivative weights sum to at most 2 in magnitude, so |gradient| <= 2 sqrt(D) bound()
// times the top band's frequency (4).
template <int D>
subject wavelet_subject() {
  typename hush::wavelet<D>::params prm;
  prm.seed = 9;
  prm.weights = {1, 0.5, 0.25};
  const hush::wavelet<D> w(prm);
  return make_subject(D == 2 ? "wavelet<2>" : "wavelet<3>", w, w.bound(),
                      2 * std::sqrt(double(D)) * w.bound() * 4);
}

std::vector<subject> subjects() {
  // Lipschitz bounds: Perlin's analytic ones (perlin_test.cpp) times, for the
  // fractals, sum_i |w_i| f_i / K = sum 0.5^i 2^i / sum 0.5^i = 5 / 1.9375.
  const double l2 = 7.31, l3 = 10.05, frac = 5 / 1.9375;
  return {make_subject("perlin<2>", hush::perlin<2>(3), 1.0, l2),
          make_subject("perlin<3>", hush::perlin<3>(3), 1.0, l3),
          make_subject("fbm<2>", make_fractal<2>(hush::fractal_kind::fbm), 1.0, l2 * frac),
          make_subject("fbm<3>", make_fractal<3>(hush::fractal_kind::fbm), 1.0, l3 * frac),
          make_subject("turbulence<3>", make_fractal<3>(hush::fractal_kind::turbulence), 1.0,
                       l3 * frac),
          wavelet_subject<2>(), wavelet_subject<3>()};
}

const double kFloatSlack = std::ldexp(1.0, -15);

}  // namespace

TEST_CASE("hard cases row 1: values at tricky coordinates match the double reference") {
  // Cells must be picked exactly as std::floor does; a wrong cell changes the
  // value by O(0.1), while float rounding stays below 2^-15.
  const float xs[] = {-1.0f,
                      -0.0f,
                      0.0f,
                      std::nextafter(-1.0f, -2.0f),
                      std::nextafter(-1.0f, 0.0f),
                      4.9999998f,
                      8388608.5f - 1.0f,  // 2^23 - 0.5
                      -8388607.5f,
                      16777216.0f,
                      -16777216.0f,
                      0.5f,
                      -0.5f};
  for (const subject& s : subjects()) {
    for (float x : xs)
      for (float y : {0.25f, -0.75f, -1.0f}) {
        INFO(s.name << " at (" << x << ", " << y << ")");
        const double ref = s.d(x, y, -0.3125);  // same position in double
        CHECK(std::fabs(double(s.f(x, y, -0.3125f)) - ref) <= kFloatSlack);
      }
    // -0 and +0 are the same point.
    CHECK(s.f(-0.0f, 0.25f, -0.0f) == s.f(0.0f, 0.25f, 0.0f));
  }
}

TEST_CASE("hard cases row 3: far coordinates stay finite and within the bound") {
  // float: 1e6 ... 2^24 and beyond; double: 2^31 ... 2^53 and beyond. The
  // lattice wraps at 2^32 cells (documented), the fraction is exact.
  const float fx[] = {1e6f, 1e6f + 0.375f, 4194304.25f,    8388607.5f,   16777215.0f, 16777216.0f,
                      3e9f, 1e20f,         -1e6f - 0.375f, -16777215.0f, -3e9f,       -1e30f};
  const double dx[] = {2147483647.25,       2147483648.5, 4294967296.75, 9007199254740991.0,
                       9007199254740992.0,  1e17,         1e300,         -2147483648.5,
                       -9007199254740991.0, -1e300};
  for (const subject& s : subjects()) {
    for (float x : fx) {
      const float v = s.f(x, 0.5f * x, -x);
      INFO(s.name << " float x = " << x);
      CHECK(std::isfinite(v));
      CHECK(std::fabs(v) <= s.bound + kFloatSlack);
    }
    for (double x : dx) {
      const double v = s.d(x, x / 3.0, -0.25);
      INFO(s.name << " double x = " << x);
      CHECK(std::isfinite(v));
      CHECK(std::fabs(v) <= s.bound);
    }
  }
}

TEST_CASE("hard cases row 5: NaN and Inf give NaN, FLT_MAX, denormals and -0 give finite values") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const subject& s : subjects()) {
    INFO(s.name);
    // Documented result: any non-finite coordinate gives NaN, value and gradient.
    for (float bad : {nan, inf, -inf}) {
      CHECK(std::isnan(s.f(bad, 0.5f, 0.5f)));
      CHECK(std::isnan(s.f(0.5f, bad, 0.5f)));
      CHECK(std::isnan(s.d(double(bad), 0.5, 0.5)));
      CHECK(std::isnan(s.grad(bad, 0.5f, 0.5f).x));
    }
    if (s.name.find("<3>") != std::string::npos) CHECK(std::isnan(s.f(0.5f, 0.5f, nan)));
    for (float big : {FLT_MAX, -FLT_MAX}) {
      CHECK(std::isfinite(s.f(big, big, big)));
      CHECK(std::fabs(s.f(big, 0.5f, -big)) <= s.bound + kFloatSlack);
    }
    CHECK(std::isfinite(s.d(DBL_MAX, -DBL_MAX, DBL_MAX)));
    // Denormals: continuity at the origin says |n(x) - n(0)| <= L |x|.
    const float den[] = {std::numeric_limits<float>::denorm_min(), -1e-40f, FLT_MIN, -FLT_MIN};
    for (float x : den) {
      const double dv = std::fabs(double(s.f(x, x, x)) - double(s.f(0.0f, 0.0f, 0.0f)));
      CHECK(dv <= s.lipschitz * std::fabs(double(x)) * 2 + kFloatSlack);
      CHECK(std::isfinite(s.grad(x, x, x).x));
    }
  }
}

TEST_CASE("hard cases row 14: tiny, odd and huge periods tile exactly") {
  // Perlin's tiles are periods: 1 (a single cell), odd sizes, and the largest
  // int. Each must repeat bit for bit (dyadic points keep x + p exact).
  for (int p : {1, 3, 7, 9, 1023, 2147483647}) {
    hush::perlin<2>::params prm;
    prm.seed = 5;
    prm.period = {p, p};
    const hush::perlin<2> n(prm);
    hush::perlin<3>::params prm3;
    prm3.seed = 5;
    prm3.period = {p, p, p};
    const hush::perlin<3> n3(prm3);
    for (int i = -40; i < 40; ++i) {
      const double x = i * 0.40625, y = -i * 0.15625, z = i * 0.0625;
      INFO("period " << p << " at " << x);
      CHECK(n(hush::dvec2{x, y}) == n(hush::dvec2{x + p, y - p}));
      CHECK(n3(hush::dvec3{x, y, z}) == n3(hush::dvec3{x - p, y + p, z + p}));
      CHECK(std::fabs(n(hush::dvec2{x, y})) <= 1.0);
    }
  }
}

TEST_CASE("hard cases row 14: wavelet tiles: odd, tiny and huge sizes are refused naming the "
          "rule; far coordinates wrap on the tile exactly") {
  for (int n : {-2, 0, 2, 14, 15, 17, 129, 4096}) {
    hush::wavelet<2>::params prm;
    prm.tile_size = n;
    INFO("tile_size " << n);
    CHECK_THROWS_WITH_AS(hush::wavelet<2>{prm}, doctest::Contains("tile_size"),
                         hush::invalid_argument);
  }
  hush::wavelet<3>::params prm3;
  prm3.tile_size = 130;  // even, above the 3D maximum
  CHECK_THROWS_AS(hush::wavelet<3>{prm3}, hush::invalid_argument);
  // Period tile_size (band 0): x + k n is exact in double for these dyadic x up to 2^28.
  hush::wavelet<2>::params p2;
  p2.tile_size = 16;
  p2.seed = 3;
  const hush::wavelet<2> w2(p2);
  hush::wavelet<3>::params p3;
  p3.tile_size = 16;
  p3.seed = 3;
  const hush::wavelet<3> w3(p3);
  for (double k : {1.0, 1024.0, 1048576.0, 16777215.0}) {
    for (int i = -8; i < 8; ++i) {
      const double x = i * 0.40625, y = -i * 0.15625, z = i * 0.0625, p = 16 * k;
      INFO("k " << k << " at " << x);
      CHECK(w2(hush::dvec2{x, y}) == w2(hush::dvec2{x + p, y - p}));
      CHECK(w3(hush::dvec3{x, y, z}) == w3(hush::dvec3{x - p, y + p, z + p}));
    }
  }
}

TEST_CASE("hard cases row 5: wavelet normals: zero, NaN and Inf give the unprojected noise, "
          "any length is normalised") {
  const hush::wavelet<3> w(4);
  const hush::footprint<3> point{};
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < 16; ++i) {
    const hush::dvec3 p{0.37 * i - 2, 1.1 - 0.23 * i, 0.61 * i};
    const double plain = w(p);
    INFO("at " << p[0]);
    for (const hush::dvec3 bad : {hush::dvec3{0, 0, 0}, hush::dvec3{nan, 0, 1},
                                  hush::dvec3{inf, 1, 0}, hush::dvec3{0, -inf, 0}})
      CHECK(w.sample(p, bad, point) == plain);
    const double unit = w.sample(p, hush::dvec3{0.6, 0, 0.8}, point);
    CHECK(std::isfinite(unit));
    for (double len : {1e-30, 1e-3, 7.0, 1e30})
      CHECK(w.sample(p, hush::dvec3{0.6 * len, 0, 0.8 * len}, point) ==
            doctest::Approx(unit).epsilon(1e-12));
  }
}

// A nearly singular Jacobian (rank 1, at a grazing angle) gives S = J J^T whose float
// rounding may be indefinite: d^T S d < 0 by an ulp of S's entries along the null
// direction, and the filter weight 2^-(kappa d^T S d) would be 2^+900 (float: exponent
// bits overflow into garbage). The quadratic form is clamped at 0 (the singular limit).
TEST_CASE("hard cases row 12: anisotropic noise with an indefinite footprint stays finite and "
          "equals its singular limit") {
  hush::anisotropic::params prm;
  prm.seed = 5;
  for (const hush::weight_rule rule :
       {hush::weight_rule::centre, hush::weight_rule::three_point,
        hush::weight_rule::least_squares}) {
    prm.filtering = rule;
    const hush::anisotropic n(prm);
    // S = a [[1, b/a], [b/a, 1]]: singular at b = a (null direction (1, -1) / sqrt 2, K = 4's
    // orientation 3); one ulp (2^7 at a = 2^30) above, d^T S d = -128 there.
    const float a = std::ldexp(1.0f, 30);
    const float sing[3] = {a, a, a};
    const auto singular = hush::footprint<2>::from_covariance(sing);
    for (int ulps = -3; ulps <= 3; ++ulps) {
      float b = a;
      for (int u = 0; u < std::abs(ulps); ++u) b = std::nextafter(b, ulps < 0 ? 0.0f : INFINITY);
      const float up[3] = {a, b, a};
      const auto fp = hush::footprint<2>::from_covariance(up);
      for (int i = 0; i < 16; ++i) {
        const hush::dvec2 p{0.37 * i - 2, 1.1 - 0.23 * i};
        INFO("rule " << int(rule) << ", " << ulps << " ulps, at " << p.x);
        const double d = n.sample(p, fp);
        const float f = n.sample(hush::vec2{float(p.x), float(p.y)}, fp);
        REQUIRE(std::isfinite(d));
        REQUIRE(std::isfinite(f));
        CHECK(std::fabs(d) <= n.bound());
        CHECK(std::fabs(f) <= n.bound() + n.float_budget());
        // The indefinite side equals the singular limit: its q is clamped to 0, the
        // singular S's own q is a rounding residue of the directions (2^30 * O(2^-52)),
        // so its weight is 1 - O(1e-5); least squares fits the clamped Gaussian.
        if (ulps > 0) CHECK(std::fabs(d - n.sample(p, singular)) <= 1e-4 * n.bound());
      }
    }
  }
}
