// hush::gabor (gabor.hpp): sparse Gabor convolution noise. Parameters,
// exact statistics (mean, unit variance, power spectrum radially and angularly,
// for every kind, 2D, 3D and on surfaces), the analytic gradient, the float
// budget, filtering and the hard cases. Tolerances come from the sample sizes
// (formulas beside each test); the spectra are gabor_spectrum's exact values.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "hush/hush.hpp"

namespace {

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
moments moments_of(const std::vector<double>& v) {
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
void fft(std::vector<std::complex<double>>& a) {
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
std::vector<double> periodogram(const std::vector<double>& img, std::size_t n, double dx) {
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
double bin_frequency(std::size_t k, std::size_t n, double dx) {
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

}  // namespace

// ---- Parameters.

TEST_CASE("gabor: every parameter out of range is refused, naming it and its range") {
  auto refused = [](auto mutate, const char* name) {
    hush::gabor<2>::params p;
    mutate(p);
    try {
      const hush::gabor<2> g(p);
      return false;
    } catch (const hush::invalid_argument& e) {
      const std::string m = e.what();
      return m.find(std::string("hush::gabor: ") + name + " = ") != std::string::npos &&
             m.find("valid: ") != std::string::npos;
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using P = hush::gabor<2>::params;
  CHECK(refused([](P& p) { p.frequency = -0.1; }, "frequency"));
  CHECK(refused([&](P& p) { p.frequency = nan; }, "frequency"));
  CHECK(refused([](P& p) { p.frequency = 2e6; }, "frequency"));
  CHECK(refused([](P& p) { p.bandwidth = 0; }, "bandwidth"));
  CHECK(refused([&](P& p) { p.bandwidth = inf; }, "bandwidth"));
  CHECK(refused([](P& p) { p.truncation = 0.7; }, "truncation"));
  CHECK(refused([](P& p) { p.truncation = 0; }, "truncation"));
  CHECK(refused([](P& p) { p.impulses = 0; }, "impulses"));
  CHECK(refused([](P& p) { p.impulses = 257; }, "impulses"));
  CHECK(refused([&](P& p) { p.impulses = nan; }, "impulses"));
  CHECK(refused([&](P& p) { p.orientation = inf; }, "orientation"));
  CHECK(refused([&](P& p) { p.elevation = nan; }, "elevation"));
  CHECK(refused([](P& p) { p.orientation_spread = 7; }, "orientation_spread"));
  CHECK(refused([](P& p) { p.orientation_spread = -1; }, "orientation_spread"));
  CHECK(refused([](P& p) { p.frequency_spread = 2.5; }, "frequency_spread"));  // > 2 F0
  CHECK(refused([](P& p) { p.kind = static_cast<gabor_kind>(9); }, "kind"));
  // The extremes of every range are accepted, in 2D and 3D.
  hush::gabor<3>::params p3;
  p3.impulses = 256;
  p3.truncation = 1e-9;
  p3.kind = gabor_kind::hybrid;
  p3.orientation_spread = 2 * kPi;
  p3.frequency_spread = 2.0;
  CHECK_NOTHROW(hush::gabor<3>{p3});
  hush::gabor<2>::params p2;
  p2.frequency = 0;
  p2.impulses = 1e-3;
  CHECK_NOTHROW(hush::gabor<2>{p2});
}

// ---- Statistics.

TEST_CASE("gabor: mean 0 and variance 1 over space and seeds, every kind, 2D and 3D") {
  // 20000 i.i.d. samples per configuration: |mean| <= 5 SE(mean) and
  // |var - 1| <= 5 SE(var), the SEs from the samples (moments_of).
  for (const gabor_kind kind :
       {gabor_kind::isotropic, gabor_kind::anisotropic, gabor_kind::hybrid}) {
    const hush::gabor<2> g2(make_params<2>(kind, 3));
    std::vector<double> v2;
    for (const auto& p : independent_points<2>(g2.kernel().radius(), 20000, 1)) v2.push_back(g2(p));
    const moments m2 = moments_of(v2);
    INFO("2D kind " << static_cast<int>(kind) << ": mean " << m2.mean << " var " << m2.var);
    CHECK(std::fabs(m2.mean) <= 5 * m2.se_mean);
    CHECK(std::fabs(m2.var - 1) <= 5 * m2.se_var);
    const hush::gabor<3> g3(make_params<3>(kind, 4));
    std::vector<double> v3;
    for (const auto& p : independent_points<3>(g3.kernel().radius(), 8000, 2)) v3.push_back(g3(p));
    const moments m3 = moments_of(v3);
    INFO("3D kind " << static_cast<int>(kind) << ": mean " << m3.mean << " var " << m3.var);
    CHECK(std::fabs(m3.mean) <= 5 * m3.se_mean);
    CHECK(std::fabs(m3.var - 1) <= 5 * m3.se_var);
  }
}

TEST_CASE("gabor: surface noise has mean 0 and variance 1 on planes of any orientation") {
  // The projection of the slab's impulses is a 2D Poisson process: on a plane
  // the variance is exactly 1 whatever the normal (isotropic noise). 8000
  // i.i.d. samples per plane (surface cells 3 apart), 5 SE.
  const hush::gabor<3> g(make_params<3>(gabor_kind::isotropic, 5));
  const double cell = 1.0 / g.inverse_surface_cell();
  for (const hush::dvec3 n :
       {hush::dvec3{0, 0, 1}, hush::dvec3{1, 1, 1}, hush::dvec3{-0.2, 0.9, -0.1}}) {
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    const hush::dvec3 u{n.x / len, n.y / len, n.z / len};
    hush::dvec3 t, b;
    hush::detail::orthonormal_basis(u, t, b);
    std::vector<double> v;
    hush::rng r(6);
    for (int i = 0; i < 8000; ++i) {
      const double s = (3.0 * (i % 100) + r.uniform<double>()) * 2 * cell;
      const double q = (3.0 * (i / 100) + r.uniform<double>()) * 2 * cell;
      const hush::dvec3 p{s * t.x + q * b.x + 0.37, s * t.y + q * b.y - 5.2,
                          s * t.z + q * b.z + 1.1};
      v.push_back(g.sample(p, u));
    }
    const moments m = moments_of(v);
    INFO("normal " << u.x << ", " << u.y << ", " << u.z << ": mean " << m.mean << " var " << m.var);
    CHECK(std::fabs(m.mean) <= 5 * m.se_mean);
    CHECK(std::fabs(m.var - 1) <= 5 * m.se_var);
  }
}

TEST_CASE("gabor: the measured power spectrum is the analytic one, radially and angularly [slow]") {
  // 8 images of 256 x 256 samples at spacing 1/8 (Nyquist 4 cycles per unit)
  // per kind. Isotropic noise: rings of width 1/8 cycle; anisotropic and
  // hybrid noise: 18 angular sectors of the annulus 0.6 ... 1.4 around F0.
  // Only bin sets whose expected density is at least 1% of the peak (Hann's
  // side lobes leak ~1e-4 of the peak into the valleys).
  constexpr std::size_t n = 256;
  const double dx = 1.0 / 8;
  for (const gabor_kind kind :
       {gabor_kind::isotropic, gabor_kind::anisotropic, gabor_kind::hybrid}) {
    std::vector<std::vector<double>> ps;
    hush::gabor<2> g(make_params<2>(kind, 0));
    for (std::uint32_t seed = 0; seed < 8; ++seed) {
      g = hush::gabor<2>(make_params<2>(kind, seed + 10));
      std::vector<double> img(n * n);
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i)
          img[j * n + i] = g(hush::dvec2{double(i) * dx + 1000.0 * seed, double(j) * dx - 77.0});
      ps.push_back(periodogram(img, n, dx));
    }
    const hush::gabor_spectrum<2> spectrum(g, 12.0);
    auto s = [&](double fx, double fy) { return spectrum({fx, fy}); };
    std::vector<int> sets(n * n, -1);
    int count = 0;
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const double fx = bin_frequency(i, n, dx), fy = bin_frequency(j, n, dx);
        const double rad = std::hypot(fx, fy);
        if (rad < 2.0 / (n * dx)) continue;  // DC and its neighbours: the mean was removed
        if (kind == gabor_kind::isotropic) {
          sets[j * n + i] = static_cast<int>(rad * 8);
          count = std::max(count, sets[j * n + i] + 1);
        } else if (rad > 0.6 && rad < 1.4) {
          const double ang = std::atan2(fy, fx);  // (-pi, pi]: 18 sectors of 20 degrees
          sets[j * n + i] = std::min(17, static_cast<int>((ang + kPi) / (2 * kPi) * 18));
          count = 18;
        }
      }
    const auto checks = compare_bins(ps, n, dx, s, sets, count);
    double peak = 0;
    for (const auto& c : checks) peak = std::fmax(peak, c.expected);
    int compared = 0;
    for (std::size_t u = 0; u < checks.size(); ++u) {
      const auto& c = checks[u];
      if (c.expected < 0.01 * peak) continue;
      ++compared;
      INFO("kind " << static_cast<int>(kind) << " set " << u << ": measured " << c.measured
                   << " expected " << c.expected << " tolerance " << c.tolerance);
      CHECK(std::fabs(c.measured - c.expected) <= c.tolerance);
    }
    CHECK(compared >= 6);
  }
}

TEST_CASE(
    "gabor: surface noise on a plane has the 2D noise spectrum, a 3D slice the projected one "
    "[slow]") {
  constexpr std::size_t n = 128;
  const double dx = 1.0 / 6;
  // Surface noise on the plane z = 0.3 (normal z) against hush::gabor<2>'s
  // spectrum with the same parameters: rings of width 1/4 cycle.
  {
    std::vector<std::vector<double>> ps;
    for (std::uint32_t seed = 0; seed < 6; ++seed) {
      const hush::gabor<3> g(make_params<3>(gabor_kind::isotropic, seed + 20));
      std::vector<double> img(n * n);
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i)
          img[j * n + i] = g.sample(hush::dvec3{double(i) * dx + 50.0 * seed, double(j) * dx, 0.3},
                                    hush::dvec3{0, 0, 1});
      ps.push_back(periodogram(img, n, dx));
    }
    const hush::gabor<2> flat(make_params<2>(gabor_kind::isotropic, 0));
    const hush::gabor_spectrum<2> spectrum(flat, 12.0);
    auto s = [&](double fx, double fy) { return spectrum({fx, fy}); };
    std::vector<int> sets(n * n, -1);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const double rad = std::hypot(bin_frequency(i, n, dx), bin_frequency(j, n, dx));
        if (rad >= 2.0 / (n * dx)) sets[j * n + i] = static_cast<int>(rad * 4);
      }
    const auto checks = compare_bins(ps, n, dx, s, sets, 16);
    double peak = 0;
    for (const auto& c : checks) peak = std::fmax(peak, c.expected);
    for (std::size_t u = 0; u < checks.size(); ++u) {
      const auto& c = checks[u];
      if (c.expected < 0.01 * peak) continue;
      INFO("surface ring " << u << ": measured " << c.measured << " expected " << c.expected);
      CHECK(std::fabs(c.measured - c.expected) <= c.tolerance);
    }
  }
  // Solid 3D noise sliced by the plane z = 0.3: the slice's spectrum is the 3D
  // spectrum integrated over f_z (projection-slice theorem), tabulated radially.
  {
    std::vector<std::vector<double>> ps;
    const hush::gabor<3> g(make_params<3>(gabor_kind::isotropic, 30));
    for (std::uint32_t seed = 0; seed < 6; ++seed) {
      const hush::gabor<3> gs(make_params<3>(gabor_kind::isotropic, seed + 30));
      std::vector<double> img(n * n);
      for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i)
          img[j * n + i] = gs(hush::dvec3{double(i) * dx, double(j) * dx, 0.3});
      ps.push_back(periodogram(img, n, dx));
    }
    const hush::gabor_spectrum<3> s3(g, 10.0);
    std::vector<double> radial(400);
    for (std::size_t k = 0; k < radial.size(); ++k) {
      const double rho = static_cast<double>(k) * 0.02;
      double sum = 0;
      const double dfz = 0.01;
      for (double fz = -4 + dfz / 2; fz < 4; fz += dfz) sum += s3({rho, 0.0, fz});
      radial[k] = sum * dfz;
    }
    auto s = [&](double fx, double fy) {
      const double x = std::hypot(fx, fy) / 0.02;
      const auto k = static_cast<std::size_t>(x);
      if (k + 1 >= radial.size()) return 0.0;
      return radial[k] + (x - static_cast<double>(k)) * (radial[k + 1] - radial[k]);
    };
    std::vector<int> sets(n * n, -1);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const double rad = std::hypot(bin_frequency(i, n, dx), bin_frequency(j, n, dx));
        if (rad >= 2.0 / (n * dx)) sets[j * n + i] = static_cast<int>(rad * 4);
      }
    const auto checks = compare_bins(ps, n, dx, s, sets, 16);
    double peak = 0;
    for (const auto& c : checks) peak = std::fmax(peak, c.expected);
    for (std::size_t u = 0; u < checks.size(); ++u) {
      const auto& c = checks[u];
      if (c.expected < 0.01 * peak) continue;
      INFO("3D slice ring " << u << ": measured " << c.measured << " expected " << c.expected);
      CHECK(std::fabs(c.measured - c.expected) <= c.tolerance);
    }
  }
}

TEST_CASE("gabor: the spectrum integrates to the variance (Parseval), every kind [slow]") {
  for (const gabor_kind kind :
       {gabor_kind::isotropic, gabor_kind::anisotropic, gabor_kind::hybrid}) {
    const hush::gabor<2> g(make_params<2>(kind));
    const hush::gabor_spectrum<2> s(g, 6.0);
    // The midpoint rule on a smooth, decaying integrand is spectrally accurate
    // (Euler-Maclaurin): df = 0.08 resolves the 0.22-wide blobs. The tail
    // beyond |f| = 6 holds ~1e-5 of the power (the taper's C1 edge).
    const double df = 0.08;
    double sum = 0;
    for (double fy = -6 + df / 2; fy < 6; fy += df)
      for (double fx = -6 + df / 2; fx < 6; fx += df) sum += s({fx, fy});
    CHECK(sum * df * df == doctest::Approx(1.0).epsilon(2e-4));
  }
}

// ---- Evaluation.

TEST_CASE("gabor: gradient is the derivative of the value (2D, 3D, filtered, surface)") {
  hush::rng r(8);
  const hush::gabor<2> g2(make_params<2>(gabor_kind::hybrid));
  const hush::gabor<3> g3(make_params<3>(gabor_kind::isotropic));
  const auto fp2 =
      hush::footprint<2>::from_derivatives(hush::dvec2{0.1, 0.05}, hush::dvec2{0, 0.2});
  const auto fp3 =
      hush::footprint<3>::from_derivatives(hush::dvec3{0.1, 0.05, 0}, hush::dvec3{0, 0.2, 0.1});
  const hush::dvec3 nrm{0.3, -0.5, 0.8};
  double worst = 0;
  auto fd_check = [&](auto value, auto analytic, auto p) {
    constexpr int D = static_cast<int>(sizeof(p) / sizeof(double));
    for (int a = 0; a < D; ++a) {
      const double h = 1e-6;
      auto pp = p, pm = p;
      pp[a] += h;
      pm[a] -= h;
      const double fd = (value(pp) - value(pm)) / (2 * h);
      worst = std::fmax(worst, std::fabs(fd - analytic.gradient[a]) / (1 + std::fabs(fd)));
    }
  };
  for (int i = 0; i < 300; ++i) {
    const hush::dvec2 p2{r.uniform<double>(-50, 50), r.uniform<double>(-50, 50)};
    const hush::dvec3 p3{r.uniform<double>(-50, 50), r.uniform<double>(-50, 50),
                         r.uniform<double>(-50, 50)};
    fd_check([&](const hush::dvec2& p) { return g2(p); }, g2.gradient(p2), p2);
    fd_check([&](const hush::dvec2& p) { return g2.sample(p, fp2); }, g2.sample_gradient(p2, fp2),
             p2);
    fd_check([&](const hush::dvec3& p) { return g3(p); }, g3.gradient(p3), p3);
    fd_check([&](const hush::dvec3& p) { return g3.sample(p, fp3); }, g3.sample_gradient(p3, fp3),
             p3);
    fd_check([&](const hush::dvec3& p) { return g3.sample(p, nrm, fp3); },
             g3.sample_gradient(p3, nrm, fp3), p3);
  }
  // Central differences with h = 1e-6: O(h^2 |n'''|) ~ 1e-10 plus rounding 1e-16 / h.
  CHECK(worst < 1e-6);
}

TEST_CASE("gabor: float evaluation stays within the stated budget of the double reference") {
  // Budget (gabor.hpp, docs/gabor.md): each of the <= 3^D max_count kernels
  // is within 2^-21 (1 + 2 pi |Phi|) of its double value (gabor_kernel_test);
  // their float sum adds one rounding of the running sum per term; times the
  // scale. The kernels' errors are independent, so the RMS grows like the
  // square root of the count; the stated bound is the worst case over the
  // ~N' kernels within reach of a point: scale 2^-21 (1 + 2 pi Phi) (N' + 1).
  hush::rng r(12);
  for (const gabor_kind kind : {gabor_kind::isotropic, gabor_kind::anisotropic}) {
    const hush::gabor<2> g(make_params<2>(kind));
    const double phi = g.marks().phi0();
    const double budget =
        g.scale() * std::ldexp(1.0, -21) * (1 + 2 * kPi * phi) * (g.parameters().impulses + 1);
    double worst = 0, sum2 = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double extent = i % 2 ? 100.0 : 1e6;
      const hush::vec2 pf{r.uniform<float>(-1, 1) * float(extent),
                          r.uniform<float>(-1, 1) * float(extent)};
      const double e = std::fabs(g(pf) - g(hush::vec_cast<double>(pf)));
      worst = std::fmax(worst, e);
      sum2 += e * e;
    }
    MESSAGE("kind " << static_cast<int>(kind) << ": max |float - double| " << worst << ", RMS "
                    << std::sqrt(sum2 / n) << ", budget " << budget);
    CHECK(worst <= budget);
  }
}

TEST_CASE("gabor: a point footprint evaluates the unfiltered noise, filtering is continuous") {
  const hush::gabor<2> g(make_params<2>(gabor_kind::isotropic));
  hush::rng r(13);
  for (int i = 0; i < 200; ++i) {
    const hush::dvec2 p{r.uniform<double>(-20, 20), r.uniform<double>(-20, 20)};
    CHECK(g.sample(p, hush::footprint<2>{}) == doctest::Approx(g(p)).epsilon(1e-13).scale(1.0));
    // Shrinking footprints converge to the point value; growing ones to the mean 0.
    const double v = g(p);
    CHECK(std::fabs(g.sample(p, hush::footprint<2>::isotropic(1e-6)) - v) < 1e-6);
    CHECK(std::fabs(g.sample(p, hush::footprint<2>::isotropic(1e-3)) - v) < 1e-3 * 10);
    CHECK(std::fabs(g.sample(p, hush::footprint<2>::isotropic(1e3))) < 1e-3);
  }
}

TEST_CASE("gabor: filtering agrees with a supersampled Gaussian pixel filter [slow]") {
  // The closed form filters the untruncated kernels and keeps their taper;
  // the reference averages the unfiltered noise over 64 x 64 stratified
  // samples weighted by the pixel's Gaussian N(0, sigma^2 S) within 4 sigma.
  // Accepted: RMS difference over 200 pixels within a quarter of the RMS of the
  // unfiltered noise's difference from the reference (filtering must remove
  // most of the aliasing error), and finite everywhere.
  const hush::gabor<2> g(make_params<2>(gabor_kind::isotropic));
  const double sigma = hush::detail::constants::kPixelFilterSigma;
  hush::rng r(14);
  for (const double width : {0.1, 0.3, 0.6}) {
    double err_filtered = 0, err_point = 0;
    for (int i = 0; i < 200; ++i) {
      const hush::dvec2 p{r.uniform<double>(-20, 20), r.uniform<double>(-20, 20)};
      const hush::dvec2 jx{width, 0.2 * width}, jy{-0.1 * width, 0.8 * width};
      const auto fp = hush::footprint<2>::from_derivatives(jx, jy);
      double num = 0, den = 0;
      constexpr int m = 64;
      for (int b = 0; b < m; ++b)
        for (int a = 0; a < m; ++a) {
          const double u = -4 + 8 * (a + 0.5) / m, v = -4 + 8 * (b + 0.5) / m;  // in sigma
          const double w = std::exp(-0.5 * (u * u + v * v));
          const hush::dvec2 q{p.x + sigma * (u * jx.x + v * jy.x),
                              p.y + sigma * (u * jx.y + v * jy.y)};
          num += w * g(q);
          den += w;
        }
      const double ref = num / den, filtered = g.sample(p, fp);
      REQUIRE(std::isfinite(filtered));
      err_filtered += (filtered - ref) * (filtered - ref);
      err_point += (g(p) - ref) * (g(p) - ref);
    }
    err_filtered = std::sqrt(err_filtered / 200);
    err_point = std::sqrt(err_point / 200);
    MESSAGE("pixel width " << width << ": RMS error filtered " << err_filtered << ", unfiltered "
                           << err_point);
    CHECK(err_filtered <= 0.25 * err_point);
  }
}

// ---- Hard cases.

TEST_CASE(
    "gabor: NaN and infinite positions give NaN; huge ones stay finite (HARD_CASES 1, 3, 5)") {
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  const hush::gabor<2> g2(make_params<2>(gabor_kind::isotropic));
  const hush::gabor<3> g3(make_params<3>(gabor_kind::anisotropic));
  for (const float bad : {nan, inf, -inf}) {
    CHECK(std::isnan(g2(hush::vec2{bad, 0.5f})));
    CHECK(std::isnan(g2(hush::vec2{0.5f, bad})));
    const auto vg = g3.gradient(hush::vec3{0.5f, 0.25f, bad});
    CHECK(std::isnan(vg.value));
    CHECK(std::isnan(vg.gradient.x));
    CHECK(std::isnan(g3.sample(hush::vec3{bad, 0, 0}, hush::vec3{0, 0, 1})));
    CHECK(std::isnan(g2.sample(hush::vec2{bad, 0}, hush::footprint<2>::isotropic(0.1f))));
  }
  CHECK(std::isnan(g3.sample(hush::vec3{1, 2, 3}, hush::vec3{nan, 0, 1})));
  const float big = std::numeric_limits<float>::max();
  for (const float x : {-1.0f, -0.0f, std::nextafter(-1.0f, 0.0f), 4.9999998f, 8388607.5f,
                        8388608.5f, 16777216.0f, -16777216.0f, 1e6f, 1e20f, big, -big, 1e-40f}) {
    const float v = g2(hush::vec2{x, 0.3f});
    CHECK(std::isfinite(v));
    CHECK(std::fabs(v) <= g2.bound());
    CHECK(std::isfinite(g3(hush::vec3{x, x, 0.3f})));
  }
  for (const double x : {2147483648.0, 9007199254740992.0, 1e300, -1e300})
    CHECK(std::isfinite(g2(hush::dvec2{x, -x})));
  // A zero normal evaluates the solid noise.
  CHECK(g3.sample(hush::vec3{1, 2, 3}, hush::vec3{0, 0, 0}) ==
        g3.sample(hush::vec3{1, 2, 3}, hush::footprint<3>{}));
}

TEST_CASE("gabor: continuous across cell boundaries and truncation circles (HARD_CASES row 2)") {
  // Along lines through the origin, across cell planes: consecutive values
  // 1e-7 apart differ by the derivative times the step, to second order.
  const hush::gabor<2> g(make_params<2>(gabor_kind::anisotropic));
  const double r = g.kernel().radius(), h = 1e-7;
  double worst = 0;
  for (int k = -20; k <= 20; ++k)
    for (const double dir : {0.0, 0.25 * kPi, 1.0}) {
      const hush::dvec2 u{std::cos(dir), std::sin(dir)};
      const double t = k * r;  // crosses the cell planes x = k r (dir 0) and others
      const hush::dvec2 a{t * u.x - 0.5 * h * u.x, t * u.y - 0.5 * h * u.y};
      const hush::dvec2 b{a.x + h * u.x, a.y + h * u.y};
      const auto ga = g.gradient(a);
      const double slope = ga.gradient.x * u.x + ga.gradient.y * u.y;
      worst = std::fmax(worst, std::fabs(g(b) - g(a) - slope * h));
    }
  CHECK(worst < 1e-11);  // O(h^2 |n''|) with |n''| ~ 100
}

TEST_CASE(
    "gabor: no repetition at cell lags 2^k along the axes and the diagonal (HARD_CASES 7) [slow]") {
  // Correlation of n(x) and n(x + 2^k r e) over 2000 random x: |rho| <= 5 / sqrt(2000).
  const hush::gabor<2> g(make_params<2>(gabor_kind::isotropic, 7));
  const double r = g.kernel().radius();
  hush::rng rr(15);
  for (int k = 1; k <= 31; ++k)
    for (const hush::dvec2 e : {hush::dvec2{1, 0}, hush::dvec2{0, 1}, hush::dvec2{1, 1}}) {
      const double lag = std::ldexp(1.0, k) * r;
      double sab = 0, saa = 0, sbb = 0;
      for (int i = 0; i < 2000; ++i) {
        const hush::dvec2 p{rr.uniform<double>(-500, 500), rr.uniform<double>(-500, 500)};
        const double a = g(p), b = g(hush::dvec2{p.x + lag * e.x, p.y + lag * e.y});
        sab += a * b;
        saa += a * a;
        sbb += b * b;
      }
      const double rho = sab / std::sqrt(saa * sbb);
      INFO("lag 2^" << k << " along (" << e.x << ", " << e.y << "): rho = " << rho);
      CHECK(std::fabs(rho) <= 5.0 / std::sqrt(2000.0));
    }
}

TEST_CASE(
    "gabor: degenerate footprints give finite values tending to the mean (HARD_CASES row 12)") {
  const hush::gabor<2> g2(make_params<2>(gabor_kind::isotropic));
  const hush::gabor<3> g3(make_params<3>(gabor_kind::hybrid));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const hush::footprint<3> fps[] = {
      hush::footprint<3>{},
      hush::footprint<3>::from_derivatives(hush::dvec3{0.2, 0.1, 0}, hush::dvec3{0, 0, 0}),
      hush::footprint<3>::from_derivatives(hush::dvec3{1e-15, 0, 0}, hush::dvec3{0, 1e-15, 0}),
      hush::footprint<3>::from_derivatives(hush::dvec3{1e15, 0, 0}, hush::dvec3{0, 1e15, 0}),
      hush::footprint<3>::from_derivatives(hush::dvec3{nan, 0, 0}, hush::dvec3{0, 1, 0})};
  hush::rng r(16);
  for (int i = 0; i < 50; ++i) {
    const hush::dvec3 p{r.uniform<double>(-9, 9), r.uniform<double>(-9, 9),
                        r.uniform<double>(-9, 9)};
    for (const auto& fp : fps) {
      const auto v = g3.sample_gradient(hush::vec_cast<float>(p), fp);
      CHECK(std::isfinite(v.value));
      CHECK(std::isfinite(v.gradient.x));
      const auto s = g3.sample_gradient(hush::vec_cast<float>(p), hush::vec3{0.f, 0.6f, 0.8f}, fp);
      CHECK(std::isfinite(s.value));
      CHECK(std::isfinite(s.gradient.z));
    }
    // The widest footprints filter everything: the mean.
    CHECK(std::fabs(g3.sample(p, fps[3])) < 1e-12);
    CHECK(std::fabs(g3.sample(p, fps[4])) < 1e-12);
    CHECK(std::fabs(g2.sample(hush::dvec2{p.x, p.y}, hush::footprint<2>::isotropic(nan))) < 1e-12);
  }
}

TEST_CASE("gabor: the observed range stays within bound() (HARD_CASES row 6)") {
  const hush::gabor<2> g(make_params<2>(gabor_kind::anisotropic));
  hush::rng r(17);
  double worst = 0;
  for (int i = 0; i < 100000; ++i)
    worst = std::fmax(
        worst,
        std::fabs(g(hush::vec2{r.uniform<float>(-1e4f, 1e4f), r.uniform<float>(-1e4f, 1e4f)})));
  MESSAGE("max |n| over 1e5 points: " << worst << " (bound " << g.bound() << ")");
  CHECK(worst <= g.bound());
  CHECK(worst > 3.0);  // unit variance: 1e5 samples reach beyond 3 sigma
}

TEST_CASE(
    "gabor: every seed gives a field, nearby seeds are uncorrelated (HARD_CASES rows 4, 10)") {
  // Seed 1 against seed 0 over 500 independent points: |rho| <= 5 / sqrt(500).
  const hush::gabor<2> g0(make_params<2>(gabor_kind::isotropic, 0));
  double prev = 0;
  for (const std::uint32_t seed : {0U, 1U, 2U, 0x7FFFFFFFU, 0x80000000U, 0xFFFFFFFFU}) {
    const hush::gabor<2> g(make_params<2>(gabor_kind::isotropic, seed));
    double s = 0, sxy = 0;
    for (int i = 0; i < 500; ++i) {
      const hush::dvec2 x{i * 3.7, 0.5};
      const double v = g(x);
      s += v * v;
      if (seed == 1U) sxy += v * g0(x);
    }
    CHECK(s > 0);
    if (seed == 1U) CHECK(std::fabs(sxy / s) < 5.0 / std::sqrt(500.0));
    CHECK(s != prev);
    prev = s;
  }
}
