// Tests of the calibration baselines (examples/coherence/baselines.hpp): their definitions,
// and Bénard et al. 2010 Table 1's ordering on analytic planes (the rasterized scenes are in
// scene_ordering_test.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <cstdint>
#include "analytic_scene.hpp"
#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "hush/core/error.hpp"
#include "hush/core/vec.hpp"
#include "hush/perlin.hpp"

namespace {

using hush_tools::coherence::baseline_kind;

}  // namespace

TEST_CASE("baselines are deterministic, zero on background, and sized like the gbuffers") {
  hush_test::plane_scene s;
  s.split = 100;
  s.b.id = 0;  // background on the right
  s.frames = 3;
  const auto g = hush_test::plane_sequence(s);
  for (auto kind : {baseline_kind::white, baseline_kind::shower_door, baseline_kind::texture}) {
    const auto a = hush_tools::coherence::make_baseline(kind, g);
    const auto b = hush_tools::coherence::make_baseline(kind, g);
    REQUIRE(a.size() == 3);
    CHECK(a == b);
    for (const auto& f : a) {
      REQUIRE(f.size() == g[0].pixels());
      CHECK(f[119 * 160 + 159] == 0);
      CHECK(f[0] != 0);
    }
  }
  // Shower door: identical frames; white: different frames.
  const auto sd = hush_tools::coherence::make_baseline(baseline_kind::shower_door, g);
  CHECK(sd[0] == sd[2]);
  const auto w = hush_tools::coherence::make_baseline(baseline_kind::white, g);
  CHECK(w[0] != w[1]);
  CHECK(hush_tools::coherence::parse_baseline("shower-door") == baseline_kind::shower_door);
  CHECK_THROWS_AS(hush_tools::coherence::parse_baseline("grey"), hush::invalid_argument);
  hush_tools::coherence::baseline_options o;
  o.feature_pixels = 0;
  CHECK_THROWS_AS(hush_tools::coherence::make_baseline(baseline_kind::white, g, o),
                  hush::invalid_argument);
}

TEST_CASE("texture calibration gives features of feature_pixels on screen in the first frame") {
  // Plane at depth 4, focal 160: 0.025 world units per pixel; the lattice scale must be
  // 1 / (8 * 0.025) = 5 cells per world unit, so the noise at a pixel equals 3D Perlin of
  // 5 * position (seed 1 + object id 1).
  hush_test::plane_scene s;
  const auto g = hush_test::plane_sequence(s);
  const auto f = hush_tools::coherence::make_baseline(baseline_kind::texture, g);
  const hush::perlin<3> p(2);
  const std::size_t px = 57 * 160 + 33;
  const float want = p(hush::vec3{static_cast<float>(g[0].position[3 * px] * 5.0),
                                  static_cast<float>(g[0].position[3 * px + 1] * 5.0), 0.0f});
  CHECK(f[0][px] == doctest::Approx(want).epsilon(1e-5));
}

TEST_CASE("Table 1 ordering on a translating and zooming plane pair") {
  // Two planes (depths 3 and 6) translating sideways (parallax) and approaching the camera:
  // velocities 1.6 ... 3.4 pixels per frame, radial and translational.
  hush_test::plane_scene s;
  s.split = 80;
  s.a.depth = 3;
  s.a.tx = 0.03;
  s.a.dz = -0.02;
  s.b.id = 2;
  s.b.depth = 6;
  s.b.tx = 0.06;
  s.b.dz = -0.04;
  s.frames = 8;
  const auto g = hush_test::plane_sequence(s);
  const hush_tools::coherence::options o;
  const auto white = hush_tools::coherence::measure(
      hush_tools::coherence::make_baseline(baseline_kind::white, g), g, o);
  const auto sd = hush_tools::coherence::measure(
      hush_tools::coherence::make_baseline(baseline_kind::shower_door, g), g, o);
  const auto tex = hush_tools::coherence::measure(
      hush_tools::coherence::make_baseline(baseline_kind::texture, g), g, o);
  // Coherent motion: texture ~1 (bilinear resampling only); shower door correlates better
  // with the unmoved screen (S = 1) than with the surfaces (C = its autocorrelation at lags
  // of 1.6 ... 3.4 pixels, 0.2 ... 0.4 cells: about 0.6 ... 0.85); white ~0 (4 standard errors
  // of ~17000 pixels). The 0.05 margins are below the smallest gap, 1 - 0.85.
  CHECK(tex.temporal.coherence_min > 0.95);
  CHECK(tex.temporal.coherence_mean > tex.temporal.screen_coherence_mean + 0.05);
  CHECK(sd.temporal.coherence_mean < sd.temporal.screen_coherence_mean - 0.05);
  CHECK(sd.temporal.screen_coherence_mean == doctest::Approx(1).epsilon(1e-9));
  CHECK(sd.temporal.coherence_mean < tex.temporal.coherence_mean - 0.05);
  CHECK(std::abs(white.temporal.coherence_mean) < 0.03);
  // Continuity: white pops everywhere; the smooth baselines do not.
  CHECK(white.temporal.popping > 0.3);
  CHECK(sd.temporal.popping < 0.05);
  CHECK(tex.temporal.popping < 0.05);
  CHECK(tex.temporal.change_p99 < sd.temporal.change_p99);
  CHECK(sd.temporal.change_p99 < white.temporal.change_p99);
  // Flatness: shower door flat, texture not (depth ratio 2 between the planes).
  CHECK(sd.flatness.frequency_cv < 0.08);
  CHECK(tex.flatness.frequency_cv > 3 * sd.flatness.frequency_cv);
}

namespace {

// Correlation of 2D Perlin with itself shifted by `lag` cells along x, over a 256 x 256-cell
// area sampled 4 times per cell (262144 samples): the noise's own autocorrelation R(lag).
double perlin_autocorrelation(std::uint32_t seed, double lag) {
  const hush::perlin<2> p(seed);
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
  for (int j = 0; j < 1024; ++j)
    for (int i = 0; i < 1024; ++i) {
      const double x = (i + 0.5) / 4, y = (j + 0.5) / 4;
      const double a = p(hush::dvec2{x, y}), b = p(hush::dvec2{x - lag, y});
      sa += a;
      sb += b;
      saa += a * a;
      sbb += b * b;
      sab += a * b;
      n += 1;
    }
  return (sab - sa * sb / n) / std::sqrt((saa - sa * sa / n) * (sbb - sb * sb / n));
}

}  // namespace

TEST_CASE("shower door coherence is the noise's autocorrelation at the motion's lag") {
  // A plane sliding 3 pixels per frame (0.375 Perlin cells of 8 pixels) past a static camera.
  hush_test::plane_scene s;
  s.a.tx = 3 * s.a.depth / s.focal;
  s.frames = 3;
  const auto g = hush_test::plane_sequence(s);
  const auto sd = hush_tools::coherence::measure_temporal(
      hush_tools::coherence::make_baseline(baseline_kind::shower_door, g), g);
  const auto tex = hush_tools::coherence::measure_temporal(
      hush_tools::coherence::make_baseline(baseline_kind::texture, g), g);
  const double r = perlin_autocorrelation(1, 3.0 / 8);
  // The frames hold ~20 x 15 = 300 cells: a correlation estimated from them scatters by about
  // (1 - R^2) / sqrt(300) ~ 0.04; allow 2.5 times that.
  CHECK(std::abs(sd.coherence_mean - r) < 0.1);
  CHECK(r < 0.8);  // so the texture's >= 0.95 is well separated
  CHECK(tex.coherence_min > 0.95);
  CHECK(tex.coherence_mean > sd.coherence_mean + 0.15);
}
