// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// gabor_spectrum<D>: the power spectrum of a gabor<D> noise, tabulated for many
// frequencies. Included at the end of hush/gabor.hpp, after the class it uses; not on
// its own.
#ifndef HUSH_GABOR_SPECTRUM_HPP
#define HUSH_GABOR_SPECTRUM_HPP

#include <cmath>
#include <cstddef>
#include <vector>

#include "hush/core/vec.hpp"
#include "hush/detail/constants.hpp"
#include "hush/gabor/kernel.hpp"

namespace hush {

// gabor_spectrum<D>: the power spectrum of a gabor<D> noise at many
// frequencies (spectrum images, tests): gabor<D>::spectrum_with with the
// kernel's envelope transform H tabulated once, every 1/64 cycle per cell up to
// the largest |f r| + |Phi| needed but at most kGaborSpectrumWindowCycles
// (4100 values, whatever F0 and a), and interpolated with Catmull-Rom cubics:
// H within 1.8e-6 H(0) in 2D and 1.4e-6 in 3D (t = 0.5, the worst of t in
// [1e-9, 0.5]; checked every 1/3200 cycle), so each ((H(k-) + H(k+)) / 2)^2
// within 3.6e-6 H(0)^2, and the spectrum within 3e-5 of its peak (measured
// against power_spectrum, every kind, 2D and 3D, F0 1e-6 ... 1e6, t 0.05 and
// 0.5, spreads and caps, 45 f each: <= 4.5e-6; docs/gabor.md "Exact
// statistics"). Beyond the table H is its leading asymptotic term, within
// 3.0e-8 H(0) (2D) and 3.1e-9 H(0) (3D) at k = 64, falling as k^-4.5: with
// the near blob in its core and the far one beyond the table (|Phi| > 32
// cycles per cell) that multiplies H(k-) <= H(0), so <= 1.5e-8 of H(0)^2
// there (not a tail: the earlier bound, 3e-14, assumed both blobs beyond
// the table). Isotropic noise's spectrum is radial: it
// is tabulated the same way against |f| (64 max_frequency r + 4 values: the
// caller's range). Frequencies above max_frequency (cycles per noise unit, any
// direction) give 0.
template <int D>
class gabor_spectrum {
 public:
  gabor_spectrum(const gabor<D>& noise, double max_frequency) : noise_(noise) {
    const double r = noise.kernel().radius();
    max_f_ = max_frequency;
    const double reach =
        std::fmin(max_frequency * r + noise.marks().phi0() + noise.marks().dphi(),
                  detail::constants::kGaborSpectrumWindowCycles);
    const auto n = static_cast<std::size_t>(std::ceil(reach * kPerCycle)) + 4;
    const double a = noise.kernel().envelope_exponent();
    a_ = a;
    h_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      h_[i] = detail::gabor_envelope_transform<D>(a, static_cast<double>(i) / kPerCycle);
    if (noise.parameters().kind == gabor_kind::isotropic) {
      // Radial: S(|f|) every 1/64 cycle per cell, from the tabulated H, where
      // it is not 0: from |Phi| - window on (spectrum_with leaves out |f r|
      // further than the window from the ring once |Phi| > window) to
      // max_frequency or |Phi| + window, at most 64 * 2 window + 4 values.
      // Starting above 0, the first value's left neighbour is taken as its
      // right one (evenness at 0): at the window's edge the values are ~1e-12
      // of the peak, and so is that error.
      const double window = detail::constants::kGaborSpectrumWindowCycles, phi = noise.marks().phi0();
      radial_lo_ = std::floor(std::fmax(0.0, phi - window) * kPerCycle) / kPerCycle;
      const double hi = std::fmin(max_frequency * r, phi + window);
      radial_.resize(static_cast<std::size_t>(std::ceil(std::fmax(hi - radial_lo_, 0.0) * kPerCycle)) + 4);
      for (std::size_t i = 0; i < radial_.size(); ++i) {
        vec<double, D> f{};
        f[0] = (radial_lo_ + static_cast<double>(i) / kPerCycle) / r;
        radial_[i] = noise_.spectrum_with(f, [this](double k) { return h(k); });
      }
    }
  }

  double operator()(const vec<double, D>& f) const {
    double len = 0;
    for (int i = 0; i < D; ++i) len += f[i] * f[i];
    len = std::sqrt(len);
    if (!(len <= max_f_)) return 0.0;
    if (!radial_.empty()) {
      const double x = len * noise_.kernel().radius() - radial_lo_;
      return x < 0.0 ? 0.0 : cubic(radial_, x);
    }
    return noise_.spectrum_with(f, [this](double k) { return h(k); });
  }

 private:
  static constexpr double kPerCycle = 64.0;
  // H from the table, its asymptotic term beyond it.
  double h(double k) const {
    if (k * kPerCycle + 2.0 < static_cast<double>(h_.size())) return cubic(h_, k);
    return detail::gabor_envelope_transform_tail<D>(a_, k);
  }
  // Catmull-Rom interpolation of an even function tabulated at k = i / 64
  // (the evenness supplies the point left of 0).
  static double cubic(const std::vector<double>& h, double k) {
    const double x = k * kPerCycle;
    const auto i = static_cast<std::size_t>(x);
    if (i + 2 >= h.size()) return h.back();
    const double t = x - static_cast<double>(i);
    const double p0 = i == 0 ? h[1] : h[i - 1], p1 = h[i], p2 = h[i + 1], p3 = h[i + 2];
    return p1 + 0.5 * t *
                    (p2 - p0 +
                     t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
  }

  gabor<D> noise_;
  double max_f_ = 0, a_ = 0, radial_lo_ = 0;
  std::vector<double> h_, radial_;
};

}  // namespace hush

#endif  // HUSH_GABOR_SPECTRUM_HPP
