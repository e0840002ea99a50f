// Styles (include/hush/style.hpp; Benard, Lagae et al. 2010 sec. 4): the tone map of
// the thresholding (mean ink follows the tone through the normal CDF), the smooth
// step's width as edge softness, cross-hatching as a product, graphite's unit-variance
// mix, the watercolour overlay's mean colour, tone from shading, validation.
//
// Statistical checks use independent standard normal samples (fixed seeds) so that
// their tolerances follow from the sample size alone: a mean of n values in [0, 1]
// has standard error at most sqrt(1/4 / n); tolerances are 4.5 standard errors
// (a false failure about once in 150 000 runs). The last case repeats the tone check
// on NPR Gabor noise, with the correlated-pixel bound derived there.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"  // the umbrella: the suite also runs against the single header
#include "npr_gabor/npr_gabor_scenes.hpp"

namespace {

namespace st = hush::style;
constexpr double kPi = 3.14159265358979323846;

// n independent standard normal values (Box-Muller on hush::rng doubles).
std::vector<double> gaussians(std::size_t n, std::uint32_t seed) {
  hush::rng r(seed, 7);
  std::vector<double> v(n);
  for (std::size_t i = 0; i + 1 < n; i += 2) {
    const double u1 = 1.0 - r.uniform<double>(), u2 = r.uniform<double>();  // u1 in (0, 1]
    const double m = std::sqrt(-2.0 * std::log(u1));
    v[i] = m * std::cos(2.0 * kPi * u2);
    v[i + 1] = m * std::sin(2.0 * kPi * u2);
  }
  if (n % 2) v[n - 1] = 0.0;
  return v;
}

double phi(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * kPi); }

// E[paper] for standard normal noise, by Simpson's rule over the smooth step
// (paper = 1 above it, 0 below): 1 - Phi(theta + w/2) + int S phi.
double expected_paper(const st::binary& b, double tone) {
  const double theta = st::threshold_of_tone(tone), w = b.width();
  if (w == 0.0) return 1.0 - st::normal_cdf(theta);
  const int m = 2000;
  const double lo = theta - 0.5 * w, h = w / m;
  double s = 0;
  for (int i = 0; i <= m; ++i) {
    const double x = lo + h * i;
    const double c = (i == 0 || i == m) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    s += c * b.paper_at(x, theta) * phi(x);
  }
  return 1.0 - st::normal_cdf(theta + 0.5 * w) + s * h / 3.0;
}

}  // namespace

TEST_CASE("normal_quantile inverts normal_cdf, tails and edge values included") {
  for (double p : {1e-300, 1e-12, 1e-6, 0.01, 0.2, 0.5, 0.7, 0.99, 1.0 - 1e-9}) {
    const double x = st::normal_quantile(p);
    CHECK(std::fabs(st::normal_cdf(x) - p) <= 1e-12 * std::max(p, 1e-3));
  }
  CHECK(st::normal_quantile(0.5) == doctest::Approx(0.0).epsilon(1e-15));
  CHECK(st::normal_quantile(0.975) == doctest::Approx(1.959963984540054).epsilon(1e-12));
  CHECK(std::isinf(st::normal_quantile(0.0)));
  CHECK(st::normal_quantile(0.0) < 0);
  CHECK(std::isinf(st::normal_quantile(1.0)));
  CHECK(std::isnan(st::normal_quantile(std::numeric_limits<double>::quiet_NaN())));
}

TEST_CASE("binary: mean paper follows the tone through Phi, to the derived smooth-step bias") {
  const std::vector<double> n = gaussians(200000, 11);
  const double tol = 4.5 * std::sqrt(0.25 / static_cast<double>(n.size()));
  for (double w : {0.0, 0.5, 1.5}) {
    const st::binary b(w);
    for (double tone : {0.05, 0.2, 0.5, 0.8, 0.95}) {
      double sum = 0;
      for (double v : n) sum += b.paper(v, tone);
      const double measured = sum / static_cast<double>(n.size());
      const double expected = expected_paper(b, tone);
      CAPTURE(w);
      CAPTURE(tone);
      CHECK(std::fabs(measured - expected) <= tol);
      // The derived bias theta phi(theta) w^2 / 40 + O(w^4), below 0.0061 w^2.
      const double theta = st::threshold_of_tone(tone);
      CHECK(std::fabs(expected - tone - theta * phi(theta) * w * w / 40.0) <= 2e-3 * w * w * w * w + 1e-12);
      CHECK(std::fabs(expected - tone) <= 0.0061 * w * w + 1e-12);
    }
  }
}

TEST_CASE("binary: the smooth step's width is the edge softness, Phi(theta+w/2) - Phi(theta-w/2)") {
  const std::vector<double> n = gaussians(100000, 12);
  const double tol = 4.5 * std::sqrt(0.25 / static_cast<double>(n.size()));
  for (double w : {0.0, 0.25, 1.0, 3.0}) {
    const st::binary b(w);
    const double tone = 0.3, theta = st::threshold_of_tone(tone);
    std::size_t soft = 0;
    for (double v : n) {
      const double p = b.paper(v, tone);
      CHECK_MESSAGE((p >= 0.0 && p <= 1.0), "paper out of [0, 1]");
      if (p > 0.0 && p < 1.0) ++soft;
    }
    const double expected = st::normal_cdf(theta + 0.5 * w) - st::normal_cdf(theta - 0.5 * w);
    CAPTURE(w);
    CHECK(std::fabs(static_cast<double>(soft) / static_cast<double>(n.size()) - expected) <= tol);
  }
  // Monotone in the noise, continuous at the step's ends.
  const st::binary b(0.5);
  const double theta = st::threshold_of_tone(0.5);
  CHECK(b.paper_at(theta - 0.25, theta) == 0.0);
  CHECK(b.paper_at(theta + 0.25, theta) == 1.0);
  CHECK(b.paper_at(theta, theta) == doctest::Approx(0.5));
  for (int i = -100; i < 100; ++i)
    CHECK(b.paper_at(0.01 * i, theta) <= b.paper_at(0.01 * (i + 1), theta));
}

TEST_CASE("binary: tone 1, tone 0, NaN tone and NaN noise have their documented results") {
  const st::binary b(0.5);
  CHECK(b.paper(5.0, 0.0) == 0.0);   // all ink
  CHECK(b.paper(-5.0, 1.0) == 1.0);  // all paper
  CHECK(b.paper(0.0, std::numeric_limits<double>::quiet_NaN()) == 1.0);
  CHECK(b.paper(std::numeric_limits<double>::quiet_NaN(), 0.2) == 1.0);
  CHECK(b.paper(std::numeric_limits<double>::infinity(), 0.2) == 1.0);
  CHECK(b.paper(-std::numeric_limits<double>::infinity(), 0.8) == 0.0);
}

TEST_CASE("crosshatch: the product of two layers at sqrt(tone), mean paper = tone") {
  const std::vector<double> n1 = gaussians(200000, 13), n2 = gaussians(200000, 14);
  const double tol = 4.5 * std::sqrt(0.25 / static_cast<double>(n1.size()));
  const st::crosshatch c(0.0);
  const st::binary layer(0.0);
  for (double tone : {0.1, 0.4, 0.7}) {
    double sum = 0;
    for (std::size_t i = 0; i < n1.size(); ++i) {
      const double p = c.paper(n1[i], n2[i], tone);
      if (i < 1000)
        REQUIRE(p == layer.paper(n1[i], std::sqrt(tone)) * layer.paper(n2[i], std::sqrt(tone)));
      sum += p;
    }
    CAPTURE(tone);
    CHECK(std::fabs(sum / static_cast<double>(n1.size()) - tone) <= tol);
  }
}

TEST_CASE("graphite: the mix of independent unit-variance noises has variance 1, tone holds") {
  const std::vector<double> n = gaussians(200000, 15), f = gaussians(200000, 16);
  const double count = static_cast<double>(n.size());
  for (double grain : {0.0, 0.6, 3.0}) {
    const st::graphite g(0.0, grain);
    double s = 0, s2 = 0, ink = 0;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const double m = g.mix(n[i], f[i]);
      s += m;
      s2 += m * m;
      ink += g.paper(n[i], f[i], 0.35);
    }
    const double mean = s / count, var = s2 / count - mean * mean;
    CAPTURE(grain);
    // Sample variance of a unit normal: standard error sqrt(2 / n).
    CHECK(std::fabs(var - 1.0) <= 4.5 * std::sqrt(2.0 / count));
    CHECK(std::fabs(ink / count - 0.35) <= 4.5 * std::sqrt(0.25 / count));
  }
}

TEST_CASE("watercolor: overlay keeps the colour at n = 0 and on average, stays in [0, 1]") {
  const st::watercolor wc(0.35);
  const std::vector<double> n = gaussians(200000, 17);
  for (double c : {0.0, 0.1, 0.45, 0.5, 0.8, 1.0}) {
    CHECK(wc.channel(c, 0.0) == doctest::Approx(c).epsilon(1e-15));
    CHECK(wc.channel(c, std::numeric_limits<double>::quiet_NaN()) == c);
    double sum = 0;
    for (double v : n) {
      const double o = wc.channel(c, v);
      REQUIRE((o >= 0.0 && o <= 1.0));
      sum += o;
    }
    CAPTURE(c);
    // Values in [0, 1]: standard error <= sqrt(1/4 / n).
    CHECK(std::fabs(sum / static_cast<double>(n.size()) - c) <=
          4.5 * std::sqrt(0.25 / static_cast<double>(n.size())));
    for (int i = -60; i < 60; ++i) CHECK(wc.channel(c, 0.05 * i) <= wc.channel(c, 0.05 * (i + 1)));
  }
  const hush::dvec3 col = wc.colour({0.2, 0.5, 0.9}, 1.0);
  CHECK(col.x == doctest::Approx(2 * 0.2 * 0.85));
  CHECK(col.z == doctest::Approx(1 - 2 * 0.1 * 0.15));
}

TEST_CASE("shading_tone: ambient + (1 - ambient) max(0, N.L), background is white") {
  const hush::dvec3 l{0, 0, 2};
  CHECK(st::shading_tone({0, 0, 1}, l, 0.1) == doctest::Approx(1.0));
  CHECK(st::shading_tone({0, 0, -1}, l, 0.1) == doctest::Approx(0.1));
  CHECK(st::shading_tone({1, 0, 1}, l, 0.0) == doctest::Approx(std::sqrt(0.5)));
  CHECK(st::shading_tone({0, 0, 0}, l, 0.1) == 1.0);
  CHECK(st::shading_tone({std::numeric_limits<double>::quiet_NaN(), 0, 1}, l, 0.1) == 1.0);
}

TEST_CASE("style parameters are validated, naming the parameter and range") {
  auto message = [](auto make) {
    try {
      make();
    } catch (const hush::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double w : {-0.1, 8.5, nan}) {
    const std::string m = message([&] { st::binary b(w); });
    CHECK(m.find("width") != std::string::npos);
    CHECK(m.find("0 <= width <= 8") != std::string::npos);
  }
  CHECK(message([&] { st::crosshatch c(-1); }).find("width") != std::string::npos);
  CHECK(message([&] { st::graphite g(0.5, -1); }).find("grain") != std::string::npos);
  CHECK(message([&] { st::graphite g(0.5, nan); }).find("0 <= grain <= 8") != std::string::npos);
  CHECK(message([&] { st::watercolor w(5); }).find("0 <= gain <= 4") != std::string::npos);
  CHECK(message([&] { st::binary b(8.0); }).empty());
}

TEST_CASE("hatching on NPR Gabor noise: ink coverage follows the tone") {
  // NPR Gabor noise with N' = 16 is close to Gaussian, so the normal-CDF tone map
  // holds for it. Its pixels are correlated: for a Gaussian field the covariance of
  // two pixels' indicators [n > theta] is int_0^rho phi_2(theta, theta; r) dr, at most
  // arcsin|rho| / (2 pi) <= |rho| / 4, so the coverage's variance over n pixels is
  // at most sum_d |rho(d)| / (4 n) (rho the kernel's autocorrelation). 4.5 of those
  // standard errors, plus 0.01 for the distance to Gaussian (N' = 16 kernels per
  // pixel: the fourth cumulant is 9 / (5 N') of the variance squared).
  hush::npr_gabor::params p;
  p.frequency = 0.25;
  p.bandwidth = 0.25;
  p.orientation = 0.3;
  const hush::npr_gabor noise(p);
  const std::size_t w = 256, h = 256, m = 8;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 6.0, 40.0);
  std::vector<float> img(w * h);
  noise.render(sc.frame(), sc.triangles(), hush::image_view<float>(img.data(), w, h));
  const hush::dvec2 F{p.frequency * std::cos(p.orientation),
                      p.frequency * std::sin(p.orientation)};
  const double abs_rho = npr_test::sum_rho_power(noise.kernel(), F, 1);
  const double count = static_cast<double>((w - 2 * m) * (h - 2 * m));
  const double tol = 4.5 * std::sqrt(abs_rho / (4.0 * count)) + 0.01;
  const st::binary hatch(0.0);
  for (double tone : {0.2, 0.5, 0.8}) {
    double paper = 0;
    for (std::size_t y = m; y < h - m; ++y)
      for (std::size_t x = m; x < w - m; ++x) paper += hatch.paper(img[y * w + x], tone);
    CAPTURE(tone);
    CAPTURE(tol);
    CHECK(std::fabs(paper / count - tone) <= tol);
  }
}

TEST_CASE("projected_normal_field: the direction of grad(1/z), exact on planes, NaN face-on") {
  // Object 1 (x < 30, y >= 1): a slanted plane, 1/z = 0.5 + 0.002 x + 0.001 y at pixel
  // centres; object 2 (x >= 30): face-on (constant depth); row 0 background; pixel
  // (10, 15) an isolated object 3 (no neighbour of its own: NaN).
  const std::size_t w = 40, h = 30;
  std::vector<float> depth(w * h, std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> object(w * h, 0);
  for (std::size_t y = 1; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const double inv = 0.5 + 0.002 * (static_cast<double>(x) + 0.5) +
                         0.001 * (static_cast<double>(y) + 0.5);
      depth[y * w + x] = x < 30 ? static_cast<float>(1.0 / inv) : 2.0f;
      object[y * w + x] = x < 30 ? 1 : 2;
    }
  object[15 * w + 10] = 3;
  hush::frame f;
  f.depth = {depth.data(), w, h};
  f.object_id = {object.data(), w, h};
  std::vector<float> field(w * h);
  st::projected_normal_field(f, hush::image_view<float>(field.data(), w, h), 1e-4);
  const double expected = std::atan2(0.001, 0.002);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const float a = field[y * w + x];
      CAPTURE(x);
      CAPTURE(y);
      if (y == 0 || x >= 30 || (x == 10 && y == 15)) {
        CHECK(std::isnan(a));
      } else {
        // Depths are float: each 1/z (< 0.6) is off by up to 0.6 * 2^-24 = 3.6e-8, so a
        // difference of two by 7.2e-8 against gradient components >= 0.001: the angle is
        // within 7.2e-8 / 0.001 = 7.2e-5 (plus float rounding of the result).
        CHECK(std::fabs(a - expected) <= 1e-4);
      }
    }
  CHECK_THROWS_WITH_AS(
      st::projected_normal_field(f, hush::image_view<float>(field.data(), 20, 20), 1e-4),
      doctest::Contains("out size"), hush::invalid_argument);
  f.object_id = {};
  CHECK_THROWS_WITH_AS(
      st::projected_normal_field(f, hush::image_view<float>(field.data(), w, h), 1e-4),
      doctest::Contains("object_id"), hush::invalid_argument);
}

TEST_CASE("curvature_field: across a cylinder's axis, falls back on planes and sphere centres") {
  // Object 1 (x < 48): a cylinder of radius R = 20 px whose axis runs through (32, 32) at
  // alpha = 0.6 rad on screen; u = -sin(alpha) (x - 32) + cos(alpha) (y - 32) is the
  // cross-axis coordinate, its normal (sin(phi) e_u, -cos(phi)) with sin(phi) = u / R, then
  // turned by a fixed 3D rotation (normals in "world space": the estimate must not care).
  // Object 2: a sphere of radius 20 px at (72, 32) (umbilic: no principal direction, and
  // only the foreshortening makes one near its rim). Object 3: the rest of x >= 48, a
  // slanted plane (flat). Expected on the cylinder: alpha + pi/2 (mod pi).
  const std::size_t w = 96, h = 64;
  const double kR = 20, alpha = 0.6, pi = 3.14159265358979323846;
  std::vector<float> depth(w * h, 0.0f);
  std::vector<std::uint32_t> object(w * h, 0);
  std::vector<hush::vec3> normal(w * h, hush::vec3{0, 0, 0});
  // A rotation about (1, 2, 2) / 3 by 1 rad (Rodrigues), applied to every normal.
  const double kx = 1.0 / 3, ky = 2.0 / 3, kz = 2.0 / 3, ca = std::cos(1.0), sa = std::sin(1.0);
  auto turn = [&](double x, double y, double z) {
    const double d = kx * x + ky * y + kz * z;
    const double cx = ky * z - kz * y, cy = kz * x - kx * z, cz = kx * y - ky * x;
    return hush::vec3{static_cast<float>(x * ca + cx * sa + kx * d * (1 - ca)),
                      static_cast<float>(y * ca + cy * sa + ky * d * (1 - ca)),
                      static_cast<float>(z * ca + cz * sa + kz * d * (1 - ca))};
  };
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const double px = static_cast<double>(x) + 0.5, py = static_cast<double>(y) + 0.5;
      const std::size_t i = y * w + x;
      if (x < 48) {
        const double u = -std::sin(alpha) * (px - 32) + std::cos(alpha) * (py - 32);
        if (std::fabs(u) >= kR) continue;
        const double s = u / kR, c = std::sqrt(1 - s * s);
        object[i] = 1;
        depth[i] = static_cast<float>(5 - c);
        normal[i] = turn(-std::sin(alpha) * s, std::cos(alpha) * s, -c);
      } else {
        const double dx = (px - 72) / kR, dy = (py - 32) / kR, r2 = dx * dx + dy * dy;
        if (r2 < 0.95 * 0.95) {
          object[i] = 2;
          depth[i] = static_cast<float>(5 - std::sqrt(1 - r2));
          normal[i] = turn(dx, dy, -std::sqrt(1 - r2));
        } else {
          object[i] = 3;
          depth[i] = static_cast<float>(1 / (0.2 + 0.002 * px + 0.001 * py));
          normal[i] = turn(0.3, 0.2, -0.93);
        }
      }
    }
  hush::frame f;
  f.depth = {depth.data(), w, h};
  f.object_id = {object.data(), w, h};
  const hush::image_view<const hush::vec3> normals(normal.data(), w, h);
  std::vector<float> field(w * h), fallback(w * h);
  st::curvature_field(f, normals, hush::image_view<float>(field.data(), w, h), 1e-3, 0.2, 1e-4);
  st::projected_normal_field(f, hush::image_view<float>(fallback.data(), w, h), 1e-4);
  auto same = [](float a, float b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  double worst = 0;
  std::size_t checked = 0;
  for (std::size_t y = 1; y + 1 < h; ++y)
    for (std::size_t x = 1; x + 1 < w; ++x) {
      const std::size_t i = y * w + x;
      const double px = static_cast<double>(x) + 0.5, py = static_cast<double>(y) + 0.5;
      CAPTURE(x);
      CAPTURE(y);
      if (object[i] == 1 && x + 2 < 48) {
        const double u = -std::sin(alpha) * (px - 32) + std::cos(alpha) * (py - 32);
        if (std::fabs(u) > 0.8 * kR) continue;
        // Central differences of n(u) (cos(phi) >= 0.6 here): the x and y differences are
        // n' times the steps -sin(alpha), cos(alpha) plus third-order terms |n'''| / 6 with
        // |n'''| / |n'| <= 1 / (R cos^2 phi)^2 = 0.0069: the direction is within 0.01 rad.
        double e = std::fmod(std::fabs(field[i] - (alpha + pi / 2)), pi);
        e = std::min(e, pi - e);
        worst = std::max(worst, e);
        ++checked;
        CHECK(e <= 0.01);
      } else if (object[i] == 3 || (object[i] == 2 && std::hypot(px - 72, py - 32) < 0.5 * kR)) {
        CHECK(same(field[i], fallback[i]));  // flat, or anisotropy below 0.2: the fallback
      }
    }
  MESSAGE("cylinder: " << checked << " pixels, worst angle error " << worst << " rad");
  CHECK(checked > 500);
  std::vector<hush::vec3> small(10);
  CHECK_THROWS_WITH_AS(st::curvature_field(f, hush::image_view<const hush::vec3>(small.data(), 2, 5),
                                           hush::image_view<float>(field.data(), w, h), 1e-3,
                                           0.2, 1e-4),
                       doctest::Contains("normals size"), hush::invalid_argument);
}
