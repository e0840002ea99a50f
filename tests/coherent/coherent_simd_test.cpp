// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Coherent noise's SIMD kernel (hush/coherent/simd-inl.h) against the scalar pass, on every
// SIMD target compiled into this test and supported by this CPU. Built into the same four
// suites as perlin_simd_test.cpp (tests/simd/CMakeLists.txt): under HUSH_STRICT_FP every
// output value, history value and fresh flag must equal the scalar pass bit for bit; with
// contraction allowed the decisions (fresh flags) must still be equal and the values within
// twice the float budget of coherent.hpp. Covered: both filters, white, band-pass and the
// caller's input, 1 and 3 channels, with and without object ids, widths around every
// vector length (tails), the backward pass (time-symmetric filter), and NaN, Inf, negative,
// zero and denormal depth and motion in every lane position.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "coherent_scenes.hpp"
#include "hush/hush.hpp"
#include "simd/each_target.hpp"

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
#include <hwy/targets.h>
#endif

namespace {

using hush_test::make_synthetic;
using hush_test::synthetic_frame;

// Bit for bit under strict FP, else within `budget`; returns the largest difference. One
// assertion per array (the first differing element is reported).
double compare_values(const float* simd, const float* scalar, std::size_t n, double budget) {
  double worst = 0;
  std::size_t bad = n;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = std::fabs(double(simd[i]) - scalar[i]);
#if HUSH_CONFIG_STRICT_FP
    (void)budget;
    const bool ok = std::memcmp(&simd[i], &scalar[i], sizeof(float)) == 0;
#else
    const bool ok = d <= budget;
#endif
    if (!ok && bad == n) bad = i;
    worst = std::max(worst, d);
  }
  INFO("first difference at " << bad << " of " << n);
  if (bad < n) INFO("simd " << simd[bad] << ", scalar " << scalar[bad]);
  REQUIRE(bad == n);
  return worst;
}

// Sprinkles bad values over a frame: in every lane position over the frame's pixels.
void spoil(synthetic_frame& s, int frame) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const float denormal = std::numeric_limits<float>::denorm_min() * 3;
  const float depth[] = {nan, inf, -1.0f, 0.0f, denormal, 1e-30f};
  const float motion[] = {nan, -inf, 1e30f, denormal, -denormal, 0.5f};
  for (std::size_t p = static_cast<std::size_t>(frame) % 7; p < s.pixels(); p += 13) {
    s.depth[p] = depth[(p / 13) % 6];
    s.velocity[3 * p + (p % 3)] = motion[(p / 7) % 6];
    s.forward[3 * p + ((p + 1) % 3)] = motion[(p / 5) % 6];
  }
}

struct setup {
  hush::coherent_filter filter;
  hush::coherent_input input;
  bool caller_input;
  int channels;
  bool ids;
};

}  // namespace

TEST_CASE("coherent SIMD pass equals the scalar pass: values, history and fresh flags") {
  const setup setups[] = {
      {hush::coherent_filter::stationary, hush::coherent_input::white, false, 1, true},
      {hush::coherent_filter::paper, hush::coherent_input::white, false, 1, true},
      {hush::coherent_filter::stationary, hush::coherent_input::bandpass, false, 3, true},
      {hush::coherent_filter::paper, hush::coherent_input::bandpass, false, 2, false},
      {hush::coherent_filter::stationary, hush::coherent_input::white, true, 2, false},
  };
  const int widths[] = {1, 5, 16, 17, 31, 33, 49, 71};
  for_each_target([&] {
    double worst = 0;
    for (const setup& su : setups)
      for (int w : widths) {
        const int h = 11;
        CAPTURE(w);
        CAPTURE(static_cast<int>(su.filter));
        CAPTURE(static_cast<int>(su.input));
        CAPTURE(su.channels);
        hush::coherent_params prm;
        prm.filter = su.filter;
        prm.input = su.input;
        prm.channels = su.channels;
        prm.alpha = 0.9;
        prm.seed = 5;
        hush::coherent_stream a(prm), b(prm);
        const std::size_t n = static_cast<std::size_t>(w) * h;
        std::vector<float> oa(n * su.channels), ob(n * su.channels);
        std::vector<hush::image_view<float>> va, vb;
        for (int c = 0; c < su.channels; ++c) {
          va.emplace_back(oa.data() + n * c, w, h);
          vb.emplace_back(ob.data() + n * c, w, h);
        }
        std::vector<float> in(n * su.channels);
        std::vector<hush::image_view<const float>> vin;
        for (int c = 0; c < su.channels; ++c) vin.emplace_back(in.data() + n * c, w, h);
        const double budget = 2 * (12 / (1 - prm.alpha) + 1) * std::ldexp(1.0, -24) * 8;
        for (int i = 0; i < 12; ++i) {
          synthetic_frame s = make_synthetic(i % 4 == 3 ? "zoom" : "rotate", 0.07, w, h);
          spoil(s, i);
          hush::frame f = s.view();
          if (!su.ids) f.object_id = {};
          for (std::size_t k = 0; k < in.size(); ++k)
            in[k] = hush::coherent_white_noise(3, 0, static_cast<std::uint32_t>(i),
                                               static_cast<std::uint32_t>(k), 1);
          const hush::span<const hush::image_view<const float>> input =
              su.caller_input ? hush::span<const hush::image_view<const float>>(vin)
                              : hush::span<const hush::image_view<const float>>();
          a.advance(hush::exec::simd, f, hush::span<const hush::image_view<float>>(va), input);
          b.advance(hush::exec::scalar, f, hush::span<const hush::image_view<float>>(vb), input);
          REQUIRE(a.fresh() == b.fresh());
          worst = std::max(worst, compare_values(oa.data(), ob.data(), oa.size(), budget));
          for (int c = 0; c < su.channels; ++c)
            compare_values(a.history(c).data(), b.history(c).data(), n, budget);
        }
      }
    MESSAGE("coherent SIMD vs scalar (" << hush::simd::chosen_target() << "): max |difference| "
                                        << worst);
  });
}

TEST_CASE("coherent SIMD time-symmetric filter (backward pass) equals the scalar one") {
  for_each_target([&] {
    for (int w : {9, 40}) {
      const int h = 13, frames = 6;
      hush::coherent_params prm;
      prm.channels = 2;
      prm.alpha = 0.8;
      std::vector<synthetic_frame> seq;
      for (int i = 0; i < frames; ++i) {
        seq.push_back(make_synthetic("rotate", 0.05, w, h));
        spoil(seq.back(), i);
      }
      std::vector<hush::frame> views;
      for (const synthetic_frame& s : seq) views.push_back(s.view());
      const std::size_t n = static_cast<std::size_t>(w) * h;
      std::vector<float> oa(n * 2 * frames), ob(n * 2 * frames);
      std::vector<hush::image_view<float>> va, vb;
      for (int k = 0; k < 2 * frames; ++k) {
        va.emplace_back(oa.data() + n * k, w, h);
        vb.emplace_back(ob.data() + n * k, w, h);
      }
      hush::coherent_symmetric(hush::exec::simd, prm, hush::span<const hush::frame>(views),
                               hush::span<const hush::image_view<float>>(va));
      hush::coherent_symmetric(hush::exec::scalar, prm, hush::span<const hush::frame>(views),
                               hush::span<const hush::image_view<float>>(vb));
      compare_values(oa.data(), ob.data(), oa.size(),
                     2 * (12 / (1 - 0.8) + 1) * std::ldexp(1.0, -24) * 8);
    }
  });
}
