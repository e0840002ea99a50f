// NPR Gabor noise's parameter sources (include/hush/npr_gabor.hpp `sources`,
// include/hush/core/param_source.hpp; Benard, Lagae et al. 2010 sec. 4): F0,
// omega0, a and N' per object and per pixel. A per-object frequency shows in each object's
// measured spectrum, a per-pixel orientation field steers the measured orientation,
// the normalisation keeps the variance 1 for each object's frequency, NaN pixels
// take the constant, and bad tables and fields are refused by name.
//
// Spectra are measured through the autocorrelation at small lags (Wiener-Khinchin:
// rho(d) = int S(f) cos(2 pi f.d) df / int S): the expected sample autocorrelation of
// the noise is the kernel's own lattice autocorrelation rho_at (npr_gabor_scenes.hpp).
// A sample autocorrelation over n pixels has standard error below
// sqrt(4 sum_k rho(k)^2 / n) (Bartlett's formula, each of its terms bounded by
// 4 rho^2 after Cauchy-Schwarz); tolerances are 4.5 of those.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"  // the umbrella: the suite also runs against the single header
#include "npr_gabor_scenes.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

struct region {
  std::size_t x0, x1, y0, y1;  // [x0, x1) x [y0, y1)
};

// Sample autocorrelation of img over `r` at lag (dx, dy) >= 0 in x... (dy may be < 0).
double sample_rho(const std::vector<float>& img, std::size_t w, const region& r, int dx, int dy) {
  double s = 0, s2 = 0, c = 0;
  std::size_t n = 0;
  for (std::size_t y = r.y0; y < r.y1; ++y)
    for (std::size_t x = r.x0; x < r.x1; ++x) {
      const double v = img[y * w + x];
      const double u = img[(y + static_cast<std::size_t>(static_cast<long>(dy))) * w + x +
                           static_cast<std::size_t>(dx)];
      s += v;
      s2 += v * v;
      c += v * u;
      ++n;
    }
  const double m = s / static_cast<double>(n);
  const double var = s2 / static_cast<double>(n) - m * m;
  return (c / static_cast<double>(n) - m * m) / var;
}

double sample_variance(const std::vector<float>& img, std::size_t w, const region& r) {
  double s = 0, s2 = 0;
  std::size_t n = 0;
  for (std::size_t y = r.y0; y < r.y1; ++y)
    for (std::size_t x = r.x0; x < r.x1; ++x) {
      const double v = img[y * w + x];
      s += v;
      s2 += v * v;
      ++n;
    }
  const double m = s / static_cast<double>(n);
  return s2 / static_cast<double>(n) - m * m;
}

double pixels(const region& r) { return static_cast<double>((r.x1 - r.x0) * (r.y1 - r.y0)); }

double sum_rho2(const hush::gabor_kernel<2>& k, const hush::dvec2& F) {
  return npr_test::sum_rho_power(k, F, 2);
}

// Bartlett's formula for the standard error of a sample autocorrelation at lag d over n
// pixels, Var = (1/n) sum_k [rho(k+d)^2 + rho(k-d) rho(k+d) + 2 rho(d)^2 rho(k)^2
// - 4 rho(d) rho(k) rho(k+d)], summed over the lags k within two radii (rho = 0 beyond):
// much tighter than the bound above where rho(d) is near 1.
double bartlett_se(const hush::gabor_kernel<2>& k, const hush::dvec2& F, int dx, int dy,
                   double n) {
  const int reach = 2 * static_cast<int>(std::ceil(k.radius()));
  const int big = reach + std::max(std::abs(dx), std::abs(dy));
  const int side = 2 * big + 1;
  std::vector<double> rho(static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0.0);
  auto at = [&](int x, int y) -> double& {
    return rho[static_cast<std::size_t>(y + big) * static_cast<std::size_t>(side) +
               static_cast<std::size_t>(x + big)];
  };
  for (int y = -big; y <= big; ++y)
    for (int x = -big; x <= big; ++x)
      if (std::abs(x) <= reach && std::abs(y) <= reach) at(x, y) = npr_test::rho_at(k, F, x, y);
  const double rd = at(dx, dy);
  double v = 0;
  for (int y = -reach; y <= reach; ++y)
    for (int x = -reach; x <= reach; ++x) {
      const double p = at(x + dx, y + dy), m = at(x - dx, y - dy), r0 = at(x, y);
      v += p * p + m * p + 2 * rd * rd * r0 * r0 - 4 * rd * r0 * p;
    }
  return std::sqrt(std::max(v, 0.0) / n);
}

hush::dvec2 freq(double f, double theta) { return {f * std::cos(theta), f * std::sin(theta)}; }

hush::npr_gabor::params small_kernel() {
  hush::npr_gabor::params p;
  p.frequency = 0.25;
  p.bandwidth = 0.25;  // r = 3.9 px: many independent pixels per region
  p.orientation = 0.0;
  return p;
}

std::vector<float> render(const hush::npr_gabor& noise, const npr_test::grid_scene& sc,
                          const hush::npr_gabor::sources& src) {
  std::vector<float> out(sc.width * sc.height);
  noise.render(sc.frame(), sc.triangles(),
               hush::image_view<float>(out.data(), sc.width, sc.height), src);
  return out;
}

// Makes the right half (x >= w/2, a grid column boundary) of a covering grid object 2.
void split_objects(npr_test::grid_scene& sc) {
  const double half = 0.5 * static_cast<double>(sc.width);
  for (std::size_t t = 0; t < sc.tri_id.size(); ++t) {
    double cx = 0;
    for (int i = 0; i < 3; ++i) cx += sc.screen[sc.indices[3 * t + static_cast<std::size_t>(i)]].x;
    if (cx / 3.0 > half) sc.obj_id[t] = 2;
  }
  for (std::size_t y = 0; y < sc.height; ++y)
    for (std::size_t x = sc.width / 2; x < sc.width; ++x)
      if (sc.object[y * sc.width + x] == 1) sc.object[y * sc.width + x] = 2;
}

}  // namespace

TEST_CASE("interpolated kernel energy is within 1e-3 of the quadrature, exact at the nodes") {
  for (double t : {1e-9, 0.05, 0.5}) {
    hush::npr_gabor::params p;
    p.truncation = t;
    const hush::npr_gabor noise(p);
    std::vector<double> cache;
    double worst = 0;
    for (int i = 0; i < 40; ++i) {
      const double f = 0.5 * (i + 0.37) / 40.0;
      const double e = noise.kernel().energy(f);
      worst = std::max(worst, std::fabs(noise.interpolated_energy(f, cache) / e - 1.0));
    }
    CAPTURE(t);
    CHECK(worst <= 1e-3);
    const double node = 3.0 / 64.0 / noise.kernel().radius();
    CHECK(noise.interpolated_energy(node, cache) ==
          doctest::Approx(noise.kernel().energy(node)).epsilon(1e-12));
    // Another radius (a per-point bandwidth): r^2 E(F r) from the same nodes.
    for (double a : {0.03, 0.5, 4.0}) {
      hush::npr_gabor::params q = p;
      q.bandwidth = a;
      const hush::npr_gabor other(q);
      const hush::gabor_kernel<2>& k = other.kernel();
      double worst_r = 0;
      for (int i = 0; i < 40; ++i) {
        const double f = 0.5 * (i + 0.37) / 40.0;
        worst_r = std::max(worst_r, std::fabs(noise.interpolated_energy(f, k.radius(), cache) /
                                                  k.energy(f) - 1.0));
      }
      CAPTURE(a);
      CHECK(worst_r <= 1e-3);
    }
  }
}

TEST_CASE("constant sources, an all-NaN field and a field of the constant give the same image") {
  const std::size_t w = 96, h = 80;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 7.0, 20.0);
  hush::npr_gabor::params p = small_kernel();
  p.orientation = 0.7;
  const hush::npr_gabor noise(p);
  const std::vector<float> plain = render(noise, sc, {});
  std::vector<float> nan_field(w * h, std::numeric_limits<float>::quiet_NaN());
  std::vector<float> same(w * h, 0.7f);
  hush::npr_gabor::sources src;
  src.orientation = hush::param_source::per_pixel({nan_field.data(), w, h});
  CHECK(render(noise, sc, src) == plain);  // NaN pixels take the constant, bit for bit
  // A per-pixel frequency of NaN everywhere: the constant's value, normalised through the
  // interpolated energy (within 1e-3 in energy, so 5e-4 in amplitude).
  hush::npr_gabor::sources fsrc;
  fsrc.frequency = hush::param_source::per_pixel({nan_field.data(), w, h});
  const std::vector<float> interp = render(noise, sc, fsrc);
  double worst = 0, peak = 0;
  for (std::size_t i = 0; i < plain.size(); ++i) {
    worst = std::max(worst, std::fabs(static_cast<double>(interp[i]) - plain[i]));
    peak = std::max(peak, std::fabs(static_cast<double>(plain[i])));
  }
  CHECK(worst <= 5e-4 * peak + 1e-5);
  // An orientation field holding 0.7 (as float) everywhere: every point reads 0.7f.
  p.orientation = static_cast<double>(0.7f);
  const hush::npr_gabor exact(p);
  hush::npr_gabor::sources osrc;
  osrc.orientation = hush::param_source::per_pixel({same.data(), w, h});
  CHECK(render(exact, sc, osrc) == render(exact, sc, {}));
}

TEST_CASE("per-object frequency shows in each object's measured spectrum, variance 1 in each") {
  const std::size_t w = 256, h = 192;
  npr_test::grid_scene sc = npr_test::covering(w, h, 8.0, 20.0);
  split_objects(sc);
  const hush::npr_gabor noise(small_kernel());
  const std::vector<double> table = {0.25, 0.1, 0.3};  // objects 0 (unused), 1, 2
  hush::npr_gabor::sources src;
  src.frequency = hush::param_source::per_object(table);
  const std::vector<float> img = render(noise, sc, src);
  const std::size_t m = 12;  // > 2 kernel radii from the image border and the seam
  const region left{m, w / 2 - m, m, h - m}, right{w / 2 + m, w - 1 - m, m, h - 1 - m};
  const auto& k = noise.kernel();
  for (int obj = 1; obj <= 2; ++obj) {
    const region& r = obj == 1 ? left : right;
    const hush::dvec2 own = freq(table[static_cast<std::size_t>(obj)], 0.0);
    const hush::dvec2 other = freq(table[static_cast<std::size_t>(3 - obj)], 0.0);
    const double tol = 4.5 * std::sqrt(4.0 * sum_rho2(k, own) / pixels(r));
    CAPTURE(obj);
    CAPTURE(tol);
    for (const auto& d : {std::pair<int, int>{1, 0}, {2, 0}, {0, 1}, {3, 1}}) {
      const double measured = sample_rho(img, w, r, d.first, d.second);
      const double expected = npr_test::rho_at(k, own, d.first, d.second);
      CHECK(std::fabs(measured - expected) <= tol);
    }
    // The other object's frequency would be far outside the tolerance at lag (2, 0).
    CHECK(std::fabs(npr_test::rho_at(k, own, 2, 0) - npr_test::rho_at(k, other, 2, 0)) > 4 * tol);
    // Variance 1: sample variance standard error sqrt((2 sum rho^2 + 9 / (5 lambda)) / n).
    const double var_tol =
        4.5 * std::sqrt((2.0 * sum_rho2(k, own) + 9.0 / (5.0 * noise.density())) / pixels(r));
    CHECK(std::fabs(sample_variance(img, w, r) - 1.0) <= var_tol);
  }
}

TEST_CASE("a per-pixel orientation field steers the measured local orientation") {
  // Three bands: orientation 0, pi/2 and NaN (-> the params' constant, pi/4).
  const std::size_t w = 300, h = 160;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 8.0, 20.0);
  hush::npr_gabor::params p = small_kernel();
  p.orientation = kPi / 4;
  const hush::npr_gabor noise(p);
  std::vector<float> field(w * h);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x)
      field[y * w + x] = x < 100 ? 0.0f
                                 : (x < 200 ? static_cast<float>(kPi / 2)
                                            : std::numeric_limits<float>::quiet_NaN());
  hush::npr_gabor::sources src;
  src.orientation = hush::param_source::per_pixel({field.data(), w, h});
  const std::vector<float> img = render(noise, sc, src);
  const auto& k = noise.kernel();
  const double angles[3] = {0.0, kPi / 2, kPi / 4};
  const std::size_t m = 12;  // beyond a kernel diameter from the band edges
  for (std::size_t b = 0; b < 3; ++b) {
    const region r{100 * b + m, 100 * b + 100 - m - 1, m, h - m - 1};
    const double tol = 4.5 * std::sqrt(4.0 * sum_rho2(k, freq(p.frequency, angles[b])) / pixels(r));
    // Lags (1, 0) and (0, 1) tell the three orientations apart: F = 1/4 along the lag
    // makes rho about cos(pi / 2) = 0, across it the envelope alone.
    CAPTURE(b);
    for (const auto& d : {std::pair<int, int>{1, 0}, {0, 1}, {1, 1}}) {
      const double measured = sample_rho(img, w, r, d.first, d.second);
      double best = 1e9;
      std::size_t best_band = 9;
      for (std::size_t c = 0; c < 3; ++c) {
        const double e = std::fabs(measured -
                                   npr_test::rho_at(k, freq(p.frequency, angles[c]), d.first, d.second));
        if (e < best) {
          best = e;
          best_band = c;
        }
        if (c == b) CHECK(e <= tol);
      }
      if (d.first != d.second) CHECK(best_band == b);  // (1, 1) cannot tell 0 from pi/2
    }
  }
}

TEST_CASE("bad per-object tables and per-pixel fields are refused by name and range") {
  npr_test::grid_scene sc(16, 16, 0, 0, 8, 2, 2);
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  std::vector<float> out(std::size_t{16} * 16);
  const hush::image_view<float> view(out.data(), 16, 16);
  const std::vector<double> bad_f = {0.1, 0.6};
  hush::npr_gabor::sources src;
  src.frequency = hush::param_source::per_object(bad_f);
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("frequency[1] = 0.59999"), hush::invalid_argument);
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("0 <= frequency <= 0.5"), hush::invalid_argument);
  const std::vector<double> bad_o = {0.0, std::numeric_limits<double>::quiet_NaN()};
  src = {};
  src.orientation = hush::param_source::per_object(bad_o);
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("orientation[1]"), hush::invalid_argument);
  std::vector<float> small(std::size_t{8} * 8, 0.0f);
  src = {};
  src.orientation = hush::param_source::per_pixel({small.data(), 8, 8});
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("orientation field size = 8x8"), hush::invalid_argument);
  // Huge, infinite and NaN pixel values never throw: non-finite -> the constant,
  // finite frequencies clamped to [0, 0.5]; the image stays finite.
  std::vector<float> wild(std::size_t{16} * 16);
  for (std::size_t i = 0; i < wild.size(); ++i)
    wild[i] = i % 3 == 0 ? std::numeric_limits<float>::infinity()
                         : (i % 3 == 1 ? 1e30f : std::numeric_limits<float>::quiet_NaN());
  src = {};
  src.frequency = hush::param_source::per_pixel({wild.data(), 16, 16});
  src.orientation = hush::param_source::per_pixel({wild.data(), 16, 16});
  noise.render(sc.frame(), sc.triangles(), view, src);
  for (float v : out) CHECK(std::isfinite(v));
}

namespace {

// The left (x < w/2) and right halves of img have bandwidths a[1], a[2] and densities
// n_prime[1], n_prime[2] (F0 = 1/4 along x): each half's autocorrelation across the stripes
// shows its own envelope and its variance is 1. Regions stay m pixels from the image border
// and the seam (more than a kernel diameter of the wider kernel: parameters constant over
// every kernel reaching them).
void check_bandwidth_halves(const std::vector<float>& img, std::size_t w, std::size_t h,
                            const std::vector<double>& a, const std::vector<double>& n_prime,
                            std::size_t m) {
  const region left{m, w / 2 - m, m, h - m}, right{w / 2 + m, w - 1 - m, m, h - 1 - m};
  const hush::dvec2 F = freq(0.25, 0.0);
  for (int obj = 1; obj <= 2; ++obj) {
    const region& r = obj == 1 ? left : right;
    hush::npr_gabor::params p = small_kernel();
    p.bandwidth = a[std::size_t(obj)];
    p.impulses = n_prime[std::size_t(obj)];
    const hush::npr_gabor own(p);
    p.bandwidth = a[std::size_t(3 - obj)];
    const hush::npr_gabor other(p);
    CAPTURE(obj);
    for (const auto& d : {std::pair<int, int>{0, 1}, {0, 2}, {0, 3}, {1, 1}}) {
      // 4.5 standard errors (Bartlett).
      const double tol = 4.5 * bartlett_se(own.kernel(), F, d.first, d.second, pixels(r));
      const double measured = sample_rho(img, w, r, d.first, d.second);
      const double expected = npr_test::rho_at(own.kernel(), F, d.first, d.second);
      CAPTURE(d.second);
      CAPTURE(tol);
      CHECK(std::fabs(measured - expected) <= tol);
      // Along y (across the stripes) the envelope alone: the other half's bandwidth
      // would be far outside the tolerance.
      if (d.first == 0 && d.second >= 2)
        CHECK(std::fabs(expected - npr_test::rho_at(other.kernel(), F, d.first, d.second)) >
              4 * tol);
    }
    const double var_tol = 4.5 * std::sqrt((2.0 * sum_rho2(own.kernel(), F) +
                                            9.0 / (5.0 * own.density())) / pixels(r));
    CHECK(std::fabs(sample_variance(img, w, r) - 1.0) <= var_tol);
  }
}

}  // namespace

TEST_CASE("per-object bandwidth shows in each object's autocorrelation, variance 1 in each") {
  const std::size_t w = 256, h = 192;
  npr_test::grid_scene sc = npr_test::covering(w, h, 8.0, 20.0);
  split_objects(sc);
  const hush::npr_gabor noise(small_kernel());  // F0 = 1/4 along x
  const std::vector<double> a = {0.25, 0.15, 0.4};  // objects 0 (unused), 1, 2
  const std::vector<double> n_prime = {16, 8, 32};
  hush::npr_gabor::sources src;
  src.bandwidth = hush::param_source::per_object(a);
  src.impulses = hush::param_source::per_object(n_prime);
  check_bandwidth_halves(render(noise, sc, src), w, h, a, n_prime, 20);
  // A table holding the constants everywhere renders the constant image bit for bit.
  const std::vector<double> same_a = {0.25, 0.25, 0.25}, same_n = {16, 16, 16};
  hush::npr_gabor::sources same;
  same.bandwidth = hush::param_source::per_object(same_a);
  same.impulses = hush::param_source::per_object(same_n);
  CHECK(render(noise, sc, same) == render(noise, sc, {}));
}

TEST_CASE("per-pixel bandwidth and impulses in two bands: each band's envelope, variance 1") {
  // One object; the fields change at x = w/2, which is a grid column boundary: triangles
  // (their density from the centroid's pixel) and points (their radius from their own
  // pixel) on either side read their band's a and N'.
  const std::size_t w = 256, h = 192;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 8.0, 20.0);
  const hush::npr_gabor noise(small_kernel());
  const std::vector<double> a = {0.25, 0.15, 0.4}, n_prime = {16, 8, 32};
  std::vector<float> a_field(w * h), n_field(w * h);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      a_field[y * w + x] = static_cast<float>(x < w / 2 ? a[1] : a[2]);
      n_field[y * w + x] = static_cast<float>(x < w / 2 ? n_prime[1] : n_prime[2]);
    }
  hush::npr_gabor::sources src;
  src.bandwidth = hush::param_source::per_pixel({a_field.data(), w, h});
  src.impulses = hush::param_source::per_pixel({n_field.data(), w, h});
  std::vector<double> a_float(a.size());  // the field's values, rounded to float
  for (std::size_t i = 0; i < a.size(); ++i) a_float[i] = static_cast<float>(a[i]);
  check_bandwidth_halves(render(noise, sc, src), w, h, a_float, n_prime, 20);
}

TEST_CASE("per-pixel bandwidth and impulses: NaN and constant fields give the constant image") {
  // Fields of NaN, and fields holding the constants, render the constant image bit for
  // bit (0.25 and 16 are floats).
  const std::size_t w = 96, h = 80;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 7.0, 20.0);
  const hush::npr_gabor noise(small_kernel());
  std::vector<float> nan_field(w * h, std::numeric_limits<float>::quiet_NaN());
  std::vector<float> same_a(w * h, 0.25f), same_n(w * h, 16.0f);
  const std::vector<float> plain = render(noise, sc, {});
  hush::npr_gabor::sources nan_src;
  nan_src.bandwidth = hush::param_source::per_pixel({nan_field.data(), w, h});
  nan_src.impulses = hush::param_source::per_pixel({nan_field.data(), w, h});
  CHECK(render(noise, sc, nan_src) == plain);
  hush::npr_gabor::sources same;
  same.bandwidth = hush::param_source::per_pixel({same_a.data(), w, h});
  same.impulses = hush::param_source::per_pixel({same_n.data(), w, h});
  CHECK(render(noise, sc, same) == plain);
  // N' = 0 everywhere: no triangle has points, the image is 0.
  std::vector<float> zero(w * h, 0.0f);
  hush::npr_gabor::sources none;
  none.impulses = hush::param_source::per_pixel({zero.data(), w, h});
  const std::vector<float> empty = render(noise, sc, none);
  CHECK(std::all_of(empty.begin(), empty.end(), [](float v) { return v == 0.0f; }));
}

TEST_CASE("per-vertex bandwidth and impulses in two halves: each half's envelope, variance 1") {
  // Vertices left of x = w/2 hold a = 0.15, N' = 8, the others a = 0.4, N' = 32: triangles
  // of the column left of the seam interpolate between them (within 8 px of it), the regions
  // checked start 20 px from it (kernel discs reaching them lie beyond the transition).
  const std::size_t w = 256, h = 192;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 8.0, 20.0);
  const hush::npr_gabor noise(small_kernel());
  const std::vector<double> a = {0.25, 0.15, 0.4}, n_prime = {16, 8, 32};
  std::vector<float> a_vertex, n_vertex;
  for (const hush::vec2& v : sc.screen) {
    const std::size_t half = v.x < static_cast<float>(w / 2) ? 1 : 2;
    a_vertex.push_back(static_cast<float>(a[half]));
    n_vertex.push_back(static_cast<float>(n_prime[half]));
  }
  hush::npr_gabor::sources src;
  src.bandwidth = hush::param_source::per_vertex(a_vertex);
  src.impulses = hush::param_source::per_vertex(n_vertex);
  std::vector<double> a_float(a.size());  // the values, rounded to float
  for (std::size_t i = 0; i < a.size(); ++i) a_float[i] = static_cast<float>(a[i]);
  check_bandwidth_halves(render(noise, sc, src), w, h, a_float, n_prime, 20);
}

TEST_CASE("per-vertex sources: NaN and constant values give the constant image, sizes refused") {
  const std::size_t w = 96, h = 80;
  const npr_test::grid_scene sc = npr_test::covering(w, h, 7.0, 20.0);
  hush::npr_gabor::params p = small_kernel();
  p.orientation = 0.5;  // a float: the orientation values below hold it exactly
  const hush::npr_gabor noise(p);
  const std::size_t n = sc.screen.size();
  std::vector<float> nan_v(n, std::numeric_limits<float>::quiet_NaN());
  std::vector<float> same_a(n, 0.25f), same_n(n, 16.0f), same_o(n, 0.5f);
  const std::vector<float> plain = render(noise, sc, {});
  hush::npr_gabor::sources nan_src;
  nan_src.bandwidth = hush::param_source::per_vertex(nan_v);
  nan_src.impulses = hush::param_source::per_vertex(nan_v);
  nan_src.orientation = hush::param_source::per_vertex(nan_v);
  CHECK(render(noise, sc, nan_src) == plain);
  // Constant vertex values: sum b_i v = v (the barycentrics sum to 1 up to rounding), so a
  // and N' may differ from the constants by an ulp; the image is then within float noise.
  hush::npr_gabor::sources same;
  same.bandwidth = hush::param_source::per_vertex(same_a);
  same.impulses = hush::param_source::per_vertex(same_n);
  same.orientation = hush::param_source::per_vertex(same_o);
  const std::vector<float> img = render(noise, sc, same);
  double worst = 0;
  for (std::size_t i = 0; i < img.size(); ++i)
    worst = std::max(worst, std::fabs(static_cast<double>(img[i]) - plain[i]));
  CHECK(worst <= 1e-4);  // the interpolated energy (1e-3 relative) where an ulp moved a
  std::vector<float> short_v(n - 1, 0.2f);
  hush::npr_gabor::sources bad;
  bad.bandwidth = hush::param_source::per_vertex(short_v);
  std::vector<float> out(w * h);
  CHECK_THROWS_WITH_AS(
      noise.render(sc.frame(), sc.triangles(), hush::image_view<float>(out.data(), w, h), bad),
      doctest::Contains(("bandwidth vertex values = " + std::to_string(n - 1)).c_str()),
      hush::invalid_argument);
}

TEST_CASE("bandwidth and impulses: bad tables and mis-sized fields are refused, wild pixels not") {
  npr_test::grid_scene sc(16, 16, 0, 0, 8, 2, 2);
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  std::vector<float> out(std::size_t{16} * 16);
  const hush::image_view<float> view(out.data(), 16, 16);
  const std::vector<double> bad_a = {0.1, 20.0}, bad_n = {16, 0};
  hush::npr_gabor::sources src;
  src.bandwidth = hush::param_source::per_object(bad_a);
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("bandwidth[1] = 20"), hush::invalid_argument);
  src = {};
  src.impulses = hush::param_source::per_object(bad_n);
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("0 < impulses <= 256"), hush::invalid_argument);
  std::vector<float> field(std::size_t{8} * 8, 0.1f);
  src = {};
  src.bandwidth = hush::param_source::per_pixel({field.data(), 8, 8});
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("bandwidth field size = 8x8"), hush::invalid_argument);
  src = {};
  src.impulses = hush::param_source::per_pixel({field.data(), 8, 8});
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), sc.triangles(), view, src),
                       doctest::Contains("impulses field size = 8x8"), hush::invalid_argument);
  // Wild per-pixel a and N' (infinite, huge, negative, NaN) never throw: non-finite ->
  // the constant, finite values clamped to [0.01, 10] and [0, 256]; the image stays finite.
  std::vector<float> wild(std::size_t{16} * 16);
  for (std::size_t i = 0; i < wild.size(); ++i)
    wild[i] = i % 4 == 0 ? std::numeric_limits<float>::infinity()
                         : (i % 4 == 1 ? 1e30f : (i % 4 == 2 ? -3.0f : std::nanf("")));
  // N' is -3 (-> 0, no points) where a is 1e30 (-> 10): a density of 8600 points per
  // square pixel there would only make the test slow.
  std::vector<float> wild_n(wild.size());
  for (std::size_t i = 0; i < wild.size(); ++i) wild_n[i] = wild[(i + 1) % wild.size()];
  src = {};
  src.bandwidth = hush::param_source::per_pixel({wild.data(), 16, 16});
  src.impulses = hush::param_source::per_pixel({wild_n.data(), 16, 16});
  noise.render(sc.frame(), sc.triangles(), view, src);
  for (float v : out) CHECK(std::isfinite(v));
}
