// Shared pieces of the libFuzzer targets (tests/fuzz): values that reach the edges of every
// parameter's domain, and the checks every evaluation must pass whatever the parameters were.
#ifndef HUSH_TESTS_FUZZ_FUZZ_UTIL_HPP
#define HUSH_TESTS_FUZZ_FUZZ_UTIL_HPP

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "hush/hush.hpp"

namespace hush_fuzz {

// Stops the run with a message: libFuzzer records the input as a crash.
[[noreturn]] inline void fail(const char* what, double detail) {
  std::fprintf(stderr, "hush fuzz: %s (%.17g)\n", what, detail);
  std::abort();
}

// A double: one of the domain's edges (NaN, infinities, zeros, the smallest subnormal, the
// largest finite value, values around 1) or any finite value.
inline double any_double(FuzzedDataProvider& in) {
  constexpr double kEdges[] = {std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               0.0,
                               -0.0,
                               std::numeric_limits<double>::denorm_min(),
                               std::numeric_limits<double>::max(),
                               -std::numeric_limits<double>::max(),
                               1e-300,
                               1e30,
                               -1.0,
                               0.5,
                               1.0,
                               2.0,
                               16.0,
                               256.0};
  if (in.ConsumeBool()) return kEdges[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kEdges) - 1)];
  return in.ConsumeFloatingPoint<double>();
}

// An int: the edges of int, small values around every range's ends, or any value in
// [lo, hi] (a range that keeps the work of a valid choice small).
inline int any_int(FuzzedDataProvider& in, int lo, int hi) {
  constexpr int kEdges[] = {std::numeric_limits<int>::min(), -1, 0, 1, 2, 3,
                            std::numeric_limits<int>::max()};
  if (in.ConsumeBool()) return kEdges[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kEdges) - 1)];
  return in.ConsumeIntegralInRange<int>(lo, hi);
}

// An enum value: one of the n named values or one past them (an invalid value).
template <class E>
E any_enum(FuzzedDataProvider& in, int n) {
  return static_cast<E>(in.ConsumeIntegralInRange<int>(0, n));
}

// A position: finite and moderate, huge, or with a NaN or infinite coordinate.
template <int D>
hush::vec<double, D> any_position(FuzzedDataProvider& in) {
  hush::vec<double, D> p;
  for (int a = 0; a < D; ++a)
    p[a] = in.ConsumeBool() ? any_double(in) : in.ConsumeFloatingPointInRange<double>(-1e3, 1e3);
  return p;
}

template <int D>
bool all_finite(const hush::vec<double, D>& p) {
  for (int a = 0; a < D; ++a)
    if (!std::isfinite(p[a])) return false;
  return true;
}

// The documented result of a point evaluation (HARD_CASES rows 1-5): never infinite; finite
// wherever the position is finite; NaN (or a finite value, for noises that document one) where
// it is not.
inline void check_value(double v, bool finite_input) {
  if (std::isinf(v)) fail("an evaluation returned an infinity", v);
  if (finite_input && !std::isfinite(v)) fail("a finite position gave a non-finite value", v);
}

// Evaluates n at a few positions in float and in double (the reference) and checks each.
// A noise whose documented domain ends before the largest double passes its bound as
// `domain`: coordinates beyond it may give NaN.
template <class Noise>
void probe_points(const Noise& n, FuzzedDataProvider& in,
                  double domain = std::numeric_limits<double>::max()) {
  constexpr int D = Noise::dimension;
  for (int k = 0; k < 4 && in.remaining_bytes() > 0; ++k) {
    const hush::vec<double, D> p = any_position<D>(in);
    bool finite = all_finite<D>(p);
    for (int a = 0; a < D; ++a) finite = finite && std::fabs(p[a]) <= domain;
    check_value(n(p), finite);
    // Float positions: finite doubles beyond float's range become infinities.
    const hush::vec<float, D> pf = hush::vec_cast<float>(p);
    const hush::vec<double, D> pd = hush::vec_cast<double>(pf);
    bool finite_f = all_finite<D>(pd);
    for (int a = 0; a < D; ++a) finite_f = finite_f && std::fabs(pd[a]) <= domain;
    check_value(static_cast<double>(n(pf)), finite_f);
  }
}

}  // namespace hush_fuzz

#endif  // HUSH_TESTS_FUZZ_FUZZ_UTIL_HPP
