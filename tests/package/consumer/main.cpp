// The package tests' consumer: uses hush::hush like any program would and
// exits 0 only if hush's Perlin noise and fractal sums give finite values in
// [-1, 1] that are not all zero, and the headers are the expected version. Linked with
// hush::simd (HUSH_CONSUMER_SIMD), exec::simd must run compiled SIMD kernels and agree with
// exec::scalar within Perlin's float budget (both are within 2^-16 of the double reference).
#include <hush/hush.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

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
#if defined(HUSH_CONSUMER_SIMD)
  if (!HUSH_CONFIG_SIMD || hush::simd::compiled_targets().empty()) {
    std::fprintf(stderr, "consumer: linked hush::simd, but exec::simd has no SIMD (%s)\n",
                 hush::simd::chosen_target().c_str());
    return 1;
  }
  hush::grid<2> g;
  g.origin = {-2.0, 1.0};
  g.step = {0.173, 0.219};
  g.size = {67, 33};
  std::vector<float> simd(g.count()), scalar(g.count());
  hush::evaluate_grid(noise, hush::exec::simd, g, simd);
  hush::evaluate_grid(noise, hush::exec::scalar, g, scalar);
  double worst = 0;
  for (std::size_t i = 0; i < simd.size(); ++i) {
    const double d = std::fabs(double(simd[i]) - double(scalar[i]));
    worst = std::isnan(d) ? INFINITY : (d > worst ? d : worst);
  }
  if (!(worst <= std::ldexp(1.0, -15))) {
    std::fprintf(stderr, "consumer: exec::simd (%s) differs from scalar by %.3g\n",
                 hush::simd::chosen_target().c_str(), worst);
    return 1;
  }
  std::printf("consumer: exec::simd on %s, max |simd - scalar| %.3g\n",
              hush::simd::chosen_target().c_str(), worst);
#endif
  std::printf("consumer: hush %s ok (%d values checked)\n", HUSH_VERSION_STRING, 2 * 32 * 32);
  return 0;
}
