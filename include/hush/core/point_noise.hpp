// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The evaluation interface every point noise offers, written once.
//
// A noise N derives from point_noise<N, D> and defines two templates:
//   template <class T> T value(const vec<double, D>& p) const;
//   template <class T> value_gradient<T, D> value_and_gradient(const vec<double, D>& p) const;
// which split the position into lattice cell and fraction in double and then
// compute in T. This base turns them into the public overloads:
//   noise(vec<float, D>)  -> float    (float arithmetic)
//   noise(vec<double, D>) -> double   (the double-precision reference)
//   noise.gradient(...)   -> value_gradient<T, D>
// Non-template overloads, so glm::vec arguments convert implicitly.
#ifndef HUSH_CORE_POINT_NOISE_HPP
#define HUSH_CORE_POINT_NOISE_HPP

#include "hush/core/vec.hpp"

namespace hush {

template <class Derived, int D>
class point_noise {
 public:
  static constexpr int dimension = D;

  float operator()(const vec<float, D>& p) const {
    return self().template value<float>(vec_cast<double>(p));
  }
  double operator()(const vec<double, D>& p) const { return self().template value<double>(p); }
  value_gradient<float, D> gradient(const vec<float, D>& p) const {
    return self().template value_and_gradient<float>(vec_cast<double>(p));
  }
  value_gradient<double, D> gradient(const vec<double, D>& p) const {
    return self().template value_and_gradient<double>(p);
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

}  // namespace hush

#endif  // HUSH_CORE_POINT_NOISE_HPP
