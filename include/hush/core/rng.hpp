// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::rng: a small deterministic random number generator. Counter-based:
// draw n of stream (seed, stream) is hash32(key ^ hash32(n)), with
// key = hash32(seed, stream). That makes it
//  - reproducible bit for bit on every compiler and standard library (no
//    std::*_distribution anywhere; HARD_CASES row 10) and in GLSL (32-bit
//    unsigned operations only),
//  - splittable: a triangle, pixel or octave gets its own stream by id, and
//    streams are independent, with no state shared between them,
//  - random access: skip(n) is O(1).
// Each stream is a permutation of all 2^32 words over its period of 2^32 draws.
#ifndef HUSH_CORE_RNG_HPP
#define HUSH_CORE_RNG_HPP

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "hush/core/error.hpp"
#include "hush/core/hash.hpp"
#include "hush/detail/constants.hpp"

namespace hush {

// ln(n!) for n >= 0: exact-factorial logarithms up to n = 20, Stirling's series
// above (relative error < 1e-16 in the series). Own code rather than
// std::lgamma, which is not thread-safe in glibc (it writes `signgam`).
inline double log_factorial(std::uint32_t n) {
  namespace c = detail::constants;
  if (n <= static_cast<std::uint32_t>(c::kLogFactorialTable)) {
    double f = 1.0;
    for (std::uint32_t i = 2; i <= n; ++i) f *= static_cast<double>(i);
    return std::log(f);
  }
  const double x = static_cast<double>(n);
  const double r = 1.0 / x, r2 = r * r;
  const double series =
      r *
      (c::kStirling[0] + r2 * (c::kStirling[1] + r2 * (c::kStirling[2] + r2 * c::kStirling[3])));
  return (x + 0.5) * std::log(x) - x + c::kHalfLog2Pi + series;
}

class rng {
 public:
  // A stream of random numbers. Different (seed, stream) pairs give
  // independent streams; the default stream is 0.
  constexpr explicit rng(std::uint32_t seed, std::uint32_t stream = 0)
      : key_(hash32(seed, stream)) {}

  // Uniform 32-bit word.
  constexpr std::uint32_t next_u32() { return hash32(key_ ^ hash32(counter_++)); }

  // Number of draws made so far, and O(1) skipping ahead (wraps at 2^32).
  constexpr std::uint32_t position() const { return counter_; }
  constexpr void skip(std::uint32_t n) { counter_ += n; }

  // Uniform in [0, 1): float from 24 bits (one draw), double from 53 bits
  // (two draws); every value is a multiple of 2^-24 or 2^-53.
  template <class T = float>
  T uniform() {
    static_assert(std::is_same<T, float>::value || std::is_same<T, double>::value,
                  "hush::rng::uniform<T>: T is float or double");
    if constexpr (std::is_same<T, float>::value) {
      return static_cast<float>(next_u32() >> 8) * 0x1p-24f;
    } else {
      const std::uint64_t hi = next_u32() >> 5;  // 27 bits
      const std::uint64_t lo = next_u32() >> 6;  // 26 bits
      return static_cast<double>((hi << 26) | lo) * 0x1p-53;
    }
  }

  // Uniform in [lo, hi). Requires lo < hi, both finite (not checked: a hot
  // path). lo + (hi - lo) u can round up to hi when u is the largest value
  // below 1; that one case returns the largest value below hi.
  template <class T>
  T uniform(T lo, T hi) {
    const T r = lo + (hi - lo) * uniform<T>();
    return r < hi ? r : std::nextafter(hi, lo);
  }

  // Standard normal deviate (mean 0, variance 1) by Marsaglia's polar method,
  // computed in double. Each try succeeds with probability pi/4; after 64
  // failed tries (probability 2e-43) it returns 0, so it always terminates.
  template <class T = float>
  T gaussian() {
    constexpr int kMaxTries = 64;
    for (int t = 0; t < kMaxTries; ++t) {
      const double u = 2.0 * uniform<double>() - 1.0;
      const double v = 2.0 * uniform<double>() - 1.0;
      const double s = u * u + v * v;
      if (s > 0.0 && s < 1.0) return static_cast<T>(u * std::sqrt(-2.0 * std::log(s) / s));
    }
    return T(0);
  }

  // Poisson-distributed count with the given mean, for any mean in
  // [0, 1e9]. Throws hush::invalid_argument for a negative, NaN, infinite or
  // larger mean. Always terminates: inversion below mean 12 is bounded by a
  // step cap, and PTRS rejection above gives up after 10^4 tries (probability
  // below 1e-9000) by returning round(mean).
  std::uint32_t poisson(double mean) {
    namespace c = detail::constants;
    if (!(mean >= 0.0 && mean <= c::kPoissonMaxMean))
      detail::throw_out_of_range("hush::rng::poisson", "mean", mean,
                                 "0 <= mean <= 1e9 (finite, not NaN)");
    if (mean == 0.0) return 0;
    if (mean < c::kPoissonInversionLimit) return poisson_inversion(mean);
    return poisson_ptrs(mean);
  }

 private:
  // Sequential search of the CDF. For mean < 12, P(k > 200) < 1e-150, so the
  // cap changes nothing but guarantees termination even if rounding keeps the
  // summed CDF below u.
  std::uint32_t poisson_inversion(double mean) {
    constexpr std::uint32_t kMaxK = 200;
    const double u = uniform<double>();
    double p = std::exp(-mean);  // >= exp(-12): no underflow
    double cdf = p;
    std::uint32_t k = 0;
    while (u >= cdf && k < kMaxK) {
      ++k;
      p *= mean / static_cast<double>(k);
      cdf += p;
    }
    return k;
  }

  // Hoermann 1993, PTRS; symbols as in the paper (a, b, v_r, alpha).
  std::uint32_t poisson_ptrs(double mean) {
    namespace c = detail::constants;
    constexpr int kMaxTries = 10000;
    const double slam = std::sqrt(mean);
    const double loglam = std::log(mean);
    const double b = c::kPtrsB0 + c::kPtrsB1 * slam;
    const double a = c::kPtrsA0 + c::kPtrsA1 * b;
    const double inv_alpha = c::kPtrsAlpha0 + c::kPtrsAlpha1 / (b - c::kPtrsAlphaB);
    const double vr = c::kPtrsVr0 - c::kPtrsVr1 / (b - c::kPtrsVrB);
    const double log_inv_alpha = std::log(inv_alpha);
    constexpr double kMaxCount = 4294967295.0;
    for (int t = 0; t < kMaxTries; ++t) {
      const double u = uniform<double>() - 0.5;
      const double v = uniform<double>();
      const double us = 0.5 - std::fabs(u);
      if (us <= 0.0) continue;  // u = -0.5 exactly: the transform is singular
      const double kd = std::floor((2.0 * a / us + b) * u + mean + c::kPtrsKOffset);
      if (kd < 0.0 || kd > kMaxCount) continue;
      if (us >= c::kPtrsUsAccept && v <= vr) return static_cast<std::uint32_t>(kd);
      if (us < c::kPtrsUsReject && v > us) continue;
      const auto k = static_cast<std::uint32_t>(kd);
      if (std::log(v) + log_inv_alpha - std::log(a / (us * us) + b) <=
          -mean + kd * loglam - log_factorial(k))
        return k;
    }
    return static_cast<std::uint32_t>(std::floor(mean + 0.5));
  }

  std::uint32_t key_;
  std::uint32_t counter_ = 0;
};

}  // namespace hush

#endif  // HUSH_CORE_RNG_HPP
