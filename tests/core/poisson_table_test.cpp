// hush::poisson_table (core/poisson_table.hpp): Poisson counts from one
// uniform word by threshold comparisons, the sampler every Gabor backend shares.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hush/core/poisson_table.hpp"
#include "hush/core/rng.hpp"

namespace {

// The Poisson pmf in log space (means up to 1e4 underflow exp(-mean)).
double poisson_pmf(double mean, std::uint32_t k) {
  if (mean == 0.0) return k == 0 ? 1.0 : 0.0;
  return std::exp(-mean + k * std::log(mean) - hush::log_factorial(k));
}

// Mean and variance of the distribution the table assigns (probability(k)).
void table_moments(const hush::poisson_table& t, double& mean, double& var) {
  double m1 = 0, m2 = 0;
  for (std::uint32_t k = 0; k <= t.max_count(); ++k) {
    const double p = t.probability(k);
    m1 += p * k;
    m2 += p * k * static_cast<double>(k);
  }
  mean = m1;
  var = m2 - m1 * m1;
}

}  // namespace

TEST_CASE("poisson_table: every count's probability is the Poisson pmf to within 2^-32") {
  // One rounding of the CDF to 2^-32 per threshold: each probability (a
  // difference of two thresholds) is within 2^-32 of the pmf, plus the CDF's
  // own summation error (~1e-12 relative for mean 1e4, far below 2^-32).
  for (const double mean : {1e-6, 0.3, 1.0, 5.09, 32.0, 81.5, 1000.0, 1e4}) {
    const hush::poisson_table t(mean);
    double total = 0, tail = 1;
    for (std::uint32_t k = 0; k <= t.max_count(); ++k) {
      CHECK(std::fabs(t.probability(k) - poisson_pmf(mean, k)) <= std::ldexp(1.0, -32) + 1e-12);
      total += t.probability(k);
      tail -= poisson_pmf(mean, k);
    }
    CHECK(total == doctest::Approx(1.0).epsilon(1e-15));
    // Counts above max_count() are what the table leaves out: below 2^-33 of
    // the Poisson distribution (up to the rounding of `tail` itself).
    CHECK(tail < std::ldexp(1.0, -33) + 1e-12);
    CHECK(t.probability(t.max_count() + 1) == 0.0);
  }
}

TEST_CASE("poisson_table: mean and variance are the Poisson's (HARD_CASES row 11)") {
  // Means 0, 1e-6, 1, 32, 1e3 (and the cap 1e4) are valid: the table's own mean
  // and variance are within (max_count + 1) 2^-32 k_max of the Poisson's.
  for (const double mean : {0.0, 1e-6, 1.0, 32.0, 1000.0, 1e4}) {
    const hush::poisson_table t(mean);
    double m = 0, v = 0;
    table_moments(t, m, v);
    const double tol = (t.max_count() + 1.0) * std::ldexp(1.0, -32) * (t.max_count() + 1.0);
    CHECK(std::fabs(m - mean) <= tol + 1e-12 * mean);
    CHECK(std::fabs(v - mean) <= tol * (t.max_count() + 1.0) + 1e-12 * mean);
    CHECK(t.exact_mean() == doctest::Approx(m).epsilon(1e-12));
  }
  // Mean 0: every word gives 0.
  const hush::poisson_table zero(0.0);
  CHECK(zero.max_count() == 0);
  CHECK(zero.count(0) == 0);
  CHECK(zero.count(0xFFFFFFFFU) == 0);
}

TEST_CASE("poisson_table: invalid means are refused, naming the parameter") {
  for (const double bad :
       {-1.0, -1e-300, 1e6, 10000.5, std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    try {
      const hush::poisson_table t(bad);
      FAIL("accepted mean " << bad);
    } catch (const hush::invalid_argument& e) {
      const std::string m = e.what();
      CHECK(m.find("hush::poisson_table: mean") != std::string::npos);
      CHECK(m.find("valid: 0 <= mean <= 10000") != std::string::npos);
    }
  }
}

TEST_CASE("poisson_table: a count is the number of thresholds at or below the word") {
  const hush::poisson_table t(5.09);
  const std::vector<std::uint32_t>& th = t.thresholds();
  REQUIRE(th.size() == t.max_count());
  CHECK(t.count(0) == 0);  // T_1 = round(2^32 e^-5.09) > 0
  CHECK(t.count(0xFFFFFFFFU) == t.max_count());
  for (std::size_t k = 0; k < th.size(); ++k) {
    CHECK(t.count(th[k]) >= k + 1);
    if (th[k] > 0 && (k == 0 || th[k - 1] < th[k])) CHECK(t.count(th[k] - 1) == k);
    if (k > 0) CHECK(th[k - 1] <= th[k]);
  }
}

TEST_CASE("poisson_table: counts drawn from hush::rng words pass a chi-square test") {
  // 2e5 draws per mean; bins with expected count >= 20 (the tail pooled):
  // chi^2 has mean df and standard deviation sqrt(2 df); accept within 5 sd.
  constexpr int kDraws = 200000;
  for (const double mean : {0.7, 5.09, 40.7}) {
    const hush::poisson_table t(mean);
    hush::rng r(11, static_cast<std::uint32_t>(mean * 100));
    std::vector<double> hist(t.max_count() + 1, 0.0);
    for (int i = 0; i < kDraws; ++i) hist[t.count(r.next_u32())] += 1.0;
    double chi2 = 0, pooled_obs = 0, pooled_exp = 0;
    int df = -1;
    for (std::uint32_t k = 0; k <= t.max_count(); ++k) {
      const double e = kDraws * t.probability(k);
      if (e >= 20.0) {
        chi2 += (hist[k] - e) * (hist[k] - e) / e;
        ++df;
      } else {
        pooled_obs += hist[k];
        pooled_exp += e;
      }
    }
    if (pooled_exp > 0) {
      chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
      ++df;
    }
    INFO("mean " << mean << ": chi2 = " << chi2 << " with " << df << " degrees of freedom");
    CHECK(std::fabs(chi2 - df) <= 5.0 * std::sqrt(2.0 * df));
  }
}
