// Helpers the GLSL suites share (glsl_test.cpp, glsl_fractal_test.cpp): the GL
// context and device of the test process, error statistics, and test points.
#ifndef HUSH_TESTS_GLSL_TEST_UTIL_HPP
#define HUSH_TESTS_GLSL_TEST_UTIL_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hush/glsl/device.hpp"
#include "hush/glsl/headless.hpp"
#include "hush/hush.hpp"

// Mesa's OSMesa keeps a few hundred bytes of per-process state (allocated in
// OSMesaMakeCurrent) after the context is destroyed; LeakSanitizer would
// report them at exit. Only leaks whose allocation stack is inside libOSMesa
// are suppressed. (Each suite is its own program; this header is included by
// exactly one translation unit of each.)
#if defined(__SANITIZE_ADDRESS__)
extern "C" const char* __lsan_default_suppressions() {  // NOLINT: the sanitizer hook's name
  return "leak:libOSMesa.so\n";
}
#endif

namespace hush_glsl_test {

// One headless context (HUSH_GL_CONTEXT) and device per test process (CTest runs each case
// alone).
inline hush::glsl::headless_device& headless() {
  static hush::glsl::headless_device h;
  return h;
}

// Max and RMS of a stream of absolute errors.
struct error_stats {
  double max = 0, sum_sq = 0;
  std::size_t n = 0;
  void add(double e) {
    max = std::max(max, e);
    sum_sq += e * e;
    ++n;
  }
  double rms() const { return n ? std::sqrt(sum_sq / double(n)) : 0.0; }
};

// n float points, uniform in [-100, 100]^D, every fourth in [-1e6, 1e6]^D
// (far out, where float positions keep few fraction bits).
template <int D>
std::vector<hush::vec<float, D>> random_points(std::size_t n, std::uint32_t seed) {
  hush::rng r(seed, D);
  std::vector<hush::vec<float, D>> pts(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double extent = i % 4 == 3 ? 1e6 : 100.0;
    for (int a = 0; a < D; ++a)
      pts[i][std::size_t(a)] = static_cast<float>(r.uniform<double>(-extent, extent));
  }
  return pts;
}

}  // namespace hush_glsl_test

#endif  // HUSH_TESTS_GLSL_TEST_UTIL_HPP
