// Fractal sums (docs/fractal.md): fBm of 3D Perlin noise with its gradient, tileable
// turbulence, and a SIMD grid of it. Quoted in docs/fractal.md.
#include <hush/hush.hpp>
#include <cstdio>
#include <vector>

int main() {
  // fBm: 6 octaves of 3D Perlin noise, features about 64 units wide, unit variance.
  hush::fractal<hush::perlin<3>>::params f;
  f.seed = 7;
  f.octaves = 6;
  f.frequency = 1.0 / 64;
  const hush::fractal<hush::perlin<3>> clouds{f};
  const float v = clouds(hush::vec3{10.5f, 3.25f, -7.0f});  // mean 0, variance 1
  const auto [v2, grad] = clouds.gradient(hush::vec3{10.5f, 3.25f, -7.0f});

  // Turbulence: sum of |octaves|, in [0, 1]. unit_variance is fBm-only, so say unit_range.
  hush::fractal<hush::perlin<2>>::params t;
  t.kind = hush::fractal_kind::turbulence;
  t.norm = hush::normalization::unit_range;
  t.period = {4, 4};  // tileable: repeats every 4 / frequency = 4 units along x and y
  const hush::fractal<hush::perlin<2>> marble{t};

  // A 256x256 tile of it on the SIMD backend (scalar loop when SIMD is not configured).
  const hush::grid<2> g{/*origin=*/{0.0, 0.0}, /*step=*/{1.0 / 64, 1.0 / 64},
                        /*size=*/{{256, 256}}};
  std::vector<float> image(g.count());
  hush::evaluate_grid(marble, hush::exec::simd, g, image);
  std::printf("fbm %f (d/dx %f), bound %f; turbulence %f, in [0, %f]\n", v, grad.x,
              clouds.bound(), image[0], marble.bound());
  return v == v2 ? 0 : 1;
}
