// Tests for hush/core/lattice.hpp (HARD_CASES rows 1, 3 and 5): lattice_split picks the cell
// std::floor picks, bit-exact, reduced modulo 2^32 or the period, for every finite float and
// double (hard values, then 10^6 random bit patterns over all exponents); its fraction is
// x - floor(x), exact where representable, rounded and clamped into [0, 1) otherwise; NaN and
// +-Inf give cells 0/1 and a NaN fraction.
//
// The reference cell is computed independently of lattice.hpp's int64 / fmod paths: floor(x) is
// decomposed into M * 2^E with a 53-bit integer M and reduced with exact integer arithmetic.
#include <doctest/doctest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "hush/core/lattice.hpp"
#include "test_util.hpp"

namespace {

constexpr std::uint64_t kWrap = std::uint64_t(1) << 32;

using hush_test::splitmix64;

// 2^e modulo m (m <= 2^32, so products of residues fit in 64 bits).
std::uint64_t pow2_mod(int e, std::uint64_t m) {
  std::uint64_t result = 1 % m, base = 2 % m;
  for (; e > 0; e >>= 1) {
    if (e & 1) result = result * base % m;
    base = base * base % m;
  }
  return result;
}

// floor(x) modulo m in [0, m), m in 1 ... 2^32, for finite x, by exact integer arithmetic:
// |floor(x)| = M * 2^E with M < 2^53 an integer.
std::uint64_t ref_floor_mod(double x, std::uint64_t m) {
  const double fl = std::floor(x);
  if (fl == 0.0) return 0;
  int e = 0;
  const double fr = std::frexp(std::fabs(fl), &e);  // |fl| = fr 2^e, fr in [1/2, 1)
  const auto mant = static_cast<std::uint64_t>(std::ldexp(fr, 53));  // exact 53-bit integer
  const int exp2 = e - 53;                                           // |fl| = mant 2^exp2
  std::uint64_t r;
  if (exp2 < 0) {
    r = (mant >> -exp2) % m;  // exact: fl is an integer, so the shifted-out bits are 0
  } else {
    r = (mant % m) * pow2_mod(exp2, m) % m;
  }
  return fl < 0.0 && r != 0 ? m - r : r;
}

// The rounding error of a + b: (a + b) - fl(a + b) exactly (TwoSum, Knuth TAOCP 4.2.2), so
// 0 means the double sum is exact.
double two_sum_error(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return (a - (s - bb)) + (b - bb);
}

std::string describe(double x, std::uint32_t period, const char* type) {
  std::ostringstream os;
  os.precision(17);
  os << "lattice_split<" << type << ">(" << x << " = " << std::hexfloat << x << std::defaultfloat
     << ", period " << period << ")";
  return os.str();
}

// Checks lattice_split<T>(x, period) against the contract; returns "" or what went wrong.
//  - i0 = floor(x) mod (period or 2^32), i1 = i0 + 1 mod the same;
//  - f = x - floor(x) exactly when that is representable in T; otherwise within one ulp of it
//    (rounded to T), and in [0, 1) always;
//  - non-finite x: i0 = 0, i1 = 1 (0 when period = 1), f NaN.
template <class T>
std::string split_error(double x, std::uint32_t period = 0) {
  const char* type = std::is_same<T, float>::value ? "float" : "double";
  const auto c = hush::lattice_split<T>(x, period);
  // Strings are built only on failure: this runs millions of times.
  const auto fail = [&](const auto&... what) {
    std::ostringstream os;
    os.precision(17);
    os << describe(x, period, type) << ": ";
    (os << ... << what);
    return os.str();
  };
  if (!std::isfinite(x)) {
    const std::uint32_t want_i1 = period == 1u ? 0u : 1u;
    if (c.i0 != 0u || c.i1 != want_i1 || !std::isnan(c.f))
      return fail("non-finite input gave i0 ", c.i0, ", i1 ", c.i1, ", f ", c.f);
    return {};
  }
  const std::uint64_t m = period == 0u ? kWrap : period;
  const auto want_i0 = static_cast<std::uint32_t>(ref_floor_mod(x, m));
  const auto want_i1 = static_cast<std::uint32_t>((std::uint64_t{want_i0} + 1u) % m);
  if (c.i0 != want_i0 || c.i1 != want_i1)
    return fail("cells (", c.i0, ", ", c.i1, "), want (", want_i0, ", ", want_i1, ")");
  if (!(c.f >= T(0) && c.f < T(1))) return fail("f = ", c.f, " is outside [0, 1)");
  // The exact fraction x - fl as s + e: s the rounded double difference, e its rounding error.
  const double fl = std::floor(x);
  const double s = x - fl;
  const double e = two_sum_error(x, -fl);
  const double f = static_cast<double>(c.f);
  if (e == 0.0 && static_cast<double>(static_cast<T>(s)) == s && s < 1.0) {
    if (f != s) return fail("f = ", f, ", want exactly ", s);  // representable in T: exact
  } else if (!(std::fabs((f - s) - e) <= static_cast<double>(std::numeric_limits<T>::epsilon()))) {
    // Not representable in T: within one ulp of T near 1 (epsilon) of the exact s + e.
    return fail("f = ", f, " is more than an ulp from x - floor(x) = ", s, " + ", e);
  }
  return {};
}

// The hard values of HARD_CASES rows 1, 3 and 5, as doubles. Each is checked as a double input
// for T = double and T = float, and rounded to float (when finite) for T = float.
std::vector<double> hard_values() {
  const double inf = std::numeric_limits<double>::infinity();
  const double p23 = 0x1p23, p24 = 0x1p24, p31 = 0x1p31, p32 = 0x1p32, p52 = 0x1p52, p53 = 0x1p53,
               p63 = 0x1p63, p64 = 0x1p64;
  std::vector<double> v = {
      -1.0,
      -0.0,
      0.0,
      std::nextafter(-1.0, -inf),
      std::nextafter(-1.0, 0.0),
      static_cast<double>(std::nextafterf(-1.0f, -INFINITY)),
      static_cast<double>(std::nextafterf(-1.0f, 0.0f)),
      1.0,
      std::nextafter(1.0, 0.0),
      static_cast<double>(4.9999998f),  // rounds to 5.0f: the literal is within half an ulp
      static_cast<double>(std::nextafterf(5.0f, 0.0f)),
      std::nextafter(5.0, 0.0),
      4.9999998,
      p23 + 0.5,
      p23 - 0.5,
      -p23 + 0.5,
      -p23 - 0.5,
      p24,
      -p24,
      p24 - 1.0,
      -(p24 - 1.0),
      p24 + 1.0,
      -(p24 + 1.0),
      static_cast<double>(1e6f + 0.3f),
      -1e-30,
      static_cast<double>(-1e-30f),
      static_cast<double>(1e-45f),
      static_cast<double>(-1e-45f),
      4.9e-324,
      -4.9e-324,
      DBL_MIN,
      -DBL_MIN,
      static_cast<double>(FLT_MIN),
      -static_cast<double>(FLT_MIN),
      static_cast<double>(FLT_MAX),
      -static_cast<double>(FLT_MAX),
      DBL_MAX,
      -DBL_MAX,
      p31,
      p31 - 1.0,
      -p31,
      -p31 - 1.0,
      p31 + 0.5,
      -p31 - 0.5,
      p32,
      -p32,
      p32 - 0.5,
      -p32 + 0.5,
      p32 + 0.5,
      -p32 - 0.5,
      p52 + 0.5,
      -p52 - 0.5,
      p53,
      -p53,
      p53 + 2.0,
      p63,
      -p63,
      std::nextafter(p63, 0.0),
      std::nextafter(-p63, 0.0),
      std::nextafter(p63, inf),
      std::nextafter(-p63, -inf),
      p64,
      -p64,
      p64 + 0x1p12,
      -p64 - 0x1p12,
      0x1p100 + 0x1p48,
      -0x1p100 - 0x1p48};
  return v;
}

template <class T>
int check_values(const std::vector<double>& xs, std::uint32_t period = 0) {
  int failures = 0;
  for (double x : xs) {
    const std::string e = split_error<T>(x, period);
    if (!e.empty() && ++failures <= 10) FAIL_CHECK(e);
  }
  return failures;
}

float float_from_bits(std::uint32_t bits) {
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}
double double_from_bits(std::uint64_t bits) {
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

}  // namespace

TEST_CASE(
    "lattice_split: picks std::floor's cell (mod 2^32) with frac = x - floor(x) at the "
    "hard values (-1, -0, nextafter(-1), 2^23 +- 0.5, 2^24, denormals, FLT/DBL_MAX, "
    "2^31, 2^63, 2^64, ...)") {
  const auto values = hard_values();
  std::vector<double> as_float;
  for (double v : values) {
    const auto f = static_cast<float>(v);
    if (std::isfinite(f)) as_float.push_back(static_cast<double>(f));
  }
  CHECK(check_values<double>(values) == 0);
  CHECK(check_values<float>(values) == 0);
  CHECK(check_values<float>(as_float) == 0);
}

TEST_CASE("lattice_split: named cells and fractions at the hard values") {
  const auto d = [](double x) { return hush::lattice_split<double>(x); };
  const auto f = [](double x) { return hush::lattice_split<float>(x); };
  // x = -1 is in cell -1 (fast floors returned -2): i0 = 2^32 - 1, frac 0.
  CHECK(d(-1.0).i0 == 0xffffffffu);
  CHECK(d(-1.0).i1 == 0u);
  CHECK(d(-1.0).f == 0.0);
  CHECK(f(-1.0).i0 == 0xffffffffu);
  CHECK(d(-0.0).i0 == 0u);
  CHECK(d(-0.0).f == 0.0);
  // Just below -1: cell -2, frac 1 - ulp.
  CHECK(d(std::nextafter(-1.0, -2.0)).i0 == 0xfffffffeu);
  CHECK(d(std::nextafter(-1.0, -2.0)).f == 1.0 - 0x1p-52);
  CHECK(f(static_cast<double>(std::nextafterf(-1.0f, -2.0f))).f == 1.0f - 0x1p-23f);
  CHECK(d(std::nextafter(-1.0, 0.0)).i0 == 0xffffffffu);
  CHECK(d(std::nextafter(-1.0, 0.0)).f == 0x1p-53);
  // Just below 5 (4.9999998f itself rounds to 5.0f).
  CHECK(f(static_cast<double>(4.9999998f)).i0 == 5u);
  CHECK(f(static_cast<double>(std::nextafterf(5.0f, 0.0f))).i0 == 4u);
  CHECK(f(static_cast<double>(std::nextafterf(5.0f, 0.0f))).f == 1.0f - 0x1p-21f);
  // Tiny negative x: x - floor(x) = 1 - 1e-30 rounds to 1 and is clamped to the largest T < 1.
  CHECK(f(-1e-30).i0 == 0xffffffffu);
  CHECK(f(-1e-30).f == 1.0f - 0x1p-24f);
  CHECK(d(-1e-30).i0 == 0xffffffffu);
  CHECK(d(-1e-30).f == 1.0 - 0x1p-53);
  CHECK(f(static_cast<double>(-1e-45f)).f == 1.0f - 0x1p-24f);
  CHECK(d(-4.9e-324).f == 1.0 - 0x1p-53);
  CHECK(d(4.9e-324).i0 == 0u);
  CHECK(d(4.9e-324).f == 4.9e-324);
  // 2^23 +- 0.5 keep their halves; float ulps reach 1 at 2^23 and 2 at 2^24.
  CHECK(f(0x1p23 - 0.5).f == 0.5f);
  CHECK(f(-0x1p23 - 0.5).i0 == static_cast<std::uint32_t>(-8388609));
  CHECK(f(-0x1p23 - 0.5).f == 0.5f);
  CHECK(f(static_cast<double>(1e6f + 0.3f)).i0 == 1000000u);
  CHECK(f(static_cast<double>(1e6f + 0.3f)).f == 0.3125f);
  // Large values wrap modulo 2^32.
  CHECK(d(0x1p31).i0 == 0x80000000u);
  CHECK(d(-0x1p31).i0 == 0x80000000u);
  CHECK(d(0x1p31 - 1.0).i0 == 0x7fffffffu);
  CHECK(d(0x1p32 + 3.5).i0 == 3u);
  CHECK(d(0x1p32 + 3.5).f == 0.5);
  CHECK(d(0x1p53).i0 == 0u);
  CHECK(d(0x1p63).i0 == 0u);
  CHECK(d(0x1p64).i0 == 0u);
  CHECK(d(-0x1p63 - 0x1p12).i0 == 0xfffff000u);  // -2^12 mod 2^32
  CHECK(d(0x1p52 + 0x1p31 + 0.5).i0 == 0x80000000u);
  CHECK(d(FLT_MAX).i0 == 0u);
  CHECK(d(-DBL_MAX).i0 == 0u);
  CHECK(d(DBL_MAX).f == 0.0);
}

TEST_CASE(
    "lattice_split: picks std::floor's cell with frac = x - floor(x) for 10^6 random "
    "floats and 10^6 random doubles over all exponents") {
  splitmix64 g{1};
  std::vector<double> floats, doubles;
  floats.reserve(1000000);
  doubles.reserve(1000000);
  while (floats.size() < 1000000) {
    const float f = float_from_bits(static_cast<std::uint32_t>(g.next() >> 32));
    if (std::isfinite(f)) floats.push_back(static_cast<double>(f));
  }
  while (doubles.size() < 1000000) {
    const double d = double_from_bits(g.next());
    if (std::isfinite(d)) doubles.push_back(d);
  }
  CHECK(check_values<float>(floats) == 0);
  CHECK(check_values<double>(floats) == 0);
  CHECK(check_values<double>(doubles) == 0);
  CHECK(check_values<float>(doubles) == 0);
}

TEST_CASE("lattice_split: plain mode's successor cell is i0 + 1 modulo 2^32") {
  for (double x : {-1.0, 0x1p32 - 0.5, -0.5, 0x1p31 - 0.5, 17.25}) {
    const auto c = hush::lattice_split<double>(x);
    CAPTURE(x);
    CHECK(c.i1 == static_cast<std::uint32_t>(c.i0 + 1u));
  }
  CHECK(hush::lattice_split<double>(-1.0).i1 == 0u);          // 2^32 - 1 wraps to 0
  CHECK(hush::lattice_split<double>(0x1p32 - 0.5).i1 == 0u);  // likewise
}

TEST_CASE(
    "lattice_split: periodic mode gives floor(x) mod p in 0 ... p - 1 and i1 = (i0 + 1) mod p "
    "for p = 1, 2, 3, 7, 256, 2^31 - 1, 2^32 - 1") {
  const std::uint32_t periods[] = {1u, 2u, 3u, 7u, 256u, 0x7fffffffu, 0xffffffffu};
  auto values = hard_values();
  splitmix64 g{2};
  for (int n = 0; n < 20000; ++n) {  // negative and positive, small and large
    const double d = double_from_bits(g.next());
    if (std::isfinite(d)) values.push_back(d);
    values.push_back(static_cast<double>(static_cast<std::int64_t>(g.next() >> 40) - (1 << 23)) +
                     0.25);
  }
  for (std::uint32_t p : periods) {
    CAPTURE(p);
    CHECK(check_values<double>(values, p) == 0);
    CHECK(check_values<float>(values, p) == 0);
  }
  // Named cases: negative x wraps into [0, p).
  CHECK(hush::lattice_split<float>(-1.0, 7).i0 == 6u);
  CHECK(hush::lattice_split<float>(-1.0, 7).i1 == 0u);
  CHECK(hush::lattice_split<float>(-7.5, 7).i0 == 6u);
  CHECK(hush::lattice_split<float>(-7.5, 7).f == 0.5f);
  CHECK(hush::lattice_split<float>(6.5, 7).i1 == 0u);
  CHECK(hush::lattice_split<float>(-0.25, 1).i0 == 0u);
  CHECK(hush::lattice_split<float>(-0.25, 1).i1 == 0u);
  CHECK(hush::lattice_split<double>(-0x1p31, 0x7fffffffu).i0 == 0x7ffffffeu);
}

TEST_CASE(
    "lattice_split: periodic mode puts x and x + p in the same cell with the same frac "
    "(when both are exactly representable)") {
  const std::uint32_t periods[] = {1u, 2u, 3u, 7u, 256u, 0x7fffffffu, 0xffffffffu};
  splitmix64 g{3};
  int compared = 0, failures = 0;
  for (int n = 0; n < 20000; ++n) {
    const std::uint32_t p = periods[g.next() % 7];
    // x: 53 random bits scaled to magnitudes up to 2^33, with 20 ... 43 fraction bits and a
    // random sign.
    const double x =
        std::ldexp(static_cast<double>(g.next() >> 11), -20 - static_cast<int>(g.next() % 24)) *
        ((g.next() & 1u) ? -1.0 : 1.0);
    const double y = x + static_cast<double>(p);
    if (two_sum_error(x, static_cast<double>(p)) != 0.0) continue;  // x + p not exact
    ++compared;
    const auto a = hush::lattice_split<double>(x, p), b = hush::lattice_split<double>(y, p);
    const auto af = hush::lattice_split<float>(x, p), bf = hush::lattice_split<float>(y, p);
    if (a.i0 != b.i0 || a.i1 != b.i1 || a.f != b.f || af.i0 != bf.i0 || af.f != bf.f) {
      if (++failures <= 10) FAIL_CHECK(describe(x, p, "double/float") << " differs from x + p");
    }
  }
  CHECK(failures == 0);
  CHECK(compared > 10000);
  // And the plain lattice repeats every 2^32 cells.
  CHECK(hush::lattice_split<double>(-2.75).i0 == hush::lattice_split<double>(0x1p32 - 2.75).i0);
  CHECK(hush::lattice_split<double>(-2.75).f == hush::lattice_split<double>(0x1p32 - 2.75).f);
}

TEST_CASE("lattice_split: NaN and +-Inf give cells 0 and 1 (0 for period 1) and a NaN frac") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (std::uint32_t p : {0u, 1u, 7u, 0xffffffffu}) {
    CAPTURE(p);
    CHECK(check_values<float>({nan, -nan, inf, -inf}, p) == 0);
    CHECK(check_values<double>({nan, -nan, inf, -inf}, p) == 0);
  }
  const auto c = hush::lattice_split<float>(nan);
  CHECK(c.i0 == 0u);
  CHECK(c.i1 == 1u);
  CHECK(std::isnan(c.f));
}
