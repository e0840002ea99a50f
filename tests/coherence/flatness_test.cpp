// Tests of the flatness metric (examples/coherence/flatness.hpp) on analytic planes.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "analytic_scene.hpp"
#include "coherence/baselines.hpp"
#include "coherence/flatness.hpp"
#include "hush/core/error.hpp"

// Default options: windows of 32 pixels at stride 16 (9 x 6 = 54 windows in 160x120).

TEST_CASE("stationary noise on a fronto-parallel plane has flatness spread near 0") {
  hush_test::plane_scene s;
  s.frames = 3;
  const auto g = hush_test::plane_sequence(s);
  const hush_tools::coherence::options o;
  for (auto kind : {hush_tools::coherence::baseline_kind::shower_door,
                    hush_tools::coherence::baseline_kind::texture}) {
    const auto frames = hush_tools::coherence::make_baseline(kind, g);
    const auto f = hush_tools::coherence::measure_flatness(frames, g, o);
    REQUIRE(f.reason.empty());
    REQUIRE(f.frames[0].regions.size() == 3);
    // 54 windows in 3 regions of 18; windows overlap by half, so ~8 independent ones per
    // region. A 32-pixel window holds 4 x 4 Perlin cells: its variance scatters by about 50%
    // and its RMS frequency by about 10% from window to window, so region values scatter by
    // ~18% and ~3.5%. Limits: about 1.4 and 2.3 times that (3 regions: CV is a 3-sample std).
    CHECK(f.frequency_cv < 0.08);
    CHECK(f.variance_cv < 0.25);
    CHECK(f.frequency_ratio < 1.2);
  }
}

TEST_CASE("texture noise on planes at depths 2 and 4 has a 2x frequency spread, shower door none") {
  hush_test::plane_scene s;
  s.split = 80;
  s.a.depth = 2;
  s.b.id = 2;
  s.b.depth = 4;
  s.frames = 2;
  const auto g = hush_test::plane_sequence(s);
  const hush_tools::coherence::options o;
  const auto tex = hush_tools::coherence::measure_flatness(
      hush_tools::coherence::make_baseline(hush_tools::coherence::baseline_kind::texture, g), g, o);
  const auto sd = hush_tools::coherence::measure_flatness(
      hush_tools::coherence::make_baseline(hush_tools::coherence::baseline_kind::shower_door, g), g,
      o);
  REQUIRE(tex.reason.empty());
  REQUIRE(sd.reason.empty());
  REQUIRE(tex.frames[0].regions.size() == 6);  // 2 objects x 3 depth bins of 8 windows
  // Texture: B's features are half the size of A's on screen (perspective), so its RMS
  // frequency doubles (the window correction makes the estimate unbiased up to wrap-around);
  // 8 windows per region scatter by ~5% each, so accept > 1.7. Shower door: estimation
  // scatter only (< 1.2 as on one plane).
  CHECK(tex.frequency_ratio > 1.7);
  CHECK(sd.frequency_ratio < 1.2);
  CHECK(tex.frequency_cv > 3 * sd.frequency_cv);
  double near = 0, far = 0;
  for (const auto& r : tex.frames[0].regions) (r.object == 1 ? near : far) += r.frequency;
  CHECK(far > 1.7 * near);
}

TEST_CASE("flatness without two measurable regions is NaN with a reason") {
  hush_test::plane_scene s;
  s.width = 40;
  s.height = 30;
  const auto g = hush_test::plane_sequence(s);
  const auto frames =
      hush_tools::coherence::make_baseline(hush_tools::coherence::baseline_kind::shower_door, g);
  const auto f = hush_tools::coherence::measure_flatness(frames, g);  // windows of 32: only 1 fits
  CHECK(std::isnan(f.frequency_cv));
  CHECK(std::isnan(f.variance_ratio));
  CHECK(!f.reason.empty());
  CHECK(!f.frames[0].reason.empty());
  hush_tools::coherence::options o;
  o.window = 2;
  CHECK_THROWS_AS(hush_tools::coherence::measure_flatness(frames, g, o), hush::invalid_argument);
}
