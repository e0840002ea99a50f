// Bénard et al. 2010, Table 1, measured: on the rasterized test scenes (examples/scene), the
// calibration baselines must land where the paper's user study put their methods:
//   shower door      flat, not coherent (it stays on the screen), continuous;
//   texture mapping  coherent (it moves with the surfaces), not flat;
//   white noise      neither coherent nor continuous (and flat: it is stationary on screen).
// 320x240, frames 90 ... 99 of each scene: there the zoom's camera is close enough (eye at
// z = 3.5) that its objects and the wall are at depths differing by 2x, and every scene
// shows at least two surfaces holding 32-pixel flatness windows.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"

namespace {

namespace hc = hush_tools::coherence;

constexpr int kWidth = 320, kHeight = 240, kFirst = 90, kFrames = 10;

std::vector<hush_tools::scene::gbuffer> render(const std::string& name) {
  const hush_tools::scene::scene s = hush_tools::scene::make_scene(name);
  std::vector<hush_tools::scene::gbuffer> g;
  for (int i = kFirst; i < kFirst + kFrames; ++i)
    g.push_back(hush_tools::scene::render_cpu(s, i, kWidth, kHeight));
  return g;
}

void check_table1(const std::string& name) {
  const auto g = render(name);
  const hc::report white = hc::measure(hc::make_baseline(hc::baseline_kind::white, g), g);
  const hc::report sd = hc::measure(hc::make_baseline(hc::baseline_kind::shower_door, g), g);
  const hc::report tex = hc::measure(hc::make_baseline(hc::baseline_kind::texture, g), g);
  for (const hc::report* r : {&white, &sd, &tex}) {
    REQUIRE(r->temporal.reason.empty());
    REQUIRE(r->flatness.reason.empty());
    REQUIRE(r->temporal.pairs_without_following == 0);
  }
  std::size_t fewest = white.temporal.pairs[0].compared;
  for (const auto& p : white.temporal.pairs) fewest = std::min(fewest, p.compared);
  CAPTURE(name);

  // -- Coherent motion. Shower door is constant in time, so S = 1 exactly and F = -1 as soon
  // as anything moves; texture loses coherence only to bilinear resampling of band-limited
  // noise (>= 2 pixels per cell after clamping), far less than the motion costs it without
  // compensation, so F near +1: 0.9 allows resampling losses up to 1/19 of the motion's.
  CHECK(sd.temporal.following_mean < -0.9);
  CHECK(tex.temporal.following_mean > 0.9);
  CHECK(tex.temporal.coherence_mean > sd.temporal.coherence_mean);
  CHECK(tex.temporal.coherence_min > 0.98);  // resampling loss <= 2%
  // White: independent frames; a correlation of n pixels scatters by 1 / sqrt(n).
  CHECK(std::abs(white.temporal.coherence_mean) < 4 / std::sqrt(static_cast<double>(fewest)));
  CHECK(std::abs(white.temporal.following_mean) < 0.05);

  // -- Temporal continuity. White noise jumps independently at every pixel: popping near
  // 0.5 (0.527 for Gaussian values, temporal_test.cpp); the smooth baselines change smoothly
  // in space (shower door by v . grad n after compensation, texture by resampling) and have
  // isolated jumps only at the rare pixels where clamping or an edge intervenes (< 1%).
  CHECK(white.temporal.popping > 0.4);
  CHECK(sd.temporal.popping < 0.01);
  CHECK(tex.temporal.popping < 0.01);
  CHECK(tex.temporal.change_mean < white.temporal.change_mean / 4);

  // -- Flatness. Shower door and white noise are stationary on screen: their spread is the
  // estimation scatter (frequency ratio < 1.2 as on an analytic plane, flatness_test.cpp).
  // Texture's screen frequency scales with depth / foreshortening: the regions here span a
  // depth ratio of 2 or more, so its max/min frequency ratio is well above 1.4.
  CHECK(sd.flatness.frequency_ratio < 1.2);
  CHECK(white.flatness.frequency_ratio < 1.2);
  CHECK(tex.flatness.frequency_ratio > 1.4);
  CHECK(tex.flatness.frequency_cv > 3 * sd.flatness.frequency_cv);
  CHECK(tex.flatness.pooled_frequency_cv > 3 * sd.flatness.pooled_frequency_cv);
}

}  // namespace

TEST_CASE("Table 1 ordering of the baselines on the translate scene") { check_table1("translate"); }
TEST_CASE("Table 1 ordering of the baselines on the rotate scene") { check_table1("rotate"); }
TEST_CASE("Table 1 ordering of the baselines on the zoom scene") { check_table1("zoom"); }
TEST_CASE("Table 1 ordering of the baselines on the walkthrough scene") {
  check_table1("walkthrough");
}
