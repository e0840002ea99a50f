// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// The spectrum error of 2D Gabor noise (docs/gabor.md, "Performance"): the
// quality note beside each gabor 2D bench row (issue 10), measured on the
// row's backend while the case is prepared.
//
// Definition: kImages fixed-seed images of kSide^2 samples kStep units apart
// (16 x 16 units, far apart from each other), each Hann-windowed and
// transformed (hush::detail::fft2) into a periodogram whose expectation is the
// power spectral density S(f); the periodograms are averaged over the images
// and over radial rings kRing cycles/unit wide, and so is the analytic
// spectrum (gabor_spectrum, tabulated gabor::power_spectrum, at the same bins). The spectrum error is the
// relative RMS difference over the rings that hold at least kFloor of the
// largest ring's power: sqrt(sum (P_r - S_r)^2 / sum S_r^2).
//
// It is not zero for a correct noise: each ring's mean has a sampling error.
// A bin's periodogram is exponential with mean S_r; the Hann window
// correlates neighbouring bins (|rho|^2 = 4/9 at lag 1 and 1/36 at lag 2 per
// axis, so a ring of K bins counts as K / kHannFactor independent ones), so
// the expected relative RMS from sampling alone is
// sqrt(sum S_r^2 kHannFactor / (kImages K_r) / sum S_r^2), printed beside it:
// a spectrum error near that figure is what a correct noise gives. The
// window's smoothing (about 2 bins, 1/8 cycle, against the ring's width a) adds
// a bias of about 1%.
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

constexpr std::size_t kSpectrumImages = 4;
constexpr std::size_t kSpectrumSide = 128;   // samples per image side (a power of two)
constexpr double kSpectrumStep = 1.0 / 8.0;  // units: Nyquist 4 cycles/unit, bins 1/16
constexpr double kSpectrumRing = 1.0 / 8.0;  // ring width, cycles/unit (two bins)
constexpr double kSpectrumFloor = 0.01;      // rings below 1% of the peak ring are left out
// Sum over lags of the Hann window's bin correlation |rho|^2, squared (two axes).
constexpr double kHannFactor = (1.0 + 2.0 * (4.0 / 9.0 + 1.0 / 36.0)) *
                               (1.0 + 2.0 * (4.0 / 9.0 + 1.0 / 36.0));

// "spectrum error E (sampling alone: S)" of `noise` evaluated on `ex`.
template <class Exec>
std::string gabor_spectrum_note(const hush::gabor<2>& noise, const Exec& ex) {
  constexpr std::size_t n = kSpectrumSide;
  std::vector<double> hann(n);
  double w2 = 0;
  for (std::size_t i = 0; i < n; ++i)
    hann[i] = 0.5 - 0.5 * std::cos(2.0 * hush::detail::constants::kPi * static_cast<double>(i) /
                                   static_cast<double>(n));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) w2 += hann[i] * hann[i] * hann[j] * hann[j];
  std::vector<double> mean_p(n * n, 0.0);
  std::vector<float> img(n * n);
  std::vector<std::complex<double>> a(n * n);
  for (std::size_t m = 0; m < kSpectrumImages; ++m) {
    hush::grid<2> g;
    g.origin = {1000.0 * static_cast<double>(m) + 0.3, -700.0 * static_cast<double>(m) - 0.6};
    g.step = {kSpectrumStep, kSpectrumStep};
    g.size = {n, n};
    hush::evaluate_grid(noise, ex, g, hush::span<float>(img));
    double mean = 0;
    for (const float v : img) mean += v;
    mean /= static_cast<double>(n * n);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i)
        a[j * n + i] = hann[i] * hann[j] * (static_cast<double>(img[j * n + i]) - mean);
    hush::detail::fft2(a.data(), n, -1);
    for (std::size_t k = 0; k < n * n; ++k)
      mean_p[k] += std::norm(a[k]) * kSpectrumStep * kSpectrumStep / w2 /
                   static_cast<double>(kSpectrumImages);
  }
  // Rings up to Nyquist: measured and analytic means and bin counts.
  const std::size_t rings = static_cast<std::size_t>(0.5 / kSpectrumStep / kSpectrumRing);
  std::vector<double> p(rings, 0.0), s(rings, 0.0), count(rings, 0.0);
  // The analytic spectrum, tabulated (gabor_spectrum: within 3e-5 of the peak; the
  // quadrature of power_spectrum per bin would take seconds).
  const hush::gabor_spectrum<2> spectrum(noise, std::sqrt(2.0) * 0.5 / kSpectrumStep);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const hush::dvec2 f{hush::detail::bin_frequency(i, n) / kSpectrumStep,
                          hush::detail::bin_frequency(j, n) / kSpectrumStep};
      const auto r = static_cast<std::size_t>(std::sqrt(f.x * f.x + f.y * f.y) / kSpectrumRing);
      if (r == 0 || r >= rings) continue;  // the mean's bin (removed) and the corners
      p[r] += mean_p[j * n + i];
      s[r] += spectrum(f);
      count[r] += 1.0;
    }
  double peak = 0;
  for (std::size_t r = 0; r < rings; ++r)
    if (count[r] > 0) peak = std::fmax(peak, s[r] / count[r]);
  double err2 = 0, ref2 = 0, noise2 = 0;
  for (std::size_t r = 0; r < rings; ++r) {
    if (count[r] == 0 || s[r] / count[r] < kSpectrumFloor * peak) continue;
    const double pm = p[r] / count[r], sm = s[r] / count[r];
    err2 += (pm - sm) * (pm - sm);
    ref2 += sm * sm;
    noise2 += sm * sm * kHannFactor / (static_cast<double>(kSpectrumImages) * count[r]);
  }
  char buf[96];
  std::snprintf(buf, sizeof buf, "spectrum error %.3f (sampling alone: %.3f)",
                std::sqrt(err2 / ref2), std::sqrt(noise2 / ref2));
  return buf;
}

}  // namespace hush_bench

#endif  // HUSH_BENCH_GABOR_QUALITY_HPP
