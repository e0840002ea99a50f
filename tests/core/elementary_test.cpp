// hush's own exp and sin/cos (detail/elementary.hpp): the float polynomials
// every backend repeats, checked against the C library in double.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>

#include "hush/detail/elementary.hpp"

namespace {

using hush::detail::exp_neg;
using hush::detail::sincos_turns;

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

}  // namespace

TEST_CASE("elementary: exp_neg<float> is within 2^-22 relative of exp on [-87, 0]") {
  // 2^-22: the polynomial's 2.5e-9, the Cody-Waite reduction's rounding of r
  // (2^-24 absolute, relative to e^r, since |r| < 0.35) and seven
  // multiply-adds, each within 2^-24 relative, on values near 1.
  double worst = 0;
  for (int i = 0; i <= 2000000; ++i) {
    const float x = static_cast<float>(-87.0 * i / 2000000.0);
    const double ref = std::exp(static_cast<double>(x));
    worst = std::fmax(worst, std::fabs(exp_neg(x) - ref) / ref);
  }
  MESSAGE("exp_neg<float>: max relative error " << worst);
  CHECK(worst <= std::ldexp(1.0, -22));
  CHECK(exp_neg(0.0f) == 1.0f);
  CHECK(exp_neg(-0.0f) == 1.0f);
}

TEST_CASE("elementary: exp_neg is 0 below the floor, 1 for x > 0, NaN for NaN") {
  CHECK(exp_neg(-87.0001f) == 0.0f);
  CHECK(exp_neg(-1e30f) == 0.0f);
  CHECK(exp_neg(-kInf) == 0.0f);
  CHECK(exp_neg(1e-7f) == 1.0f);
  CHECK(exp_neg(1e30f) == 1.0f);
  CHECK(std::isnan(exp_neg(kNaN)));
  CHECK(std::isnan(exp_neg(std::numeric_limits<double>::quiet_NaN())));
  CHECK(exp_neg(-1.5) == std::exp(-1.5));  // double: the C library
  CHECK(exp_neg(3.0) == 1.0);
}

TEST_CASE("elementary: sincos_turns<float> is within 2^-23 of sin and cos of 2 pi t") {
  // 2^-23: the polynomials (3.4e-9 relative, 4.8e-11 absolute) and four or
  // five multiply-adds on values at most 1 in magnitude; the reduction to a
  // quarter turn is exact for every finite t.
  double worst = 0;
  auto check = [&](float t) {
    const hush::detail::sin_cos<float> f = sincos_turns(t);
    const double a = hush::detail::constants::kTwoPi * static_cast<double>(t);
    worst = std::fmax(worst, std::fabs(f.sin - std::sin(a)));
    worst = std::fmax(worst, std::fabs(f.cos - std::cos(a)));
  };
  for (int i = -1000000; i <= 1000000; ++i) check(static_cast<float>(i) / 250000.0f);
  for (int i = 0; i < 100000; ++i) check(static_cast<float>(i) * 10.48576f - 524288.0f);
  for (int q = -8; q <= 8; ++q) {  // quadrant boundaries and their neighbours
    const float t = static_cast<float>(q) * 0.125f;
    check(t);
    check(std::nextafter(t, 2.0f));
    check(std::nextafter(t, -2.0f));
  }
  MESSAGE("sincos_turns<float>: max absolute error " << worst);
  CHECK(worst <= std::ldexp(1.0, -23));
}

TEST_CASE("elementary: sincos_turns has the quadrants' exact values and NaN for non-finite t") {
  const hush::detail::sin_cos<float> q0 = sincos_turns(0.0f), q1 = sincos_turns(0.25f),
                                     q2 = sincos_turns(0.5f), q3 = sincos_turns(-0.25f);
  CHECK(q0.sin == 0.0f);
  CHECK(q0.cos == 1.0f);
  CHECK(q1.sin == 1.0f);
  CHECK(q1.cos == 0.0f);
  CHECK(q2.sin == 0.0f);
  CHECK(q2.cos == -1.0f);
  CHECK(q3.sin == -1.0f);
  CHECK(q3.cos == 0.0f);
  for (const float bad : {kNaN, kInf, -kInf}) {
    const hush::detail::sin_cos<float> f = sincos_turns(bad);
    CHECK(std::isnan(f.sin));
    CHECK(std::isnan(f.cos));
  }
  // Huge finite arguments stay finite and on the unit circle.
  for (const float t : {1e20f, -3e38f, 16777217.0f}) {
    const hush::detail::sin_cos<float> f = sincos_turns(t);
    CHECK(std::fabs(f.sin * f.sin + f.cos * f.cos - 1.0f) < 1e-6f);
  }
  // Double: the C library after the same exact reduction.
  const hush::detail::sin_cos<double> d = sincos_turns(0.1);
  CHECK(d.sin == doctest::Approx(std::sin(0.2 * hush::detail::constants::kPi)).epsilon(1e-15));
  CHECK(d.cos == doctest::Approx(std::cos(0.2 * hush::detail::constants::kPi)).epsilon(1e-15));
}
