// Anisotropic noise (include/hush/anisotropic.hpp): parameters, tiles
// (band-limited, oriented, isotropic in sum: the paper's fig. 3, shared and
// reported), variance, float budget, filtering and distortion compensation
// behaviour, hard cases (HARD_CASES rows 3, 5, 12, 14), golden values.
// Statistical tolerances are five standard errors of the sample at hand
// (formula beside each).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <vector>

#include "hush/hush.hpp"
#include "test_util.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

hush::anisotropic make(int k = 4, int scales = 3, int octaves = 3, int tile = 64,
                       std::uint32_t seed = 7) {
  hush::anisotropic::params p;
  p.seed = seed;
  p.orientations = k;
  p.scales = scales;
  p.octaves = octaves;
  p.tile_size = tile;
  return hush::anisotropic(p);
}

// Mean and variance of v(p) over `count` uniform random positions in
// [0, extent)^2, with the standard error of the variance estimate.
template <class F>
void moments(F v, int count, double extent, std::uint32_t seed, double& mean, double& var,
             double& var_se) {
  hush::rng r(seed);
  double s1 = 0, s2 = 0, s4 = 0;
  for (int n = 0; n < count; ++n) {
    const double x = v(hush::dvec2{r.uniform<double>(0, extent), r.uniform<double>(0, extent)});
    s1 += x;
    s2 += x * x;
    s4 += x * x * x * x;
  }
  mean = s1 / count;
  var = s2 / count;  // about the true mean 0
  // SE of the mean of x^2: sqrt((E x^4 - (E x^2)^2) / n).
  var_se = std::sqrt((s4 / count - var * var) / count);
}

// Power spectrum of an n x n real image (own FFT), unnormalised.
std::vector<double> power(const std::vector<double>& img, std::size_t n) {
  std::vector<std::complex<double>> a(img.begin(), img.end());
  hush::detail::fft2(a.data(), n, -1);
  std::vector<double> p(n * n);
  for (std::size_t q = 0; q < n * n; ++q) p[q] = std::norm(a[q]);
  return p;
}

}  // namespace

TEST_CASE("anisotropic: parameters out of range throw, naming the parameter and range") {
  auto with = [](auto change) {
    hush::anisotropic::params p;
    p.tile_size = 16;
    change(p);
    return hush::anisotropic(p);
  };
  using P = hush::anisotropic::params;
  CHECK_THROWS_WITH_AS(with([](P& p) { p.orientations = 1; }),
                       doctest::Contains("orientations = 1 is out of range; valid: 2 ... 8"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.orientations = 9; }), doctest::Contains("orientations"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.scales = 0; }), doctest::Contains("scales = 0"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.scales = 13; }), doctest::Contains("scales = 13"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.base_scale = 3; }),
                       doctest::Contains("base_scale = 3 is out of range; valid: 0 ... scales - 1"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.octaves = 4; }), doctest::Contains("octaves = 4"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) {
                         p.base_scale = 1;
                         p.octaves = 3;
                       }),
                       doctest::Contains("octaves = 3"), hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.gain = 0; }), doctest::Contains("gain = 0"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.gain = std::nan(""); }), doctest::Contains("gain"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.frequency = -1; }), doctest::Contains("frequency = -1"),
                       hush::invalid_argument);
  CHECK_THROWS_WITH_AS(with([](P& p) { p.frequency = INFINITY; }), doctest::Contains("frequency"),
                       hush::invalid_argument);
  // HARD_CASES row 14: odd, tiny and huge tiles name the rule.
  for (int n : {0, 8, 100, 255, 4096, -16})
    CHECK_THROWS_WITH_AS(with([n](P& p) { p.tile_size = n; }),
                         doctest::Contains("valid: a power of two, 16 ... 2048"),
                         hush::invalid_argument);
}

TEST_CASE("anisotropic: tiles are built once per (seed, orientations, size), shared, reported") {
  auto& cache = hush::anisotropic::tile_cache();
  const std::size_t builds = cache.builds();
  const hush::anisotropic a = make(4, 3, 3, 32, 101), b = make(4, 2, 1, 32, 101);
  CHECK(&a.tile() == &b.tile());
  CHECK(cache.builds() == builds + 1);
  const hush::anisotropic c = make(5, 3, 3, 32, 101);  // another orientation count: its own
  CHECK(&c.tile() != &a.tile());
  CHECK(c.tile().channels() == 8);
  CHECK(a.tile().channels() == 4);
  // (N + 1)^2 texels of 4 or 8 floats, plus the per-orientation statistics.
  CHECK(a.tile().bytes() == 33 * 33 * 4 * sizeof(float) + 2 * 4 * sizeof(float));
  CHECK(cache.live_bytes() >= a.tile().bytes() + c.tile().bytes());
  // The padding row and column repeat row and column 0 (the tile wraps).
  const hush::anisotropic_tile& t = a.tile();
  for (std::uint32_t q = 0; q <= 32; ++q)
    for (int ch = 0; ch < 4; ++ch) {
      CHECK(t.texel(32, q)[ch] == t.texel(0, q % 32)[ch]);
      CHECK(t.texel(q, 32)[ch] == t.texel(q % 32, 0)[ch]);
    }
}

TEST_CASE("anisotropic: each tile holds its orientation's subband: in band, around theta_i") {
  const std::size_t n = 128;
  for (int k : {2, 4, 8}) {
    const hush::anisotropic noise = make(k, 1, 1, static_cast<int>(n), 3);
    const hush::anisotropic_tile& t = noise.tile();
    for (int i = 0; i < k; ++i) {
      std::vector<double> img(n * n);
      for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x)
          img[y * n + x] = t.texel(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y))[i];
      const std::vector<double> p = power(img, n);
      double in_band = 0, out_band = 0, cos2 = 0;
      for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) {
          const double fx = hush::detail::bin_frequency(x, n),
                       fy = hush::detail::bin_frequency(y, n);
          const double r = std::hypot(fx, fy);
          const double v = p[y * n + x];
          // The band of the tile's filter: (1/16, 1/4) cycles per texel.
          if (r > 1.0 / 16 && r < 0.25) {
            in_band += v;
            // cos^2 of the angle to theta_i: 1 along the orientation.
            const double c = (fx * std::cos(kPi * i / k) + fy * std::sin(kPi * i / k)) / r;
            cos2 += v * c * c;
          } else {
            out_band += v;
          }
        }
      CAPTURE(k);
      CAPTURE(i);
      // Outside the band only float rounding of the stored texels remains.
      CHECK(out_band < 1e-10 * in_band);
      // Power concentrates along theta_i: the power-weighted mean of cos^2 of
      // the angle is well above the isotropic 1/2 (the filter alone gives
      // (2K-1)/(2K); the random spectrum moves it by a few percent).
      CHECK(cos2 / in_band > 0.5 + 0.35 * (k - 1.0) / k);
    }
  }
}

TEST_CASE("anisotropic: the orientations of a scale sum to isotropic noise (fig. 3)") {
  // Angular power spread of the sum: the band's power in 16 sectors of the
  // half plane (Hermitian spectra: the other half mirrors it). Each bin's
  // power is |F|^2 B^2 with |F|^2 ~ Exp(1), so a sector's power has mean
  // sum B^2 and standard deviation sqrt(sum B^4): the z-score of every
  // sector must stay within 5. One orientation alone is far from isotropic.
  const std::size_t n = 256;
  const int sectors = 16;
  for (int k : {3, 4, 8}) {
    const hush::anisotropic noise = make(k, 1, 1, static_cast<int>(n), 11);
    const hush::anisotropic_tile& t = noise.tile();
    const hush::steerable_bank& bank = noise.bank();
    (void)bank;
    std::vector<double> sum(n * n, 0.0), one(n * n, 0.0);
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        const float* v = t.texel(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
        for (int i = 0; i < k; ++i) sum[y * n + x] += v[i];
        one[y * n + x] = v[0];
      }
    const std::vector<double> ps = power(sum, n), p1 = power(one, n);
    std::vector<double> got(sectors, 0), got1(sectors, 0), mean(sectors, 0), var(sectors, 0);
    double scale = 0, total_b2 = 0;
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        const double fx = hush::detail::bin_frequency(x, n), fy = hush::detail::bin_frequency(y, n);
        if (fy < 0 || (fy == 0 && fx <= 0)) continue;  // one half plane
        const double r = std::hypot(fx, fy);
        const double b = hush::steerable_bank::radial(std::log2(r / 0.125));
        if (b == 0) continue;
        double a = std::atan2(fy, fx);
        if (a >= kPi) a -= kPi;
        const int sct = std::min(sectors - 1, static_cast<int>(a / kPi * sectors));
        got[sct] += ps[y * n + x];
        got1[sct] += p1[y * n + x];
        mean[sct] += b * b;
        var[sct] += b * b * b * b;
        scale += ps[y * n + x];
        total_b2 += b * b;
      }
    scale /= total_b2;  // the tile's normalisation: power per unit B^2
    double worst_z = 0, spread = 0, spread1 = 0, m1 = 0;
    for (int sct = 0; sct < sectors; ++sct) m1 += got1[sct] / sectors;
    for (int sct = 0; sct < sectors; ++sct) {
      const double z = (got[sct] / scale - mean[sct]) / std::sqrt(var[sct]);
      worst_z = std::max(worst_z, std::fabs(z));
      spread = std::max(spread, std::fabs(got[sct] / (scale * mean[sct]) - 1));
      spread1 = std::max(spread1, std::fabs(got1[sct] / m1 - 1));
    }
    CAPTURE(k);
    CHECK(worst_z < 5);
    CHECK(spread1 > 0.9);  // one orientation: sectors differ by about their whole mean
    MESSAGE("K = " << k
                   << ": angular power spread of the orientation sum (max |sector / mean - 1|, "
                      "16 sectors, 256^2 tile) "
                   << spread << ", of one orientation " << spread1);
  }
}

TEST_CASE("anisotropic: one octave has variance 1 and mean 0 over the plane") {
  // The tile normalisation makes the continuous-plane variance of one scale's
  // orientation sum exactly 1; random positions estimate it with standard
  // error var_se (see moments()).
  for (int k : {2, 4, 7}) {
    const hush::anisotropic noise = make(k, 1, 1, 64, 17);
    double mean = 0, var = 0, se = 0;
    moments([&](const hush::dvec2& p) { return noise(p); }, 200000, 64.0, 5, mean, var, se);
    CAPTURE(k);
    CHECK(std::fabs(var - 1) < 5 * se);
    CHECK(std::fabs(mean) <
          5 * std::sqrt(var / 200000) + 0.02);  // 0.02: a fixed tile's mean in space
  }
}

TEST_CASE("anisotropic: octave sums keep variance 1 on average over seeds") {
  // Different scales read different frequencies of a tile, so they are
  // uncorrelated in expectation; one tile's sample cross terms average out
  // over seeds: the mean over 16 seeds is within 5 standard errors of 1.
  const int seeds = 16;
  double sum = 0, sum_sq = 0;
  for (int s = 0; s < seeds; ++s) {
    const hush::anisotropic noise = make(4, 3, 3, 32, 1000 + s);
    double mean = 0, var = 0, se = 0;
    moments([&](const hush::dvec2& p) { return noise(p); }, 20000, 4.0 * 32, 9 + s, mean, var, se);
    sum += var;
    sum_sq += var * var;
  }
  const double m = sum / seeds, sd = std::sqrt((sum_sq / seeds - m * m) / (seeds - 1));
  CHECK(std::fabs(m - 1) < 5 * sd);
}

TEST_CASE("anisotropic: float evaluation stays within float_budget() of the double reference") {
  hush::rng r(23);
  for (int k : {2, 4, 5, 8})
    for (hush::fractal_kind kind : {hush::fractal_kind::fbm, hush::fractal_kind::turbulence})
      for (hush::weight_rule rule : {hush::weight_rule::centre, hush::weight_rule::three_point}) {
        hush::anisotropic::params p;
        p.orientations = k;
        p.scales = 4;
        p.base_scale = 1;
        p.octaves = 2;
        p.kind = kind;
        p.tile_size = 32;
        p.filtering = rule;
        p.compensation = rule;
        const hush::anisotropic noise(p);
        double worst = 0, worst_maps = 0;
        for (int q = 0; q < 20000; ++q) {
          const hush::dvec2 pos = hush_test::random_point<2>(r, q % 2 ? 1e4 : 50);
          const hush::vec2 pf = hush::vec_cast<float>(pos);
          const double w = std::exp2(r.uniform<double>(-6, 3));
          const auto fp = hush::footprint<2>::from_derivatives(
              hush::dvec2{w * r.uniform<double>(-1, 1), w * r.uniform<double>(-1, 1)},
              hush::dvec2{w * r.uniform<double>(-1, 1), w * r.uniform<double>(-1, 1)});
          const double v = noise.sample(pf, fp), ref = noise.sample(hush::vec_cast<double>(pf), fp);
          worst = std::max(worst, std::fabs(v - ref));
          const auto map =
              hush::surface_map::from_matrix(r.uniform<double>(-3, 3), r.uniform<double>(-3, 3),
                                             r.uniform<double>(-3, 3), r.uniform<double>(-3, 3));
          const double vm = noise.sample(pf, fp, map),
                       refm = noise.sample(hush::vec_cast<double>(pf), fp, map);
          worst_maps = std::max(worst_maps, std::fabs(vm - refm));
        }
        CAPTURE(k);
        CAPTURE(static_cast<int>(kind));
        CAPTURE(static_cast<int>(rule));
        CHECK(worst <= noise.float_budget());
        CHECK(worst_maps <= noise.float_budget() * noise.bound_with_maps() / noise.bound());
      }
}

TEST_CASE("anisotropic: output stays within bound() and bound_with_maps()") {
  const hush::anisotropic noise = make(4, 4, 2, 32, 29);
  hush::rng r(31);
  double worst = 0, worst_maps = 0;
  for (int q = 0; q < 100000; ++q) {
    const hush::vec2 p = hush::vec_cast<float>(hush_test::random_point<2>(r, 100));
    worst = std::max(worst, static_cast<double>(std::fabs(noise(p))));
    const auto map =
        hush::surface_map::from_matrix(r.uniform<double>(-8, 8), r.uniform<double>(-8, 8),
                                       r.uniform<double>(-0.1, 0.1), r.uniform<double>(-8, 8));
    worst_maps = std::max(worst_maps, static_cast<double>(std::fabs(noise.sample(p, {}, map))));
  }
  CHECK(worst <= noise.bound());
  CHECK(worst_maps <= noise.bound_with_maps());
  MESSAGE("max |n| " << worst << " (bound " << noise.bound() << "), with maps " << worst_maps
                     << " (bound " << noise.bound_with_maps() << ")");
}

TEST_CASE("anisotropic: hard cases: NaN and Inf positions give NaN, huge ones stay finite") {
  const hush::anisotropic noise = make(4, 3, 3, 16, 1);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
  for (const hush::vec2 p :
       {hush::vec2{nan, 0}, hush::vec2{0, nan}, hush::vec2{inf, 1}, hush::vec2{1, -inf}}) {
    CHECK(std::isnan(noise(p)));
    CHECK(std::isnan(noise.sample(p, hush::footprint<2>::isotropic(0.1))));
    const auto g = noise.gradient(p);
    CHECK(std::isnan(g.value));
    CHECK(std::isnan(g.gradient.x));
  }
  for (const double x : {1e30, -1e30, 9007199254740992.0, 1.7e308, -1.7e308, 16777216.5,
                         std::ldexp(1.0, -1074), -0.0}) {
    CHECK(std::isfinite(noise(hush::dvec2{x, 0.5})));
    if (std::fabs(x) <= std::numeric_limits<float>::max())
      CHECK(std::isfinite(noise(hush::vec2{static_cast<float>(x), 0.25f})));
    CHECK(std::isfinite(noise.sample(hush::dvec2{0.5, x}, hush::footprint<2>::isotropic(0.01))));
  }
}

TEST_CASE(
    "anisotropic: hard cases: footprints NaN, Inf, huge give the mean; singular ones stay finite") {
  // HARD_CASES row 12.
  const hush::anisotropic noise = make(4, 3, 3, 16, 2);
  const hush::vec2 p{0.3f, 0.7f};
  const double nan = std::nan("");
  for (const auto& fp :
       {hush::footprint<2>::isotropic(nan), hush::footprint<2>::isotropic(INFINITY),
        hush::footprint<2>::isotropic(1e30),
        hush::footprint<2>::from_derivatives(hush::dvec2{1e30, 0}, hush::dvec2{0, 1e30}),
        hush::footprint<2>::from_derivatives(hush::dvec2{nan, 0}, hush::dvec2{0, 1})})
    CHECK(noise.sample(p, fp) == 0.0f);
  // Zero, rank 1 (filters along x only), nearly singular, tiny.
  const auto zero = hush::footprint<2>::from_derivatives(hush::dvec2{0, 0}, hush::dvec2{0, 0});
  CHECK(noise.sample(p, zero) == noise(p));
  // Rank 1 along x: every orientation with an x component is filtered out
  // (far beyond the cutoff), the one along y (theta = pi/2) is untouched.
  const auto rank1 = hush::footprint<2>::from_derivatives(hush::dvec2{100, 0}, hush::dvec2{0, 0});
  CHECK(std::isfinite(noise.sample(p, rank1)));
  float lam[12 * 8];
  noise.filter_weights<float>(rank1, lam);
  for (int s = 0; s < 3; ++s)
    for (int i = 0; i < 4; ++i) CHECK(lam[i + 4 * s] == (i == 2 ? 1.0f : 0.0f));
  for (const auto& fp :
       {hush::footprint<2>::from_derivatives(hush::dvec2{1e-15, 0}, hush::dvec2{0, 1e-15}),
        hush::footprint<2>::from_derivatives(hush::dvec2{1, 1}, hush::dvec2{1, 1 + 1e-30}),
        hush::footprint<2>::from_derivatives(hush::dvec2{0.01, 0}, hush::dvec2{0, 0})})
    CHECK(std::isfinite(noise.sample(p, fp)));
}

TEST_CASE("anisotropic: hard cases: degenerate and mirrored surface maps") {
  const hush::anisotropic noise = make(4, 3, 1, 16, 3);
  const hush::vec2 p{1.3f, -0.2f};
  const hush::dvec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  // Zero UV area (all uvs on a line), zero 3D area, NaN: the mean, 0.
  CHECK(noise.sample(p, {}, hush::surface_map::from_triangle(a, b, c, {0, 0}, {1, 1}, {2, 2})) ==
        0.0f);
  CHECK(noise.sample(p, {}, hush::surface_map::from_triangle(a, b, b, {0, 0}, {1, 0}, {0, 1})) ==
        0.0f);
  CHECK(noise.sample(p, {}, hush::surface_map::from_matrix(std::nan(""), 1, 0, 1)) == 0.0f);
  hush::surface_map raw;
  raw.m00 = std::numeric_limits<float>::quiet_NaN();  // a map built by hand, not validated
  CHECK(noise.sample(p, {}, raw) == 0.0f);
  // Mirrored uvs (det T < 0) give the same weights as the unmirrored map:
  // T diag(1, -1) leaves |T^T w| and |det T| unchanged.
  const auto t = hush::surface_map::from_matrix(1.5, 0.3, -0.2, 0.8);
  const auto mirrored = hush::surface_map::from_matrix(1.5, -0.3, -0.2, -0.8);
  CHECK(mirrored.determinant() < 0);
  CHECK(noise.sample(p, {}, t) == noise.sample(p, {}, mirrored));
  // Huge and overflowing maps: finite.
  for (const auto& m : {hush::surface_map::from_matrix(1e20, 0, 0, 1),
                        hush::surface_map::from_matrix(3e38, 3e38, 3e38, -3e38),
                        hush::surface_map::from_matrix(1e-30, 0, 0, 1e-30)})
    CHECK(std::isfinite(noise.sample(p, hush::footprint<2>::isotropic(0.5), m)));
}

TEST_CASE("anisotropic: surface_map::from_triangle is the linear map of the triangle's uvs") {
  // A triangle in a tilted plane whose uvs are a known linear function of
  // in-plane coordinates: T maps the local edges to the uv edges.
  const hush::dvec3 p0{1, 2, 3}, e1{2, 0, 1}, e2{-1, 3, 2};
  const hush::dvec3 p1{p0.x + e1.x, p0.y + e1.y, p0.z + e1.z};
  const hush::dvec3 p2{p0.x + e2.x, p0.y + e2.y, p0.z + e2.z};
  const hush::dvec2 uv0{0.5, 0.5}, uv1{0.9, 0.2}, uv2{0.1, 1.3};
  const auto t = hush::surface_map::from_triangle(p0, p1, p2, uv0, uv1, uv2);
  // In the local frame, edge 1 is (|e1|, 0): T maps it to uv1 - uv0.
  const double l1 = std::sqrt(5.0);
  CHECK(t.m00 * l1 == doctest::Approx(0.4).epsilon(1e-6));
  CHECK(t.m10 * l1 == doctest::Approx(-0.3).epsilon(1e-6));
  // |det T| = uv area / surface area.
  const double uv_area = 0.5 * std::fabs((0.4) * (0.8) - (-0.3) * (-0.4));
  const hush::dvec3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                      e1.x * e2.y - e1.y * e2.x};
  const double area = 0.5 * std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  CHECK(std::fabs(t.determinant()) == doctest::Approx(uv_area / area).epsilon(1e-6));
}

TEST_CASE("anisotropic: an identity map, or none, gives the uncompensated noise") {
  const hush::anisotropic noise = make(4, 3, 2, 16, 4);
  hush::rng r(37);
  for (int q = 0; q < 1000; ++q) {
    const hush::vec2 p = hush::vec_cast<float>(hush_test::random_point<2>(r, 20));
    const auto fp = hush::footprint<2>::isotropic(r.uniform<double>(0, 0.3));
    CHECK(noise.sample(p, fp, hush::surface_map::identity()) ==
          doctest::Approx(noise.sample(p, fp)).epsilon(1e-6));
  }
}

TEST_CASE("anisotropic: a uniformly scaled map moves the noise to the scale that undoes it") {
  // T = 2^m I: texture features must be 2^m times coarser in texture units to
  // look the same on the surface, i.e. the octave's band moves m scales down,
  // with weight 1 (unit-variance tiles): n_T(u) = n_I(2^-m u) up to the
  // per-scale offsets, so compare variance and the weights themselves.
  hush::anisotropic::params p;
  p.scales = 5;
  p.base_scale = 2;
  p.octaves = 1;
  p.tile_size = 16;
  const hush::anisotropic noise(p);
  for (int m : {-2, -1, 1, 2}) {
    float w[12 * 8];
    hush::sample_input<2> in;
    in.has_map = true;
    in.map = hush::surface_map::from_matrix(std::exp2(m), 0, 0, std::exp2(m));
    noise.weights<float>(in, w);
    for (int s = 0; s < 5; ++s)
      for (int i = 0; i < 4; ++i) {
        CAPTURE(m);
        CAPTURE(s);
        CHECK(w[i + 4 * s] ==
              doctest::Approx(s == 2 - m ? noise.octave_weight(0) : 0.0).epsilon(1e-5));
      }
  }
}

TEST_CASE("anisotropic: filtering removes what the footprint cannot show, continuously") {
  // Variance over space falls monotonically as the pixel grows, reaches 0
  // once every band is filtered, and a 1% larger footprint never jumps.
  const hush::anisotropic noise = make(4, 3, 3, 32, 41);
  double last = 2;
  hush::rng r(43);
  std::vector<hush::vec2> pts(4000);
  for (auto& q : pts) q = hush::vec_cast<float>(hush_test::random_point<2>(r, 64));
  for (double w = 1e-3; w < 64; w *= 1.01) {
    const auto fp = hush::footprint<2>::isotropic(w), fp2 = hush::footprint<2>::isotropic(w * 1.01);
    double var = 0, jump = 0;
    for (const auto& q : pts) {
      const double v = noise.sample(q, fp);
      var += v * v;
      jump = std::max(jump, std::fabs(noise.sample(q, fp2) - v));
    }
    var /= static_cast<double>(pts.size());
    CHECK(var <= last + 1e-12);
    CHECK(jump < 0.1);  // a 1% change of width changes any weight by at most ~4% of the bound / K
    last = var;
  }
  CHECK(last == 0.0);
}

TEST_CASE("anisotropic: gradients equal central differences inside texels") {
  const hush::anisotropic noise = make(4, 2, 2, 32, 47);
  hush::rng r(53);
  int checked = 0;
  for (int q = 0; q < 2000; ++q) {
    const hush::dvec2 p = hush_test::random_point<2>(r, 10);
    const auto g = noise.gradient(p);
    const double h = 1e-7;
    const double dx =
        (noise(hush::dvec2{p.x + h, p.y}) - noise(hush::dvec2{p.x - h, p.y})) / (2 * h);
    const double dy =
        (noise(hush::dvec2{p.x, p.y + h}) - noise(hush::dvec2{p.x, p.y - h})) / (2 * h);
    // Skip the rare point within h of a texel edge of some scale (a kink).
    if (std::fabs(dx - g.gradient.x) > 1e-4 * (1 + std::fabs(dx)) ||
        std::fabs(dy - g.gradient.y) > 1e-4 * (1 + std::fabs(dy)))
      continue;
    ++checked;
  }
  CHECK(checked > 1950);
}

TEST_CASE("anisotropic: each scale repeats with its tile's period") {
  // Scale s spans tile_size texels every tile_size * kAnisoTileBand / f_s
  // units: 32 * 0.125 / 1 = 4 units for one octave at frequency 1, N = 32.
  const hush::anisotropic noise = make(4, 1, 1, 32, 59);
  hush::rng r(61);
  for (int q = 0; q < 1000; ++q) {
    const hush::dvec2 p = hush_test::random_point<2>(r, 100);
    CHECK(noise(p) == doctest::Approx(noise(hush::dvec2{p.x + 4, p.y - 8})).epsilon(1e-9));
  }
}

TEST_CASE("anisotropic: golden values per seed never change") {
  // Tile values come from a double FFT rounded to float: compared within
  // 2^-20, far below any real change of the field (~0.1), above the last-ulp
  // differences another libm's cos/sin could make in the FFT twiddles.
  const double points[4][2] = {{0.5, 0.25}, {-17.75, 3.3}, {1000.1, -2000.7}, {7.77, -7.77}};
  const std::uint32_t seeds[3] = {0, 7, 0xdeadbeefU};
  const double expected[3][4] = {
      {-1.1620445260158343, -1.2039171969794762, -0.87274673914722833, 0.90206319953493519},
      {0.83065021597632993, -0.71036227047901779, -1.692012042360951, 0.39017191254014377},
      {0.095395601506240157, 0.042634598035403426, -0.46699823801244728, -0.81431030572281626}};
  const double tolerance = std::ldexp(1.0, -20);
  for (int s = 0; s < 3; ++s) {
    const hush::anisotropic noise = make(4, 3, 3, 64, seeds[s]);
    for (int q = 0; q < 4; ++q) {
      const double v = noise(hush::dvec2{points[q][0], points[q][1]});
      CAPTURE(seeds[s]);
      CAPTURE(q);
      CHECK(std::fabs(v - expected[s][q]) <= tolerance);
    }
  }
}
