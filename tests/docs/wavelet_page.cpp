// Wavelet noise (docs/wavelet.md): three bands, a footprint-filtered sample, 3D noise projected
// onto a surface, and a SIMD batch of filtered samples. Quoted in docs/wavelet.md.
#include <hush/hush.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  hush::wavelet<2>::params prm;    // 128^2 tile, seed 0, one band
  prm.weights = {1.0, 0.5, 0.25};  // bands 0, 1, 2: frequencies 1, 2, 4
  prm.seed = 7;
  const hush::wavelet<2> noise{prm};  // unit variance, |value| <= noise.bound()

  const float v = noise(hush::vec2{0.3f, 0.7f});
  // One sample per pixel: dP/dx and dP/dy of the screen-to-noise mapping. Bands finer than
  // the pixel fade out; nothing pops as the footprint changes.
  const auto fp =
      hush::footprint<2>::from_derivatives(hush::dvec2{0.3, 0.0}, hush::dvec2{0.0, 0.3});
  const float a = noise.sample(hush::vec2{0.3f, 0.7f}, fp);

  // 3D noise on a surface: projected along the normal, it keeps its band limit.
  const hush::wavelet<3> solid{7};
  const float b = solid.sample(hush::vec3{1.0f, 2.0f, 3.0f}, hush::vec3{0.0f, 0.6f, 0.8f},
                               hush::footprint<3>::isotropic(0.01));

  // A batch of filtered samples on the SIMD backend (or exec::scalar, exec::glsl{device}).
  std::vector<hush::vec2> positions;
  std::vector<hush::footprint<2>> footprints;
  for (int i = 0; i < 1000; ++i) {
    positions.push_back(hush::vec2{0.01f * float(i), 0.5f});
    footprints.push_back(hush::footprint<2>::isotropic(0.001 * i));  // widening with distance
  }
  hush::samples<2> batch;
  batch.positions = positions;
  batch.footprints = footprints;
  std::vector<float> out(positions.size());
  hush::evaluate(noise, hush::exec::simd, batch, hush::span<float>(out));

  std::printf("value %f filtered %f projected %f last sample %f (bound %.2f, %zu bytes)\n", v, a,
              b, out.back(), noise.bound(), noise.memory_bytes());
  return std::isfinite(v + a + b + out.back()) ? 0 : 1;
}
