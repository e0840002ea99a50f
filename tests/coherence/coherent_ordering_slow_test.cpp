// Coherent noise measured with the temporal-coherence metrics (docs/coherence.md) on the
// rasterized test scenes, beside the three calibration baselines of Benard et al. Table 1:
// it must follow the motion like texture mapping (motion following F far above the shower
// door's -1 and white noise's 0) while each frame stays flat like the screen-space noises
// (flatness spread far below texture mapping's). And the paper's filter, which fades on
// moving surfaces, must be less flat than hush's stationary one.
//
// 320 x 240, the noise run from frame 0, measured over frames 90 ... 99 (the set-up of
// scene_ordering_test.cpp and of docs/coherence.md's baseline table); alpha 0.98 (the
// paper's), band-pass input with 4-pixel Perlin cells (the paper smooths its white noise).
// Slow (rendering 100 frames of four scenes): label `slow`, Release run only.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "hush/coherent.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"

namespace {

namespace hc = hush_tools::coherence;

constexpr int kWidth = 320, kHeight = 240, kFirst = 90, kFrames = 10;

hush::coherent_params params(hush::coherent_filter filter) {
  hush::coherent_params p;
  p.filter = filter;
  p.input = hush::coherent_input::bandpass;
  p.bandpass_pixels = 4;
  p.seed = 3;
  return p;
}

// Frame i of the scene, rendered when asked (the rasterizer is deterministic), so the
// sequence is never held: the causal pass reads it once, the symmetric one twice.
class frames_on_demand {
 public:
  explicit frames_on_demand(const hush_tools::scene::scene& s) : s_(s) {}
  const hush_tools::scene::gbuffer& operator()(int i) {
    if (i != current_) {
      hush_tools::scene::render_cpu(s_, i, kWidth, kHeight, {}, g_);
      current_ = i;
    }
    return g_;
  }

 private:
  const hush_tools::scene::scene& s_;
  hush_tools::scene::gbuffer g_;
  int current_ = -1;
};

std::vector<hc::noise_frame> causal(frames_on_demand& frames, hush::coherent_filter filter) {
  hush::coherent_stream st(params(filter));
  std::vector<hc::noise_frame> result;
  std::vector<float> out(std::size_t(kWidth) * kHeight);
  for (int i = 0; i < kFirst + kFrames; ++i) {
    st.advance(hush::exec::simd, hush_tools::scene::as_frame(frames(i)),
               hush::image_view<float>(out.data(), kWidth, kHeight));
    if (i >= kFirst) result.push_back(out);
  }
  return result;
}

std::vector<hc::noise_frame> symmetric(frames_on_demand& frames) {
  hush::coherent_sequence<float> io;
  io.frames = kFirst + kFrames;
  io.frame_at = [&](std::size_t i) { return hush_tools::scene::as_frame(frames(int(i))); };
  std::vector<hc::noise_frame> result(kFrames);
  io.write = [&](std::size_t i, hush::span<const hush::image_view<float>> r) {
    if (i < std::size_t(kFirst)) return;
    result[i - kFirst].assign(r[0].data, r[0].data + std::size_t(kWidth) * kHeight);
  };
  hush::coherent_symmetric(hush::exec::simd, params(hush::coherent_filter::stationary), io);
  return result;
}

void check_scene(const std::string& name) {
  CAPTURE(name);
  const hush_tools::scene::scene s = hush_tools::scene::make_scene(name);
  std::vector<hush_tools::scene::gbuffer> g;  // the measured frames
  for (int i = kFirst; i < kFirst + kFrames; ++i)
    g.push_back(hush_tools::scene::render_cpu(s, i, kWidth, kHeight));
  frames_on_demand all(s);
  const hc::report white = hc::measure(hc::make_baseline(hc::baseline_kind::white, g), g);
  const hc::report sd = hc::measure(hc::make_baseline(hc::baseline_kind::shower_door, g), g);
  const hc::report tex = hc::measure(hc::make_baseline(hc::baseline_kind::texture, g), g);
  const hc::report paper = hc::measure(causal(all, hush::coherent_filter::paper), g);
  const hc::report causal_r = hc::measure(causal(all, hush::coherent_filter::stationary), g);
  const hc::report symmetric_r = hc::measure(symmetric(all), g);
  for (const hc::report* r : {&white, &sd, &tex, &paper, &causal_r, &symmetric_r}) {
    REQUIRE(r->temporal.reason.empty());
    REQUIRE(r->flatness.reason.empty());
  }
  for (const hc::report* r : {&causal_r, &symmetric_r}) {
    const std::string filter = r == &causal_r ? "causal" : "symmetric";
    CAPTURE(filter);
    const std::string line = name + " " + filter + ": following " +
                             std::to_string(r->temporal.following_mean) + " (texture " +
                             std::to_string(tex.temporal.following_mean) + ", shower door " +
                             std::to_string(sd.temporal.following_mean) + ", white " +
                             std::to_string(white.temporal.following_mean) + "); frequency CV " +
                             std::to_string(r->flatness.frequency_cv) + " (texture " +
                             std::to_string(tex.flatness.frequency_cv) + ", shower door " +
                             std::to_string(sd.flatness.frequency_cv) + ", white " +
                             std::to_string(white.flatness.frequency_cv) + ")";
    MESSAGE(line);
    // Follows the motion: F far above white noise (0) and the shower door (-1), and below
    // texture mapping, which never renews (a coherent noise renews 1 - alpha^2 of its
    // variance per frame, so 1 - C >= 1 - alpha on every pixel).
    CHECK(r->temporal.following_mean > 0.5);
    CHECK(r->temporal.following_mean > white.temporal.following_mean + 0.5);
    CHECK(r->temporal.following_mean > sd.temporal.following_mean + 1.4);
    CHECK(r->temporal.following_mean <= tex.temporal.following_mean);
    // Continuous: no popping, like the smooth baselines, unlike white noise (~0.5).
    CHECK(r->temporal.popping < 0.01);
    // Flat: far below texture mapping's spread, near the screen-space noises'.
    CHECK(r->flatness.frequency_cv < tex.flatness.frequency_cv / 4);
    CHECK(r->flatness.pooled_frequency_cv < tex.flatness.pooled_frequency_cv / 4);
    // Contrast: within twice the shower door's spread plus the estimation scatter of the
    // variance CV (0.05, docs/coherence.md).
    CHECK(r->flatness.variance_cv < 2 * sd.flatness.variance_cv + 0.05);
  }
  // The paper's filter fades and blurs moving surfaces: less flat than hush's. (On the
  // walkthrough the ground near the camera is magnified several times over the filter's
  // memory, which stretches both filters' noise; their contrast spreads are alike there.)
  CHECK(paper.flatness.frequency_cv > causal_r.flatness.frequency_cv);
  if (name != "walkthrough") CHECK(paper.flatness.variance_cv > causal_r.flatness.variance_cv);
}

}  // namespace

TEST_CASE("coherent noise on translate: follows the motion, stays flat") {
  check_scene("translate");
}
TEST_CASE("coherent noise on rotate: follows the motion, stays flat") { check_scene("rotate"); }
TEST_CASE("coherent noise on zoom: follows the motion, stays flat") { check_scene("zoom"); }
TEST_CASE("coherent noise on walkthrough: follows the motion, stays flat") {
  check_scene("walkthrough");
}

TEST_CASE(
    "coherent noise on the rotate scene at 64 x 48 over 10,000 frames: the torus keeps the "
    "wall's standard deviation and sharpness (the issue's measurement)") {
  // The paper's filter (Kass & Pesare eq. 7) on this set-up has a reference measurement of an
  // sd 0.43 of the wall's after 100 frames, sharpness 1.2 against 2.0. Measured here over
  // frames 100 ... 9999 on pixels whose 4-neighbours show the same object. The torus turns
  // 2 degrees per frame (180 frames per turn), so 10,000 frames hold ~55 turns: the ratios'
  // standard errors are below 0.005.
  const hush_tools::scene::scene s = hush_tools::scene::make_scene("rotate");
  const int w = 64, h = 48, frames = 10000;
  for (auto filter : {hush::coherent_filter::stationary, hush::coherent_filter::paper}) {
    hush::coherent_params p;
    p.filter = filter;
    hush::coherent_stream st(p);
    hush_tools::scene::gbuffer g;
    std::vector<float> out(std::size_t(w) * h);
    double sum[2] = {0, 0}, count[2] = {0, 0}, diff[2] = {0, 0}, pairs[2] = {0, 0};
    for (int i = 0; i < frames; ++i) {
      hush_tools::scene::render_cpu(s, i, w, h, {}, g);
      st.advance(hush::exec::simd, hush_tools::scene::as_frame(g),
                 hush::image_view<float>(out.data(), w, h));
      if (i < 100) continue;
      for (int y = 1; y + 1 < h; ++y)
        for (int x = 1; x + 1 < w; ++x) {
          const std::size_t q = std::size_t(y) * w + x;
          const std::uint32_t id = g.object_id[q];
          if ((id != 1 && id != 2) || g.object_id[q - 1] != id || g.object_id[q + 1] != id ||
              g.object_id[q - w] != id || g.object_id[q + w] != id)
            continue;
          const int k = id == 1 ? 0 : 1;
          sum[k] += double(out[q]) * out[q];
          count[k] += 1;
          for (const std::size_t r : {q + 1, q + std::size_t(w)}) {
            diff[k] += (double(out[r]) - out[q]) * (double(out[r]) - out[q]);
            pairs[k] += 1;
          }
        }
    }
    const double var[2] = {sum[0] / count[0], sum[1] / count[1]};
    const double sharp[2] = {diff[0] / pairs[0] / var[0], diff[1] / pairs[1] / var[1]};
    const double sd_ratio = std::sqrt(var[0] / var[1]), sharp_ratio = sharp[0] / sharp[1];
    const std::string name = filter == hush::coherent_filter::paper ? "paper" : "stationary";
    const std::string line = name + " filter: torus sd / wall sd " + std::to_string(sd_ratio) +
                             ", sharpness torus " + std::to_string(sharp[0]) + " / wall " +
                             std::to_string(sharp[1]) + " = " + std::to_string(sharp_ratio);
    MESSAGE(line);
    if (filter == hush::coherent_filter::stationary) {
      CHECK(std::fabs(sd_ratio - 1) < 0.03);
      CHECK(sharp_ratio >= 0.85);
    } else {
      CHECK(sd_ratio < 0.6);
      CHECK(sharp_ratio < 0.85);  // misses the target the stationary filter meets
    }
  }
}
