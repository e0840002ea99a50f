// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// exp and sin/cos that evaluate the same operations in scalar code, in every
// SIMD target (hush/simd/lanes-inl.h mirrors them operation by
// operation) and in GLSL (hush/glsl/gabor_glsl.hpp), so that noises built on
// them can be bit-identical between scalar and SIMD evaluation (std::exp and
// Highway's Exp differ in their last bits). In double they are the C
// library's functions: the double instantiation of a noise is its reference.
//
//   exp_neg<T>(x)          e^x for x <= 0 (x > 0 is taken as 0)
//   sincos_turns<T>(t)     {sin(2 pi t), cos(2 pi t)}, t in turns
//
// Float accuracy (tests/core/elementary_test.cpp measures it over the whole
// range): exp_neg within 2^-22 relative (polynomial 2.5e-9 plus the
// roundings of the reduction and of seven multiply-adds), and exactly 0 below
// kExpFloor = -87; sincos_turns within 2^-23 absolute for every finite t (the
// reduction to a quarter turn is exact). Non-finite arguments give NaN
// (exp_neg of -Inf gives 0).
#ifndef HUSH_DETAIL_ELEMENTARY_HPP
#define HUSH_DETAIL_ELEMENTARY_HPP

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "hush/config.hpp"
#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

template <class T>
struct sin_cos {
  T sin, cos;
};

// e^x for x <= 0; x > 0 is clamped to 0 (the callers' arguments are minus a
// non-negative quantity, which rounding can push a few ulp above 0).
template <class T>
HUSH_INLINE T exp_neg(T x) {
  namespace c = constants;
  if constexpr (std::is_same<T, double>::value) {
    return std::exp(x > 0.0 ? 0.0 : x);  // NaN stays NaN
  } else {
    static_assert(std::is_same<T, float>::value, "exp_neg<T>: T is float or double");
    if (!(x >= float(c::kExpFloor))) return x == x ? 0.0f : x;  // below the floor, or NaN
    if (x > 0.0f) x = 0.0f;
    const float n = std::floor(x * float(c::kLog2E) + 0.5f);  // in [-126, 0]
    const float r = (x - n * float(c::kLn2Hi)) - n * float(c::kLn2Lo);
    float p = float(c::kExpPoly[c::kExpDegree]);
    for (int i = c::kExpDegree - 1; i >= 0; --i) p = p * r + float(c::kExpPoly[i]);
    // 2^n from the exponent field: n + 127 in [1, 127], a normal float.
    const std::uint32_t bits = static_cast<std::uint32_t>(static_cast<int>(n) + 127) << 23;
    float scale;
    std::memcpy(&scale, &bits, sizeof scale);
    return p * scale;
  }
}

// {sin(2 pi t), cos(2 pi t)}: t = q/4 + r with q = floor(4t + 1/2) quarter
// turns and r = t - q/4 in [-1/8, 1/8], both exact for |t| < 2^22; larger t
// (and NaN, Inf) are first replaced by t - floor(t), exact for every finite t
// (a float that large has at most one fractional bit), so 4t never overflows.
// The quadrant k = q mod 4 is kept in floating point, so no non-finite value
// is ever converted to an integer, and rotates (sin 2 pi r, cos 2 pi r). The
// reduction is exact for every finite t: the accuracy does not depend on |t|.
template <class T>
HUSH_INLINE sin_cos<T> sincos_turns(T t) {
  namespace c = constants;
  const T u = std::fabs(t) < T(c::kTurnsReduceLimit) ? t : t - std::floor(t);
  const T q = std::floor(u * T(4) + T(0.5));
  const T r = u - q * T(0.25);
  T s, co;
  if constexpr (std::is_same<T, double>::value) {
    s = std::sin(c::kTwoPi * r);
    co = std::cos(c::kTwoPi * r);
  } else {
    static_assert(std::is_same<T, float>::value, "sincos_turns<T>: T is float or double");
    const float z = r * r;
    float ps = float(c::kSinPoly[c::kSinDegree]);
    for (int i = c::kSinDegree - 1; i >= 0; --i) ps = ps * z + float(c::kSinPoly[i]);
    float pc = float(c::kCosPoly[c::kCosDegree]);
    for (int i = c::kCosDegree - 1; i >= 0; --i) pc = pc * z + float(c::kCosPoly[i]);
    s = r * ps;
    co = pc;
  }
  const T k = q - T(4) * std::floor(q * T(0.25));  // 0, 1, 2 or 3 (NaN for NaN t)
  const bool odd = k == T(1) || k == T(3);
  const T sin_sign = k >= T(2) ? T(-1) : T(1);
  const T cos_sign = (k == T(1) || k == T(2)) ? T(-1) : T(1);
  return {(odd ? co : s) * sin_sign, (odd ? s : co) * cos_sign};
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_DETAIL_ELEMENTARY_HPP
