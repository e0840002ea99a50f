// Compiled by the `single_header_standalone` test with nothing but the single
// header on the include path, a different configuration from the test suites
// (HUSH_NO_GLM, -std=c++17 -Wall -Wextra -Werror -pedantic, no doctest), and
// linked with standalone_second.cpp, which includes the header too: a
// non-inline definition in the header would fail to link.
#include "hush/hush.hpp"

#include <cmath>
#include <cstdio>

#if !defined(HUSH_SINGLE_HEADER) || HUSH_CONFIG_GLM != 0
#error "expected the single header, configured without GLM (HUSH_NO_GLM)"
#endif

float second_translation_unit(float x);  // standalone_second.cpp

int main() {
  const hush::perlin<2> p{3};
  const float a = p(hush::vec2{1.5f, -2.25f});
  const float b = second_translation_unit(0.3f);
  if (!std::isfinite(a) || !std::isfinite(b) || std::fabs(a) > 1.0f || std::fabs(b) > 1.0f) {
    std::fprintf(stderr, "unexpected values %g %g\n", static_cast<double>(a),
                 static_cast<double>(b));
    return 1;
  }
  std::printf("hush %s single header, standalone: ok\n", HUSH_VERSION_STRING);
  return 0;
}
