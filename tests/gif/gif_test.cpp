// The animated GIF writer (examples/gif/gif.hpp): what it writes decodes (stb_image, an
// independent reader) to the same gray levels, frame for frame, with the delay, for images
// that fill the LZW table many times over (noise) and that barely use it (flat); bad
// arguments are refused.
#include <doctest/doctest.h>

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

void round_trip(int w, int h, int n, bool noise) {
  CAPTURE(w);
  CAPTURE(h);
  CAPTURE(noise);
  const auto in = frames(w, h, n, 7, noise);
  const std::vector<std::uint8_t> file = hush::gif::encode(in, w, h, 4);
  int *delays = nullptr, x = 0, y = 0, z = 0, comp = 0;
  stbi_uc* out = stbi_load_gif_from_memory(file.data(), static_cast<int>(file.size()), &delays, &x,
                                           &y, &z, &comp, 4);
  REQUIRE(out != nullptr);
  CHECK(x == w);
  CHECK(y == h);
  CHECK(z == n);
  std::size_t bad = 0;
  for (int k = 0; k < z; ++k) {
    CHECK(delays[k] == 40);  // milliseconds
    for (int p = 0; p < w * h; ++p) {
      const stbi_uc* px = out + (std::size_t(k) * std::size_t(w * h) + std::size_t(p)) * 4;
      const std::uint8_t g = in[std::size_t(k)][std::size_t(p)];
      bad += px[0] != g || px[1] != g || px[2] != g || px[3] != 255;
    }
  }
  CHECK(bad == 0);
  stbi_image_free(out);
  stbi_image_free(delays);
}

}  // namespace

TEST_CASE("GIF frames decode to the same gray levels: noise, smooth ramps, odd sizes") {
  round_trip(97, 61, 3, true);  // ~6000 codes per frame: the table is cleared and refilled
  round_trip(200, 150, 2, false);
  round_trip(1, 1, 1, true);
  round_trip(3, 700, 2, true);
}

TEST_CASE("GIF encoding refuses what the format cannot hold") {
  const auto f = frames(4, 4, 1, 1, true);
  CHECK_THROWS_AS(hush::gif::encode({}, 4, 4, 4), hush::invalid_argument);
  CHECK_THROWS_AS(hush::gif::encode(f, 0, 4, 4), hush::invalid_argument);
  CHECK_THROWS_AS(hush::gif::encode(f, 4, 70000, 4), hush::invalid_argument);
  CHECK_THROWS_AS(hush::gif::encode(f, 4, 3, 4), hush::invalid_argument);  // 16 != 12 bytes
  CHECK_THROWS_AS(hush::gif::encode(f, 4, 4, -1), hush::invalid_argument);
}
