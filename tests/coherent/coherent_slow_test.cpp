// Coherent noise over 10,000 frames (HARD_CASES row 13): on sub-pixel translation, rotation
// and zoom, hush's stationary filter keeps the standard deviation of moving surfaces within
// +-3% of still ones in every quarter of the run and their sharpness >= 0.85 of still ones;
// the paper's filter (Kass & Pesare eq. 7) loses both. Label `slow` (Release run only).
//
// 64 x 64 synthetic frames (tests/coherent/coherent_scenes.hpp), alpha 0.98 (the paper's), white
// input. Statistics: frame values are correlated over (1 + alpha^2) / (1 - alpha^2) = 49
// frames, so a quarter (2500 frames) holds ~51 independent frames of ~2000 moving and ~1500
// still pixels (interior, 2 pixels from an edge): standard error of a variance
// sqrt(2 / (51 x 2000)) = 0.0044, of the sd ratio ~0.004; the bound 3% is the stated one and
// stands 7 standard errors clear of the noise.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "coherent_scenes.hpp"
#include "hush/hush.hpp"

namespace {

using hush_test::make_synthetic;
using hush_test::region_stats;
using hush_test::synthetic_frame;

constexpr int kSize = 64, kFrames = 10000, kQuarters = 4, kWarmUp = 200;

struct quarter {
  region_stats moving, still;
  double sd_ratio() const { return std::sqrt(moving.variance() / still.variance()); }
  double sharpness_ratio() const { return moving.sharpness() / still.sharpness(); }
};

std::vector<quarter> run(hush::coherent_filter filter, const std::string& kind, double amount) {
  hush::coherent_params prm;
  prm.filter = filter;
  prm.seed = 11;
  hush::coherent_stream st(prm);
  const synthetic_frame s = make_synthetic(kind, amount, kSize, kSize);
  std::vector<float> out(std::size_t(kSize) * kSize);
  std::vector<quarter> q(kQuarters);
  for (int i = 0; i < kFrames; ++i) {
    st.advance(hush::exec::scalar, s.view(), hush::image_view<float>(out.data(), kSize, kSize));
    if (i < kWarmUp) continue;  // the paper's filter needs ~1 / (1 - alpha) frames to fade
    quarter& part = q[std::size_t(i) * kQuarters / kFrames];
    part.moving.add(out, s, 1, 2);
    part.still.add(out, s, 2, 2);
  }
  return q;
}

}  // namespace

TEST_CASE(
    "coherent over 10,000 frames: stationary on moving surfaces, where the paper's "
    "filter fades") {
  struct motion {
    const char* kind;
    double amount;
  };
  for (const motion& m : {motion{"translate", 0.5}, motion{"translate", 0.23},
                          motion{"rotate", 0.02}, motion{"zoom", 1.01}, motion{"zoom", 0.99}}) {
    const std::string kind = m.kind;
    CAPTURE(kind);
    CAPTURE(m.amount);
    const std::vector<quarter> hush_filter =
        run(hush::coherent_filter::stationary, m.kind, m.amount);
    const std::vector<quarter> paper = run(hush::coherent_filter::paper, m.kind, m.amount);
    std::string line = std::string(m.kind) + " " + std::to_string(m.amount) +
                       ": stationary sd ratio / sharpness ratio per quarter:";
    for (const quarter& q : hush_filter)
      line += " " + std::to_string(q.sd_ratio()) + " / " + std::to_string(q.sharpness_ratio());
    line += "; paper:";
    for (const quarter& q : paper)
      line += " " + std::to_string(q.sd_ratio()) + " / " + std::to_string(q.sharpness_ratio());
    MESSAGE(line);
    for (const quarter& q : hush_filter) {
      CHECK(std::fabs(q.sd_ratio() - 1) < 0.03);
      CHECK(q.sharpness_ratio() >= 0.85);
      CHECK(std::fabs(q.still.variance() - 1) < 5 * 0.0044 * std::sqrt(2.0));  // still: exact
    }
    for (const quarter& q : paper) CHECK(q.sd_ratio() < 0.85);
  }
}

TEST_CASE("coherent over 10,000 frames at alpha 0.999: no drift, finite history") {
  // Near alpha = 1 the stationary filter still holds on translation and rotation (no
  // accumulated magnification); the history stays finite and normal.
  for (const std::string kind : {"translate", "rotate"}) {
    CAPTURE(kind);
    hush::coherent_params prm;
    prm.alpha = 0.999;
    hush::coherent_stream st(prm);
    const synthetic_frame s = make_synthetic(kind, kind == "rotate" ? 0.01 : 0.37, kSize, kSize);
    std::vector<float> out(std::size_t(kSize) * kSize);
    region_stats moving, still;
    for (int i = 0; i < kFrames; ++i) {
      st.advance(hush::exec::scalar, s.view(), hush::image_view<float>(out.data(), kSize, kSize));
      if (i < kFrames / 2) continue;
      moving.add(out, s, 1, 2);
      still.add(out, s, 2, 2);
    }
    for (float v : st.history(0))
      REQUIRE((v == 0.0f || std::fabs(v) >= std::numeric_limits<float>::min()));
    // alpha 0.999: values correlate over ~2000 frames: the last 5000 hold only ~2.5
    // independent frames of ~2000 pixels: standard error of the sd ratio ~0.02.
    const double ratio = std::sqrt(moving.variance() / still.variance());
    MESSAGE(kind << " alpha 0.999: sd ratio " << ratio << ", sharpness ratio "
                 << moving.sharpness() / still.sharpness());
    CHECK(std::fabs(ratio - 1) < 0.1);
    CHECK(moving.sharpness() / still.sharpness() >= 0.85);
  }
  // A sustained zoom-in is the documented limitation (docs/coherent.md): the noise stretches
  // with the surface over the filter's memory. Measured and reported, not bounded.
  for (const double zoom : {1.002, 1.01}) {
    hush::coherent_params prm;
    prm.alpha = 0.999;
    hush::coherent_stream st(prm);
    const synthetic_frame s = make_synthetic("zoom", zoom, kSize, kSize);
    std::vector<float> out(std::size_t(kSize) * kSize);
    region_stats moving, still;
    for (int i = 0; i < kFrames; ++i) {
      st.advance(hush::exec::scalar, s.view(), hush::image_view<float>(out.data(), kSize, kSize));
      if (i < kFrames / 2) continue;
      moving.add(out, s, 1, 2);
      still.add(out, s, 2, 2);
    }
    MESSAGE("zoom " << zoom << " per frame at alpha 0.999: sd ratio "
                    << std::sqrt(moving.variance() / still.variance()) << ", sharpness ratio "
                    << moving.sharpness() / still.sharpness());
    for (float v : st.history(0)) REQUIRE(std::isfinite(v));
  }
}
