// NPR Gabor noise (include/hush/npr_gabor.hpp; Benard, Lagae et al. 2010): the LOD
// weights (eqs. 2, 4 and the N < 1 case), validation, statistics (variance and
// autocorrelation, i.e. the spectrum, across triangle sizes and zoom), temporal
// coherence (points follow the surface, frequency stays in pixels) and visibility.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hush/hush.hpp"  // the umbrella: the suite also runs against the single header
#include "npr_gabor_scenes.hpp"

#ifndef HUSH_NPR_HUGE_SEEDS
#define HUSH_NPR_HUGE_SEEDS 32  // seeds of the huge-triangle test (64 to measure)
#endif
#ifndef HUSH_NPR_PLANE_SEEDS
#define HUSH_NPR_PLANE_SEEDS 4  // seeds of the foreshortened-plane test (64 to measure)
#endif

namespace {

using npr_test::grid_scene;

// Sample mean and variance of out over the pixels [m, w - m) x [m, h - m).
struct moments {
  double mean = 0, variance = 0;
  std::size_t n = 0;
};
moments interior_moments(const std::vector<float>& img, std::size_t w, std::size_t h,
                         std::size_t m) {
  moments r;
  double s = 0, s2 = 0;
  for (std::size_t y = m; y < h - m; ++y)
    for (std::size_t x = m; x < w - m; ++x) {
      const double v = img[y * w + x];
      s += v;
      s2 += v * v;
      ++r.n;
    }
  r.mean = s / static_cast<double>(r.n);
  r.variance = s2 / static_cast<double>(r.n) - r.mean * r.mean;
  return r;
}

std::vector<float> render(const hush::npr_gabor& noise, const grid_scene& sc) {
  std::vector<float> out(sc.width * sc.height);
  noise.render(sc.frame(), sc.triangles(),
               hush::image_view<float>(out.data(), sc.width, sc.height));
  return out;
}

// Standard error of a sample variance over n pixels of the unit-variance noise
// (see npr_gabor_scenes.hpp): sqrt((2 sum_d rho(d)^2 + 9 / (5 lambda)) / n). The
// fourth-cumulant term lambda E[v^4] scale^4 (int g^2)^2 = E[v^4] / (lambda E[v^2]^2)
// = (1/5) / (lambda / 9) is an upper bound under the LOD weights (w^4 <= w^2).
double variance_standard_error(const hush::npr_gabor& noise, std::size_t n) {
  const auto& k = noise.kernel();
  const double f = noise.parameters().frequency, th = noise.parameters().orientation;
  const hush::dvec2 F{f * std::cos(th), f * std::sin(th)};
  const double sum = npr_test::sum_rho_power(k, F, 2);
  return std::sqrt((2.0 * sum + 9.0 / (5.0 * noise.density())) / static_cast<double>(n));
}

hush::npr_gabor::params small_kernel() {
  hush::npr_gabor::params p;
  p.frequency = 0.25;  // 4-pixel period
  p.bandwidth = 0.25;  // r = 3.9 px: many independent pixels per image
  p.orientation = 0.3;
  return p;
}

}  // namespace

TEST_CASE("LOD weights: sum of squared weights is N, continuous in N, alpha(N) of eq. 4") {
  for (double n : {0.01, 0.3, 0.999, 1.0, 1.5, 2.0, 3.0, 3.999, 4.0, 7.3, 64.0, 1000.5}) {
    const hush::npr_gabor_lod l = hush::npr_gabor_lod::of(n);
    double s2 = 0;
    for (std::uint64_t j = 0; j < l.count; ++j) s2 += l.weight(j) * l.weight(j);
    CHECK(s2 == doctest::Approx(n).epsilon(1e-12));
    if (n >= 1) {
      const double m = std::exp2(std::floor(std::log2(n)));
      CHECK(l.first == static_cast<std::uint64_t>(m));
      CHECK(l.second_weight == doctest::Approx(std::sqrt(n / m - 1.0)));
      CHECK(l.count <= 2 * l.first);
    }
  }
  // No pops: every point's weight changes by O(sqrt(eps)) across N = 1, 2, 4, ... 1024.
  for (int e = 0; e <= 10; ++e) {  // an integer counter (clang-analyzer FloatLoopCounter)
    const double m = std::ldexp(1.0, e);
    const auto below = hush::npr_gabor_lod::of(m * (1 - 1e-9));
    const auto above = hush::npr_gabor_lod::of(m * (1 + 1e-9));
    const std::uint64_t count = std::max(below.count, above.count);
    for (std::uint64_t j = 0; j < count; ++j) {
      const double wb = j < below.count ? below.weight(j) : 0.0;
      const double wa = j < above.count ? above.weight(j) : 0.0;
      CHECK(std::fabs(wb - wa) < 1e-4);
    }
  }
  CHECK(hush::npr_gabor_lod::of(0.0).count == 0);
  CHECK(hush::npr_gabor_lod::of(std::numeric_limits<double>::quiet_NaN()).count == 0);
  // N is clamped at kNprGaborMaxPoints = 2^40: 2^40 points of weight 1.
  CHECK(hush::npr_gabor_lod::of(1e300).count == std::uint64_t(1) << 40);
  CHECK(hush::npr_gabor_lod::of(1e300).first_weight == 1.0);
}

TEST_CASE("parameters and inputs are validated, naming the parameter and range") {
  auto bad = [](auto edit, const char* name) {
    hush::npr_gabor::params p;
    edit(p);
    try {
      hush::npr_gabor n{p};
      FAIL("accepted bad ", name);
    } catch (const hush::invalid_argument& e) {
      CHECK(std::string(e.what()).find(name) != std::string::npos);
    }
  };
  bad([](auto& p) { p.frequency = 0.6; }, "frequency");
  bad([](auto& p) { p.bandwidth = std::nan(""); }, "bandwidth");
  bad([](auto& p) { p.truncation = 0.9; }, "truncation");
  bad([](auto& p) { p.impulses = 0; }, "impulses");
  bad([](auto& p) { p.orientation = INFINITY; }, "orientation");
  bad([](auto& p) { p.depth_tolerance = -1; }, "depth_tolerance");

  grid_scene sc(16, 16, 0, 0, 8, 2, 2);
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  std::vector<float> out(std::size_t{16} * 16);
  const hush::image_view<float> view(out.data(), 16, 16);
  auto tris = sc.triangles();
  std::vector<std::uint32_t> idx = sc.indices;
  idx[4] = 1000;  // out of range
  tris.indices = idx;
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), tris, view),
                       doctest::Contains("triangles.indices[4]"), hush::invalid_argument);
  tris = sc.triangles();
  tris.triangle_id = hush::span<const std::uint32_t>(sc.tri_id.data(), 3);
  CHECK_THROWS_WITH_AS(noise.render(sc.frame(), tris, view),
                       doctest::Contains("triangles.triangle_id size"), hush::invalid_argument);
  hush::frame f = sc.frame();
  f.object_id = {};
  CHECK_THROWS_WITH_AS(noise.render(f, sc.triangles(), view), doctest::Contains("object_id"),
                       hush::invalid_argument);
  CHECK_THROWS_AS(
      noise.render(sc.frame(), sc.triangles(), hush::image_view<float>(out.data(), 8, 8)),
      hush::invalid_argument);
}

TEST_CASE("variance 1 and the kernel's autocorrelation, for triangles from N = 0.18 to 11") {
  // One image per triangle size, sizes 2^(k/2) apart across the M switches (N < 1
  // included: those triangles carry one point of weight sqrt(N)). Each image's sample
  // variance must be 1 within 4.5 standard errors (variance_standard_error), its
  // autocorrelation at lags of a half and a whole period along omega0 the kernel's.
  const std::size_t w = 192, h = 192;
  const hush::npr_gabor noise{small_kernel()};
  const std::size_t m = 8;
  const double se = variance_standard_error(noise, (w - 2 * m) * (h - 2 * m));
  const auto& p = noise.parameters();
  const hush::dvec2 F{p.frequency * std::cos(p.orientation), p.frequency * std::sin(p.orientation)};
  const double rho_half = npr_test::rho_at(noise.kernel(), F, 2, 0);
  const double rho_full = npr_test::rho_at(noise.kernel(), F, 4, 1);
  MESSAGE("standard error of the variance: ", se, "; rho(2,0) = ", rho_half,
          ", rho(4,1) = ", rho_full);
  for (int k = -3; k <= 9; k += 3) {
    const double n_per_triangle = std::exp2(0.5 * k) * 0.5;  // 0.18 ... 11.3
    const double cell = std::sqrt(2.0 * n_per_triangle / noise.density());
    const grid_scene sc = npr_test::covering(w, h, cell, noise.kernel().radius() + 1);
    const auto img = render(noise, sc);
    const moments mo = interior_moments(img, w, h, m);
    double c_half = 0, c_full = 0;
    std::size_t n = 0;
    for (std::size_t y = m; y < h - m; ++y)
      for (std::size_t x = m; x < w - m; ++x) {
        c_half += (img[y * w + x] - mo.mean) * (img[y * w + x + 2] - mo.mean);
        c_full += (img[y * w + x] - mo.mean) * (img[(y + 1) * w + x + 4] - mo.mean);
        ++n;
      }
    c_half /= static_cast<double>(n) * mo.variance;
    c_full /= static_cast<double>(n) * mo.variance;
    MESSAGE("N per triangle ", n_per_triangle, " variance ", mo.variance, " rho(2,0) ", c_half,
            " rho(4,1) ", c_full);
    CHECK(std::fabs(mo.variance - 1.0) < 4.5 * se);
    // The correlation estimates' spread is below the variance's relative one.
    CHECK(std::fabs(c_half - rho_half) < 4.5 * se);
    CHECK(std::fabs(c_full - rho_full) < 4.5 * se);
  }
}

TEST_CASE("weighting the N < 1 point by N (the paper's words) would lose variance") {
  // The same field of small triangles (N = 0.25) rendered as shipped has variance 1;
  // its variance is the sum of squared weights per area, so a weight of N instead of
  // sqrt(N) would give 0.25: far outside the tolerance the test above uses.
  const std::size_t w = 160, h = 160, m = 8;
  const hush::npr_gabor noise{small_kernel()};
  const double cell = std::sqrt(2.0 * 0.25 / noise.density());
  const grid_scene sc = npr_test::covering(w, h, cell, noise.kernel().radius() + 1);
  const moments mo = interior_moments(render(noise, sc), w, h, m);
  const double se = variance_standard_error(noise, (w - 2 * m) * (h - 2 * m));
  CHECK(std::fabs(mo.variance - 1.0) < 4.5 * se);
  CHECK(4.5 * se < 0.75);
}

TEST_CASE("thinning: E[g] = N, continuous in N, a point only for u < 2N below N = 1/2") {
  using lod = hush::npr_gabor_lod;
  // E_u[g(N, u)] = N by the midpoint rule over u (g is piecewise linear in u: the rule's
  // error is below 1 / (2 K^2 N) from the ramp's end only).
  const int k = 200000;
  for (double n : {0.001, 0.01, 0.1, 0.25, 0.4999, 0.5, 0.5001, 0.7, 0.99, 1.0}) {
    double sum = 0;
    for (int i = 0; i < k; ++i) sum += lod::thinned_square(n, (i + 0.5) / k);
    CHECK(sum / k == doctest::Approx(n).epsilon(1e-6));
  }
  // Continuous in N for every u: at N = 1/2 (the pieces meet), N = 1 (weight 1 above) and
  // N = 0; zero for u >= 2N.
  for (double u : {0.0, 0.1, 0.37, 0.5, 0.9, 0.999}) {
    CHECK(std::fabs(lod::thinned_square(0.5 - 1e-12, u) - lod::thinned_square(0.5 + 1e-12, u)) <
          1e-9);
    CHECK(std::fabs(lod::thinned_square(1.0 - 1e-12, u) - 1.0) < 1e-9);
    CHECK(lod::thinned_square(1e-12, u) <= (u == 0.0 ? 1.0 : 0.0));
    CHECK(lod::thinned_square(0.2, u) == (u >= 0.4 ? 0.0 : doctest::Approx(1.0 - u / 0.4)));
  }
  CHECK(lod::thinned_square(std::numeric_limits<double>::quiet_NaN(), 0.5) == 0.0);
  CHECK(lod::thinned_square(-1.0, 0.0) == 0.0);
}

TEST_CASE("thinning keeps variance 1 and the spectrum with min(1, 2N) points per triangle") {
  // As the unthinned test above: variance within 4.5 standard errors (the fourth-cumulant
  // bound w^4 <= w^2 holds for thinned weights too), autocorrelation at two lags the
  // kernel's. The points kept are the unthinned ones less those with u >= 2N: given the
  // unthinned count T, the thinned count is Binomial(T, min(1, 2N)) (u is independent of
  // the point): within 5 standard deviations.
  const std::size_t w = 192, h = 192, m = 8;
  hush::npr_gabor::params p = small_kernel();
  const hush::npr_gabor plain{p};
  p.thinning = true;
  const hush::npr_gabor noise{p};
  const double se = variance_standard_error(noise, (w - 2 * m) * (h - 2 * m));
  const hush::dvec2 F{p.frequency * std::cos(p.orientation), p.frequency * std::sin(p.orientation)};
  const double rho_half = npr_test::rho_at(noise.kernel(), F, 2, 0);
  const double rho_full = npr_test::rho_at(noise.kernel(), F, 4, 1);
  for (double n_per_triangle : {0.06, 0.15, 0.35, 0.7}) {
    const double cell = std::sqrt(2.0 * n_per_triangle / noise.density());
    const grid_scene sc = npr_test::covering(w, h, cell, noise.kernel().radius() + 1);
    std::vector<hush::npr_gabor_splat> all, kept;
    plain.make_splats(sc.frame(), sc.triangles(), all);
    noise.make_splats(sc.frame(), sc.triangles(), kept);
    const double t = static_cast<double>(all.size()), q = std::min(1.0, 2.0 * n_per_triangle);
    MESSAGE("N ", n_per_triangle, ": ", kept.size(), " of ", all.size(), " points kept");
    CHECK(std::fabs(static_cast<double>(kept.size()) - q * t) <= 5.0 * std::sqrt(t * q * (1 - q)) + 1);
    const auto img = render(noise, sc);
    const moments mo = interior_moments(img, w, h, m);
    double c_half = 0, c_full = 0;
    for (std::size_t y = m; y < h - m; ++y)
      for (std::size_t x = m; x < w - m; ++x) {
        c_half += (img[y * w + x] - mo.mean) * (img[y * w + x + 2] - mo.mean);
        c_full += (img[y * w + x] - mo.mean) * (img[(y + 1) * w + x + 4] - mo.mean);
      }
    c_half /= static_cast<double>(mo.n) * mo.variance;
    c_full /= static_cast<double>(mo.n) * mo.variance;
    MESSAGE("variance ", mo.variance, " rho(2,0) ", c_half, " rho(4,1) ", c_full);
    CHECK(std::fabs(mo.variance - 1.0) < 4.5 * se);
    CHECK(std::fabs(c_half - rho_half) < 4.5 * se);
    CHECK(std::fabs(c_full - rho_full) < 4.5 * se);
  }
}

TEST_CASE("temporal coherence: a translated surface carries its noise with it") {
  // Points are attached to the triangles (same seed, same barycentrics every frame), the
  // kernel lives in screen space: moving the mesh by (5, -3) pixels moves the image.
  const hush::npr_gabor noise{small_kernel()};
  const std::size_t w = 96, h = 96;
  const grid_scene a(w, h, 2.0, 6.0, 7.0, 12, 12);
  const grid_scene b(w, h, 7.0, 3.0, 7.0, 12, 12);
  const auto ia = render(noise, a), ib = render(noise, b);
  double worst = 0, energy = 0;
  for (std::size_t y = 10; y < 80; ++y)
    for (std::size_t x = 10; x < 80; ++x) {
      worst = std::max(worst, std::fabs(double(ia[y * w + x]) - ib[(y - 3) * w + x + 5]));
      energy += double(ia[y * w + x]) * ia[y * w + x];
    }
  CHECK(energy > 100.0);  // not trivially zero
  CHECK(worst < 1e-4);    // float rounding of the moved positions only
  // A different seed is a different noise (the comparison above can fail).
  auto p = small_kernel();
  p.seed = 1;
  const auto ic = render(hush::npr_gabor{p}, b);
  double diff = 0;
  for (std::size_t y = 10; y < 80; ++y)
    for (std::size_t x = 10; x < 80; ++x)
      diff = std::max(diff, std::fabs(double(ia[y * w + x]) - ic[(y - 3) * w + x + 5]));
  CHECK(diff > 0.5);
}

TEST_CASE("points are a prefix: growing a triangle within one level only reweights") {
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  for (std::uint32_t j = 0; j < 8; ++j) {
    const auto a = noise.point_of(3, 17, j), b = noise.point_of(3, 17, j);
    CHECK(a.b[0] == b.b[0]);
    CHECK(a.b[0] + a.b[1] + a.b[2] == doctest::Approx(1.0));
    CHECK(a.b[0] >= 0);
    CHECK(a.b[1] >= 0);
    CHECK(a.b[2] >= 0);
    CHECK(std::fabs(a.amplitude) < 1.0);
  }
  CHECK(noise.point_of(3, 17, 0).b[1] != noise.point_of(3, 18, 0).b[1]);
  CHECK(noise.point_of(3, 17, 0).b[1] != noise.point_of(4, 17, 0).b[1]);
}

TEST_CASE("visibility: object, triangle and depth tests cut the kernels, back faces emit nothing") {
  const std::size_t w = 64, h = 64;
  grid_scene sc(w, h, 8, 8, 12, 4, 4);
  auto p = small_kernel();
  p.bandwidth = 0.1;  // r = 9.8 px: kernels spill well beyond the plane
  p.depth_test = false;
  p.object_test = false;
  const auto all = render(hush::npr_gabor{p}, sc);
  double outside = 0;
  for (std::size_t x = 0; x < w; ++x) outside += std::fabs(all[2 * w + x]);  // row 2: off the plane
  CHECK(outside > 0.1);
  p.object_test = true;
  auto cut = render(hush::npr_gabor{p}, sc);
  for (std::size_t i = 0; i < w * h; ++i)
    if (sc.object[i] == 0) CHECK(cut[i] == 0.0f);
  // Triangle test: every pixel only sees its own triangle's points.
  p.triangle_test = true;
  cut = render(hush::npr_gabor{p}, sc);
  double in = 0;
  for (std::size_t i = 0; i < w * h; ++i) {
    if (sc.object[i] == 0) CHECK(cut[i] == 0.0f);
    in += std::fabs(cut[i]);
  }
  CHECK(in > 1.0);
  // Depth test: a region whose depth is 10% off the plane gets nothing at tolerance 2%,
  // a linear fade with the soft test at tolerance 6.67% (1.5 tolerances: half weight).
  p.triangle_test = false;
  p.depth_test = true;
  for (std::size_t y = 20; y < 40; ++y)
    for (std::size_t x = 20; x < 40; ++x) sc.depth[y * w + x] = 1.1f;
  cut = render(hush::npr_gabor{p}, sc);
  for (std::size_t y = 20; y < 40; ++y)
    for (std::size_t x = 20; x < 40; ++x) CHECK(cut[y * w + x] == 0.0f);
  CHECK(cut[10 * w + 10] != 0.0f);
  p.soft_depth = true;
  auto hard_p = p;
  hard_p.soft_depth = false;
  hard_p.depth_tolerance = 1.0;  // everything passes
  const auto full = render(hush::npr_gabor{hard_p}, sc);
  // rel = |z_pixel * (1/z_plane) - 1| = 0.1 = 1.5 tolerances: weight 2 - 1.5 = 0.5.
  p.depth_tolerance = 0.1 / 1.5;
  const auto soft = render(hush::npr_gabor{p}, sc);
  for (std::size_t y = 20; y < 40; ++y)
    for (std::size_t x = 20; x < 40; ++x)
      CHECK(soft[y * w + x] == doctest::Approx(0.5 * full[y * w + x]).epsilon(1e-3).scale(1e-5));
  // Back faces: the same mesh with every triangle's winding reversed renders nothing.
  grid_scene back = sc;
  for (std::size_t t = 0; t + 2 < back.indices.size(); t += 3)
    std::swap(back.indices[t + 1], back.indices[t + 2]);
  const auto none = render(hush::npr_gabor{p}, back);
  for (float v : none) CHECK(v == 0.0f);
  p.cull_back_faces = false;
  const auto two_sided = render(hush::npr_gabor{p}, back);
  CHECK(std::any_of(two_sided.begin(), two_sided.end(), [](float v) { return v != 0.0f; }));
}

TEST_CASE("hard inputs: NaN, behind-camera and huge triangles give a finite image") {
  const std::size_t w = 32, h = 32;
  grid_scene sc(w, h, 0, 0, 8, 4, 4);
  sc.screen[1] = {std::nanf(""), 3.0f};
  sc.vdepth[7] = -1.0f;
  sc.screen[20] = {1e30f, -1e30f};
  const auto img = render(hush::npr_gabor{small_kernel()}, sc);
  for (float v : img) CHECK(std::isfinite(v));
}

TEST_CASE("float render is within its budget of the double reference") {
  const std::size_t w = 80, h = 80;
  const grid_scene sc(w, h, -10, -10, 9.5, 11, 11);
  const hush::npr_gabor noise{small_kernel()};
  const auto f = render(noise, sc);
  std::vector<double> d(w * h);
  noise.render(sc.frame(), sc.triangles(), hush::image_view<double>(d.data(), w, h));
  double worst = 0;
  for (std::size_t i = 0; i < w * h; ++i) worst = std::max(worst, std::fabs(f[i] - d[i]));
  // Per kernel 2^-21 (1 + 2 pi F0 r) (gabor_kernel.hpp) times scale; about N' kernels
  // reach a pixel, each weight |w v| <= 1: bound N' scale 2^-21 (1 + 2 pi F0 r) x 4
  // (the neighbourhood's count exceeds N' by a few standard deviations).
  const auto& p = noise.parameters();
  const double bound =
      4.0 * p.impulses * noise.scale() * std::ldexp(1.0, -21) *
      (1.0 + hush::detail::constants::kTwoPi * p.frequency * noise.kernel().radius());
  MESSAGE("float vs double: ", worst, " (bound ", bound, ")");
  CHECK(worst < bound);
  CHECK(worst > 0.0);
}

namespace {

// Stage 1's screen position of a point of root barycentrics b in triangle (s, z), as
// triangle_splats computes it (sum b_i z_i s_i / sum b_i z_i, double, the same order).
hush::dvec2 project(const hush::npr_gabor::point& pt, const hush::triangle_list& t,
                    std::size_t tri) {
  double sx[3], sy[3], z[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint32_t v = t.indices[3 * tri + i];
    sx[i] = static_cast<double>(t.screen[v].x);
    sy[i] = static_cast<double>(t.screen[v].y);
    z[i] = static_cast<double>(t.depth[v]);
  }
  const double hw = pt.b[0] * z[0] + pt.b[1] * z[1] + pt.b[2] * z[2];
  return {(pt.b[0] * z[0] * sx[0] + pt.b[1] * z[1] * sx[1] + pt.b[2] * z[2] * sx[2]) / hw,
          (pt.b[0] * z[0] * sy[0] + pt.b[1] * z[1] * sy[1] + pt.b[2] * z[2] * sy[2]) / hw};
}

// The LOD of grid_scene triangle `tri` (constant sources): N = lambda |cross| / 2.
hush::npr_gabor_lod lod_of(const hush::npr_gabor& noise, const hush::triangle_list& t,
                           std::size_t tri) {
  const hush::vec2 a = t.screen[t.indices[3 * tri]], b = t.screen[t.indices[3 * tri + 1]],
                   c = t.screen[t.indices[3 * tri + 2]];
  const double e1x = double(b.x) - a.x, e1y = double(b.y) - a.y;
  const double e2x = double(c.x) - a.x, e2y = double(c.y) - a.y;
  return hush::npr_gabor_lod::of(noise.density() * 0.5 * std::fabs(e1x * e2y - e1y * e2x));
}

}  // namespace

TEST_CASE("sequence: every J below the count once, in J order; M's points a prefix of 2M's") {
  // Two triangles well inside a 256^2 image (nothing culled): each triangle's records are
  // J = 0 ... count - 1 in order, at point_of(J)'s position. Doubling N' doubles N (the
  // same screen triangles), so M doubles: the records of the smaller N are the first ones
  // of the larger, the same points bit for bit (position; the weights change with the LOD).
  const std::size_t w = 256, h = 256;
  const grid_scene sc(w, h, 40, 40, 176, 1, 1);
  const auto tris = sc.triangles();
  hush::npr_gabor::params p = small_kernel();
  p.impulses = 8;
  const hush::npr_gabor small{p};
  p.impulses = 16;
  const hush::npr_gabor large{p};
  std::vector<hush::npr_gabor_splat> a, b;
  small.make_splats(sc.frame(), tris, a);
  large.make_splats(sc.frame(), tris, b);
  std::size_t at_a = 0, at_b = 0;
  for (std::size_t t = 0; t < 2; ++t) {
    const hush::npr_gabor_lod la = lod_of(small, tris, t), lb = lod_of(large, tris, t);
    REQUIRE(lb.first == 2 * la.first);  // M doubles
    REQUIRE(la.count > 1000);
    for (std::uint64_t j = 0; j < lb.count; ++j) {
      REQUIRE(at_b < b.size());
      const hush::npr_gabor_splat& rb = b[at_b++];
      CHECK(rb.index == j);
      CHECK(rb.triangle == tris.triangle_id[t]);
      const hush::dvec2 s = project(large.point_of(1, tris.triangle_id[t], j), tris, t);
      CHECK((rb.x == s.x && rb.y == s.y));
      if (j < la.count) {
        REQUIRE(at_a < a.size());
        const hush::npr_gabor_splat& ra = a[at_a++];
        CHECK(ra.index == j);
        CHECK((ra.x == rb.x && ra.y == rb.y));
      }
    }
  }
  CHECK(at_a == a.size());
  CHECK(at_b == b.size());
  // J = 0 is the flat sequence's point 0: words 0 and 1 of the triangle's stream.
  const auto p0 = large.point_of(1, 5, 0);
  hush::rng r(hush::hash32(hush::hash32(hush::seed_key(p.seed), 1), 5),
              hush::detail::constants::kNprGaborStream);
  const std::uint32_t w0 = r.next_u32(), w1 = r.next_u32();
  const double su = std::sqrt(hush::detail::gabor_half<double>(w0, 0));
  CHECK(p0.b[0] == 1.0 - su);
  CHECK(p0.amplitude == 2.0 * hush::detail::gabor_half<double>(w1, 0) - 1.0);
}

TEST_CASE("culling is exact: the walk's records are every point's, each culled alone") {
  // A triangle of 600-pixel legs (N = 6.0e4, 2^16 points) around a 64^2 image: the walk
  // skips the subtrees whose screen triangle misses the image grown by r. The reference
  // generates all 2^16 points by point_of(J) and keeps those whose pixel range meets the
  // image: the same J, positions and weights bit for bit, from far fewer nodes.
  const std::size_t w = 64, h = 64;
  const grid_scene sc(w, h, -300, -200, 600, 1, 1);
  const auto tris = sc.triangles();
  const hush::npr_gabor noise{small_kernel()};
  std::vector<hush::npr_gabor_splat> got;
  std::uint64_t nodes = 0;
  noise.make_splats(sc.frame(), tris, got, {}, &nodes);
  const double r = noise.kernel().radius();
  std::size_t at = 0;
  std::uint64_t total = 0;
  for (std::size_t t = 0; t < 2; ++t) {
    const hush::npr_gabor_lod lod = lod_of(noise, tris, t);
    total += lod.count;
    for (std::uint64_t j = 0; j < lod.count; ++j) {
      const auto pt = noise.point_of(1, tris.triangle_id[t], j);
      const hush::dvec2 s = project(pt, tris, t);
      // The pixel centres within r, clamped to the image: none, the point is culled.
      if (std::max(std::ceil(s.x - r - 0.5), 0.0) > std::min(std::floor(s.x + r - 0.5), w - 1.0) ||
          std::max(std::ceil(s.y - r - 0.5), 0.0) > std::min(std::floor(s.y + r - 0.5), h - 1.0))
        continue;
      REQUIRE(at < got.size());
      const hush::npr_gabor_splat& g = got[at++];
      CHECK(g.index == j);
      CHECK(g.triangle == tris.triangle_id[t]);
      CHECK((g.x == s.x && g.y == s.y));
      CHECK(g.weight == lod.weight(j) * pt.amplitude * noise.scale());
    }
  }
  CHECK(at == got.size());
  MESSAGE("records ", got.size(), " of ", total, " points; nodes examined ", nodes);
  CHECK(got.size() > 100);
  CHECK(nodes < total / 16);
}

TEST_CASE("marginal uniformity: point J falls uniformly into the 16 depth-2 sub-triangles") {
  // Over triangle ids (a fixed seed), point J's root barycentrics must be uniform on the
  // triangle: the random child order is what makes them so (a fixed order would put J = 5,
  // the own point of a depth-2 node, always into the same depth-2 sub-triangle: chi^2 = 15 n).
  // Cell (i, j, k) = floor(4 b) (clamped to 3): i + j + k = 3 for the 10 upright cells,
  // 2 for the 6 inverted ones. Pearson's chi^2 over the 16 cells with n = 3200 (200
  // expected per cell, far above the 5 the chi^2 approximation needs) against its 1e-4
  // upper quantile for 15 degrees of freedom (Wilson-Hilferty: k (1 - 2/(9k) + z sqrt(2/(9k)))^3,
  // z = 3.719): a false failure once in 10^4 seeds per J.
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  const int n = 3200, dof = 15;
  const double z = 3.719, c = 2.0 / (9.0 * dof);
  const double limit = dof * std::pow(1.0 - c + z * std::sqrt(c), 3.0);
  // J = 5, 22, 100: depth-2, 3 and 4 nodes on different paths (21 would lie in 5's node).
  for (std::uint64_t jj : {0, 5, 22, 100}) {
    int cells[4][4][2] = {};
    int odd = 0;
    for (int id = 0; id < n; ++id) {
      const auto pt = noise.point_of(7, static_cast<std::uint32_t>(id), jj);
      int q[3];
      for (int k = 0; k < 3; ++k) q[k] = std::min(3, static_cast<int>(std::floor(4.0 * pt.b[k])));
      const int s = q[0] + q[1] + q[2];
      if (s == 3 || s == 2)
        ++cells[q[0]][q[1]][s - 2];
      else
        ++odd;
    }
    double chi2 = 0;
    int used = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int s = 0; s < 2; ++s) {
          const int k = s + 2 - i - j;  // upright (s = 1: i + j + k = 3) or inverted (s = 0)
          if (k < 0 || k > 3) continue;
          ++used;
          const double e = n / 16.0;
          chi2 += (cells[i][j][s] - e) * (cells[i][j][s] - e) / e;
        }
    MESSAGE("J = ", jj, ": chi^2 = ", chi2, " (limit ", limit, ")");
    CHECK(used == 16);
    CHECK(odd == 0);
    CHECK(chi2 < limit);
  }
}

TEST_CASE("huge triangles: legs 1e5 and 1e6 px keep variance 1 with bounded work") {
  // One triangle of legs L around a 64^2 frame (N = lambda L^2 / 2 = 1.7e9 and 1.7e11 with
  // the small kernel, 1.7e8 and 1.7e10 at the defaults: far above the old clamp of 2^22, which
  // gave variance 2^22 / N). The walk examines only the subtrees near the frame: a few
  // thousand nodes, not the 2^22 points the clamp used to generate. The mean of the frames'
  // variances over `seeds` seeds must be 1 within 4.5 standard errors,
  // variance_standard_error / sqrt(seeds): its Poisson fourth-cumulant term is not below the
  // measured spread of the hierarchical (stratified) points: the frames' variances have sd
  // 0.065 over 64 seeds (0.068 - 0.069 over the 32 here) against 0.0695 from the formula and
  // 0.059 without its fourth-cumulant term (docs/npr-gabor.md, "Huge triangles").
  const std::size_t w = 64, h = 64;
  const int seeds = HUSH_NPR_HUGE_SEEDS;
  hush::npr_gabor::params p = small_kernel();
  const double se = variance_standard_error(hush::npr_gabor{p}, w * h);
  for (double legs : {1e5, 1e6}) {
    const grid_scene sc(w, h, -legs / 3, -legs / 3, legs, 1, 1);
    double sum = 0, sum2 = 0;
    std::uint64_t most_nodes = 0;
    for (int k = 0; k < seeds; ++k) {
      p.seed = static_cast<std::uint32_t>(100 + k);
      const hush::npr_gabor noise{p};
      std::vector<hush::npr_gabor_splat> splats;
      std::uint64_t nodes = 0;
      noise.make_splats(sc.frame(), sc.triangles(), splats, {}, &nodes);
      most_nodes = std::max(most_nodes, nodes);
      std::vector<float> out(w * h);
      noise.splat(hush::exec::scalar, sc.frame(), splats.data(), splats.size(),
                  hush::image_view<float>(out.data(), w, h));
      const double v = interior_moments(out, w, h, 0).variance;
      sum += v;
      sum2 += v * v;
      if (k == 0)
        MESSAGE("legs ", legs, ": N = ", noise.density() * legs * legs / 2, ", records ",
                splats.size(), ", nodes examined ", nodes);
    }
    const double mean = sum / seeds;
    const double sd = std::sqrt(std::max(0.0, sum2 / seeds - mean * mean) * seeds / (seeds - 1));
    MESSAGE("legs ", legs, ": mean variance ", mean, " over ", seeds, " seeds, sd ", sd,
            " (Poisson bound ", se, "); most nodes ", most_nodes);
    CHECK(std::fabs(mean - 1.0) < 4.5 * se / std::sqrt(double(seeds)));
    CHECK(most_nodes < 8000);
  }
}

TEST_CASE("local density: the hats sum to 1 over the levels, continuous at 1/4, 1 and 4") {
  // Root (coarsest) to finest level K, counts n 4^-k (an affine node's children each have a
  // quarter of its area): sum_k local_square(n 4^-k) / (n 4^-k) = 1 for every n > 0, the
  // partition of unity of the hat in log4 (docs/npr-gabor.md "Local density").
  using lod = hush::npr_gabor_lod;
  for (int K : {0, 1, 2, 5, 21})
    // n from 1e-3 to below 1e7 in ratios of 1.0137: 1693 steps (ln 1e10 / ln 1.0137 = 1692.2),
    // counted in an integer (clang-analyzer FloatLoopCounter).
    for (int i = 0; i < 1693; ++i) {
      const double n = 1e-3 * std::pow(1.0137, i);
      double sum = 0, nk = n;
      for (int k = 0; k <= K; ++k, nk *= 0.25) sum += lod::local_square(nk, k == 0, k == K) / nk;
      CHECK(std::fabs(sum - 1.0) < 1e-12);
    }
  // No pops: every level's squared weight moves by < 1e-4 for a relative change of n of 1e-9
  // at the hat's corners (n = 1/4, 1, 4) and at the root's and finest level's joins.
  for (double n : {0.25, 1.0, 4.0})
    for (bool coarsest : {false, true})
      for (bool finest : {false, true}) {
        const double lo = lod::local_square(n * (1 - 1e-9), coarsest, finest);
        const double hi = lod::local_square(n * (1 + 1e-9), coarsest, finest);
        CHECK(std::fabs(hi - lo) < 1e-4);
      }
  CHECK(lod::local_square(0.0, true, false) == 0.0);
  CHECK(lod::local_square(std::numeric_limits<double>::quiet_NaN(), true, true) == 0.0);
  CHECK(lod::local_square(0.5, true, false) == 0.5);  // the paper's N < 1 point: sqrt(N)^2
  CHECK(lod::local_square(0.25, false, false) == 0.0);
  CHECK(lod::local_square(4.0, false, false) == 0.0);
  CHECK(lod::local_square(1e30, false, true) == hush::detail::constants::kNprGaborMaxPoints);
  // Validation is unchanged by the option.
  hush::npr_gabor::params p = small_kernel();
  p.local_density = true;
  p.impulses = 0;
  CHECK_THROWS_WITH_AS(hush::npr_gabor{p}, doctest::Contains("impulses"), hush::invalid_argument);
}

namespace {
// A ground plane under perspective: one quad (two triangles) covering a w x h image and
// `margin` pixels beyond, its top edge at depth `far`, its bottom edge at depth 1 (clip W):
// object-uniform points are (far)^3 times denser on screen near the top than near the bottom.
grid_scene ground_plane(std::size_t w, std::size_t h, double margin, float far) {
  grid_scene sc(w, h, -margin, -margin, static_cast<double>(w) + 2 * margin, 1, 1);
  sc.vdepth = {far, far, 1.0f, 1.0f};  // vertices (0,0), (1,0) top; (0,1), (1,1) bottom
  return sc;
}
// The variance of the pixels of rows [y0, y1), columns [m, w - m) about 0 (the noise's mean).
double window_variance(const std::vector<float>& img, std::size_t w, std::size_t m, std::size_t y0,
                       std::size_t y1) {
  double s2 = 0;
  for (std::size_t y = y0; y < y1; ++y)
    for (std::size_t x = m; x < w - m; ++x) s2 += double(img[y * w + x]) * img[y * w + x];
  return s2 / static_cast<double>((y1 - y0) * (w - 2 * m));
}
}  // namespace

TEST_CASE("local density: variance 1 near and far on a foreshortened plane; per triangle not") {
  // The plane's top is 4x as deep as its bottom. With one N = lambda A per triangle (the
  // paper) the screen density follows the perspective: the far window's variance is far
  // above the near one's. With local_density each window's variance (mean over `seeds`
  // seeds) must be 1 within 4.5 standard errors: variance_standard_error / sqrt(seeds), its
  // fourth-cumulant bound w^4 <= w^2 scaled by the largest squared weight, max f = 1.0615
  // (n h(n) at log4 n = 1 - 1 / ln 4), i.e. se times sqrt(1.0615) at most. The depth
  // test is off (the grid scene's depth buffer is flat); the object test stays on.
  const std::size_t w = 160, h = 160, m = 8, band = 40;
  const int seeds = HUSH_NPR_PLANE_SEEDS;
  hush::npr_gabor::params p = small_kernel();
  p.depth_test = false;
  const grid_scene sc = ground_plane(w, h, 16.0, 4.0f);
  double near_paper = 0, far_paper = 0, near_local = 0, far_local = 0;
  for (int k = 0; k < seeds; ++k) {
    p.seed = static_cast<std::uint32_t>(40 + k);
    p.local_density = false;
    const auto paper = render(hush::npr_gabor{p}, sc);
    p.local_density = true;
    const auto local = render(hush::npr_gabor{p}, sc);
    far_paper += window_variance(paper, w, m, m, m + band) / seeds;
    near_paper += window_variance(paper, w, m, h - m - band, h - m) / seeds;
    far_local += window_variance(local, w, m, m, m + band) / seeds;
    near_local += window_variance(local, w, m, h - m - band, h - m) / seeds;
  }
  // A per-pixel N' field equal to the constant everywhere reads each node's density at its
  // centroid's pixel (the path of varying densities) and must give the same records.
  std::vector<float> field(w * h, static_cast<float>(p.impulses));
  hush::npr_gabor::sources src;
  src.impulses = hush::param_source::per_pixel({field.data(), w, h});
  std::vector<hush::npr_gabor_splat> constant, per_pixel;
  hush::npr_gabor{p}.make_splats(sc.frame(), sc.triangles(), constant);
  hush::npr_gabor{p}.make_splats(sc.frame(), sc.triangles(), per_pixel, src);
  REQUIRE(constant.size() == per_pixel.size());
  bool same = true;
  for (std::size_t i = 0; i < constant.size(); ++i)
    same = same && constant[i].weight == per_pixel[i].weight &&
           constant[i].index == per_pixel[i].index;
  CHECK(same);
  const double se = variance_standard_error(hush::npr_gabor{p}, band * (w - 2 * m)) *
                    std::sqrt(1.0615 / seeds);
  MESSAGE("per triangle: far ", far_paper, " near ", near_paper, "; local density: far ",
          far_local, " near ", near_local, "; standard error ", se);
  CHECK(std::fabs(far_local - 1.0) < 4.5 * se);
  CHECK(std::fabs(near_local - 1.0) < 4.5 * se);
  CHECK(far_paper - near_paper > 20 * se);  // what the option fixes
}

TEST_CASE("local density: triangles with N <= 1/4 keep the per-triangle records, thinned too") {
  // Below n = 1/4 the root is the only node with a weight (f_root = n = sqrt(N)^2) and
  // nothing is walked, so the option changes no record; with thinning the root's squared
  // weight is the per-triangle thinned one (E_u[g] = n) in both.
  hush::npr_gabor::params p = small_kernel();
  for (bool thin : {false, true}) {
    p.thinning = thin;
    p.local_density = false;
    const hush::npr_gabor paper{p};
    p.local_density = true;
    const hush::npr_gabor local{p};
    const double cell = std::sqrt(2.0 * 0.2 / paper.density());  // N = 0.2 per triangle
    const grid_scene sc = npr_test::covering(64, 64, cell, paper.kernel().radius() + 1);
    std::vector<hush::npr_gabor_splat> a, b;
    paper.make_splats(sc.frame(), sc.triangles(), a);
    local.make_splats(sc.frame(), sc.triangles(), b);
    REQUIRE(a.size() == b.size());
    REQUIRE(!a.empty());
    bool same = true;
    for (std::size_t i = 0; i < a.size(); ++i)
      same = same && a[i].x == b[i].x && a[i].y == b[i].y && a[i].weight == b[i].weight &&
             a[i].index == b[i].index && a[i].triangle == b[i].triangle;
    CHECK(same);
  }
}

TEST_CASE("local density: huge triangles keep bounded work, nodes near the image only") {
  // As "huge triangles" above (legs 1e5 and 1e6 px around a 64^2 frame, n_root 1.7e9 and
  // 1.7e11): the local walk visits the nodes that meet the image (grown by r) with
  // n > 1/4, and examines their 4 children each. Level k's nodes of count n_k meeting the
  // frame grown by r number about lambda B / n_k (B = (w + 2r)^2), and the levels with
  // n_k > 1/4 sum to at most lambda B 4 (1 + 1/4 + ...) = (16/3) lambda B: the bound is 4x
  // that (children examined), the nodes straddling the box's border being the slack.
  const std::size_t w = 64, h = 64;
  hush::npr_gabor::params p = small_kernel();
  const hush::npr_gabor paper{p};
  p.local_density = true;
  const hush::npr_gabor noise{p};
  for (double legs : {1e5, 1e6}) {
    const grid_scene sc(w, h, -legs / 3, -legs / 3, legs, 1, 1);
    std::vector<hush::npr_gabor_splat> splats, paper_splats;
    std::uint64_t nodes = 0, paper_nodes = 0;
    noise.make_splats(sc.frame(), sc.triangles(), splats, {}, &nodes);
    paper.make_splats(sc.frame(), sc.triangles(), paper_splats, {}, &paper_nodes);
    MESSAGE("legs ", legs, ": records ", splats.size(), " (per triangle ", paper_splats.size(),
            "), nodes examined ", nodes, " (per triangle ", paper_nodes, ")");
    const double grown = static_cast<double>(w) + 2 * noise.kernel().radius();
    CHECK(static_cast<double>(nodes) < 4 * (16.0 / 3.0) * noise.density() * grown * grown);
    CHECK(!splats.empty());
  }
}

TEST_CASE("near plane: a ground plane under the camera has variance 1 up to the image bottom") {
  // Both triangles have a vertex behind the camera (depth -1). Stage 1 walks them with the
  // local density's count per node, whatever params::local_density says, clipping the nodes
  // at w_near = far / 1024: the band of the image's bottom 40 rows (depths 0.4 - 0.5) must
  // have variance 1 within 4.5 standard errors (as "local density: variance 1 near and far",
  // whose standard error this is: se / sqrt(seeds), scaled by sqrt(max f) = sqrt(1.0615)),
  // where such triangles used to emit nothing (variance 0); so must a band at the top.
  const std::size_t w = 160, h = 160, m = 8, band = 40;
  const int seeds = 4;
  hush::npr_gabor::params p = small_kernel();
  const grid_scene sc = npr_test::ground_under_camera(-1.0f);
  double near_v = 0, far_v = 0;
  for (int k = 0; k < seeds; ++k) {
    p.seed = static_cast<std::uint32_t>(70 + k);
    // params::local_density off: crossing triangles use the count per node anyway (the same
    // records with it on: "near plane: no point behind it ..." below).
    const auto img = render(hush::npr_gabor{p}, sc);
    near_v += window_variance(img, w, m, h - m - band, h - m) / seeds;
    far_v += window_variance(img, w, m, m, m + band) / seeds;
  }
  const double se =
      variance_standard_error(hush::npr_gabor{p}, band * (w - 2 * m)) * std::sqrt(1.0615 / seeds);
  MESSAGE("ground under the camera: bottom band ", near_v, ", top band ", far_v,
          "; standard error ", se);
  CHECK(std::fabs(near_v - 1.0) < 4.5 * se);
  CHECK(std::fabs(far_v - 1.0) < 4.5 * se);
}

TEST_CASE("near plane: no point behind it, deterministic, option-independent, bounded nodes") {
  // Every record's point (point_of: its root barycentrics) is in front of w_near = 3 / 1024;
  // two calls give the same records bit for bit, and so does params::local_density (the
  // crossing triangles use it anyway). Nodes: the walk examines 4 children of each node
  // visited, and visits the nodes with a count above 1/4 whose part in front of w_near meets
  // the image grown by r: in front, level by level, about lambda B / n_k of them (B the
  // grown image's area: (16/3) lambda B over the levels, as "local density: huge
  // triangles"); crossing w_near, the nodes along the line w = w_near, whose part in front
  // meets the image only while they reach depth 0.4 (the image's bottom) from w_near: a few
  // levels, 2^k nodes each. The bound is 4 (16/3) lambda B per triangle.
  const std::size_t w = 160, h = 160;
  hush::npr_gabor::params p = small_kernel();
  const grid_scene sc = npr_test::ground_under_camera(-1.0f);
  const hush::npr_gabor noise{p};
  std::vector<hush::npr_gabor_splat> a, b, c;
  std::uint64_t nodes = 0;
  noise.make_splats(sc.frame(), sc.triangles(), a, {}, &nodes);
  noise.make_splats(sc.frame(), sc.triangles(), b);
  p.local_density = true;
  hush::npr_gabor{p}.make_splats(sc.frame(), sc.triangles(), c);
  REQUIRE(!a.empty());
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() == c.size());
  bool same = true, in_front = true;
  double nearest = 1e300;
  for (std::size_t i = 0; i < a.size(); ++i) {
    same = same && a[i].x == b[i].x && a[i].y == b[i].y && a[i].weight == b[i].weight &&
           a[i].index == b[i].index && a[i].x == c[i].x && a[i].weight == c[i].weight;
    const auto pt = noise.point_of(a[i].object, a[i].triangle, a[i].index);
    const std::uint32_t* v = &sc.indices[3 * (a[i].triangle)];
    double z = 0;
    for (int k = 0; k < 3; ++k) z += pt.b[k] * sc.vdepth[v[k]];
    nearest = std::min(nearest, z);
    in_front = in_front && z >= 3.0 / 1024.0;
  }
  CHECK(same);
  CHECK(in_front);
  const double grown_w = static_cast<double>(w) + 2 * noise.kernel().radius();
  const double grown_h = static_cast<double>(h) + 2 * noise.kernel().radius();
  const double bound = 2 * 4 * (16.0 / 3.0) * noise.density() * grown_w * grown_h;
  MESSAGE("records ", a.size(), ", nearest point's depth ", nearest, ", nodes ", nodes, " (bound ",
          bound, ")");
  CHECK(static_cast<double>(nodes) < bound);
}

namespace {
// The relative change of the records' squared weights between two frames, matched by
// (triangle, J): sum |w_a^2 - w_b^2| / sum w_a^2 (a record in one frame only counts with its
// whole w^2). What the variance sees (Campbell's theorem: the density of sum w^2).
double weight_change(const std::vector<hush::npr_gabor_splat>& a,
                     const std::vector<hush::npr_gabor_splat>& b) {
  std::map<std::pair<std::uint32_t, std::uint64_t>, double> wb;
  for (const auto& r : b) wb[{r.triangle, r.index}] = double(r.weight) * r.weight;
  double d = 0, total = 0;
  for (const auto& r : a) {
    const double wa = double(r.weight) * r.weight;
    total += wa;
    const auto it = wb.find({r.triangle, r.index});
    d += std::fabs(wa - (it == wb.end() ? 0.0 : it->second));
    if (it != wb.end()) wb.erase(it);
  }
  for (const auto& kv : wb) d += kv.second;
  return d / total;
}
}  // namespace

TEST_CASE("near plane: no pop as a triangle's depth ratio passes 4 or a vertex passes depth 0") {
  // Every squared weight is continuous in the vertex depths: the share of the count per node
  // ramps with log(far / near) from 4 to 8 (constants.hpp), a node's count n_P and the
  // per-triangle N move with the vertices, and at depth w_near the nodes that switch to
  // "crossing" (weight 0) already had n_P far above 4 (weight 0). So the records' squared
  // weights change by O(eps) for a relative move eps of the vertices: a tenth of the move, a
  // tenth of the change (checked: at most a fifth), where a switch (a pop) would change them by
  // the same O(1) however small the move (a hard switch at ratio 4: 1.25 for both moves,
  // tried). Three places: the depth ratio passing 4 (the
  // per-triangle LOD against a sliver of the count per node), the ground's near edge passing
  // w_near = 3 / 1024 (clipping starts) and passing depth 0 (a vertex behind the camera).
  hush::npr_gabor::params p = small_kernel();
  const hush::npr_gabor noise{p};
  const auto records = [&](const grid_scene& sc) {
    std::vector<hush::npr_gabor_splat> r;
    noise.make_splats(sc.frame(), sc.triangles(), r);
    REQUIRE(!r.empty());
    return r;
  };
  const auto ratio = [&](double eps) {
    return weight_change(records(ground_plane(160, 160, 16.0, float(4.0 * (1 - eps)))),
                         records(ground_plane(160, 160, 16.0, float(4.0 * (1 + eps)))));
  };
  const auto edge = [&](double at, double eps) {
    return weight_change(records(npr_test::ground_under_camera(float(at - eps))),
                         records(npr_test::ground_under_camera(float(at + eps))));
  };
  const double w_near = 3.0 / 1024;
  const double r1 = ratio(1e-3), r2 = ratio(1e-4), n1 = edge(w_near, 1e-4), n2 = edge(w_near, 1e-5),
               z1 = edge(0.0, 1e-4), z2 = edge(0.0, 1e-5);
  MESSAGE("squared-weight change for a move of eps, 10 eps: depth ratio 4: ", r2, ", ", r1,
          "; near edge at w_near: ", n2, ", ", n1, "; at depth 0: ", z2, ", ", z1);
  CHECK(r2 < r1 / 5);
  CHECK(n2 < n1 / 5);
  CHECK(z2 < z1 / 5);
}

namespace {

// FNV-1a (64 bits) over the float bits of every pixel, row by row.
std::uint64_t frame_digest(const std::vector<double>& img) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const double v : img) {
    const float f = static_cast<float>(v);
    std::uint32_t u = 0;
    std::memcpy(&u, &f, sizeof u);
    for (int b = 0; b < 4; ++b) h = (h ^ ((u >> (8 * b)) & 0xffU)) * 1099511628211ULL;
  }
  return h;
}

// v as exact decimal (%.17g round-trips a double), for regenerating the golden values.
std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

TEST_CASE("npr_gabor golden: values and frame digests per seed never change") {
  // Like tests/golden_test.cpp: a change here changes every user's images; say so in the
  // changelog and regenerate deliberately. Three 48 x 40 frames on exec::scalar, double
  // reference: (0) default params, orientation 0.4, a plane of 10-pixel cells; (1) a small
  // kernel with thinning and the triangle test on 3-pixel cells (N < 1), orientation per
  // pixel and frequency per vertex; (2) isotropic, local density, bandwidth per object, on a
  // foreshortened plane (depth ratio 4). Pinned: the record count (stage 1), three pixels
  // within 2^-40 (FMA contraction moves last bits only) and FNV-1a over the float-rounded
  // frame (the double's last-bit changes flip a float only with probability ~2^-29 per pixel).
  // The float render stays within 2^-12 of the reference frame (its budget is far smaller).
  const std::size_t w = 48, h = 40;
  const std::size_t pixels[3][2] = {{5, 5}, {24, 20}, {40, 33}};
  const std::uint32_t seeds[2] = {0, 7};
  const std::size_t expected_records[3][2] = {{184, 178}, {1131, 1139}, {3205, 3209}};
  const double expected[3][2][3] = {
      {{-1.0929173595171142, -0.31542156772137497, 0.031226015527319267},
       {-0.39007166842447211, -0.34956549573830903, 1.4678932713847042}},
      {{0.20742508185936429, 0.15907909335029002, -0.28879126623145479},
       {-0.15351539182831708, -1.8512275595971044, -0.55095790853611271}},
      {{1.676089387872298, -2.3789336234812861, 0.20583661952768889},
       {0.82019976376486847, 0.13963573026736648, -0.37420604288063469}}};
  const std::uint64_t digests[3][2] = {{0xe525c4c9f94b67a1ULL, 0x57bdc25b16bcee9cULL},
                                       {0x0ad5ddab12ed3845ULL, 0x46bb1aadc05bff69ULL},
                                       {0xb3553787be833ddbULL, 0x67bb7ecd26302896ULL}};

  std::vector<float> field(w * h);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x)
      field[y * w + x] = 0.03f * static_cast<float>(x) - 0.05f * static_cast<float>(y);
  const std::vector<double> band = {0.1, 0.3};  // objects 0 (background) and 1
  const grid_scene scenes[3] = {npr_test::covering(w, h, 10.0, 16.0),
                                npr_test::covering(w, h, 3.0, 8.0), ground_plane(w, h, 8.0, 4.0f)};
  std::vector<float> vertex_freq(scenes[1].screen.size());
  for (std::size_t v = 0; v < vertex_freq.size(); ++v)
    vertex_freq[v] = 0.15f + 0.01f * static_cast<float>(v % 7);
  for (int c = 0; c < 3; ++c) {
    hush::npr_gabor::params p = c == 0 ? hush::npr_gabor::params{} : small_kernel();
    hush::npr_gabor::sources src;
    if (c == 0) p.orientation = 0.4;
    if (c == 1) {
      p.thinning = true;
      p.triangle_test = true;
      src.orientation = hush::param_source::per_pixel({field.data(), w, h});
      src.frequency = hush::param_source::per_vertex(vertex_freq);
    }
    if (c == 2) {
      p.isotropic = true;
      p.local_density = true;
      p.depth_test = false;  // the grid scene's depth buffer is flat
      src.bandwidth = hush::param_source::per_object(band);
    }
    const grid_scene& sc = scenes[c];
    for (int s = 0; s < 2; ++s) {
      p.seed = seeds[s];
      const hush::npr_gabor noise{p};
      std::vector<hush::npr_gabor_splat> records;
      noise.make_splats(sc.frame(), sc.triangles(), records, src);
      std::vector<double> ref(w * h);
      noise.render(hush::exec::scalar, sc.frame(), sc.triangles(),
                   hush::image_view<double>(ref.data(), w, h), src);
      std::vector<float> f(w * h);
      noise.render(hush::exec::scalar, sc.frame(), sc.triangles(),
                   hush::image_view<float>(f.data(), w, h), src);
      CAPTURE(c);
      CAPTURE(s);
      CHECK(records.size() == expected_records[c][s]);
      for (int i = 0; i < 3; ++i) {
        const double v = ref[pixels[i][1] * w + pixels[i][0]];
        CHECK_MESSAGE(std::fabs(v - expected[c][s][i]) <= std::ldexp(1.0, -40), exact(v));
      }
      const std::uint64_t digest = frame_digest(ref);
      char hex[24];
      std::snprintf(hex, sizeof hex, "0x%016llxULL", static_cast<unsigned long long>(digest));
      CHECK_MESSAGE(digest == digests[c][s], hex);
      double worst = 0;
      for (std::size_t i = 0; i < w * h; ++i) worst = std::max(worst, std::fabs(f[i] - ref[i]));
      CHECK(worst <= std::ldexp(1.0, -12));
    }
  }
}
