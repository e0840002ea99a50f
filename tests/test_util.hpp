// Helpers shared by hush's test suites. Includes only the umbrella header, so
// suites that also run against the single header can use it.
#ifndef HUSH_TESTS_TEST_UTIL_HPP
#define HUSH_TESTS_TEST_UTIL_HPP

#include <cstdint>

#include "hush/hush.hpp"

namespace hush_test {

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
