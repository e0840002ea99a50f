#include <hush/hush.hpp>
#include <cstdio>

int main() {
  const hush::perlin<3> noise{/*seed=*/7};                    // range [-1, 1]
  const auto [value, gradient] = noise.gradient(hush::vec3{1.5f, 2.25f, -0.5f});
  hush::fractal<hush::perlin<2>>::params fbm;                 // 6 octaves, unit variance
  fbm.octaves = 6;
  const hush::fractal<hush::perlin<2>> clouds{fbm};
  std::printf("%f (%f %f %f) %f\n", value, gradient.x, gradient.y, gradient.z,
              clouds(hush::vec2{0.3f, 0.7f}));
}
