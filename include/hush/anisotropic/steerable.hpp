// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// hush::steerable_bank: the frequency-domain decomposition behind anisotropic
// noise (Goldberg, Zwicker & Durand 2008, sec. 2): polar-separable filters
//
//   D_{i,s}(w) = G_i(theta) B(log2(|w| / f_s)),  i = 0 ... K-1, s = 0 ... S-1,
//
// plus a low-pass residual L below scale 0 and a high-pass residual R above
// scale S-1, with f_s = base_frequency * 2^s (cycles per unit; scale 0 is the
// lowest) and theta_i = pi i / K. They are the squares of Portilla &
// Simoncelli's (2000) steerable-pyramid filters, i.e. analysis followed by
// synthesis (derivation in docs/anisotropic.md, "The filter bank"):
//
//   B(x)   = cos^2(pi x / 2) for |x| < 1, else 0   (x in octaves; the paper's
//            eq. 1 as extracted has the cases garbled: this is the product of
//            Portilla & Simoncelli's squared high-pass H^2(r) and low-pass
//            L^2(r/2)/4, which is one raised cosine in log2 r over two octaves)
//   G_i    = alpha_K^2 cos^{2(K-1)}(theta - theta_i),
//   alpha_K = 2^{K-1} (K-1)! / sqrt(K (2(K-1))!)   (the paper's "2^{i-1}" is an
//            extraction error), over the whole circle: G_i(theta + pi) = G_i(theta),
//            so every D is even and noise tiles built from it are real.
//   L(w)   = 1 - B(x_0) below f_0 (1 under f_0 / 2), R(w) = 1 - B(x_{S-1}) above
//            f_{S-1} (1 over 2 f_{S-1}), x_s = log2(|w| / f_s).
//
// Properties (tests/anisotropic/steerable_test.cpp measures them):
//  - invertibility: L + sum_{i,s} D_{i,s} + R = 1 at every frequency (to 1e-15):
//    the orientations sum to one because sum_i cos^{2(K-1)}(theta - pi i / K) =
//    K C(2K-2, K-1) / 4^{K-1} for every theta, and adjacent scales because
//    cos^2(pi x / 2) + cos^2(pi (x - 1) / 2) = 1;
//  - steerability: the analysis filters A_i = alpha_K cos^{K-1}(theta - theta_i)
//    (D_i = A_i^2) steer exactly: A at any orientation phi equals
//    sum_i b_i(phi) A_i with b_i(phi) = (1/K) sum_{m = -(K-1), step 2}^{K-1}
//    cos(m (theta_i - phi)) (steering_weight()). The squared filters D carry
//    angular harmonics up to 2(K-1) and need 2K-1 basis filters to steer
//    linearly; with K the best linear blend of the D_i approximates a rotated
//    D (docs/anisotropic.md gives the measured error).
// Pure math, no allocation except in decompose(); thread-safe.
#ifndef HUSH_ANISOTROPIC_STEERABLE_HPP
#define HUSH_ANISOTROPIC_STEERABLE_HPP

#include <cmath>
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "hush/core/error.hpp"
#include "hush/core/vec.hpp"
#include "hush/detail/constants.hpp"
#include "hush/detail/fft.hpp"

namespace hush {

class steerable_bank {
 public:
  struct params {
    int orientations = 4;         // K, kAnisoMinOrientations ... kAnisoMaxOrientations
    int scales = 3;               // S, 1 ... kAnisoMaxScales
    double base_frequency = 1.0;  // f_0: centre of scale 0, cycles per unit, finite > 0
  };

  steerable_bank() : steerable_bank(params{}) {}
  // Throws hush::invalid_argument naming the parameter and its valid range.
  explicit steerable_bank(const params& prm) : prm_(prm) {
    namespace c = detail::constants;
    detail::require_in_range("hush::steerable_bank", "orientations", prm.orientations,
                             c::kAnisoMinOrientations, c::kAnisoMaxOrientations, "2 ... 8");
    detail::require_in_range("hush::steerable_bank", "scales", prm.scales, 1, c::kAnisoMaxScales,
                             "1 ... 12");
    if (!(prm.base_frequency > 0.0 && prm.base_frequency < 1e300))
      detail::throw_out_of_range("hush::steerable_bank", "base_frequency", prm.base_frequency,
                                 "a finite number > 0 (cycles per unit)");
    for (int i = 0; i < prm.orientations; ++i) {
      const double t = orientation_angle(i);
      dir_[i] = {std::cos(t), std::sin(t)};
    }
  }

  const params& parameters() const { return prm_; }
  int orientations() const { return prm_.orientations; }
  int scales() const { return prm_.scales; }
  // K S subbands; index i + K s (orientation fastest).
  int subbands() const { return prm_.orientations * prm_.scales; }
  // f_s = f_0 2^s, cycles per unit.
  double centre_frequency(int s) const { return std::ldexp(prm_.base_frequency, s); }
  // theta_i = pi i / K and its unit vector (cos, sin).
  double orientation_angle(int i) const {
    return detail::constants::kPi * static_cast<double>(i) / static_cast<double>(orientations());
  }
  const dvec2& direction(int i) const { return dir_[i]; }

  // ---- The filter pieces (static: functions of K and of an angle or octave offset).

  // alpha_K = 2^{K-1} (K-1)! / sqrt(K (2K-2)!).
  static double alpha(int k) {
    double fact = 1.0, fact2 = 1.0;
    for (int m = 2; m <= k - 1; ++m) fact *= m;
    for (int m = 2; m <= 2 * (k - 1); ++m) fact2 *= m;
    return std::ldexp(fact, k - 1) / std::sqrt(static_cast<double>(k) * fact2);
  }
  // The analysis filter's angular part A(dtheta) = alpha_K cos^{K-1}(dtheta),
  // from c = cos(dtheta) (odd in c for even K).
  static double analysis_angular(int k, double cos_dtheta) {
    return alpha(k) * power(cos_dtheta, k - 1);
  }
  // G(dtheta) = A^2 = alpha_K^2 cos^{2(K-1)}(dtheta), from c = cos(dtheta).
  static double angular(int k, double cos_dtheta) {
    const double a = analysis_angular(k, cos_dtheta);
    return a * a;
  }
  // Steering weight b_i(phi): A(theta - phi) = sum_i b_i(phi) A(theta - theta_i).
  static double steering_weight(int k, int i, double phi) {
    const double d = detail::constants::kPi * static_cast<double>(i) / static_cast<double>(k) - phi;
    double sum = 0;
    for (int m = -(k - 1); m <= k - 1; m += 2) sum += std::cos(m * d);
    return sum / static_cast<double>(k);
  }
  // B(x) = cos^2(pi x / 2) for |x| < 1, else 0 (x in octaves from a centre).
  static double radial(double x) {
    if (!(std::fabs(x) < 1.0)) return 0.0;
    const double c = std::cos(0.5 * detail::constants::kPi * x);
    return c * c;
  }

  // ---- The filters at frequency w (cycles per unit).

  // D_{i,s}(w); 0 at w = 0.
  double subband(int i, int s, const dvec2& w) const {
    const double r = std::hypot(w.x, w.y);
    if (!(r > 0.0)) return 0.0;
    const double b = radial(std::log2(r / centre_frequency(s)));
    if (b == 0.0) return 0.0;
    return angular(orientations(), (w.x * dir_[i].x + w.y * dir_[i].y) / r) * b;
  }
  // The isotropic sum over orientations of scale s: B(log2(|w| / f_s)).
  double scale_band(int s, const dvec2& w) const {
    const double r = std::hypot(w.x, w.y);
    return r > 0.0 ? radial(std::log2(r / centre_frequency(s))) : 0.0;
  }
  // L(w): 1 below f_0 / 2, 1 - B above, 0 from f_0 on.
  double low_residual(const dvec2& w) const {
    const double r = std::hypot(w.x, w.y);
    if (!(r > 0.5 * centre_frequency(0))) return 1.0;
    const double x = std::log2(r / centre_frequency(0));
    return x >= 0.0 ? 0.0 : 1.0 - radial(x);
  }
  // R(w): 0 below f_{S-1}, 1 - B above, 1 from 2 f_{S-1} on.
  double high_residual(const dvec2& w) const {
    const double r = std::hypot(w.x, w.y);
    const double top = centre_frequency(scales() - 1);
    if (!(r > top)) return 0.0;
    const double x = std::log2(r / top);
    return x >= 1.0 ? 1.0 : 1.0 - radial(x);
  }
  // L + sum D + R: 1 everywhere (invertibility); for tests.
  double total(const dvec2& w) const {
    double t = low_residual(w) + high_residual(w);
    for (int s = 0; s < scales(); ++s)
      for (int i = 0; i < orientations(); ++i) t += subband(i, s, w);
    return t;
  }

 private:
  static double power(double c, int n) {
    double p = 1.0;
    for (int m = 0; m < n; ++m) p *= c;
    return p;
  }

  params prm_;
  dvec2 dir_[detail::constants::kAnisoMaxOrientations] = {};
};

// The decomposition of a periodic n x n image (row-major, n a power of two
// >= 2) by the bank, with frequencies in cycles per pixel: subband images
// n_{i,s} = IFFT(FFT(image) D_{i,s}) and the two residuals, each n x n,
// real (the filters are even). Their sum is the image (to about 1e-12
// relative). Throws hush::invalid_argument when n is not a power of two or
// the bank's top band does not fit below the Nyquist frequency (2 f_{S-1} <= 1/2
// is not required: the high residual takes what lies above).
struct steerable_decomposition {
  std::size_t size = 0;
  std::vector<std::vector<double>> subbands;  // index i + K s
  std::vector<double> low, high;              // residuals
};

inline steerable_decomposition decompose(const std::vector<double>& image, std::size_t n,
                                         const steerable_bank& bank) {
  if (!detail::is_power_of_two(n) || n < 2 || image.size() != n * n)
    hush::detail::raise_error(
        "hush::decompose: the image must be n x n with n a power of two >= 2 (got " +
        std::to_string(image.size()) + " pixels, n = " + std::to_string(n) + ")");
  using cd = std::complex<double>;
  std::vector<cd> spectrum(image.begin(), image.end());
  detail::fft2(spectrum.data(), n, -1);
  auto filtered = [&](auto filter) {
    std::vector<cd> a(n * n);
    for (std::size_t y = 0; y < n; ++y)
      for (std::size_t x = 0; x < n; ++x) {
        const dvec2 w{detail::bin_frequency(x, n), detail::bin_frequency(y, n)};
        a[y * n + x] = spectrum[y * n + x] * filter(w);
      }
    detail::fft2(a.data(), n, +1);
    std::vector<double> out(n * n);
    const double scale = 1.0 / static_cast<double>(n * n);
    for (std::size_t p = 0; p < n * n; ++p) out[p] = a[p].real() * scale;
    return out;
  };
  steerable_decomposition d;
  d.size = n;
  for (int s = 0; s < bank.scales(); ++s)
    for (int i = 0; i < bank.orientations(); ++i)
      d.subbands.push_back(filtered([&](const dvec2& w) { return bank.subband(i, s, w); }));
  d.low = filtered([&](const dvec2& w) { return bank.low_residual(w); });
  d.high = filtered([&](const dvec2& w) { return bank.high_residual(w); });
  return d;
}

}  // namespace hush

#endif  // HUSH_ANISOTROPIC_STEERABLE_HPP
