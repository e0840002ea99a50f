// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Splitting a coordinate into lattice cell and fraction, robustly.
//
// Fast floors elsewhere got x = -1 wrong (returned cell -2), mirrored negative
// cells by truncating, or produced NaN past INT_MAX (HARD_CASES rows 1 and 3).
// hush splits in double: for any finite float or double x,
//   cell = floor(x) exactly as std::floor picks it, reduced modulo 2^32
//          (or modulo the period in periodic mode), and
//   frac = x - floor(x), computed exactly in double, then rounded to T and
//          clamped below 1, so frac is in [0, 1) for every finite x.
// Domain: every finite x. The noise lattice is 2^32 cells wide: cell indices
// wrap, so noise(x + 2^32) == noise(x) for exactly representable x. For float
// x with |x| >= 2^24 every value is an integer (frac = 0); double keeps
// fraction bits up to 2^52. Non-finite x (NaN, +-Inf) gives cell 0 and a NaN
// fraction, so every noise built on this returns NaN for them.
#ifndef HUSH_CORE_LATTICE_HPP
#define HUSH_CORE_LATTICE_HPP

#include <cmath>
#include <cstdint>
#include <limits>

#include "hush/config.hpp"

namespace hush {

// One axis of a lattice lookup: the cell containing x, its successor (after
// wrapping), and the position inside the cell.
template <class T>
struct lattice_coord {
  std::uint32_t i0;  // floor(x) modulo 2^32 (or modulo the period)
  std::uint32_t i1;  // the next cell: i0 + 1, wrapped the same way
  T f;               // x - floor(x) in [0, 1); NaN when x is not finite
};

namespace detail {

// The largest T below 1: where frac rounds up to 1 (x just below an integer,
// e.g. x = -1e-30), it is clamped here so that frac stays inside its cell.
template <class T>
constexpr T one_minus_ulp() {
  return T(1) - std::numeric_limits<T>::epsilon() / T(2);
}

// Integral doubles strictly inside (-2^63, 2^63) convert to int64 exactly.
constexpr double kInt64Limit = 9223372036854775808.0;  // 2^63
// From 2^52 on every double is an integer.
constexpr double kDoubleIntegers = 4503599627370496.0;  // 2^52

// c modulo m (m in 1 ... 2^32), in [0, m).
HUSH_INLINE std::uint64_t floor_mod(std::int64_t c, std::uint64_t m) {
  const std::int64_t r = c % static_cast<std::int64_t>(m);
  return static_cast<std::uint64_t>(r < 0 ? r + static_cast<std::int64_t>(m) : r);
}
// floor(x) of a finite double, already integral, modulo m, in [0, m).
// |fl| < 2^63 takes the integer path; beyond, std::fmod is exact.
HUSH_INLINE std::uint64_t floor_mod(double fl, std::uint64_t m) {
  if (fl > -kInt64Limit && fl < kInt64Limit) return floor_mod(static_cast<std::int64_t>(fl), m);
  double r = std::fmod(fl, static_cast<double>(m));  // exact; sign of fl
  if (r < 0) r += static_cast<double>(m);            // exact: |r| < m <= 2^32
  return static_cast<std::uint64_t>(r);
}

}  // namespace detail

namespace detail {

// lattice_split for what the fast path leaves: NaN, +-Inf, and |x| >= 2^52,
// where every double is an integer (cell x, fraction 0).
template <class T>
lattice_coord<T> lattice_split_large(double x, std::uint32_t period) {
  if (!std::isfinite(x)) return {0u, period == 1u ? 0u : 1u, std::numeric_limits<T>::quiet_NaN()};
  constexpr std::uint64_t kWrap = std::uint64_t(1) << 32;
  const auto i0 = static_cast<std::uint32_t>(floor_mod(x, period == 0 ? kWrap : period));
  return {i0, period != 0 && i0 + 1u == period ? 0u : i0 + 1u, T(0)};
}

}  // namespace detail

// Splits x into cell and fraction (see the file comment for the contract).
// period = 0: the plain lattice (cells modulo 2^32);
// period = p in 1 ... 2^32 - 1: cells modulo p, so the noise repeats every p units.
template <class T>
HUSH_INLINE lattice_coord<T> lattice_split(double x, std::uint32_t period = 0) {
  // One compare sends NaN, Inf and huge x to the slow path.
  if (!(std::fabs(x) < detail::kDoubleIntegers)) return detail::lattice_split_large<T>(x, period);
  // floor(x) and the cell from one conversion: below 2^52 truncation is
  // exact, and a non-integral negative x truncates one cell too high.
  std::int64_t cell = static_cast<std::int64_t>(x);
  cell -= static_cast<double>(cell) > x;
  const double fl = static_cast<double>(cell);
  // Exact except for tiny negative x, where it rounds to 1; "+ 0" makes the
  // fraction of x = -0 +0, as x - std::floor(x) is.
  const double fd = (x - fl) + 0.0;
  T f = static_cast<T>(fd);
  if (f >= T(1)) f = detail::one_minus_ulp<T>();
  if (period == 0) {
    // Modulo 2^32 is the low word of the two's complement cell: no division.
    const auto i0 = static_cast<std::uint32_t>(cell);
    return {i0, i0 + 1u, f};  // unsigned: wraps at 2^32 by definition
  }
  const auto i0 = static_cast<std::uint32_t>(detail::floor_mod(cell, period));
  return {i0, i0 + 1u == period ? 0u : i0 + 1u, f};
}

}  // namespace hush

#endif  // HUSH_CORE_LATTICE_HPP
