// Helpers of hush::gabor's suites (gabor_test.cpp, gabor_slow_test.cpp,
// gabor_kernel_test.cpp):
// parameters, sample moments, independent points, periodograms and their
// comparison with the exact spectrum, bin by bin set.
#ifndef HUSH_TESTS_GABOR_TEST_UTIL_HPP
#define HUSH_TESTS_GABOR_TEST_UTIL_HPP

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"

namespace gabor_test_util {

constexpr double kPi = hush::detail::constants::kPi;
using hush::gabor_kind;

template <int D>
typename hush::gabor<D>::params make_params(gabor_kind kind, std::uint32_t seed = 1) {
  typename hush::gabor<D>::params p;
  p.seed = seed;
  p.kind = kind;
  p.orientation = 0.6;
  p.elevation = 0.3;
  if (kind == gabor_kind::hybrid) {
    p.orientation_spread = 1.2;
    p.frequency_spread = 0.6;
  }
  return p;
}

// Mean, variance and the variance's standard error from i.i.d. samples:
// SE(var) = sqrt((m4 - var^2) / n), SE(mean) = sqrt(var / n).
struct moments {
  double mean = 0, var = 0, se_mean = 0, se_var = 0;
};
inline moments moments_of(const std::vector<double>& v) {
  const double n = static_cast<double>(v.size());
  double m = 0;
  for (const double x : v) m += x;
  m /= n;
  double m2 = 0, m4 = 0;
  for (const double x : v) {
    const double d = (x - m) * (x - m);
    m2 += d;
    m4 += d * d;
  }
  m2 /= n;
  m4 /= n;
  return {m, m2, std::sqrt(m2 / n), std::sqrt((m4 - m2 * m2) / n)};
}

// Positions whose 3^D cell neighbourhoods are disjoint (cells 3 apart along
// x), so the noise values there are independent: i.i.d. samples of the
// stationary process. `cell` is the process's cell side.
template <int D>
std::vector<hush::vec<double, D>> independent_points(double cell, int n, std::uint32_t seed) {
  hush::rng r(seed, 77);
  std::vector<hush::vec<double, D>> pts(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    hush::vec<double, D> p;
    p[0] = (3.0 * (i % 1000) + r.uniform<double>()) * cell;
    p[1] = (3.0 * (i / 1000) + r.uniform<double>()) * cell;
    if constexpr (D == 3) p[2] = (r.uniform<double>() - 0.5) * 1000.0 * cell;
    pts[static_cast<std::size_t>(i)] = p;
  }
  return pts;
}

// Radix-2 complex FFT in place (own code: Cooley-Tukey, bit reversal).
inline void fft(std::vector<std::complex<double>>& a) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double ang = -2 * kPi / static_cast<double>(len);
    const std::complex<double> wl(std::cos(ang), std::sin(ang));
    for (std::size_t i = 0; i < n; i += len) {
      std::complex<double> w(1);
      for (std::size_t k = 0; k < len / 2; ++k, w *= wl) {
        const std::complex<double> u = a[i + k], v = a[i + k + len / 2] * w;
        a[i + k] = u + v;
        a[i + k + len / 2] = u - v;
      }
    }
  }
}

// Periodogram of an n x n image sampled at spacing dx, Hann-windowed and
// normalised so that its expectation is the spectral density S(f) (for a
// spectrum that varies slowly over a few bins and does not alias):
// P = |FFT(w (v - mean))|^2 dx^2 / sum w^2, frequency bin k at k / (n dx).
inline std::vector<double> periodogram(const std::vector<double>& img, std::size_t n, double dx) {
  double mean = 0;
  for (const double v : img) mean += v;
  mean /= static_cast<double>(img.size());
  std::vector<double> w(n);
  double w2 = 0;
  for (std::size_t i = 0; i < n; ++i)
    w[i] = 0.5 - 0.5 * std::cos(2 * kPi * static_cast<double>(i) / static_cast<double>(n));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) w2 += w[i] * w[i] * w[j] * w[j];
  std::vector<std::complex<double>> rows(n * n), line(n);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t i = 0; i < n; ++i) line[i] = w[i] * w[j] * (img[j * n + i] - mean);
    fft(line);
    for (std::size_t i = 0; i < n; ++i) rows[j * n + i] = line[i];
  }
  std::vector<double> p(n * n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) line[j] = rows[j * n + i];
    fft(line);
    for (std::size_t j = 0; j < n; ++j) p[j * n + i] = std::norm(line[j]) * dx * dx / w2;
  }
  return p;
}

// The signed frequency of bin k of an n-point DFT at spacing dx.
inline double bin_frequency(std::size_t k, std::size_t n, double dx) {
  const double kk =
      k < n / 2 ? static_cast<double>(k) : static_cast<double>(k) - static_cast<double>(n);
  return kk / (static_cast<double>(n) * dx);
}

// Measured against expected averages of the periodogram over bin sets. Each
// bin's periodogram is ~exponential with mean S; Hann windowing correlates
// neighbouring bins, |rho|^2 = 4/9 at lag 1 and 1/36 at lag 2 per axis, so the
// variance of a mean over n bins and m images is at most S^2 (1 + 8/9 +
// 1/18)^2 / (n m). Accepted: within 5 standard errors plus the window's
// smoothing bias, (1/6) max|lap S| bin^2 (its spectral window has a second
// moment of 1/3 bin^2 per axis). Aliases are left out: beyond the Nyquist
// frequency the spectra compared here hold under 1e-5 of the peak, and only
// bin sets above 1% of the peak are compared.
struct bin_set_check {
  double measured = 0, expected = 0, tolerance = 0;
};

template <class Spectrum>
std::vector<bin_set_check> compare_bins(const std::vector<std::vector<double>>& periodograms,
                                        std::size_t n, double dx, const Spectrum& spectrum,
                                        const std::vector<int>& set_of_bin, int sets) {
  const auto u_sets = static_cast<std::size_t>(sets);
  std::vector<double> sum_p(u_sets, 0), sum_s(u_sets, 0), count(u_sets, 0), curv(u_sets, 0);
  // The expected spectrum at the bins of the sets and their neighbours.
  std::vector<double> expected(n * n, -1.0);
  auto at = [&](std::size_t i, std::size_t j) {
    double& e = expected[(j % n) * n + (i % n)];
    if (e < 0) e = spectrum(bin_frequency(i % n, n, dx), bin_frequency(j % n, n, dx));
    return e;
  };
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const int set = set_of_bin[j * n + i];
      if (set < 0) continue;
      const auto u = static_cast<std::size_t>(set);
      const double s = at(i, j);
      for (const auto& p : periodograms) sum_p[u] += p[j * n + i];
      sum_s[u] += s;
      count[u] += 1;
      const double lap = at(i + 1, j) + at(i + n - 1, j) + at(i, j + 1) + at(i, j + n - 1) - 4 * s;
      curv[u] = std::fmax(curv[u], std::fabs(lap));
    }
  std::vector<bin_set_check> out(u_sets);
  const double m = static_cast<double>(periodograms.size());
  const double rho = (1 + 8.0 / 9.0 + 1.0 / 18.0) * (1 + 8.0 / 9.0 + 1.0 / 18.0);
  for (std::size_t u = 0; u < out.size(); ++u) {
    if (count[u] == 0) continue;
    out[u].measured = sum_p[u] / (count[u] * m);
    out[u].expected = sum_s[u] / count[u];
    out[u].tolerance = 5 * out[u].expected * std::sqrt(rho / (count[u] * m)) + curv[u] / 6;
  }
  return out;
}

// ---- The spectra's quadratures (gabor_kernel_test.cpp, gabor_slow_test.cpp).

// A stand-in for H (cell units) with its structure and the worst tail the
// asymptotics allow (docs/gabor.md: |H(k) - core| <= 1.7 H(0) k^-3.5 in 2D,
// 1.2 k^-4 in 3D, t = 0.5): the Gaussian core plus two cosines at the taper's
// radii (<= 1 cycle per unit k), even and smooth in k like H, at 1 / 40 of
// the real quadrature's cost, so the full orientation average stays cheap.
template <int D>
double stand_in_h(double A, double k) {
  const double core = std::pow(kPi / A, 0.5 * D), k2 = k * k;
  const double tail = (D == 2 ? 1.7 : 1.2) * core * std::pow(1.0 + k2, D == 2 ? -1.75 : -2.0);
  return core * std::exp(-kPi * kPi * k2 / A) +
         0.5 * tail * (std::cos(2 * kPi * std::sqrt(hush::detail::constants::kGaborTaperStart) * k) + std::cos(2 * kPi * k));
}

// stand_in_h<D>(A, .) counting its calls in `calls`.
template <int D>
auto counted_stand_in(double A, long& calls) {
  return [A, &calls](double k) {
    ++calls;
    return stand_in_h<D>(A, k);
  };
}

// Hybrid 3D noise's spectrum the way hush computed it before the caps
// (power_spectrum's cost ~ |Phi|^2 |xi| per value): |Phi| by panels 1 / 2
// wide, on each sphere the cap in its own polar cosine (panels ~ |Phi| |xi|)
// and azimuth (trapezoidal, nodes ~ |Phi|). Smooth, periodic in the azimuth:
// accurate where it is affordable.
template <class H>
double old_hybrid_3d_mean(const hush::gabor<3>& g, const hush::dvec3& xi, H h) {
  const auto& m = g.marks();
  const double reach = m.phi0() + 0.5 * m.dphi(), cap = m.cos_cap();
  const double xi_len = std::sqrt(xi.x * xi.x + xi.y * xi.y + xi.z * xi.z);
  auto one = [&](const hush::dvec3& phi) {
    const hush::dvec3 lo{xi.x - phi.x, xi.y - phi.y, xi.z - phi.z};
    const hush::dvec3 hi{xi.x + phi.x, xi.y + phi.y, xi.z + phi.z};
    const double v = 0.5 * (h(std::sqrt(lo.x * lo.x + lo.y * lo.y + lo.z * lo.z)) +
                            h(std::sqrt(hi.x * hi.x + hi.y * hi.y + hi.z * hi.z)));
    return v * v;
  };
  auto sphere = [&](double ph) {
    const int n = 32 + static_cast<int>(std::ceil(32.0 * reach));
    const int panels = 2 + static_cast<int>(std::ceil(4.0 * reach * (xi_len + 1.0)));
    auto ring = [&](double ct) {
      double sum = 0;
      const double st = std::sqrt(std::fmax((1.0 - ct) * (1.0 + ct), 0.0));
      for (int i = 0; i < n; ++i) {
        const double lx = st * std::cos(2.0 * kPi * i / n), ly = st * std::sin(2.0 * kPi * i / n);
        hush::dvec3 phi;
        for (int k = 0; k < 3; ++k)
          phi[k] = ph * ((m.frame_t()[k] * lx + m.frame_b()[k] * ly) + m.frame_axis()[k] * ct);
        sum += one(phi);
      }
      return sum / n;
    };
    return hush::detail::integrate(ring, cap, 1.0, panels) / (1.0 - cap);
  };
  const int panels = 1 + static_cast<int>(std::ceil(2.0 * m.dphi()));
  return hush::detail::integrate(sphere, m.phi0() - 0.5 * m.dphi(), m.phi0() + 0.5 * m.dphi(),
                                 panels) /
         m.dphi();
}

inline hush::gabor<3> hybrid_3d(double cycles, double spread_cycles, double cap_angle, double truncation) {
  hush::gabor<3>::params p;
  p.kind = hush::gabor_kind::hybrid;
  const double r = hush::gabor_kernel<3>(0.8, truncation).radius();
  p.frequency = cycles / r;
  p.frequency_spread = spread_cycles / r;
  p.truncation = truncation;
  p.orientation = 0.5236;
  p.elevation = 0.3;
  p.orientation_spread = cap_angle;
  return hush::gabor<3>(p);
}

// xi (cycles per cell) at `cycles` from 0, `angle` radians from the cap's
// axis, in the plane of the axis and frame_t.
inline hush::dvec3 off_axis(const hush::gabor<3>& g, double cycles, double angle) {
  const auto& m = g.marks();
  hush::dvec3 xi;
  for (int k = 0; k < 3; ++k)
    xi[k] = cycles * (std::cos(angle) * m.frame_axis()[k] + std::sin(angle) * m.frame_t()[k]);
  return xi;
}


}  // namespace gabor_test_util

#endif  // HUSH_TESTS_GABOR_TEST_UTIL_HPP
