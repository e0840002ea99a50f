// NPR Gabor noise (include/hush/npr_gabor.hpp) against Benard et al. 2010, Table 1, measured
// with the temporal-coherence metrics (docs/coherence.md) on the rasterized test scenes
// (320x240, frames 90 ... 99, as tests/coherence/scene_ordering_test.cpp): NPR Gabor noise
// keeps the 2D look of the shower door (its frequency spread across depths is close to the
// shower door's, far below texture mapping's) while following the motion (F far above the
// shower door's -1). Label `slow` (Release run only).
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "hush/npr_gabor.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"
#include "triangles.hpp"

namespace {

namespace hc = hush_tools::coherence;

constexpr int kWidth = 320, kHeight = 240, kFirst = 90, kFrames = 10;

void check_ordering(const std::string& name) {
  CAPTURE(name);
  const hush_tools::scene::scene s = hush_tools::scene::make_scene(name);
  std::vector<hush_tools::scene::gbuffer> g;
  std::vector<hc::noise_frame> npr;
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  std::vector<float> out(std::size_t(kWidth) * kHeight);
  for (int i = kFirst; i < kFirst + kFrames; ++i) {
    g.push_back(hush_tools::scene::render_cpu(s, i, kWidth, kHeight));
    const hush_tools::scene::triangle_frame t =
        hush_tools::scene::project_triangles(s, i, kWidth, kHeight);
    noise.render(hush_tools::scene::as_frame(g.back()), t.view(),
                 hush::image_view<float>(out.data(), kWidth, kHeight));
    npr.push_back(out);
  }
  const hc::report sd = hc::measure(hc::make_baseline(hc::baseline_kind::shower_door, g), g);
  const hc::report tex = hc::measure(hc::make_baseline(hc::baseline_kind::texture, g), g);
  const hc::report n = hc::measure(npr, g);
  REQUIRE(n.temporal.reason.empty());
  REQUIRE(n.flatness.reason.empty());
  MESSAGE(name, ": NPR Gabor F ", n.temporal.following_mean, " freq CV ", n.flatness.frequency_cv,
          "; shower door F ", sd.temporal.following_mean, " freq CV ", sd.flatness.frequency_cv,
          "; texture freq CV ", tex.flatness.frequency_cv);
  // Flatness: within 0.03 of the shower door's CV, under a quarter of texture mapping's.
  CHECK(n.flatness.frequency_cv < sd.flatness.frequency_cv + 0.03);
  CHECK(n.flatness.frequency_cv < 0.25 * tex.flatness.frequency_cv);
  // Coherent motion: following the surfaces (F > 0.5), the shower door stays (F = -1).
  CHECK(n.temporal.following_mean > 0.5);
  CHECK(n.temporal.following_mean > sd.temporal.following_mean + 1.5);
  // Temporal continuity: no popping (the LOD keeps weights continuous).
  CHECK(n.temporal.popping < 0.001);
}

}  // namespace

TEST_CASE("NPR Gabor noise: flat like the shower door, moving like texture (translate)") {
  check_ordering("translate");
}
TEST_CASE("NPR Gabor noise: flat like the shower door, moving like texture (rotate)") {
  check_ordering("rotate");
}
TEST_CASE("NPR Gabor noise: flat like the shower door, moving like texture (zoom)") {
  check_ordering("zoom");
}
TEST_CASE("NPR Gabor noise: flat like the shower door, moving like texture (walkthrough)") {
  check_ordering("walkthrough");
}
