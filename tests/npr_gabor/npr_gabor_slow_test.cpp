// NPR Gabor noise (include/hush/npr_gabor.hpp), the long sweep (label `slow`: Release
// run only): the variance stays 1 within +-2% while the triangles' screen area sweeps
// across several powers of two in steps of 2^(1/4) (zoom about the image centre: the same
// surface points, the LOD switching M at every power of two).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "hush/npr_gabor.hpp"
#include "npr_gabor_scenes.hpp"

TEST_CASE("variance within +-2% across triangle areas N = 0.25 ... 45 (no pops at M switches)") {
  // Per zoom level the sample variance over `seeds` independent images of n pixels each
  // has standard error se = sqrt((2 sum_d rho(d)^2 + 9 / (5 lambda)) / (seeds n)) (see
  // tests/npr_gabor/npr_gabor_test.cpp); every level must be within 4.5 se of 1, and 4.5 se must be
  // below 2% so that passing establishes the +-2% bound.
  hush::npr_gabor::params p;
  p.frequency = 0.25;
  p.bandwidth = 0.35;
  p.orientation = 0.3;
  const std::size_t w = 384, h = 384, m = 8;
  const std::uint32_t seeds = 6;
  const hush::npr_gabor probe{p};
  const auto& k = probe.kernel();
  const hush::dvec2 F{p.frequency * std::cos(p.orientation), p.frequency * std::sin(p.orientation)};
  const double sum = npr_test::sum_rho_power(k, F, 2);
  const double n = static_cast<double>((w - 2 * m) * (h - 2 * m)) * seeds;
  const double se = std::sqrt((2.0 * sum + 9.0 / (5.0 * probe.density())) / n);
  MESSAGE("standard error ", se, ", tolerance ", 4.5 * se);
  REQUIRE(4.5 * se < 0.02);
  std::vector<float> img(w * h);
  for (int step = -8; step <= 24; step += 3) {  // N = 2^(step / 4): 0.25 ... 45
    const double n_tri = std::exp2(0.25 * step);
    const double cell = std::sqrt(2.0 * n_tri / probe.density());
    const npr_test::grid_scene sc = npr_test::covering(w, h, cell, k.radius() + 1);
    double s = 0, s2 = 0, count = 0;
    for (std::uint32_t seed = 0; seed < seeds; ++seed) {
      p.seed = seed;
      const hush::npr_gabor noise{p};
      noise.render(sc.frame(), sc.triangles(), hush::image_view<float>(img.data(), w, h));
      for (std::size_t y = m; y < h - m; ++y)
        for (std::size_t x = m; x < w - m; ++x) {
          const double v = img[y * w + x];
          s += v;
          s2 += v * v;
          count += 1;
        }
    }
    const double mean = s / count, var = s2 / count - mean * mean;
    MESSAGE("N per triangle ", n_tri, ": variance ", var);
    CHECK(std::fabs(var - 1.0) < 4.5 * se);
  }
}
