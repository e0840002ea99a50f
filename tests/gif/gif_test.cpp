// The animated GIF writer (examples/gif/gif.hpp): what it writes decodes (stb_image, an
// independent reader) to the same gray levels, frame for frame, with the delay, for images
// that fill the LZW table many times over (noise) and that barely use it (flat); RGB frames
// decode to the palette colour of their dithered index, every 4 x 4 block of one colour
// averages to that colour (the ordered dithering's bound), and bad arguments are refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "gif/gif.hpp"
#include "hush/core/error.hpp"
#include "hush/core/rng.hpp"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_GIF
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace {

std::vector<std::vector<std::uint8_t>> frames(int w, int h, int n, std::uint32_t seed, bool noise) {
  hush::rng r(seed);
  std::vector<std::vector<std::uint8_t>> f(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k)
    for (int p = 0; p < w * h; ++p)
      f[std::size_t(k)].push_back(noise ? static_cast<std::uint8_t>(r.next_u32() >> 24)
                                        : static_cast<std::uint8_t>((p / 7 + 3 * k) % 256));
  return f;
}

// Decodes `file` (RGBA, 4 bytes per pixel, frames one after the other); checks size, frame
// count and delay.
std::vector<stbi_uc> decode(const std::vector<std::uint8_t>& file, int w, int h, int n) {
  int *delays = nullptr, x = 0, y = 0, z = 0, comp = 0;
  stbi_uc* out = stbi_load_gif_from_memory(file.data(), static_cast<int>(file.size()), &delays, &x,
                                           &y, &z, &comp, 4);
  REQUIRE(out != nullptr);
  REQUIRE(x == w);
  REQUIRE(y == h);
  REQUIRE(z == n);
  for (int k = 0; k < z; ++k) CHECK(delays[k] == 40);  // milliseconds
  std::vector<stbi_uc> px(out, out + std::size_t(x) * std::size_t(y) * std::size_t(z) * 4);
  stbi_image_free(out);
  stbi_image_free(delays);
  return px;
}

void round_trip(int w, int h, int n, bool noise) {
  CAPTURE(w);
  CAPTURE(h);
  CAPTURE(noise);
  const auto in = frames(w, h, n, 7, noise);
  const std::vector<stbi_uc> out = decode(hush_tools::gif::encode(in, w, h, 4), w, h, n);
  std::size_t bad = 0;
  for (int k = 0; k < n; ++k)
    for (int p = 0; p < w * h; ++p) {
      const stbi_uc* px = &out[(std::size_t(k) * std::size_t(w * h) + std::size_t(p)) * 4];
      const std::uint8_t g = in[std::size_t(k)][std::size_t(p)];
      bad += px[0] != g || px[1] != g || px[2] != g || px[3] != 255;
    }
  CHECK(bad == 0);
}

}  // namespace

TEST_CASE("RGB GIF frames decode to the palette colour of each pixel's dithered index") {
  // Random colours: every index is used, the LZW table is refilled many times.
  const int w = 67, h = 45, n = 3;
  hush::rng r(11);
  std::vector<std::vector<std::uint8_t>> in(n);
  for (auto& f : in)
    for (int p = 0; p < 3 * w * h; ++p) f.push_back(static_cast<std::uint8_t>(r.next_u32() >> 24));
  const std::vector<stbi_uc> px = decode(hush_tools::gif::encode_rgb(in, w, h, 4), w, h, n);
  const std::vector<std::uint8_t>& pal = hush_tools::gif::palette();
  std::size_t bad = 0, far = 0;
  for (int k = 0; k < n; ++k)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(w) + std::size_t(x);
        const std::uint8_t* c = &in[std::size_t(k)][3 * p];
        const std::size_t i =
            hush_tools::gif::dither(c[0], c[1], c[2], std::size_t(x), std::size_t(y));
        const stbi_uc* d = &px[(std::size_t(k) * std::size_t(w * h) + p) * 4];
        bad += i >= 252 || d[0] != pal[3 * i] || d[1] != pal[3 * i + 1] ||
               d[2] != pal[3 * i + 2] || d[3] != 255;
        // A pixel is within one palette step (255 / 5 for red and blue) of its colour.
        for (int ch = 0; ch < 3; ++ch) far += std::abs(int(d[ch]) - int(c[ch])) > 51;
      }
  CHECK(bad == 0);
  CHECK(far == 0);
}

TEST_CASE("RGB dithering: each 4 x 4 block of one colour averages to it within step/32 + 1/2") {
  // One colour per 4 x 4 block, 256 blocks sweeping each channel; the decoded block mean
  // must be within 255 / (L - 1) / 32 + 1/2 of the colour (gif.cpp's derivation; L = 6, 7, 6).
  const int w = 64, h = 64;
  std::vector<std::uint8_t> f(3 * w * h);
  auto colour = [](int bx, int by, int ch) {
    const int k = by * 16 + bx;  // 0 ... 255
    return static_cast<std::uint8_t>(ch == 0 ? k : (ch == 1 ? (k * 37) % 256 : 255 - k));
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int ch = 0; ch < 3; ++ch)
        f[3 * std::size_t(y * w + x) + std::size_t(ch)] = colour(x / 4, y / 4, ch);
  const std::vector<stbi_uc> px = decode(hush_tools::gif::encode_rgb({f}, w, h, 4), w, h, 1);
  const double levels[3] = {6, 7, 6};
  double worst[3] = {0, 0, 0};
  for (int by = 0; by < 16; ++by)
    for (int bx = 0; bx < 16; ++bx)
      for (int ch = 0; ch < 3; ++ch) {
        double sum = 0;
        for (int y = 4 * by; y < 4 * by + 4; ++y)
          for (int x = 4 * bx; x < 4 * bx + 4; ++x) sum += px[4 * std::size_t(y * w + x) + std::size_t(ch)];
        const double err = std::fabs(sum / 16.0 - colour(bx, by, ch));
        worst[ch] = std::max(worst[ch], err / (255.0 / (levels[ch] - 1) / 32.0 + 0.5));
      }
  CAPTURE(worst[0]);
  CAPTURE(worst[1]);
  CAPTURE(worst[2]);
  for (double e : worst) CHECK(e <= 1.0);
  MESSAGE("worst block error / bound: " << worst[0] << ", " << worst[1] << ", " << worst[2]);
}

TEST_CASE("GIF frames decode to the same gray levels: noise, smooth ramps, odd sizes") {
  round_trip(97, 61, 3, true);  // ~6000 codes per frame: the table is cleared and refilled
  round_trip(200, 150, 2, false);
  round_trip(1, 1, 1, true);
  round_trip(3, 700, 2, true);
}

TEST_CASE("GIF encoding refuses what the format cannot hold") {
  const auto f = frames(4, 4, 1, 1, true);
  CHECK_THROWS_AS(hush_tools::gif::encode({}, 4, 4, 4), hush::invalid_argument);
  CHECK_THROWS_AS(hush_tools::gif::encode(f, 0, 4, 4), hush::invalid_argument);
  CHECK_THROWS_AS(hush_tools::gif::encode(f, 4, 70000, 4), hush::invalid_argument);
  CHECK_THROWS_AS(hush_tools::gif::encode(f, 4, 3, 4), hush::invalid_argument);  // 16 != 12 bytes
  CHECK_THROWS_AS(hush_tools::gif::encode(f, 4, 4, -1), hush::invalid_argument);
  CHECK_THROWS_WITH_AS(hush_tools::gif::encode_rgb(f, 4, 4, 4),  // 16 != 48 bytes
                       doctest::Contains("3 * width * height"), hush::invalid_argument);
  CHECK_THROWS_AS(hush_tools::gif::encode_rgb({}, 4, 4, 4), hush::invalid_argument);
}
