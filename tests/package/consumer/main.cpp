// The package tests' consumer: uses hush::hush like any program would and
// exits 0 only if hush's Perlin noise and fractal sums give finite values in
// [-1, 1] that are not all zero, and the headers are the expected version.
#include <hush/hush.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>

int main() {
  if (std::strcmp(HUSH_VERSION_STRING, HUSH_EXPECTED_VERSION) != 0) {
    std::fprintf(stderr, "consumer: headers are hush %s, expected %s\n", HUSH_VERSION_STRING,
                 HUSH_EXPECTED_VERSION);
    return 1;
  }
  const hush::perlin<2> noise{42};
  hush::fractal<hush::perlin<2>>::params prm;
  prm.seed = 42;
  prm.octaves = 6;
  prm.norm = hush::normalization::unit_range;  // |fbm| <= 1
  const hush::fractal<hush::perlin<2>> fbm{prm};

  int bad = 0, nonzero = 0;
  for (int j = 0; j < 32; ++j) {
    for (int i = 0; i < 32; ++i) {
      const hush::vec2 p{0.173f * static_cast<float>(i) - 2.0f,
                         0.219f * static_cast<float>(j) + 1.0f};
      for (const float v : {noise(p), fbm(p)}) {
        if (!std::isfinite(v) || v < -1.0f || v > 1.0f) ++bad;
        if (v != 0.0f) ++nonzero;
      }
    }
  }
  if (bad != 0 || nonzero == 0) {
    std::fprintf(stderr, "consumer: %d values out of [-1, 1] or not finite, %d non-zero\n", bad,
                 nonzero);
    return 1;
  }
  std::printf("consumer: hush %s ok (%d values checked)\n", HUSH_VERSION_STRING, 2 * 32 * 32);
  return 0;
}
