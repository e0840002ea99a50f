// The README's usage example: Perlin noise and a 6-octave fBm sum of it.
#include <cstdio>

#include "hush/hush.hpp"

int main() {
  const hush::perlin<3> perlin{/*seed=*/7};

  hush::fractal<hush::perlin<3>>::params prm;
  prm.seed = 7;
  prm.octaves = 6;  // fBm, normalised to unit variance by default
  const hush::fractal<hush::perlin<3>> fbm{prm};

  for (float x : {0.0f, 0.25f, 0.5f, 0.75f}) {
    const hush::vec3 p{x, 1.5f, -2.25f};
    std::printf("x = %.2f  perlin = %+.6f  fbm = %+.6f\n", x, perlin(p), fbm(p));
  }
}
