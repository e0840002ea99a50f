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

// floor(x) of a finite double modulo m (m in 1 ... 2^32), in [0, m).
// |fl| < 2^63 takes the integer path; beyond, std::fmod is exact.
HUSH_INLINE std::uint64_t floor_mod(double fl, std::uint64_t m) {
  constexpr double kInt64Limit = 9223372036854775808.0;  // 2^63
  if (fl > -kInt64Limit && fl < kInt64Limit) {
    const std::int64_t i = static_cast<std::int64_t>(fl);
    const std::int64_t r = i % static_cast<std::int64_t>(m);
    return static_cast<std::uint64_t>(r < 0 ? r + static_cast<std::int64_t>(m) : r);
  }
  double r = std::fmod(fl, static_cast<double>(m));  // exact; sign of fl
  if (r < 0) r += static_cast<double>(m);            // exact: |r| < m <= 2^32
  return static_cast<std::uint64_t>(r);
}

}  // namespace detail

// Splits x into cell and fraction (see the file comment for the contract).
// period = 0: the plain lattice (cells modulo 2^32);
// period = p in 1 ... 2^32 - 1: cells modulo p, so the noise repeats every p units.
template <class T>
HUSH_INLINE lattice_coord<T> lattice_split(double x, std::uint32_t period = 0) {
  if (!std::isfinite(x)) return {0u, period == 1u ? 0u : 1u, std::numeric_limits<T>::quiet_NaN()};
  const double fl = std::floor(x);
  const double fd = x - fl;  // exact except for tiny negative x, where it rounds to 1
  T f = static_cast<T>(fd);
  if (f >= T(1)) f = detail::one_minus_ulp<T>();
  constexpr std::uint64_t kWrap = std::uint64_t(1) << 32;
  if (period == 0) {
    const auto i0 = static_cast<std::uint32_t>(detail::floor_mod(fl, kWrap));
    return {i0, i0 + 1u, f};  // unsigned: wraps at 2^32 by definition
  }
  const auto i0 = static_cast<std::uint32_t>(detail::floor_mod(fl, period));
  return {i0, i0 + 1u == period ? 0u : i0 + 1u, f};
}

}  // namespace hush

#endif  // HUSH_CORE_LATTICE_HPP
