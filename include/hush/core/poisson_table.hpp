// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::poisson_table: Poisson-distributed counts for one fixed mean from one
// uniform 32-bit word, by integer comparisons only.
//
// hush::rng::poisson computes in double (exp, log, rejection loops), which a
// GPU cannot repeat bit for bit. When the mean is fixed (a noise's impulse
// density per cell), the cumulative distribution can be computed once, on the
// CPU in double, and rounded to 32-bit thresholds
//
//   T_k = round(2^32 P(X < k)),  k = 1 ... n,
//
// kept while T_k < 2^32 (n = max_count()). The count of a uniform word u is
// then the number of thresholds at or below it, count(u) = #{k : T_k <= u}:
// integer comparisons only, so the CPU, the SIMD kernels and GLSL shaders that
// hold the same table draw the same count from the same word.
//
// Contract:
//  - mean: 0 <= mean <= kPoissonTableMaxMean (1e4); anything else, NaN and
//    +-Inf included, throws hush::invalid_argument naming "mean".
//  - distribution: with u uniform over all 2^32 words, count k has probability
//    (T_{k+1} - T_k) / 2^32 (T_0 = 0, T_{n+1} = 2^32), within 2^-32 of the
//    Poisson pmf for every k (one rounding of a CDF accurate to ~1e-13);
//    counts above n, whose total Poisson probability is below 2^-33, do not
//    occur. probability(k) and exact_mean() return the table's own values.
//  - cost: the thresholds are built once (O(n) exp, n ~ mean + 7 sqrt(mean)
//    + 20); count() is a binary search, O(log n), and never fails.
#ifndef HUSH_CORE_POISSON_TABLE_HPP
#define HUSH_CORE_POISSON_TABLE_HPP

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/rng.hpp"  // log_factorial
#include "hush/detail/constants.hpp"

namespace hush {

class poisson_table {
 public:
  // An empty table: mean 0, every count 0.
  poisson_table() = default;

  // The thresholds of Poisson(mean). Throws hush::invalid_argument when mean
  // is NaN, infinite, negative or above kPoissonTableMaxMean.
  explicit poisson_table(double mean) : mean_(mean) {
    namespace c = detail::constants;
    detail::require_in_range("hush::poisson_table", "mean", mean, 0.0, c::kPoissonTableMaxMean,
                             "0 <= mean <= 10000 (finite, not NaN)");
    if (mean == 0.0) return;
    constexpr double kWords = 4294967296.0;  // 2^32
    const double log_mean = std::log(mean);
    // The cap only guards the loop; for every valid mean the CDF reaches
    // 1 - 2^-33 long before it (P(X > mean + 7 sqrt(mean) + 20) < 1e-12).
    const auto cap = static_cast<std::uint32_t>(mean + 12.0 * std::sqrt(mean) + 64.0);
    double cdf = 0.0;
    for (std::uint32_t k = 0; k < cap; ++k) {
      // pmf(k) in log space: exp(-mean) underflows for means above ~745.
      cdf += std::exp(-mean + static_cast<double>(k) * log_mean - log_factorial(k));
      const double t = std::floor(cdf * kWords + 0.5);  // T_{k+1}
      if (!(t < kWords)) break;                         // unreachable by any word: the table ends
      thresholds_.push_back(static_cast<std::uint32_t>(t));
    }
  }

  // The mean asked for.
  double mean() const { return mean_; }
  // The largest count the table draws (its number of thresholds).
  std::uint32_t max_count() const { return static_cast<std::uint32_t>(thresholds_.size()); }
  // T_1 ... T_n, ascending (non-decreasing).
  const std::vector<std::uint32_t>& thresholds() const { return thresholds_; }

  // The count of word u: the number of thresholds <= u (binary search).
  std::uint32_t count(std::uint32_t u) const {
    return static_cast<std::uint32_t>(std::upper_bound(thresholds_.begin(), thresholds_.end(), u) -
                                      thresholds_.begin());
  }

  // The probability the table gives count k (0 above max_count()).
  double probability(std::uint32_t k) const {
    constexpr double kWords = 4294967296.0;
    const std::size_t n = thresholds_.size();
    if (k > n) return 0.0;
    const double lo = k == 0 ? 0.0 : static_cast<double>(thresholds_[k - 1]);
    const double hi = k == n ? kWords : static_cast<double>(thresholds_[k]);
    return (hi - lo) / kWords;
  }

  // The table's exact mean, sum_k P(count >= k) = sum_k (2^32 - T_k) / 2^32:
  // within ~n 2^-32 of mean(); what statistics of processes built on the
  // table (e.g. a sparse convolution noise's variance) should use.
  double exact_mean() const {
    constexpr double kWords = 4294967296.0;
    double m = 0.0;
    for (const std::uint32_t t : thresholds_) m += (kWords - static_cast<double>(t)) / kWords;
    return m;
  }

 private:
  double mean_ = 0.0;
  std::vector<std::uint32_t> thresholds_;
};

}  // namespace hush

#endif  // HUSH_CORE_POISSON_TABLE_HPP
