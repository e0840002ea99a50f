// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// What Gabor noise's impulses carry (hush/gabor.hpp): the kinds of noise, the fields of
// a stream word as values in (0, 1), and gabor_marks<D>: an impulse's weight and
// frequency vector drawn from uniform values. Shared by gabor<D> and by NPR Gabor noise
// (hush/npr_gabor.hpp).
#ifndef HUSH_GABOR_MARKS_HPP
#define HUSH_GABOR_MARKS_HPP

#include <cmath>
#include <cstdint>

#include "hush/config.hpp"
#include "hush/core/vec.hpp"
#include "hush/detail/constants.hpp"
#include "hush/detail/elementary.hpp"

namespace hush {

enum class gabor_kind { isotropic, anisotropic, hybrid };

namespace detail {

// Fields of a stream word as values in (0, 1) (constants.hpp): byte i (0 =
// highest) as (2m + 1) 2^-9, half i (0 = high) as (2m + 1) 2^-17. Exact in
// float and in GLSL (an integer below 2^17 times a power of two).
template <class T>
HUSH_INLINE T gabor_byte(std::uint32_t w, unsigned i) {
  namespace c = constants;
  const std::uint32_t m = (w >> (c::kGaborByteBits * (3u - i))) & c::kGaborByteMask;
  return T((m << 1) | 1u) * T(c::kGaborByteScale);
}
// An impulse's offset along one axis from a point at fraction f of its cell,
// the impulse at position u (gabor_byte) of the cell o cells away: f - (o + u),
// one rounding (o + u is exact: a multiple of 2^-9 below 4 in magnitude for the
// |o| <= 2 of every path), so the SIMD paths may keep o + u per impulse and the
// point's f per lane (one subtraction and one list per axis in the SIMD test).
template <class T>
HUSH_INLINE T gabor_offset(T f, int o, T u) {
  return f - (T(o) + u);
}
template <class T>
HUSH_INLINE T gabor_half(std::uint32_t w, unsigned i) {
  namespace c = constants;
  const std::uint32_t m = (w >> (c::kGaborHalfBits * (1u - i))) & c::kGaborHalfMask;
  return T((m << 1) | 1u) * T(c::kGaborHalfScale);
}

// An orthonormal basis (t, b) of the plane orthogonal to unit n, by Duff et
// al., "Building an orthonormal basis, revisited" (JCGT 2017), in double.
inline void orthonormal_basis(const vec<double, 3>& n, vec<double, 3>& t, vec<double, 3>& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace detail

// gabor_marks<D>: what an impulse of each kind carries besides its position,
// drawn from uniform values in (0, 1): its weight and its frequency vector
// (cycles per cell). Shared by gabor<D> and by noises that place impulses
// their own way (NPR Gabor noise). The values are consumed in this order:
//   [0] weight w = 2 u - 1 (exact)
//   isotropic, hybrid, 2D: [1] orientation theta = theta0 + spread (u - 1/2) turns
//   isotropic, hybrid, 3D: [1] cos(polar) = 1 - (1 - cos(cap)) u, [2] azimuth u turns,
//                          in the frame whose third axis is omega0
//   hybrid:                [next] |F| = Phi0 + dPhi (u - 1/2)
// anisotropic impulses take only the weight. values() is how many they take;
// gabor<D> draws them from its cells' words (constants.hpp, "Impulse marks").
template <int D>
class gabor_marks {
 public:
  gabor_marks() = default;
  // phi0, dphi: frequency and its range's width in cycles per cell (F r);
  // orientation, elevation, spread: radians (validated by gabor<D>).
  gabor_marks(gabor_kind kind, double phi0, double dphi, double orientation, double elevation,
              double spread)
      : kind_(kind), phi0_(phi0), dphi_(dphi) {
    namespace c = detail::constants;
    const double ca = std::cos(orientation), sa = std::sin(orientation);
    const double ce = std::cos(elevation), se = std::sin(elevation);
    if constexpr (D == 2) {
      axis_ = {ca, sa};
      // omega0's angle reduced to (-1/2, 1/2] turns from its sine and cosine, as the axis is:
      // unreduced, a large orientation loses its fraction (or overflows) in float.
      theta0_ = kind == gabor_kind::isotropic ? 0.0 : std::atan2(sa, ca) / c::kTwoPi;
      spread_ = kind == gabor_kind::isotropic ? 1.0 : spread / c::kTwoPi;
    } else {
      axis_ = {ce * ca, ce * sa, se};
      cos_cap_ = kind == gabor_kind::isotropic ? -1.0 : std::cos(0.5 * spread);
      if (kind == gabor_kind::isotropic) {
        t_ = {1, 0, 0};
        b_ = {0, 1, 0};
        axis_frame_ = {0, 0, 1};
      } else {
        detail::orthonormal_basis(axis_, t_, b_);
        axis_frame_ = axis_;
      }
    }
    for (int i = 0; i < D; ++i) fixed_[i] = phi0 * axis_[i];
  }

  gabor_kind kind() const { return kind_; }
  // How many uniform values one impulse's marks take.
  int values() const {
    if (kind_ == gabor_kind::anisotropic) return 1;
    return 1 + (D == 2 ? 1 : 2) + (kind_ == gabor_kind::hybrid ? 1 : 0);
  }

  // The weight and frequency vector (cycles per cell) from uniform values u
  // (values() of them), with float or double arithmetic.
  template <class T>
  void draw(const T* u, T& weight, vec<T, D>& frequency) const {
    namespace c = detail::constants;
    weight = T(2) * u[0] - T(1);
    if (kind_ == gabor_kind::anisotropic) {
      for (int i = 0; i < D; ++i) frequency[i] = T(fixed_[i]);
      return;
    }
    const T phi = kind_ == gabor_kind::hybrid ? T(phi0_) + T(dphi_) * (u[D] - T(0.5)) : T(phi0_);
    if constexpr (D == 2) {
      const detail::sin_cos<T> sc = detail::sincos_turns(T(theta0_) + T(spread_) * (u[1] - T(0.5)));
      frequency = {phi * sc.cos, phi * sc.sin};
    } else {
      vec<T, 3> dir;
      direction(u[1], u[2], dir);
      for (int i = 0; i < 3; ++i) frequency[i] = phi * dir[i];
    }
  }

  // 3D: the unit direction of values (u1, u2): uniform in the cap around
  // omega0 (the whole sphere for isotropic noise).
  template <class T>
  void direction(T u1, T u2, vec<T, 3>& dir) const {
    const T ct = T(1) - T(1.0 - cos_cap_) * u1;
    const T st = std::sqrt((T(1) - ct) * (T(1) + ct));
    const detail::sin_cos<T> sc = detail::sincos_turns(u2);
    const T lx = st * sc.cos, ly = st * sc.sin;
    for (int i = 0; i < 3; ++i) dir[i] = (T(t_[i]) * lx + T(b_[i]) * ly) + T(axis_frame_[i]) * ct;
  }

  // Orientation omega0 (unit), its frequency vector Phi0 omega0, and the
  // constants the SIMD and GLSL code read.
  const vec<double, D>& axis() const { return axis_; }
  const vec<double, D>& fixed_frequency() const { return fixed_; }
  double phi0() const { return phi0_; }
  double dphi() const { return dphi_; }
  double theta0() const { return theta0_; }
  double spread_turns() const { return spread_; }
  double cos_cap() const { return cos_cap_; }
  const vec<double, 3>& frame_t() const { return t_; }
  const vec<double, 3>& frame_b() const { return b_; }
  const vec<double, 3>& frame_axis() const { return axis_frame_; }

 private:
  gabor_kind kind_ = gabor_kind::isotropic;
  double phi0_ = 0, dphi_ = 0;
  vec<double, D> axis_{}, fixed_{};
  double theta0_ = 0, spread_ = 1;  // 2D, turns
  double cos_cap_ = -1;             // 3D
  vec<double, 3> t_{}, b_{}, axis_frame_{};
};

}  // namespace hush

#endif  // HUSH_GABOR_MARKS_HPP
