// Second translation unit of the `single_header_standalone` test (see standalone_main.cpp).
#include "hush/hush.hpp"

float second_translation_unit(float x) {
  hush::fractal<hush::perlin<3>>::params prm;
  prm.norm = hush::normalization::unit_range;
  const hush::fractal<hush::perlin<3>> f{prm};
  return f(hush::vec3{x, 2.0f * x, -x});
}
