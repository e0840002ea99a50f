// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// A small radix-2 FFT in double for power-of-two sizes: what the anisotropic
// noise needs to build its subband tiles and decompose images (anisotropic/steerable.hpp),
// without a dependency. hush's own rather than Eigen's FFT (unsupported/Eigen/FFT,
// which the tests use as the reference): it keeps hush/anisotropic.hpp in the
// umbrella and single headers (Eigen lives outside the default include path and
// costs seconds per translation unit), and its operation order is fixed, so
// tiles do not change with the FFT back end a user configures for Eigen.
//
//   fft(a, n, sign)   in-place DFT of n = 2^k complex values:
//                     A[k] = sum_j a[j] exp(sign 2 pi i j k / n), sign = -1 (forward)
//                     or +1 (inverse, unnormalised: divide by n yourself)
//   fft2(a, n, sign)  the same on an n x n row-major array: rows, then columns
// Accuracy: iterative Cooley-Tukey with twiddles from std::cos / std::sin of
// 2 pi k / n; the result is within about 2 log2(n) ulps (relative to the
// largest magnitude) of the exact DFT (tests/anisotropic/steerable_test.cpp compares it
// with Eigen's FFT and a direct DFT).
#ifndef HUSH_DETAIL_FFT_HPP
#define HUSH_DETAIL_FFT_HPP

#include <cmath>
#include <complex>
#include <cstddef>
#include <utility>
#include <vector>

#include "hush/detail/constants.hpp"

namespace hush {
namespace detail {

inline bool is_power_of_two(std::size_t n) { return n != 0 && (n & (n - 1)) == 0; }

// Twiddles exp(sign 2 pi i k / n), k < n / 2.
inline std::vector<std::complex<double>> fft_twiddles(std::size_t n, int sign) {
  std::vector<std::complex<double>> w(n / 2);
  for (std::size_t k = 0; k < n / 2; ++k) {
    const double angle = 2.0 * constants::kPi * static_cast<double>(k) / static_cast<double>(n);
    w[k] = {std::cos(angle), static_cast<double>(sign) * std::sin(angle)};
  }
  return w;
}

// In-place DFT of a[0 ... n-1] with the twiddles of (n, sign).
inline void fft(std::complex<double>* a, std::size_t n, const std::complex<double>* w) {
  if (n < 2) return;
  // Bit-reversal permutation.
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const std::size_t half = len / 2, stride = n / len;
    for (std::size_t i = 0; i < n; i += len)
      for (std::size_t k = 0; k < half; ++k) {
        // t = w a, written out: std::complex's operator* adds C99 Annex G's
        // NaN recovery (a libgcc call per product); the inputs here are finite.
        const std::complex<double> wk = w[k * stride], x = a[i + k + half];
        const std::complex<double> t(wk.real() * x.real() - wk.imag() * x.imag(),
                                     wk.real() * x.imag() + wk.imag() * x.real());
        a[i + k + half] = a[i + k] - t;
        a[i + k] = a[i + k] + t;
      }
  }
}

// In-place DFT of a[0 ... n-1], n a power of two (not checked: callers validate).
inline void fft(std::complex<double>* a, std::size_t n, int sign) {
  fft(a, n, fft_twiddles(n, sign).data());
}

// In-place 2D DFT of an n x n row-major array (n a power of two).
inline void fft2(std::complex<double>* a, std::size_t n, int sign) {
  const std::vector<std::complex<double>> w = fft_twiddles(n, sign);
  for (std::size_t r = 0; r < n; ++r) fft(a + r * n, n, w.data());
  std::vector<std::complex<double>> column(n);
  for (std::size_t c = 0; c < n; ++c) {
    for (std::size_t r = 0; r < n; ++r) column[r] = a[r * n + c];
    fft(column.data(), n, w.data());
    for (std::size_t r = 0; r < n; ++r) a[r * n + c] = column[r];
  }
}

// The signed frequency of DFT bin k of an n-point transform, in cycles per
// sample: k / n for k <= n / 2, (k - n) / n above.
inline double bin_frequency(std::size_t k, std::size_t n) {
  const auto kk = static_cast<double>(k), nn = static_cast<double>(n);
  return (2 * k <= n ? kk : kk - nn) / nn;
}

}  // namespace detail
}  // namespace hush

#endif  // HUSH_DETAIL_FFT_HPP
