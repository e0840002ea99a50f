// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The transcendental functions the anisotropic noise's weights need, in a
// form SIMD code can repeat operation by operation (hush/simd/lanes-inl.h;
// band_profile in hush/anisotropic/simd-inl.h):
//   exp2_nonpositive(y) = 2^y for y <= 0      (filtering weights, exp(-x))
//   log2_positive(m)     = log2(m) for m > 0   (distortion: the map's stretch)
//   band_profile(x)      = cos^2(pi x / 2) for |x| < 1, else 0
//                          (the steerable bank's radial profile in octaves)
// For T = double they are std::exp2, std::log2 and std::cos: the reference.
// For T = float they are polynomials in float with a fixed operation order
// (coefficients in detail/constants.hpp, kAnisoSeries), so scalar and SIMD
// code give the same bits under HUSH_STRICT_FP. Float error against the
// double functions (tests/anisotropic/anisotropic_test.cpp measures them):
//   exp2_nonpositive: within 4 ulp relative for y in [-25, 0]; 0 below -126;
//   log2_positive:    within 2^-21 absolute plus 2 ulp of the result;
//   band_profile:     within 2^-22 absolute.
// Special values: exp2_nonpositive(NaN) = NaN; log2_positive(m) = -inf for
// 0 <= m < 2^-126 (float; the double reference returns log2 m <= -126 there),
// log2_positive(+inf) = +inf, NaN for NaN or negative m; band_profile(NaN) = NaN,
// band_profile(+-inf) = 0.
#ifndef HUSH_DETAIL_APPROX_MATH_HPP
#define HUSH_DETAIL_APPROX_MATH_HPP

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "hush/config.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

// A non-negative int as a container index (keeps index arithmetic in int).
HUSH_INLINE std::size_t index(int i) { return static_cast<std::size_t>(i); }

HUSH_INLINE float bits_to_float(std::uint32_t u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}
HUSH_INLINE std::uint32_t float_to_bits(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// 2^y for y <= 0: n = round-half-up(y), r = y - n in [-1/2, 1/2], 2^r by its
// Taylor polynomial (Horner), times 2^n built from exponent bits.
template <class T>
HUSH_INLINE T exp2_nonpositive(T y) {
  if constexpr (std::is_same<T, double>::value) {
    return std::exp2(y);
  } else {
    const auto& c = constants::kAnisoSeries.exp2;
    if (!(y >= -126.0f)) return y != y ? y : 0.0f;  // NaN stays NaN; underflow to 0
    const float n = std::floor(y + 0.5f);
    const float r = y - n;  // exact (Sterbenz)
    float p = float(c[7]);
    p = p * r + float(c[6]);
    p = p * r + float(c[5]);
    p = p * r + float(c[4]);
    p = p * r + float(c[3]);
    p = p * r + float(c[2]);
    p = p * r + float(c[1]);
    p = p * r + float(c[0]);
    // 2^n for n in [-126, 0]: a normal float, exponent field n + 127.
    const auto e = static_cast<std::uint32_t>(static_cast<std::int32_t>(n) + 127) << 23;
    return p * bits_to_float(e);
  }
}

// log2(m) for m > 0: m = 2^e * a with a in [sqrt(1/2), sqrt(2)), then
// log2 a = (2 / ln 2) atanh(z), z = (a - 1) / (a + 1), by its odd series.
template <class T>
HUSH_INLINE T log2_positive(T m) {
  if constexpr (std::is_same<T, double>::value) {
    return std::log2(m);
  } else {
    const auto& c = constants::kAnisoSeries.log2;
    // Zero and values below the smallest normal float give -inf (every weight
    // built on them is 0), +inf stays +inf, NaN and negative m give NaN.
    if (!(m >= std::numeric_limits<float>::min()))
      return m >= 0.0f ? -std::numeric_limits<float>::infinity()
                       : std::numeric_limits<float>::quiet_NaN();
    if (!(m < std::numeric_limits<float>::infinity())) return m;
    std::uint32_t b = float_to_bits(m);
    auto e = static_cast<std::int32_t>(b >> 23) - 127;
    b = (b & 0x007fffffu) | 0x3f800000u;  // a in [1, 2)
    float a = bits_to_float(b);
    if (a > float(constants::kSqrt2)) {
      a = a * 0.5f;  // exact
      e += 1;
    }
    const float z = (a - 1.0f) / (a + 1.0f);
    const float z2 = z * z;
    float p = float(c[4]);
    p = p * z2 + float(c[3]);
    p = p * z2 + float(c[2]);
    p = p * z2 + float(c[1]);
    p = p * z2 + float(c[0]);
    return static_cast<float>(e) + p * z;
  }
}

// The bank's radial profile in octaves: cos^2(pi x / 2) = (1 - sin(pi z)) / 2
// with z = |x| - 1/2 in [-1/2, 1/2) for |x| < 1, and 0 outside.
template <class T>
HUSH_INLINE T band_profile(T x) {
  if constexpr (std::is_same<T, double>::value) {
    if (x != x) return x;
    if (!(std::fabs(x) < 1.0)) return 0.0;
    const double c = std::cos(0.5 * constants::kPi * x);
    return c * c;
  } else {
    const auto& c = constants::kAnisoSeries.sinpi;
    if (x != x) return x;
    const float ax = std::fabs(x);
    if (!(ax < 1.0f)) return 0.0f;
    const float z = ax - 0.5f;  // exact
    const float z2 = z * z;
    float p = float(c[6]);
    p = p * z2 + float(c[5]);
    p = p * z2 + float(c[4]);
    p = p * z2 + float(c[3]);
    p = p * z2 + float(c[2]);
    p = p * z2 + float(c[1]);
    p = p * z2 + float(c[0]);
    return 0.5f - 0.5f * (p * z);
  }
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_DETAIL_APPROX_MATH_HPP
