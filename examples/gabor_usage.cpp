// Gabor noise (docs/gabor.md): the three kinds, a filtered sample, surface noise, a SIMD
// batch on a grid, and the analytic power spectrum. Quoted in docs/gabor.md.
#include <hush/hush.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  hush::gabor<2>::params prm;  // isotropic, F0 = 1 cycle/unit, a = 0.8, N' = 16
  prm.kind = hush::gabor_kind::anisotropic;
  prm.frequency = 2.0;
  prm.orientation = 0.25 * 3.14159265358979;  // omega0 at 45 degrees
  const hush::gabor<2> noise{prm};            // unit variance, mean 0

  const float v = noise(hush::vec2{0.3f, 0.7f});
  const auto [g, grad] = noise.gradient(hush::vec2{0.3f, 0.7f});
  // Filtered over a pixel: dP/dx and dP/dy of the screen-to-noise mapping.
  const auto fp =
      hush::footprint<2>::from_derivatives(hush::dvec2{0.2, 0.0}, hush::dvec2{0.0, 0.6});
  const float f = noise.sample(hush::vec2{0.3f, 0.7f}, fp);

  const hush::gabor<3> solid{hush::gabor<3>::params{}};
  const float s = solid.sample(hush::vec3{1.0f, 2.0f, 3.0f}, hush::vec3{0.0f, 0.0f, 1.0f},
                               hush::footprint<3>::isotropic(0.01));  // surface noise

  hush::grid<2> grid;  // 256 x 256 samples, 1/32 apart
  grid.origin = {0.0, 0.0};
  grid.step = {1.0 / 32, 1.0 / 32};
  grid.size = {256, 256};
  std::vector<float> image(grid.count());
  hush::evaluate_grid(noise, hush::exec::simd, grid, hush::span<float>(image));
  double var = 0;
  for (const float x : image) var += double(x) * x;

  const double peak = noise.power_spectrum(hush::dvec2{2.0 * std::cos(0.25 * 3.14159265358979),
                                                       2.0 * std::sin(0.25 * 3.14159265358979)});
  std::printf("value %f (gradient %f %f) filtered %f surface %f grid variance %.2f peak %.3f\n", v,
              grad.x, grad.y, f, s, var / double(image.size()), peak);
  return std::isfinite(v + f + s) && g == v ? 0 : 1;
}
