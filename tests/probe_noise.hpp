// A test-only "noise" whose value is an exact, simple function of every
// per-sample input (position, footprint, normal), so that tests of the
// batch plumbing (exec.hpp's samples overloads, the GLSL samples layout)
// can tell each input apart and compare backends for exact equality: with
// inputs that are small multiples of 1/8, every intermediate is exact in float.
//   point value  v(p)    = p0 + p1 / 2 (+ p2 / 4)
//   sample value v(s)    = v(p) + S00 + S01 / 2 + S(D-1, D-1) / 4
//                          + (normal given ? 2 n.x + 4 n.z : -8)
//                          + (surface map given (2D) ? m00 + m01 / 2 + m10 / 4 + m11 / 8 : 0)
//   gradient             = (1, 1/2[, 1/4]) for both
// It also shows how a user's own noise plugs into hush::evaluate.
#ifndef HUSH_TESTS_PROBE_NOISE_HPP
#define HUSH_TESTS_PROBE_NOISE_HPP

#include "hush/hush.hpp"

namespace hush_test {

template <int D>
class probe_noise : public hush::sample_noise<probe_noise<D>, D> {
 public:
  static constexpr bool takes_footprint = true;
  static constexpr bool takes_normal = D == 3;
  static constexpr bool takes_surface_map = D == 2;

  template <class T>
  T value(const hush::vec<double, D>& p) const {
    T v = T(p[0]) + T(p[1]) / T(2);
    if constexpr (D == 3) v += T(p[2]) / T(4);
    return v;
  }
  template <class T>
  hush::value_gradient<T, D> value_and_gradient(const hush::vec<double, D>& p) const {
    hush::value_gradient<T, D> r{value<T>(p), {}};
    for (int a = 0; a < D; ++a) r.gradient[a] = T(1) / T(1 << a);
    return r;
  }
  template <class T>
  T sample_value(const hush::sample_input<D>& s) const {
    const T fp = T(s.fp.covariance(0, 0)) + T(s.fp.covariance(0, 1)) / T(2) +
                 T(s.fp.covariance(D - 1, D - 1)) / T(4);
    const T nrm = s.has_normal ? T(2) * T(s.normal.x) + T(4) * T(s.normal.z) : T(-8);
    const T map = s.has_map ? ((T(s.map.m00) + T(s.map.m01) / T(2)) + T(s.map.m10) / T(4)) +
                                  T(s.map.m11) / T(8)
                            : T(0);
    return value<T>(s.position) + fp + nrm + map;
  }
  template <class T>
  hush::value_gradient<T, D> sample_value_and_gradient(const hush::sample_input<D>& s) const {
    hush::value_gradient<T, D> r = value_and_gradient<T>(s.position);
    r.value = sample_value<T>(s);
    return r;
  }
};

}  // namespace hush_test

#endif  // HUSH_TESTS_PROBE_NOISE_HPP
