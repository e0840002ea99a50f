// hush::gabor's long statistical sweeps (label slow: the Release run only,
// tests/CMakeLists.txt): the measured power spectrum against the exact one,
// radially and angularly, on surfaces and 3D slices, Parseval, filtering
// against a supersampled pixel filter, no repetition at lags 2^k. Tolerances
// from the sample sizes; the spectra are gabor_spectrum's exact values. Also
// the hybrid spectra's quadratures against their expensive references (the
// old sphere quadrature, the full average, H's quadrature).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "gabor_test_util.hpp"
#include "hush/hush.hpp"

using namespace gabor_test_util;  // NOLINT(google-build-using-namespace): the suites' helpers

TEST_CASE("gabor: the measured power spectrum is the analytic one, radially and angularly") {
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
    "gabor: surface noise on a plane has the 2D noise spectrum, a 3D slice the projected one") {
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

TEST_CASE("gabor: the spectrum integrates to the variance (Parseval), every kind") {
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

TEST_CASE("gabor: filtering agrees with a supersampled Gaussian pixel filter") {
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

TEST_CASE("gabor: no repetition at cell lags 2^k along the axes and the diagonal (HARD_CASES 7)") {
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

// ---- Hybrid spectra against their references (too slow for the
// sanitizer runs; the bounded-cost check at F0 = 1e6 is in gabor_kernel_test).

TEST_CASE("gabor: hybrid 3D spectra over the caps equal the old sphere quadrature where it was cheap") {
  // |Phi| = 1 +- 0.25 cycles per cell, caps of apex angle 1 rad (t = 0.05)
  // and 2.5 rad (t = 0.5), the stand-in H: the old quadrature (above) is cheap
  // here and accurate (smooth integrands). xi inside the band (on the axis
  // at |Phi|), at its edge (the cap's rim at |Phi|'s ends), outside (beyond
  // the rim, opposite the axis: the -Phi blob, 0 and far). The caps' rule
  // (cap_mean: square-root ends cut and mapped away) matches to 1e-11 of the
  // peak (measured 1.6e-15; 1.2e-12 at |Phi| = 1.5 +- 0.5, |xi| up to 3.5).
  double worst = 0;
  for (const double t : {0.05, 0.5}) {
    {
      const double cap = t < 0.1 ? 1.0 : 2.5;
      const hush::gabor<3> g = hybrid_3d(1.0, 0.5, cap, t);
      const double A = g.kernel().envelope_exponent(), r = g.kernel().radius();
      auto h = [A](double k) { return stand_in_h<3>(A, k); };
      auto mean = [&](const hush::dvec3& xi) {
        const hush::dvec3 f{xi.x / r, xi.y / r, xi.z / r};
        const double one = g.spectrum_with(f, [](double) { return 1.0; });
        return g.spectrum_with(f, h) / one;  // the factor cancels
      };
      const double peak = old_hybrid_3d_mean(g, off_axis(g, 1.0, 0.0), h);
      const double cases[][2] = {{1.0, 0.0}, {0.75, 0.5 * cap}, {1.25, 0.5 * cap}, {1.0, 0.5 * cap + 0.4},
                                 {0.0, 0.0}, {1.0, 3.0},        {2.5, 1.0}};
      for (const auto& c : cases) {
        CAPTURE(t);
        CAPTURE(cap);
        CAPTURE(c[0]);
        CAPTURE(c[1]);
        const hush::dvec3 xi = off_axis(g, c[0], c[1]);
        const double err = std::fabs(mean(xi) - old_hybrid_3d_mean(g, xi, h)) / peak;
        worst = std::fmax(worst, err);
        CHECK(err <= 1e-11);
      }
    }
  }
  MESSAGE("max |caps - old| / peak = " << worst);
}

TEST_CASE("gabor: hybrid power_spectrum's table of H equals the quadrature") {
  // H in cell units depends on t alone (A = -ln t). The table (panels 1
  // cycle per cell wide, 20 Chebyshev points) against the quadrature between
  // its nodes up to the window (64 cycles per cell), t at both ends of its
  // range: within 1e-14 of H(0) (measured below). And power_spectrum of hybrid
  // noise (the table) against spectrum_with of the quadrature itself (the
  // current method) at moderate |Phi|, f inside, at the edge of and outside
  // the band: 1e-12 relative.
  double worst_table = 0, worst_spectrum = 0;
  for (const double t : {1e-9, 0.5}) {
    hush::gabor<2>::params p2;
    p2.kind = hush::gabor_kind::hybrid;
    p2.truncation = t;
    const double r2 = hush::gabor_kernel<2>(0.8, t).radius();
    p2.frequency = 1.5 / r2;
    p2.frequency_spread = 0.5 / r2;
    p2.orientation = 0.5236;
    p2.orientation_spread = 0.3;
    const hush::gabor<2> g2(p2);
    const hush::gabor<3> g3 = hybrid_3d(1.0, 0.5, 1.0, t);
    const double a2 = g2.kernel().envelope_exponent(), a3 = g3.kernel().envelope_exponent();
    auto exact2 = [a2](double k) { return hush::detail::gabor_envelope_transform<2>(a2, k); };
    auto exact3 = [a3](double k) { return hush::detail::gabor_envelope_transform<3>(a3, k); };
    const double far = 100.0 / r2;  // beyond the window: the whole table
    const auto table2 = g2.transform_table(hush::dvec2{far, 0.0});
    const auto table3 = g3.transform_table(hush::dvec3{far, 0.0, 0.0});
    CHECK(table2.calls() == 64 * 19 + 1);
    for (int i = 0; i < 256; ++i) {
      const double k = 64.0 * (i + 0.318) / 256.0;
      worst_table = std::fmax(worst_table, std::fabs(table2(k) - exact2(k)) / exact2(0.0));
      worst_table = std::fmax(worst_table, std::fabs(table3(k) - exact3(k)) / exact3(0.0));
    }
    // f inside the band, at its edge (the arc's end, |Phi|'s end), outside
    // (the -Phi blob's side, far). The quadrature of H costs ~0.1 ms in 2D
    // (J0): three values of the 2D spectrum, ~2000 calls each.
    const double f_cases[][2] = {{1.5, 0.5236}, {1.75, 0.5236 + 0.15}, {3.0, 3.7}};
    for (const auto& c : f_cases) {
      const double cycles = c[0], angle = c[1];
      const hush::dvec2 f2{cycles / r2 * std::cos(angle), cycles / r2 * std::sin(angle)};
      if (t == 0.5) {
        const double s2 = g2.power_spectrum(f2), e2 = g2.spectrum_with(f2, exact2);
        worst_spectrum = std::fmax(worst_spectrum, std::fabs(s2 - e2) / e2);
      }
      for (const double angle3 : {0.0, 0.5, 1.0, 3.0}) {
        const hush::dvec3 xi = off_axis(g3, 0.7 * cycles, angle3);
        const double r3 = g3.kernel().radius();
        const hush::dvec3 f3{xi.x / r3, xi.y / r3, xi.z / r3};
        const double s3 = g3.power_spectrum(f3), e3 = g3.spectrum_with(f3, exact3);
        worst_spectrum = std::fmax(worst_spectrum, std::fabs(s3 - e3) / e3);
      }
    }
  }
  MESSAGE("table: max |table - H| / H(0) = " << worst_table
                                            << "; spectra: max relative difference " << worst_spectrum);
  CHECK(worst_table <= 1e-14);
  CHECK(worst_spectrum <= 1e-12);
}

TEST_CASE("gabor: hybrid 3D spectra over the frequency window and the caps equal the full average") {
  // |Phi| = 66 +- 5 cycles per cell, a cap of apex angle 1 rad, the stand-in
  // H, t = 0.05: the full average (window = infinity: every |Phi| and the
  // whole cap, ~1.8e6 calls of h) against the windows' (f on the axis, at the
  // rim, opposite (the -Phi blob), at 0). What the windows leave out is
  // pointwise below the tail's square at W, (1.2 W^-4)^2 = 5e-15 of H(0)^2
  // (3D: docs/gabor.md "Cost of the kernel's statistics"); relative to the
  // hybrid peak (spread over the frequency range and the cap) ~1e-11: a 1e-9
  // tolerance as in 2D. Calls of h per value: <= 1296 |Phi| nodes (the
  // frequency window's panels) times 2 x 1072 nodes (the caps') times 2.
  const hush::gabor<3> g = hybrid_3d(66.0, 10.0, 1.0, 0.05);
  const double A = g.kernel().envelope_exponent(), r = g.kernel().radius();
  long calls = 0;
  auto h = counted_stand_in<3>(A, calls);
  const double inf = std::numeric_limits<double>::infinity();
  auto at = [&](double cycles, double angle) {
    const hush::dvec3 xi = off_axis(g, cycles, angle);
    return hush::dvec3{xi.x / r, xi.y / r, xi.z / r};
  };
  const double peak = g.spectrum_with(at(66.0, 0.0), h, inf);
  const double cases[][2] = {{66.0, 0.0}, {66.3, 0.5}, {70.0, 3.0}, {0.0, 0.0}};
  for (const auto& c : cases) {
    CAPTURE(c[0]);
    CAPTURE(c[1]);
    calls = 0;
    const double windowed = g.spectrum_with(at(c[0], c[1]), h);
    CHECK(calls <= 1296L * 2 * 1072 * 2);
    CHECK(std::fabs(windowed - g.spectrum_with(at(c[0], c[1]), h, inf)) <= 1e-9 * peak);
  }
}
