// Proves that this suite compiles against single_include/hush/hush.hpp, the
// amalgamation, and not against include/: the generated header defines
// HUSH_SINGLE_HEADER, and no one-concept header (hush/perlin.hpp) is reachable.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "hush/hush.hpp"

#if !defined(HUSH_SINGLE_HEADER) || HUSH_SINGLE_HEADER != 1
#error "hush/hush.hpp is not the single header: include/ leaked into the include path"
#endif
#if defined(__has_include)
#if __has_include("hush/perlin.hpp")
#error "hush/perlin.hpp is reachable: include/ leaked into the single-header include path"
#endif
#endif

TEST_CASE("single header: is the amalgamation, with the version of include/hush/config.hpp") {
  CHECK(HUSH_SINGLE_HEADER == 1);
  CHECK(std::string(HUSH_VERSION_STRING) == std::to_string(HUSH_VERSION_MAJOR) + "." +
                                                std::to_string(HUSH_VERSION_MINOR) + "." +
                                                std::to_string(HUSH_VERSION_PATCH));
}

TEST_CASE("single header: perlin and fractal evaluate to finite values in range") {
  const hush::perlin<3> p{7};
  hush::fractal<hush::perlin<2>>::params prm;
  prm.norm = hush::normalization::unit_range;
  const hush::fractal<hush::perlin<2>> f{prm};
  for (int i = 0; i < 64; ++i) {
    const float x = 0.37f * static_cast<float>(i) - 5.0f;
    const float a = p(hush::vec3{x, 0.5f * x, 1.25f});
    const float b = f(hush::vec2{x, -0.75f * x});
    CHECK(std::isfinite(a));
    CHECK(std::fabs(a) <= 1.0f);
    CHECK(std::isfinite(b));
    CHECK(std::fabs(b) <= 1.0f);
  }
}
