// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The Gabor kernel (Lagae, Lefebvre, Drettakis, Dutre, "Procedural noise using
// sparse Gabor convolution", SIGGRAPH 2009, sec. 3.1, eq. 4), 2D and 3D:
//
//   g(x) = e^{-pi a^2 |x|^2} cos(2 pi <F, x>) tau(|x|^2 / r^2),
//
// a Gaussian envelope of bandwidth a (1/noise units) times a harmonic of
// frequency vector F (cycles per noise unit; F = F0 omega0 in the paper), with
// K = 1 (noises scale their sum instead). It is what hush::gabor<D> sums and
// what NPR Gabor noise splats, so it lives here once, for both:
//
//   hush::gabor_kernel<2> k{/*bandwidth a=*/0.8, /*truncation t=*/0.05};
//   double r = k.radius();                               // support radius
//   float g = k.value(hush::vec2{0.1f, 0.2f}, hush::dvec2{1.0, 0.0});
//   auto [g2, grad] = k.value_and_gradient(hush::dvec2{0.1, 0.2}, hush::dvec2{1.0, 0.0});
//   double p = k.power_spectrum(hush::dvec2{1.0, 0.0}, hush::dvec2{1.0, 0.0});
//
// Truncation (Lagae 2009 sec. 3.1; the error analysis of Lagae, Lefebvre,
// Dutre, "Improving Gabor noise", TVCG 2011): the support radius is where the
// envelope falls to t, r = sqrt(ln(1/t) / pi) / a. The paper cuts the kernel
// there, a jump of t; hush tapers it with a smoothstep over s = |x|^2 / r^2 in
// [s0, 1], s0 = kGaborTaperStart = 0.8 (constants.hpp), so that the kernel and
// every noise built on it are C1:
//   - g equals the Gabor kernel for |x| <= r sqrt(s0) and g = 0 for |x| >= r;
//   - |g - g_Gabor| <= t^s0 everywhere (0.091 for the default t = 0.05);
//   - truncation_error(F) is the relative RMS difference, sqrt(int (g -
//     g_Gabor)^2 / int g_Gabor^2): 0.068 in 2D and 0.11 in 3D for t = 0.05
//     and F >> a (tests/gabor/gabor_kernel_test.cpp).
//
// Evaluation happens in cell units d = x / r (the noise's cells are r wide),
// where the envelope is e^{-A |d|^2} with A = pi a^2 r^2 = ln(1/t) and the
// frequency is Phi = F r cycles per cell. The float path is separable:
//   g = Re[(e_x c_x + i e_x s_x)(w e_yz c_yz + i w e_yz s_yz)] * tau, with
//   e_yz c_yz + i e_yz s_yz = (e_y e_z)(c_y + i s_y)(c_z + i s_z),
//   e_a = e^{-A d_a^2},  (s_a, c_a) = sin/cos(2 pi Phi_a d_a),
// with hush's own exp and sin/cos (detail/elementary.hpp), so a grid can
// share each axis's factors between samples and SIMD repeats it bit for bit.
// value<double> is the reference (C library exp, sin, cos); float values are
// within 2^-21 (1 + 2 pi |Phi|) of it for |d| < 1 (relative to K = 1),
// measured 3e-7 (tests/gabor/gabor_kernel_test.cpp).
//
// Spectra (noise units; D = 2, 3). The Fourier transform of the untruncated
// kernel is a^-D (e^{-pi |f - F|^2 / a^2} + e^{-pi |f + F|^2 / a^2}) / 2, two
// Gaussians at +-F (Lagae 2009 eq. 5); its power spectrum is the square
// (untruncated_power_spectrum). The tapered kernel's transform is
// (H(f - F) + H(f + F)) / 2 with H the radial transform of the tapered
// envelope, computed by quadrature (envelope_transform, power_spectrum,
// energy): exact to ~1e-13 relative, no closed form exists; above
// kGaborAsymptoticCycles cycles per cell by the leading asymptotic term,
// within 2e-13 there (radial_transform_tail), so each costs bounded time.
//
// Filtering (Lagae 2009 sec. 5): the kernel convolved with a Gaussian of
// covariance Sigma (noise units) is again a Gabor kernel,
//   (g_Gabor * N(0, Sigma))(x) = sqrt(det Q) e^{-pi F^T (I - Q) F / a^2}
//                                e^{-pi a^2 x^T Q x} cos(2 pi <Q F, x>),
//   Q = (I + 2 pi a^2 Sigma)^-1,
// derived in docs/gabor.md (complete the square in the product of the two
// transforms). gabor_filter<D> computes Q and the constants from a footprint;
// the taper is kept at the unfiltered support.
#ifndef HUSH_GABOR_KERNEL_HPP
#define HUSH_GABOR_KERNEL_HPP

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "hush/config.hpp"
#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/vec.hpp"
#include "hush/detail/constants.hpp"
#include "hush/detail/elementary.hpp"
#include "hush/detail/quadrature.hpp"

namespace hush {
namespace detail {

// ---- The kernel in cell units, operation by operation as the SIMD kernels
// (hush/gabor/simd-inl.h) and GLSL (hush/glsl/gabor_glsl.hpp) repeat it.

// The taper tau(s) = v^2 (3 - 2v), v = clamp((1 - s) k, 0, 1), k = 1 / (1 - s0),
// and its derivative dtau/ds = -6 k v (1 - v). tau and dtau are exactly 0 for
// s >= 1 ((1 - s) k > 0 exactly when s < 1), so vector code may add the
// terms of samples outside the support (+-0) instead of masking them.
template <class T>
struct gabor_taper_value {
  T tau, dtau;
};
template <class T>
HUSH_INLINE T gabor_taper_v(T s, T k) {
  T v = (T(1) - s) * k;
  v = v < T(1) ? v : T(1);  // NaN s gives 1, as the SIMD Min(v, 1) does
  return v > T(0) ? v : T(0);
}
template <class T>
HUSH_INLINE T gabor_taper(T s, T k) {
  const T v = gabor_taper_v(s, k);
  return (v * v) * (T(3) - T(2) * v);
}
template <class T>
HUSH_INLINE gabor_taper_value<T> gabor_taper_derivative(T s, T k) {
  const T v = gabor_taper_v(s, k);
  return {(v * v) * (T(3) - T(2) * v), (T(-6) * k) * (v * (T(1) - v))};
}

// One axis of the separable kernel: offset d (cell units), d^2, the envelope
// factor e^{-A d^2} and sin/cos(2 pi phi d).
template <class T>
struct gabor_axis {
  T d, d2, e, s, c;
};
template <class T>
HUSH_INLINE gabor_axis<T> gabor_axis_factors(T d, T neg_a, T phi) {
  gabor_axis<T> f;
  f.d = d;
  f.d2 = d * d;
  f.e = exp_neg(neg_a * f.d2);
  const sin_cos<T> sc = sincos_turns(phi * d);
  f.s = sc.sin;
  f.c = sc.cos;
  return f;
}

// What the kernel of one impulse is along every axis but x: its weight times
// the envelope factors, the harmonic's cos and sin, and the squared offset.
template <class T>
struct gabor_row {
  T we, c, s, d2;
};
template <class T>
HUSH_INLINE gabor_row<T> gabor_row_of(T w, const gabor_axis<T>& y) {
  return {w * y.e, y.c, y.s, y.d2};
}
template <class T>
HUSH_INLINE gabor_row<T> gabor_row_of(T w, const gabor_axis<T>& y, const gabor_axis<T>& z) {
  return {w * (y.e * z.e), y.c * z.c - y.s * z.s, y.s * z.c + y.c * z.s, y.d2 + z.d2};
}

// The weighted kernel of one (x factors, row) pair, for s = x.d2 + row.d2 < 1
// (0 for s >= 1), from the products of each side: the x side's e c and e s
// and the row's we c and we s, so that a grid forms them once per column and
// once per row and per sample only (ec b - es q) tau(s).
template <class T>
HUSH_INLINE T gabor_pair_of_products(T ec, T es, T b, T q, T s, T taper_k) {
  return (ec * b - es * q) * gabor_taper(s, taper_k);
}
template <class T>
HUSH_INLINE T gabor_pair(const gabor_axis<T>& x, const gabor_row<T>& r, T taper_k) {
  return gabor_pair_of_products(x.e * x.c, x.e * x.s, r.we * r.c, r.we * r.s, x.d2 + r.d2, taper_k);
}
// The same with the gradient's coefficients: dg/dd_a = u d_a - v phi_a.
template <class T>
struct gabor_pair_gradient {
  T value, u, v;
};
// The value and gradient coefficients of p cos(2 pi theta) tau(s) (p = w e^{-A s},
// theta = <phi, d>) from pc = p cos and ps = p sin: d/dd_a = p cos (2 d_a tau' -
// 2 A d_a tau) - 2 pi phi_a p sin tau. Both forms (pair, point term) end here.
template <class T>
HUSH_INLINE gabor_pair_gradient<T> gabor_gradient_of_harmonics(T pc, T ps, T s, T taper_k, T a) {
  const gabor_taper_value<T> tw = gabor_taper_derivative(s, taper_k);
  return {pc * tw.tau, (pc + pc) * (tw.dtau - a * tw.tau), T(constants::kTwoPi) * (ps * tw.tau)};
}
template <class T>
HUSH_INLINE gabor_pair_gradient<T> gabor_pair_gradient_of_products(T ec, T es, T b, T q, T s,
                                                                   T taper_k, T a) {
  const T pc = ec * b - es * q;  // p cos(theta), p = e_x we
  const T ps = es * b + ec * q;  // p sin(theta)
  return gabor_gradient_of_harmonics(pc, ps, s, taper_k, a);
}
template <class T>
HUSH_INLINE gabor_pair_gradient<T> gabor_pair_with_gradient(const gabor_axis<T>& x,
                                                            const gabor_row<T>& r, T taper_k, T a) {
  return gabor_pair_gradient_of_products(x.e * x.c, x.e * x.s, r.we * r.c, r.we * r.s, x.d2 + r.d2,
                                         taper_k, a);
}

// The point form (random points; grids keep the separable pair above, so that
// a grid forms its factors once per row and column): one impulse's weighted
// kernel w e^{-A s} cos(2 pi theta) tau(s) from s = |d|^2 < 1 (0 for s >= 1)
// and theta = <phi, d>, i.e. one exp and one cos instead of D of each. The
// two forms are the same function; in float they differ by rounding only
// (docs/gabor.md, "Float accuracy": bounded there and tested in gabor_test).
// theta is summed as phi_x d_x + phi_y d_y (3D: phi_x d_x + (phi_y d_y +
// phi_z d_z)), as s is.
template <class T, int D>
HUSH_INLINE T gabor_point_phase(const T* phi, const T* d) {
  if constexpr (D == 2)
    return phi[0] * d[0] + phi[1] * d[1];
  else
    return phi[0] * d[0] + (phi[1] * d[1] + phi[2] * d[2]);
}
template <class T>
HUSH_INLINE T gabor_point_term(T w, T s, T theta, T neg_a, T taper_k) {
  return ((w * exp_neg(neg_a * s)) * sincos_turns(theta).cos) * gabor_taper(s, taper_k);
}
template <class T>
HUSH_INLINE gabor_pair_gradient<T> gabor_point_term_with_gradient(T w, T s, T theta, T neg_a,
                                                                  T taper_k, T a) {
  const T p = w * exp_neg(neg_a * s);
  const sin_cos<T> sc = sincos_turns(theta);
  return gabor_gradient_of_harmonics(p * sc.cos, p * sc.sin, s, taper_k, a);
}

// The sum of one point's terms at solid points, unfiltered and filtered (grids'
// separable form and surface samples add in one chain): the k-th term in the
// summation order (cells in raster order, impulses in stream order, kept ones
// counted) goes to partial sum k mod 4, the total is (s0 + s1) + (s2 + s3). The
// SIMD paths hold the four partial sums in one 4-lane vector and add a point's
// terms four at a time without a branch on their count (a loop's exit,
// mispredicted once per point, cost ~7 ns of ~77 per 2D point on AVX3); GLSL
// keeps a vec4. Each partial sum starts at +0 and so never becomes -0: the SIMD
// paths may add +0 for missing terms.
template <class T>
struct gabor_point_sum {
  T part[4] = {T(0), T(0), T(0), T(0)};
  unsigned k = 0;
  HUSH_INLINE void add(T v) {
    part[k & 3u] += v;
    ++k;
  }
  HUSH_INLINE T total() const { return (part[0] + part[1]) + (part[2] + part[3]); }
};

// ---- Closed forms and quadratures in cell units (double).

// The radially symmetric part of an integral over the unit ball: int phi(|d|) dd
// = c_D int_0^1 phi(rho) rho^(D-1) drho, with the integrand split at the taper's
// start (where the taper has a kink in its second derivative).
template <int D, class F>
double ball_integral(F phi, int panels) {
  const double rho0 = std::sqrt(constants::kGaborTaperStart);
  auto radial = [&](double rho) { return phi(rho) * (D == 2 ? rho : rho * rho); };
  const double c = D == 2 ? constants::kTwoPi : 2.0 * constants::kTwoPi;
  return c * (integrate(radial, 0.0, rho0, panels) + integrate(radial, rho0, 1.0, panels));
}

// The angular average of cos(2 pi xi rho <u, omega>) over unit u: J0 in 2D,
// sin(z)/z in 3D, z = 2 pi xi rho.
template <int D>
double angular_average(double z) {
  if constexpr (D == 2) {
    return bessel_j0(z);
  } else {
    return std::fabs(z) < 1e-4 ? 1.0 - z * z / 6.0 : std::sin(z) / z;
  }
}

// The leading term, as q -> inf, of the radial transform below for f(rho) =
// e^{-c rho^2} w(rho^2) with w, w' continuous and jumps dw2[j] in w'' (in s =
// rho^2) at s = s0 (the taper's start) and s = 1 (the support's edge), f = 0
// beyond. (rho f)'' jumps by J_j = rho_j e^{-c s_j} 4 s_j dw2[j] at rho_j =
// sqrt(s_j); integrating by parts three times (3D, where the transform is
// (2/q) int_0^1 rho f sin(omega rho)) or with J0's Hankel asymptotics (2D),
// omega = 2 pi q (docs/gabor.md "Cost of the kernel's statistics"):
//   3D: (2/q) sum_j -J_j cos(omega rho_j) / omega^3            = O(q^-4),
//   2D: 2 pi sum_j J_j sqrt(2 / (pi omega rho_j)) sin(omega rho_j - pi/4) / omega^3
//                                                               = O(q^-3.5).
// The rest is O(1/q) smaller: below 2e-13 of the energy, truncation error and
// H(0) from q = kGaborAsymptoticCycles on (tests/gabor/gabor_kernel_test.cpp).
template <int D>
double radial_transform_tail(double c, double q, const double (&dw2)[2]) {
  const double s_j[2] = {constants::kGaborTaperStart, 1.0};
  const double omega = constants::kTwoPi * q, omega3 = omega * omega * omega;
  double sum = 0;
  for (int j = 0; j < 2; ++j) {
    if (dw2[j] == 0.0) continue;
    const double rho = std::sqrt(s_j[j]);
    const double jump = rho * std::exp(-c * s_j[j]) * 4.0 * s_j[j] * dw2[j];
    if constexpr (D == 3) {
      sum -= (2.0 / q) * jump * std::cos(omega * rho) / omega3;
    } else {
      sum += constants::kTwoPi * jump * std::sqrt(2.0 / (constants::kPi * omega * rho)) *
             std::sin(omega * rho - 0.25 * constants::kPi) / omega3;
    }
  }
  return sum;
}

// int over the unit ball of e^{-c |d|^2} w(|d|^2) cos(2 pi q <u, d>) dd, u a
// unit vector, w as above with the jumps dw2. Quadrature up to q =
// kGaborAsymptoticCycles, the leading asymptotic term beyond: the cost is
// bounded (at most 514 panels) for every q. NaN q gives NaN. Panels 2 +
// ceil(q / 2): 16 nodes per <= 1.8 cycles; with half as many panels, or four
// times as many, the result moves by < 1e-16 of the transform at q = 0.
template <int D, class W>
double radial_transform(double c, W w, double q, const double (&dw2)[2]) {
  q = std::fabs(q);
  if (!(q <= constants::kGaborAsymptoticCycles)) return radial_transform_tail<D>(c, q, dw2);
  const int panels = 2 + static_cast<int>(std::ceil(0.5 * q));
  return ball_integral<D>(
      [&](double rho) {
        const double s = rho * rho;
        return std::exp(-c * s) * w(s) * angular_average<D>(constants::kTwoPi * q * rho);
      },
      panels);
}

// k = 1 / (1 - s0) of the taper; its second derivative in s is k^2 (6 - 12 v):
// -6 k^2 where it starts (v = 1), 6 k^2 at the support's edge (v = 0).
inline double gabor_taper_k() { return 1.0 / (1.0 - constants::kGaborTaperStart); }

// int over the unit ball of e^{-c |d|^2} w(|d|^2) dd (no oscillation: fixed panels).
template <int D, class W>
double radial_mean(double c, W w) {
  return ball_integral<D>(
      [&](double rho) {
        const double s = rho * rho;
        return std::exp(-c * s) * w(s);
      },
      8);
}

// The jumps of the taper's second derivative in s: w = tau: w'' jumps by -6 k^2 at
// s0 (from 0) and by -6 k^2 at 1 (from 6 k^2 to 0).
struct gabor_envelope_jumps {
  double dw2[2];
  gabor_envelope_jumps() {
    const double k = gabor_taper_k();
    dw2[0] = dw2[1] = -6.0 * k * k;
  }
};

// H(xi): the Fourier transform of the tapered envelope e^{-A |d|^2} tau(|d|^2)
// at |xi| cycles per cell (radial, real).
template <int D>
double gabor_envelope_transform(double a, double xi) {
  const double k = gabor_taper_k();
  return radial_transform<D>(a, [k](double s) { return gabor_taper(s, k); }, xi,
                             gabor_envelope_jumps().dw2);
}
// Its leading asymptotic term alone (O(1) cost at any xi): within 1.1e-13 of
// H(0) from kGaborAsymptoticCycles on, the left-out term falling as xi^-4.5
// (2D) / xi^-5 (3D) below (docs/gabor.md "Cost of the kernel's statistics").
template <int D>
double gabor_envelope_transform_tail(double a, double xi) {
  return radial_transform_tail<D>(a, std::fabs(xi), gabor_envelope_jumps().dw2);
}

// int g^2 over the cell-unit ball for |Phi| = phi:
// (1/2) int e^{-2A s} tau^2 (1 + cos(4 pi <Phi, d>)), the cosine's part a
// transform at q = 2 phi. w = tau^2: w'' = 2 tau'^2 + 2 tau tau'' jumps by
// -12 k^2 at s0 and is continuous (0) at 1.
template <int D>
double gabor_energy(double a, double phi) {
  const double k = gabor_taper_k();
  const double dw2[2] = {-12.0 * k * k, 0.0};
  auto w = [k](double s) {
    const double tau = gabor_taper(s, k);
    return tau * tau;
  };
  return 0.5 * (radial_mean<D>(2.0 * a, w) + radial_transform<D>(2.0 * a, w, 2.0 * phi, dw2));
}

// int (g - g_Gabor)^2 and int g_Gabor^2 over all space (cell units), for the
// truncation error. Outside the ball g = 0, and the Gabor kernel's energy there
// is what the ball integral leaves of the closed form
// int e^{-2A|d|^2} cos^2 = (pi / 2A)^(D/2) (1 + e^{-2 pi^2 phi^2 / A}) / 2 =: full.
// Inside, (1 - tau)^2 - 1 = tau^2 - 2 tau =: w, so int (g - g_Gabor)^2 =
// full + (1/2) int_ball e^{-2A s} w (1 + cos(4 pi <Phi, d>)). w'' = 2 tau'' (tau - 1)
// + 2 tau'^2 is continuous (0) at s0 and jumps by 12 k^2 at 1 (from -12 k^2).
template <int D>
double gabor_truncation_error(double a, double phi) {
  const double k = gabor_taper_k();
  const double dw2[2] = {0.0, 12.0 * k * k};
  auto w = [k](double s) {
    const double tau = gabor_taper(s, k);
    return tau * tau - 2.0 * tau;
  };
  const double pi2 = constants::kPi * constants::kPi;
  const double full = std::pow(constants::kPi / (2.0 * a), 0.5 * D) * 0.5 *
                      (1.0 + std::exp(-2.0 * pi2 * phi * phi / a));
  const double inside =
      0.5 * (radial_mean<D>(2.0 * a, w) + radial_transform<D>(2.0 * a, w, 2.0 * phi, dw2));
  return std::sqrt((full + inside) / full);
}

}  // namespace detail

template <int D>
class gabor_kernel {
  static_assert(D == 2 || D == 3, "hush::gabor_kernel is 2D or 3D");

 public:
  static constexpr int dimension = D;

  // bandwidth a in [1e-6, 1e6] (1/noise units), truncation t in [1e-9, 0.5]
  // (the envelope's value at the support radius); hush::invalid_argument
  // naming the parameter otherwise.
  gabor_kernel(double bandwidth, double truncation) : a_(bandwidth), t_(truncation) {
    namespace c = detail::constants;
    detail::require_in_range("hush::gabor_kernel", "bandwidth", bandwidth, c::kGaborMinBandwidth,
                             c::kGaborMaxBandwidth, "1e-06 <= bandwidth <= 1e+06 (1/noise units)");
    detail::require_in_range("hush::gabor_kernel", "truncation", truncation, c::kGaborMinTruncation,
                             c::kGaborMaxTruncation, "1e-09 <= truncation <= 0.5");
    exponent_ = -std::log(t_);
    r_ = std::sqrt(exponent_ / c::kPi) / a_;
  }

  double bandwidth() const { return a_; }
  double truncation() const { return t_; }
  // Support radius r = sqrt(ln(1/t) / pi) / a (noise units): g = 0 beyond.
  double radius() const { return r_; }
  // Radius up to which g is the Gabor kernel exactly: r sqrt(s0).
  double taper_radius() const { return r_ * std::sqrt(detail::constants::kGaborTaperStart); }
  // A = pi a^2 r^2 = ln(1/t): the envelope is e^{-A |x / r|^2}.
  double envelope_exponent() const { return exponent_; }

  // g at offset x (noise units) for frequency vector F (cycles per noise
  // unit), in T (float: hush's separable float path; double: the reference).
  template <class T>
  T value(const vec<T, D>& x, const vec<double, D>& F) const {
    return eval<T, false>(x, F).value;
  }
  template <class T>
  value_gradient<T, D> value_and_gradient(const vec<T, D>& x, const vec<double, D>& F) const {
    return eval<T, true>(x, F);
  }

  // Power spectrum |g^(f)|^2 of this kernel (noise units: f and F in cycles
  // per unit), and of the untruncated Gabor kernel in closed form.
  double power_spectrum(const vec<double, D>& f, const vec<double, D>& F) const {
    double lo = 0, hi = 0;
    for (int i = 0; i < D; ++i) {
      lo += (f[i] - F[i]) * (f[i] - F[i]);
      hi += (f[i] + F[i]) * (f[i] + F[i]);
    }
    const double h = 0.5 * (envelope_transform(std::sqrt(lo)) + envelope_transform(std::sqrt(hi)));
    return h * h;
  }
  double untruncated_power_spectrum(const vec<double, D>& f, const vec<double, D>& F) const {
    double lo = 0, hi = 0;
    for (int i = 0; i < D; ++i) {
      lo += (f[i] - F[i]) * (f[i] - F[i]);
      hi += (f[i] + F[i]) * (f[i] + F[i]);
    }
    const double pi = detail::constants::kPi, a2 = a_ * a_;
    const double h = 0.5 * std::pow(a_, -D) * (std::exp(-pi * lo / a2) + std::exp(-pi * hi / a2));
    return h * h;
  }
  // The Fourier transform of the tapered envelope e^{-pi a^2 |x|^2} tau at
  // |f| = k cycles per unit (radial, real): H in the spectra above.
  double envelope_transform(double k) const {
    return std::pow(r_, D) * detail::gabor_envelope_transform<D>(exponent_, k * r_);
  }
  // int g^2 dx for |F| = frequency (noise units): what a sparse convolution
  // of these kernels at density lambda with weights w has as variance,
  // lambda E[w^2] energy(F) (Campbell's theorem).
  double energy(double frequency) const {
    return std::pow(r_, D) * detail::gabor_energy<D>(exponent_, frequency * r_);
  }
  // Relative RMS difference of g and the untruncated Gabor kernel, |F| = frequency.
  double truncation_error(double frequency) const {
    return detail::gabor_truncation_error<D>(exponent_, frequency * r_);
  }

 private:
  template <class T, bool WithGradient>
  value_gradient<T, D> eval(const vec<T, D>& x, const vec<double, D>& F) const {
    const T inv_r = T(1.0 / r_), neg_a = T(-exponent_);
    const T k = T(1.0 / (1.0 - detail::constants::kGaborTaperStart));
    detail::gabor_axis<T> ax[std::size_t{D}];
    T phi[std::size_t{D}];
    T s = 0;
    for (int i = 0; i < D; ++i) {
      phi[i] = T(F[i] * r_);
      ax[i] = detail::gabor_axis_factors(x[i] * inv_r, neg_a, phi[i]);
      s += ax[i].d2;
    }
    value_gradient<T, D> r{T(0), {}};
    if (s >= T(1)) return r;  // outside the support (NaN offsets give NaN below)
    detail::gabor_row<T> row;
    if constexpr (D == 2)
      row = detail::gabor_row_of(T(1), ax[1]);
    else
      row = detail::gabor_row_of(T(1), ax[1], ax[2]);
    if constexpr (WithGradient) {
      const auto p = detail::gabor_pair_with_gradient(ax[0], row, k, T(exponent_));
      r.value = p.value;
      for (int i = 0; i < D; ++i) r.gradient[i] = (p.u * ax[i].d - p.v * phi[i]) * inv_r;
    } else {
      r.value = detail::gabor_pair(ax[0], row, k);
    }
    return r;
  }

  double a_, t_, exponent_ = 0, r_ = 0;
};

namespace detail {

// Eigenvalues and eigenvectors of a symmetric D x D matrix (D = 2, 3) by
// cyclic Jacobi rotations: unconditionally stable, and accurate for nearly
// singular and badly scaled matrices (a rank-1 footprint times 1e12), where
// cofactor formulas cancel catastrophically. a is overwritten (its diagonal
// ends holding the eigenvalues); v's columns are the eigenvectors.
template <int D>
void jacobi_eigen(double (&a)[std::size_t{D}][std::size_t{D}],
                  double (&v)[std::size_t{D}][std::size_t{D}]) {
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j) v[i][j] = i == j ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0, diag = 0;
    for (int i = 0; i < D; ++i) {
      diag += a[i][i] * a[i][i];
      for (int j = i + 1; j < D; ++j) off += a[i][j] * a[i][j];
    }
    if (!(off > 1e-34 * diag)) return;  // converged (or NaN: give up)
    for (int p = 0; p < D; ++p)
      for (int q = p + 1; q < D; ++q) {
        if (a[p][q] == 0.0) continue;
        // The rotation that zeroes a[p][q]: t = tan, the smaller root.
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double at = std::fabs(theta);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (at + (at < 1e150 ? std::sqrt(at * at + 1.0) : at));
        const double c = 1.0 / std::sqrt(t * t + 1.0), sn = t * c;
        for (int k = 0; k < D; ++k) {  // columns p and q
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - sn * akq;
          a[k][q] = sn * akp + c * akq;
        }
        for (int k = 0; k < D; ++k) {  // rows p and q
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - sn * aqk;
          a[q][k] = sn * apk + c * aqk;
        }
        for (int k = 0; k < D; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - sn * vkq;
          v[k][q] = sn * vkp + c * vkq;
        }
        a[p][q] = a[q][p] = 0.0;  // zero by construction; rounding leaves a residue
      }
  }
}

}  // namespace detail

// The closed-form filtered kernel (Lagae 2009 sec. 5) for one sample's
// footprint, in the kernel's cell units (d = x / r, Phi = F r):
//   Q = (I + 2 A sigma^2 S / r^2)^-1  (S the footprint matrix, sigma =
//       kPixelFilterSigma pixels: the Gaussian pixel filter N(0, sigma^2 S)),
//   amplitude = sqrt(det Q),  attenuation(Phi) = e^{-Phi^T M Phi},
//   M = (pi^2 / A) (I - Q),  frequency Q Phi,  envelope e^{-A d^T Q d}.
// 3D: computed from S's eigen-decomposition S = V diag(l) V^T (Jacobi), with
// l clamped at 0 (rounding can leave a singular S an eigenvalue a few ulp
// below 0): Q = V diag(q) V^T, q = 1 / (1 + k l), and I - Q = V diag(k l q)
// V^T, k = 2 A sigma^2 / r^2, so nothing cancels however large k l.
// 2D: in closed form, Q = adj(I + k S) / det(I + k S), det(I + k S) = 1 + k tr S +
// k^2 det S, I - Q = (k S + k^2 det S I) / det(I + k S) (nothing cancels either), and
// amplitude = 1 / sqrt(det(I + k S)): one division and one square root instead of
// Jacobi's rotation. det S = ac - b^2 is exact to one rounding for a float S (a c and
// b^2 are exact in doubles). An S that is not positive semi-definite (rounding, or
// from_covariance's unchecked input) is first projected onto those matrices, its
// eigenvalues clamped at 0 as the 3D form does; a NaN entry counts as 0. Every
// footprint (zero, rank 1, det 1e-30 or 1e30, the "everything" footprint)
// gives Q with eigenvalues in (0, 1]: nothing here is NaN, and for the widest
// footprints the amplitude underflows towards 0: the filtered noise is its mean.
template <int D>
struct gabor_filter {
  double q[std::size_t{D}][std::size_t{D}];  // Q, symmetric
  double m[std::size_t{D}]
          [std::size_t{D}];  // M = (pi^2 / A) (I - Q), symmetric positive semi-definite
  double amplitude;  // sqrt(det Q), in (0, 1]

  // `a` = A = ln(1/t), `inv_r` = 1 / r, fp the footprint in noise units.
  gabor_filter(const footprint<D>& fp, double a, double inv_r) {
    double s[std::size_t{D}][std::size_t{D}];
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) s[i][j] = static_cast<double>(fp.covariance(i, j));
    build(s, a, inv_r);
  }
  // The same for S given in double (symmetric, finite, positive semi-definite up
  // to rounding): surface noise's footprint projected onto the tangent plane,
  // which is not rounded to float (gabor<3>::surface_frame).
  gabor_filter(const double (&cov)[std::size_t{D}][std::size_t{D}], double a, double inv_r) {
    double s[std::size_t{D}][std::size_t{D}];
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) s[i][j] = cov[i][j];
    build(s, a, inv_r);
  }

 private:
  // s is overwritten (jacobi_eigen).
  void build(double (&s)[std::size_t{D}][std::size_t{D}], double a, double inv_r) {
    namespace c = detail::constants;
    const double k = 2.0 * a * c::kPixelFilterSigma * c::kPixelFilterSigma * inv_r * inv_r;
    if constexpr (D == 2) {
      build_2d(s[0][0], s[0][1], s[1][1], k, c::kPi * c::kPi / a);
      return;
    }
    double v[std::size_t{D}][std::size_t{D}];
    detail::jacobi_eigen<D>(s, v);
    double qd[std::size_t{D}], md[std::size_t{D}];
    double det = 1.0;  // det Q
    const double mk = c::kPi * c::kPi / a;
    for (int i = 0; i < D; ++i) {
      const double kl = k * (s[i][i] > 0.0 ? s[i][i] : 0.0);
      qd[i] = 1.0 / (1.0 + kl);
      md[i] = mk * (kl * qd[i]);  // kl / (1 + kl) with one division per eigenvalue
      det *= qd[i];
    }
    amplitude = std::sqrt(det);  // one square root; det Q of a float S is far above underflow
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) {
        double qq = 0, mm = 0;
        for (int e = 0; e < D; ++e) {
          qq += v[i][e] * qd[e] * v[j][e];
          mm += v[i][e] * md[e] * v[j][e];
        }
        q[i][j] = qq;
        m[i][j] = mm;
      }
  }
  // The 2D closed form (above) of S = [[sa, sb], [sb, sc]], in this order of double
  // operations, no fused ones (filters_2d in gabor/shared_points-inl.h repeats it in lanes).
  void build_2d(double sa, double sb, double sc, double k, double mk) {
    sa = sa == sa ? sa : 0.0;  // NaN counts as 0
    sb = sb == sb ? sb : 0.0;
    sc = sc == sc ? sc : 0.0;
    double det = sa * sc - sb * sb;
    if (!(sa >= 0.0 && sc >= 0.0 && det >= 0.0)) {
      // Onto the positive semi-definite matrices: the eigenvalues mean +- rad, the
      // smaller clamped at 0 (S - lo I = (hi - lo) v v^T; rad > 0 here), or S = 0.
      const double mean = 0.5 * (sa + sc), half = 0.5 * (sa - sc);
      const double rad = std::sqrt(half * half + sb * sb);
      const double hi = mean + rad, lo = mean - rad;
      const double f = hi > 0.0 ? hi / (rad + rad) : 0.0;
      sa = (sa - lo) * f;
      sb = sb * f;
      sc = (sc - lo) * f;
      det = 0.0;
    }
    const double ka = k * sa, kb = k * sb, kc = k * sc, kkd = (k * k) * det;
    const double inv = 1.0 / (((1.0 + ka) + kc) + kkd);  // 1 / det(I + k S)
    q[0][0] = (1.0 + kc) * inv;
    q[0][1] = q[1][0] = -(kb * inv);
    q[1][1] = (1.0 + ka) * inv;
    m[0][0] = mk * ((ka + kkd) * inv);
    m[0][1] = m[1][0] = mk * (kb * inv);
    m[1][1] = mk * ((kc + kkd) * inv);
    amplitude = std::sqrt(inv);
  }
};

namespace detail {

// Index of entry (r, c) of a symmetric E x E matrix's upper triangle, stored
// row by row: (0,0), (0,1), [(0,2),] (1,1), [(1,2), (2,2)].
template <int E>
constexpr int gabor_sym(int r, int c) {
  return r <= c ? r * E - r * (r - 1) / 2 + (c - r) : gabor_sym<E>(c, r);
}

// A gabor_filter as the filtered kernel reads it, rounded to T once (every
// backend the same): Q's upper triangle q, M's with the off-diagonal doubled (m2:
// Phi^T M Phi = sum over r <= c of m2_rc Phi_r Phi_c) and the amplitude.
template <class T, int E>
struct gabor_filter_coefs {
  static constexpr int kSize = E * (E + 1) / 2;
  T q[std::size_t{kSize}], m2[std::size_t{kSize}];
  T amplitude;
  explicit gabor_filter_coefs(const gabor_filter<E>& f) : amplitude(static_cast<T>(f.amplitude)) {
    for (int r = 0; r < E; ++r)
      for (int c = r; c < E; ++c) {
        q[gabor_sym<E>(r, c)] = static_cast<T>(f.q[r][c]);
        m2[gabor_sym<E>(r, c)] = static_cast<T>(f.m[r][c]) * (r == c ? T(1) : T(2));
      }
  }
};

}  // namespace detail

}  // namespace hush

#endif  // HUSH_GABOR_KERNEL_HPP
