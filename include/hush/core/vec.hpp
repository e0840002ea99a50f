// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Tiny fixed-size vectors: just enough to pass points, gradients and steps.
// hush::vec<T, N> holds N values of T (N = 2, 3, 4) with members x, y, z, w and
// indexing; vec2/vec3/vec4 are float, dvec2/dvec3/dvec4 double. When GLM is
// available (config.hpp) they convert implicitly from and to glm::vec<N, T, Q>,
// so `noise(glm::vec3{...})` works and a hush vector assigns to a glm one.
// Arithmetic is deliberately minimal: this is not a math library.
#ifndef HUSH_CORE_VEC_HPP
#define HUSH_CORE_VEC_HPP

#include <cstddef>
#include <type_traits>

#include "hush/config.hpp"

#if HUSH_CONFIG_GLM
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#define HUSH_VEC_GLM_INTEROP(N)                                                     \
  template <glm::qualifier Q>                                                       \
  constexpr vec(const glm::vec<(N), T, Q>& g) { /* NOLINT: implicit by design */    \
    for (int i = 0; i < (N); ++i) (*this)[i] = g[i];                                \
  }                                                                                 \
  template <glm::qualifier Q>                                                       \
  constexpr operator glm::vec<(N), T, Q>() const { /* NOLINT: implicit by design */ \
    glm::vec<(N), T, Q> g{};                                                        \
    for (int i = 0; i < (N); ++i) g[i] = (*this)[i];                                \
    return g;                                                                       \
  }
#else
#define HUSH_VEC_GLM_INTEROP(N)
#endif

// Members shared by the three sizes. Indexing goes through the named members
// (not pointer arithmetic across them) so it stays well defined.
#define HUSH_VEC_COMMON(N)                  \
  static constexpr int size() { return N; } \
  HUSH_VEC_GLM_INTEROP(N)

namespace hush {

namespace detail {
// vec's subscript takes any integer type, i in 0 ... N - 1: hush loops over axes with int
// and over containers with std::size_t, and neither needs a cast (nor warns under
// -Wsign-conversion) to index a vector.
template <class I>
using index_type = std::enable_if_t<std::is_integral<I>::value>;
}  // namespace detail

template <class T, int N>
struct vec;

template <class T>
struct vec<T, 2> {
  T x{}, y{};
  constexpr vec() = default;
  constexpr vec(T x_, T y_) : x(x_), y(y_) {}
  template <class I, class = detail::index_type<I>>
  constexpr T& operator[](I i) {
    return i == 0 ? x : y;
  }
  template <class I, class = detail::index_type<I>>
  constexpr const T& operator[](I i) const {
    return i == 0 ? x : y;
  }
  HUSH_VEC_COMMON(2)
};

template <class T>
struct vec<T, 3> {
  T x{}, y{}, z{};
  constexpr vec() = default;
  constexpr vec(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  template <class I, class = detail::index_type<I>>
  constexpr T& operator[](I i) {
    return i == 0 ? x : (i == 1 ? y : z);
  }
  template <class I, class = detail::index_type<I>>
  constexpr const T& operator[](I i) const {
    return i == 0 ? x : (i == 1 ? y : z);
  }
  HUSH_VEC_COMMON(3)
};

template <class T>
struct vec<T, 4> {
  T x{}, y{}, z{}, w{};
  constexpr vec() = default;
  constexpr vec(T x_, T y_, T z_, T w_) : x(x_), y(y_), z(z_), w(w_) {}
  template <class I, class = detail::index_type<I>>
  constexpr T& operator[](I i) {
    return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w));
  }
  template <class I, class = detail::index_type<I>>
  constexpr const T& operator[](I i) const {
    return i == 0 ? x : (i == 1 ? y : (i == 2 ? z : w));
  }
  HUSH_VEC_COMMON(4)
};

#undef HUSH_VEC_COMMON
#undef HUSH_VEC_GLM_INTEROP

using vec2 = vec<float, 2>;
using vec3 = vec<float, 3>;
using vec4 = vec<float, 4>;
using dvec2 = vec<double, 2>;
using dvec3 = vec<double, 3>;
using dvec4 = vec<double, 4>;

// Exact component-wise equality (NaN != NaN, -0 == +0, as for the elements).
template <class T, int N>
constexpr bool operator==(const vec<T, N>& a, const vec<T, N>& b) {
  for (int i = 0; i < N; ++i)
    if (!(a[i] == b[i])) return false;
  return true;
}
template <class T, int N>
constexpr bool operator!=(const vec<T, N>& a, const vec<T, N>& b) {
  return !(a == b);
}

// Component-wise conversion between element types (float <-> double).
template <class To, class From, int N>
constexpr vec<To, N> vec_cast(const vec<From, N>& a) {
  vec<To, N> r;
  for (int i = 0; i < N; ++i) r[i] = static_cast<To>(a[i]);
  return r;
}

// A noise value together with its gradient (d value / d position), returned by
// gradient() of the differentiable noises: `auto [v, g] = noise.gradient(p);`.
template <class T, int N>
struct value_gradient {
  T value;
  vec<T, N> gradient;
};

}  // namespace hush

#endif  // HUSH_CORE_VEC_HPP
