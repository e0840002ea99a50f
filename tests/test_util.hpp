// Helpers shared by hush's test suites. Includes only the umbrella header, so
// suites that also run against the single header can use it.
#ifndef HUSH_TESTS_TEST_UTIL_HPP
#define HUSH_TESTS_TEST_UTIL_HPP

#include <cmath>
#include <cstdint>

#include "hush/hush.hpp"

namespace hush_test {

// Float error budget for values (perlin.hpp contract), from a forward error
// analysis: the fade's Horner terms reach 15 for a result near 1 (about 20
// ulp), each lerp multiplies that by a difference of up to 2 sqrt(2), and two
// (2D) or three (3D) lerp levels plus the corner dots add their own rounding:
// under 128 ulp of 1 in all, i.e. 2^-16.
inline const double kFloatBudget = std::ldexp(1.0, -16);
// The same analysis for the double reference: 2^-16 * 2^-29.
inline const double kDoubleBudget = std::ldexp(1.0, -45);

// Analytic Lipschitz bounds of the scaled noise (docs/design.md, "Perlin noise
// bounds"): |dn/dx_a| <= scale * (max|g| + max s' * max|g| * max|d|), with
// max s' = 15/8 (the fade's slope at t = 1/2) and |d| <= sqrt(D); the gradient
// norm is at most sqrt(D) times that.
template <int D>
inline double lipschitz_bound() {
  const double max_ds = 15.0 / 8.0;
  const double g = D == 2 ? 1.0 : std::sqrt(2.0);
  const double scale =
      D == 2 ? hush::detail::constants::kPerlin2Scale : hush::detail::constants::kPerlin3Scale;
  return std::sqrt(double(D)) * scale * (g + max_ds * g * std::sqrt(double(D)));
}

// Uniform random position in [-extent, extent]^D, from hush's own tested RNG.
template <int D>
hush::vec<double, D> random_point(hush::rng& r, double extent) {
  hush::vec<double, D> p;
  for (int a = 0; a < D; ++a) p[a] = r.uniform<double>(-extent, extent);
  return p;
}

// splitmix64 (Steele, Lea, Flood 2014): an input generator independent of
// the code under test, for tests of hush's own hashing and RNG.
struct splitmix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::uint32_t next_u32() { return static_cast<std::uint32_t>(next() >> 32); }
};

}  // namespace hush_test

#endif  // HUSH_TESTS_TEST_UTIL_HPP
