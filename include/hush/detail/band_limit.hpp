// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// How band-limited a sampled noise band is: the fraction of its power below
// half its peak radial frequency (Cook & DeRose sec. 1 and Fig. 8-9:
// Perlin noise leaks power into the octave below, wavelet noise does not).
// A measurement for tests, `hush bench` and the gallery; not part of the
// umbrella header.
//
//   band_limit_fraction(values, n, dx)
//
// Definition (every figure hush reports uses exactly this):
//  - values: an n x n row-major grid sample of one band, spacing dx (noise
//    units), n a power of two >= 8;
//  - the periodogram P(k) = |DFT2(h (v - m))|^2 with h the separable Hann
//    window (without it the image's edges, which the DFT sees as a tiling,
//    put a cross of power at low frequencies) and m the h-weighted mean of v
//    (so the windowed image has no DC), bin k at frequency
//    |f| = |k| / (n dx) (detail/fft.hpp's bin_frequency, per axis);
//  - the radially averaged spectrum: the mean of P over ring r, the bins with
//    round(|k|) = r, r = 1 ... n/2; its peak ring r* (the lowest on ties),
//    peak frequency f* = r* / (n dx);
//  - fraction = sum of P over the bins with 0 < |k| < r* / 2, divided by the
//    sum of P over all bins with |k| > 0.
// Range [0, 1]; statistical: each bin is ~exponential about the spectral
// density, so where the low power is spread over the bins below r*/2 the
// fraction's relative standard deviation is about 1 / sqrt(their number)
// (~5 % for r* = 22, 380 bins; twice that with the Hann window's correlation
// of neighbouring bins). Where a few bins dominate it varies far more: improved
// Perlin 2D measures 0.038 on [0, 64)^2 and 0.010 on the window of `hush
// bench` (seed 7). Non-finite values give NaN.
#ifndef HUSH_DETAIL_BAND_LIMIT_HPP
#define HUSH_DETAIL_BAND_LIMIT_HPP

#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

#include "hush/detail/constants.hpp"
#include "hush/detail/fft.hpp"

namespace hush {
namespace detail {

struct band_limit_result {
  double fraction = 0;        // power below f* / 2 over all power (see above)
  double peak_frequency = 0;  // f*, cycles per noise unit
};

inline band_limit_result band_limit_fraction(const std::vector<double>& values, std::size_t n,
                                             double dx) {
  band_limit_result r;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (n < 8 || !is_power_of_two(n) || values.size() != n * n || !(dx > 0)) return {nan, nan};
  std::vector<double> h(n);
  for (std::size_t i = 0; i < n; ++i)
    h[i] = 0.5 - 0.5 * std::cos(2 * constants::kPi * static_cast<double>(i) /
                                static_cast<double>(n));
  // The window-weighted mean: removing it zeroes the windowed image's DC exactly, so no
  // DC power leaks through the window's main lobe into ring 1.
  double mean = 0, hsum = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      mean += h[i] * h[j] * values[j * n + i];
      hsum += h[i] * h[j];
    }
  mean /= hsum;
  if (!std::isfinite(mean)) return {nan, nan};
  std::vector<std::complex<double>> a(n * n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) a[j * n + i] = h[i] * h[j] * (values[j * n + i] - mean);
  fft2(a.data(), n, -1);
  // Ring index of every bin (|k| in bins), ring sums and counts.
  const std::size_t rings = n / 2 + 1;
  std::vector<double> ring_sum(rings, 0.0), ring_count(rings, 0.0), radius(n * n);
  const double nn = static_cast<double>(n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const double kx = bin_frequency(i, n) * nn, ky = bin_frequency(j, n) * nn;
      const double k = std::sqrt(kx * kx + ky * ky);
      radius[j * n + i] = k;
      const auto ring = static_cast<std::size_t>(std::lround(k));
      if (ring >= 1 && ring < rings) {
        ring_sum[ring] += std::norm(a[j * n + i]);
        ring_count[ring] += 1;
      }
    }
  std::size_t peak = 1;
  for (std::size_t ring = 2; ring < rings; ++ring)
    if (ring_sum[ring] / ring_count[ring] > ring_sum[peak] / ring_count[peak]) peak = ring;
  double below = 0, total = 0;
  for (std::size_t b = 0; b < n * n; ++b) {
    if (radius[b] == 0) continue;
    const double p = std::norm(a[b]);
    total += p;
    if (radius[b] < 0.5 * static_cast<double>(peak)) below += p;
  }
  r.fraction = total > 0 ? below / total : nan;
  r.peak_frequency = static_cast<double>(peak) / (nn * dx);
  return r;
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_DETAIL_BAND_LIMIT_HPP
