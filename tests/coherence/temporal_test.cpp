// Tests of the motion-coherence and continuity metrics (examples/coherence/temporal.hpp) on
// G-buffers whose motion is known exactly.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "analytic_scene.hpp"
#include "coherence/temporal.hpp"
#include "hush/core/error.hpp"
#include "hush/core/rng.hpp"

namespace {

using hush_tools::coherence::noise_frame;

// A full-screen plane at depth 1 whose every pixel moves by the integer (vx, vy).
std::vector<hush_tools::scene::gbuffer> shift_sequence(int w, int h, float vx, float vy) {
  hush_test::plane_scene s;
  s.width = w;
  s.height = h;
  std::vector<hush_tools::scene::gbuffer> g = hush_test::plane_sequence(s);
  for (std::size_t p = 0; p < g[1].pixels(); ++p) {
    g[1].velocity[3 * p] = vx;
    g[1].velocity[3 * p + 1] = vy;
  }
  return g;
}

noise_frame white(int w, int h, std::uint32_t stream) {
  hush::rng r(99, stream);
  noise_frame f(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (float& v : f) v = r.uniform(-1.0f, 1.0f);
  return f;
}

}  // namespace

TEST_CASE("an exactly shifted image with the matching velocity has coherence 1 and no change") {
  const int w = 160, h = 120, vx = 3, vy = -2;
  const auto g = shift_sequence(w, h, vx, vy);
  const noise_frame f0 = white(w, h, 0);
  noise_frame f1(f0.size(), 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (x - vx >= 0 && x - vx < w && y - vy >= 0 && y - vy < h)
        f1[static_cast<std::size_t>(y * w + x)] =
            f0[static_cast<std::size_t>((y - vy) * w + x - vx)];
  const auto t = hush_tools::coherence::measure_temporal({f0, f1}, g);
  REQUIRE(t.pairs.size() == 1);
  // Only rounding of the correlation sums separates it from 1.
  CHECK(t.coherence_mean == doctest::Approx(1).epsilon(1e-12));
  CHECK(t.change_mean == 0);
  CHECK(t.change_p999 < 1.0 / hush_tools::coherence::kChangeBinsPerSigma);
  CHECK(t.popping == 0);
  // The pixels whose source column x - 3 < 0 or source row y + 2 > h - 1 are off-screen.
  CHECK(t.pairs[0].offscreen == static_cast<std::size_t>(vx * h + (-vy) * w - vx * (-vy)));
  CHECK(t.pairs[0].disoccluded == 0);
  CHECK(t.pairs[0].compared + t.pairs[0].offscreen == static_cast<std::size_t>(w * h));
}

TEST_CASE("independent white frames have coherence within 4 standard errors of 0") {
  const int w = 160, h = 120;
  const auto g = shift_sequence(w, h, 0, 0);
  const auto t = hush_tools::coherence::measure_temporal({white(w, h, 0), white(w, h, 1)}, g);
  const double n = static_cast<double>(t.pairs[0].compared);
  REQUIRE(n == w * h);
  // The sample correlation of independent variables has standard error 1 / sqrt(n).
  CHECK(std::abs(t.coherence_mean) < 4 / std::sqrt(n));
  // D = (a - b) / sigma with a, b uniform on [-1, 1), sigma = 1 / sqrt(3): E|D| = 2 sqrt(3) / 3
  // = 1.1547, standard deviation sqrt(2/9) sqrt(3) = 0.8165; 5 standard errors.
  CHECK(std::abs(t.change_mean - 2 * std::sqrt(3.0) / 3) < 5 * 0.8165 / std::sqrt(n));
  // The median of |a - b| for uniform a, b on [-1, 1] is 2 - sqrt(2) = 0.586 (in sigmas x sqrt 3)
  CHECK(t.change_p50 == doctest::Approx((2 - std::sqrt(2.0)) * std::sqrt(3.0)).epsilon(0.03));
  // Isolated jumps: D minus the mean of 4 independent neighbours has variance 2.5 (sigma^2
  // units); a Gaussian of that variance exceeds 1 with probability 0.527. D is triangular
  // (lighter tails), so allow 0.4 ... 0.65.
  CHECK(t.popping > 0.4);
  CHECK(t.popping < 0.65);
}

TEST_CASE("a sub-pixel translation of a smooth image keeps coherence near 1") {
  // Texture-like noise: a sum of two sinusoids attached to the plane, sampled per frame at the
  // object-space position; wavelengths >= 16 pixels. Bilinear resampling of a sinusoid of
  // wavelength L at offset t loses at most 1 - cos(pi / L) of its amplitude and adds no
  // uncorrelated error to first order, so coherence >= 0.99 and |D| stays below
  // (2 pi / L)^2 / 8 * amplitude / sigma = 0.02 / 0.5 per unit amplitude (second-order error).
  hush_test::plane_scene s;
  s.a.tx = 0.037;  // world units per frame: 1.48 pixels at depth 4, focal 160
  s.a.ty = -0.011;
  s.frames = 4;
  const auto g = hush_test::plane_sequence(s);
  std::vector<noise_frame> frames;
  for (const auto& gb : g) {
    noise_frame f(gb.pixels());
    for (std::size_t p = 0; p < gb.pixels(); ++p) {
      const double ox = gb.position[3 * p] * s.focal / s.a.depth;  // in pixels
      const double oy = gb.position[3 * p + 1] * s.focal / s.a.depth;
      f[p] = static_cast<float>(std::sin(2 * M_PI * ox / 16) + std::cos(2 * M_PI * oy / 23));
    }
    frames.push_back(f);
  }
  const auto t = hush_tools::coherence::measure_temporal(frames, g);
  CHECK(t.coherence_min > 0.99);
  CHECK(t.change_p999 < 0.1);
  CHECK(t.popping == 0);
  CHECK(t.pairs_without_coherence == 0);
}

TEST_CASE("pixels reprojected off the image are off-screen and a depth mismatch disoccludes") {
  // Plane A (left, depth 4) slides right by 2 pixels per frame; plane B (right) is fixed.
  hush_test::plane_scene s;
  s.split = 80;
  s.a.tx = 2 * s.a.depth / s.focal;
  s.b.id = 2;
  s.b.depth = 8;
  const auto g = hush_test::plane_sequence(s);
  const auto t =
      hush_tools::coherence::measure_temporal({white(160, 120, 0), white(160, 120, 1)}, g);
  // Columns 78, 79 of A reproject to 76, 77 (still A): fine. B's pixels have velocity 0:
  // fine. A's columns 0, 1 reproject to x < 0.5: off-screen.
  CHECK(t.pairs[0].offscreen == 2 * 120);
  CHECK(t.pairs[0].disoccluded == 0);

  // B now slides left by 2 pixels per frame too.
  s.b.tx = -2 * s.b.depth / s.focal;
  const auto g2 = hush_test::plane_sequence(s);
  const auto t2 =
      hush_tools::coherence::measure_temporal({white(160, 120, 0), white(160, 120, 1)}, g2);
  // B's columns 80, 81 came from columns 82, 83 (B): fine; B's last 2 columns from x > w - 0.5.
  CHECK(t2.pairs[0].offscreen == 4 * 120);

  // A depth step: frame 1's depth disagrees with frame 0's by 5% > depth_epsilon (2%).
  auto g3 = g;
  for (float& d : g3[0].depth) d *= 1.05f;
  const auto t3 =
      hush_tools::coherence::measure_temporal({white(160, 120, 0), white(160, 120, 1)}, g3);
  CHECK(t3.pairs[0].disoccluded == t3.pairs[0].covered - t3.pairs[0].offscreen);
  CHECK(std::isnan(t3.coherence_mean));
  CHECK(!t3.pairs[0].reason.empty());
}

TEST_CASE("an object seen where the previous frame saw another is excluded by object ID") {
  hush_test::plane_scene s;
  s.split = 80;
  s.b.id = 2;
  auto g = hush_test::plane_sequence(s);
  // Every pixel of frame 1 moves 3 pixels right: columns 80 ... 82 of B came from A's 77 ... 79.
  for (std::size_t p = 0; p < g[1].pixels(); ++p) g[1].velocity[3 * p] = 3;
  const auto t =
      hush_tools::coherence::measure_temporal({white(160, 120, 0), white(160, 120, 1)}, g);
  CHECK(t.pairs[0].offscreen == 3 * 120);
  CHECK(t.pairs[0].disoccluded == 3 * 120);
}

TEST_CASE("background-only frames give NaN with a reason and no crash") {
  hush_test::plane_scene s;
  auto g = hush_test::plane_sequence(s);
  for (auto& gb : g) std::fill(gb.object_id.begin(), gb.object_id.end(), 0u);
  const auto t =
      hush_tools::coherence::measure_temporal({white(160, 120, 0), white(160, 120, 1)}, g);
  CHECK(std::isnan(t.coherence_mean));
  CHECK(std::isnan(t.change_mean));
  CHECK(std::isnan(t.popping));
  CHECK(!t.reason.empty());
  CHECK(t.pairs_without_coherence == 1);
}

TEST_CASE("mismatched sequences and options are rejected with hush::invalid_argument") {
  hush_test::plane_scene s;
  const auto g = hush_test::plane_sequence(s);
  const noise_frame f = white(160, 120, 0);
  CHECK_THROWS_AS(hush_tools::coherence::measure_temporal({f}, g), hush::invalid_argument);
  CHECK_THROWS_AS(hush_tools::coherence::measure_temporal({f, noise_frame(7)}, g),
                  hush::invalid_argument);
  CHECK_THROWS_AS(hush_tools::coherence::measure_temporal({f}, {g[0]}), hush::invalid_argument);
  noise_frame bad = f;
  bad[5] = NAN;
  CHECK_THROWS_AS(hush_tools::coherence::measure_temporal({f, bad}, g), hush::invalid_argument);
  hush_tools::coherence::options o;
  o.depth_epsilon = -1;
  CHECK_THROWS_AS(hush_tools::coherence::measure_temporal({f, f}, g, o), hush::invalid_argument);
  auto short_velocity = g;
  short_velocity[1].velocity.pop_back();
  CHECK_THROWS_AS(hush_tools::coherence::measure_temporal({f, f}, short_velocity),
                  hush::invalid_argument);
}
