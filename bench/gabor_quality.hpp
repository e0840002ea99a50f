// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The spectrum error of Gabor noise (docs/gabor.md, "Measured figures"): the
// quality note beside each unfiltered gabor 2D and 3D bench row,
// measured on the row's backend while the case is prepared.
//
// Definition (2D and 3D alike): kImages fixed-seed images (3D: volumes) of
// kSide^D samples kStep units apart (spectrum_setup below; far apart from
// each other), each Hann-windowed and transformed (hush::detail::fft2, and
// along z in 3D) into a periodogram whose expectation is the power spectral
// density S(f); the periodograms are averaged over the images and over radial
// rings (3D: spherical shells) kRing cycles/unit wide, and so is the analytic
// spectrum (gabor_spectrum, tabulated gabor::power_spectrum, at the same
// bins). The spectrum error is the relative RMS difference over the rings that
// hold at least kFloor of the largest ring's power: sqrt(sum (P_r - S_r)^2 /
// sum S_r^2).
//
// It is not zero for a correct noise: each ring's mean has a sampling error.
// A bin's periodogram is exponential with mean S_r; the Hann window
// correlates neighbouring bins (|rho|^2 = 4/9 at lag 1 and 1/36 at lag 2 per
// axis, so a ring of K bins counts as K / kHannAxisFactor^D independent ones),
// so the expected relative RMS from sampling alone is
// sqrt(sum S_r^2 kHannAxisFactor^D / (kImages K_r) / sum S_r^2), printed
// beside it: a spectrum error near that figure is what a correct noise gives.
// The window's smoothing (a bin variance of 1/3 bin^2 per axis: 2D bins 1/16,
// 3D 1/12.8 cycle/unit, against the spectrum's radial standard deviation
// a / (2 sqrt pi) = 0.23 cycle/unit) adds a bias of about 1% (2D) and 2% (3D).
#ifndef HUSH_BENCH_GABOR_QUALITY_HPP
#define HUSH_BENCH_GABOR_QUALITY_HPP

#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "hush/detail/constants.hpp"
#include "hush/detail/fft.hpp"
#include "hush/exec.hpp"
#include "hush/gabor.hpp"

namespace hush_bench {

// The sample set of each dimension: kImages images of kSide^D samples kStep
// units apart (2D: 16 x 16 units; 3D: 12.8^3 units, bins 1/12.8 cycle/unit).
template <int D>
struct spectrum_setup;
template <>
struct spectrum_setup<2> {
  static constexpr std::size_t kImages = 4;
  static constexpr std::size_t kSide = 128;   // samples per image side (a power of two)
  static constexpr double kStep = 1.0 / 8.0;  // units: Nyquist 4 cycles/unit, bins 1/16
};
template <>
struct spectrum_setup<3> {
  // One 64^3 volume (262144 samples, what four 2D images hold): rings in 3D hold
  // ~40 times more bins than in 2D at the same radius, so one suffices.
  static constexpr std::size_t kImages = 1;
  static constexpr std::size_t kSide = 64;
  static constexpr double kStep = 1.0 / 5.0;  // Nyquist 2.5 cycles/unit (F0 = 1), bins 1/12.8
};
constexpr double kSpectrumRing = 1.0 / 8.0;  // ring (shell) width, cycles/unit
constexpr double kSpectrumFloor = 0.01;      // rings below 1% of the peak ring are left out
// Sum over lags of the Hann window's bin correlation |rho|^2 along one axis.
constexpr double kHannAxisFactor = 1.0 + 2.0 * (4.0 / 9.0 + 1.0 / 36.0);

// In-place D-dimensional DFT of a kSide^D array, x fastest (fft2 per xy slice,
// then 1D transforms along z).
template <int D>
void spectrum_fft(std::vector<std::complex<double>>& a, std::size_t n) {
  if constexpr (D == 2) {
    hush::detail::fft2(a.data(), n, -1);
  } else {
    for (std::size_t k = 0; k < n; ++k) hush::detail::fft2(a.data() + k * n * n, n, -1);
    const std::vector<std::complex<double>> w = hush::detail::fft_twiddles(n, -1);
    std::vector<std::complex<double>> column(n);
    for (std::size_t c = 0; c < n * n; ++c) {
      for (std::size_t k = 0; k < n; ++k) column[k] = a[k * n * n + c];
      hush::detail::fft(column.data(), n, w.data());
      for (std::size_t k = 0; k < n; ++k) a[k * n * n + c] = column[k];
    }
  }
}

// "spectrum error E (sampling alone: S)" of `noise` evaluated on `ex`.
template <int D, class Exec>
std::string gabor_spectrum_note(const hush::gabor<D>& noise, const Exec& ex) {
  using setup = spectrum_setup<D>;
  constexpr std::size_t n = setup::kSide;
  constexpr double step = setup::kStep;
  std::size_t total = 1;
  for (int a = 0; a < D; ++a) total *= n;
  std::vector<double> hann(n);
  for (std::size_t i = 0; i < n; ++i)
    hann[i] = 0.5 - 0.5 * std::cos(2.0 * hush::detail::constants::kPi * static_cast<double>(i) /
                                   static_cast<double>(n));
  // The window of sample k (x fastest) and its energy.
  auto window = [&](std::size_t k) {
    double w = 1;
    for (int a = 0; a < D; ++a, k /= n) w *= hann[k % n];
    return w;
  };
  double w2 = 0;
  for (std::size_t k = 0; k < total; ++k) w2 += window(k) * window(k);
  double cell = 1;  // the sample cell's volume, step^D
  for (int a = 0; a < D; ++a) cell *= step;
  std::vector<double> mean_p(total, 0.0);
  std::vector<float> img(total);
  std::vector<std::complex<double>> spec(total);
  for (std::size_t m = 0; m < setup::kImages; ++m) {
    hush::grid<D> g;
    const double shift[3] = {1000.0, -700.0, 450.0}, off[3] = {0.3, -0.6, 0.45};
    for (int ax = 0; ax < D; ++ax) {
      g.origin[ax] = shift[ax] * static_cast<double>(m) + off[ax];
      g.step[ax] = step;
      g.size[ax] = n;
    }
    hush::evaluate_grid(noise, ex, g, hush::span<float>(img));
    double mean = 0;
    for (const float v : img) mean += v;
    mean /= static_cast<double>(total);
    for (std::size_t k = 0; k < total; ++k)
      spec[k] = window(k) * (static_cast<double>(img[k]) - mean);
    spectrum_fft<D>(spec, n);
    for (std::size_t k = 0; k < total; ++k)
      mean_p[k] += std::norm(spec[k]) * cell / w2 / static_cast<double>(setup::kImages);
  }
  // Rings up to Nyquist: measured and analytic means and bin counts.
  const std::size_t rings = static_cast<std::size_t>(0.5 / step / kSpectrumRing);
  std::vector<double> p(rings, 0.0), s(rings, 0.0), count(rings, 0.0);
  // The analytic spectrum, tabulated (gabor_spectrum: within 3e-5 of the peak; the
  // quadrature of power_spectrum per bin would take seconds).
  const hush::gabor_spectrum<D> spectrum(noise, std::sqrt(double(D)) * 0.5 / step);
  for (std::size_t k = 0; k < total; ++k) {
    hush::vec<double, D> f;
    double f2 = 0;
    for (std::size_t a = 0, rest = k; a < D; ++a, rest /= n) {
      f[a] = hush::detail::bin_frequency(rest % n, n) / step;
      f2 += f[a] * f[a];
    }
    const auto r = static_cast<std::size_t>(std::sqrt(f2) / kSpectrumRing);
    if (r == 0 || r >= rings) continue;  // the mean's bin (removed) and the corners
    p[r] += mean_p[k];
    s[r] += spectrum(f);
    count[r] += 1.0;
  }
  double hann_factor = 1;
  for (int ax = 0; ax < D; ++ax) hann_factor *= kHannAxisFactor;
  double peak = 0;
  for (std::size_t r = 0; r < rings; ++r)
    if (count[r] > 0) peak = std::fmax(peak, s[r] / count[r]);
  double err2 = 0, ref2 = 0, noise2 = 0;
  for (std::size_t r = 0; r < rings; ++r) {
    if (count[r] == 0 || s[r] / count[r] < kSpectrumFloor * peak) continue;
    const double pm = p[r] / count[r], sm = s[r] / count[r];
    err2 += (pm - sm) * (pm - sm);
    ref2 += sm * sm;
    noise2 += sm * sm * hann_factor / (static_cast<double>(setup::kImages) * count[r]);
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "spectrum error %.3f (sampling alone: %.3f)",
                std::sqrt(err2 / ref2), std::sqrt(noise2 / ref2));
  return buf;
}

}  // namespace hush_bench

#endif  // HUSH_BENCH_GABOR_QUALITY_HPP
