// hush::gabor_kernel and hush::gabor_filter (gabor_kernel.hpp): the Gabor
// kernel of Lagae et al. 2009 with its smooth truncation, its spectra, energy
// and closed-form filtering, each checked against an independent brute-force
// computation.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>

#include "gabor_test_util.hpp"
#include "hush/hush.hpp"  // the umbrella: the suite also runs against the single header

namespace {

constexpr double kPi = hush::detail::constants::kPi;
constexpr double kS0 = hush::detail::constants::kGaborTaperStart;
using gabor_test_util::counted_stand_in;
using gabor_test_util::off_axis;

// The Gabor kernel of the paper (K = 1), untruncated, in double.
double gabor_pure(double a, const hush::dvec2& x, const hush::dvec2& f) {
  return std::exp(-kPi * a * a * (x.x * x.x + x.y * x.y)) *
         std::cos(2.0 * kPi * (f.x * x.x + f.y * x.y));
}

// Midpoint-rule integral over [-r, r]^2 of fn(x) on n x n cells.
template <class Fn>
double square_integral(double r, int n, Fn fn) {
  const double h = 2.0 * r / n;
  double sum = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) sum += fn(hush::dvec2{-r + (i + 0.5) * h, -r + (j + 0.5) * h});
  return sum * h * h;
}

}  // namespace

TEST_CASE("gabor_kernel: bandwidth and truncation out of range are refused by name") {
  auto refused = [](double a, double t, const char* name) {
    try {
      const hush::gabor_kernel<2> k(a, t);
      return false;
    } catch (const hush::invalid_argument& e) {
      return std::string(e.what()).find(std::string("hush::gabor_kernel: ") + name) !=
             std::string::npos;
    }
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(refused(0.0, 0.05, "bandwidth"));
  CHECK(refused(-1.0, 0.05, "bandwidth"));
  CHECK(refused(nan, 0.05, "bandwidth"));
  CHECK(refused(2e6, 0.05, "bandwidth"));
  CHECK(refused(1.0, 0.0, "truncation"));
  CHECK(refused(1.0, 0.6, "truncation"));
  CHECK(refused(1.0, nan, "truncation"));
  CHECK_NOTHROW(hush::gabor_kernel<3>(1e-6, 1e-9));
  CHECK_NOTHROW(hush::gabor_kernel<3>(1e6, 0.5));
}

TEST_CASE("gabor_kernel: the support radius is where the envelope falls to the truncation") {
  for (const double a : {0.05, 0.8, 3.0})
    for (const double t : {0.5, 0.05, 1e-3, 1e-9}) {
      const hush::gabor_kernel<2> k(a, t);
      CHECK(std::exp(-kPi * a * a * k.radius() * k.radius()) == doctest::Approx(t).epsilon(1e-12));
      CHECK(k.envelope_exponent() == doctest::Approx(-std::log(t)).epsilon(1e-15));
      // Zero on and beyond the support, in float and double.
      const hush::dvec2 F{0.7 * a, 0.2 * a};
      CHECK(std::fabs(k.value(hush::dvec2{k.radius(), 0.0}, F)) <
            1e-30);  // d = r (1/r) < 1 by rounding
      CHECK(k.value(hush::dvec2{k.radius() * (1 + 1e-12), 0.0}, F) == 0.0);
      CHECK(k.value(hush::dvec2{0.0, -1.5 * k.radius()}, F) == 0.0);
      CHECK(k.value(hush::vec2{0.0f, -1.5f * static_cast<float>(k.radius())}, F) == 0.0f);
    }
}

TEST_CASE("gabor_kernel: the Gabor kernel inside the taper radius, within t^s0 of it beyond") {
  hush::rng r(3);
  for (const double t : {0.05, 0.01}) {
    const double a = 0.8;
    const hush::gabor_kernel<2> k(a, t);
    // The largest deviation is the envelope times (1 - taper) over the shell
    // s in [s0, 1]: at most t^s0, in fact about t (scanned here in 1e5 steps).
    double bound = 0;
    for (int i = 0; i <= 100000; ++i) {
      const double s = kS0 + (1 - kS0) * i / 100000.0;
      bound =
          std::fmax(bound, std::pow(t, s) * (1 - hush::detail::gabor_taper(s, 1.0 / (1.0 - kS0))));
    }
    CHECK(bound <= std::pow(t, kS0));
    MESSAGE("t = " << t << ": max |g - g_Gabor| = " << bound << " = " << bound / t << " t");
    double inside = 0, outside = 0;
    for (int i = 0; i < 20000; ++i) {
      const hush::dvec2 x{r.uniform<double>(-1.2, 1.2) * k.radius(),
                          r.uniform<double>(-1.2, 1.2) * k.radius()};
      const hush::dvec2 F{r.uniform<double>(-2, 2), r.uniform<double>(-2, 2)};
      const double diff = std::fabs(k.value(x, F) - gabor_pure(a, x, F));
      if (std::hypot(x.x, x.y) <= k.taper_radius() * (1 - 1e-12))
        inside = std::fmax(inside, diff);
      else
        outside = std::fmax(outside, diff);
    }
    CHECK(inside <= 1e-14);
    CHECK(outside <= bound + 1e-15);
    CHECK(outside > 0.9 * bound);  // and is attained
  }
}

TEST_CASE("gabor_kernel: the float taper is exactly 0 from s = 1 on, exactly 1 where v >= 1") {
  // The SIMD grid kernel adds the terms of samples outside the support unmasked and skips
  // the taper where v = (1 - s) k >= 1: both rely on these exact values of the shared
  // taper (hush/gabor_kernel.hpp), every float s near the two ends and beyond.
  const float k = static_cast<float>(1.0 / (1.0 - kS0));
  int wrong = 0;
  auto outside = [&](float s) {
    const auto tw = hush::detail::gabor_taper_derivative(s, k);
    const bool out = !(s < 1.0f);
    if (out != (hush::detail::gabor_taper(s, k) == 0.0f) || out != (tw.tau == 0.0f) ||
        (out && tw.dtau != 0.0f))
      ++wrong;
  };
  auto flat = [&](float s) {
    if ((1.0f - s) * k >= 1.0f && hush::detail::gabor_taper(s, k) != 1.0f) ++wrong;
    if (s > 0.8001f && hush::detail::gabor_taper(s, k) == 1.0f) ++wrong;  // and tapers after s0
  };
  // Every float in [0.999, 1.001] and in [0.799, 0.801] (s0 = 0.8), and some beyond (positive
  // floats are ordered as their bit patterns).
  auto bits = [](float f) {
    std::uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
  };
  for (std::uint32_t b = bits(0.999f); b <= bits(1.001f); ++b) {
    float s;
    std::memcpy(&s, &b, sizeof s);
    outside(s);
  }
  for (std::uint32_t b = bits(0.799f); b <= bits(0.801f); ++b) {
    float s;
    std::memcpy(&s, &b, sizeof s);
    flat(s);
  }
  for (int i = 0; i <= 100; ++i) {
    outside(1.0f + 0.02f * static_cast<float>(i));
    flat(0.008f * static_cast<float>(i));
  }
  CHECK(wrong == 0);
  CHECK(hush::detail::gabor_taper(std::numeric_limits<float>::infinity(), k) == 0.0f);
}

TEST_CASE("gabor_kernel: the point form's sum is four partial sums by kept index, then paired") {
  // gabor_point_sum defines the float sum that scalar points, the SIMD lockstep and shared
  // paths and GLSL repeat (term k into partial k mod 4, then (s0 + s1) + (s2 + s3)).
  // Terms chosen so that each order rounds differently: 1e8 absorbs a 1 (float spacing 8
  // there) in one running sum but not when the 1s fall in partials of their own.
  const float t[6] = {1e8f, 1.0f, -1e8f, 1.0f, 0.5f, 0.25f};
  hush::detail::gabor_point_sum<float> ps;
  float chain = 0.0f;
  for (float v : t) {
    ps.add(v);
    chain += v;
  }
  // Partials: (1e8 + 0.5), (1 + 0.25), -1e8, 1 -> (1e8 + 1.25) + (-1e8 + 1) = 1e8 - 1e8 = 0.
  const float s0 = 1e8f + 0.5f, s1 = 1.0f + 0.25f, s2 = -1e8f, s3 = 1.0f;
  CHECK(ps.total() == (s0 + s1) + (s2 + s3));
  CHECK(ps.total() != chain);  // the running sum: ((1e8 + 1) - 1e8) + 1 + 0.5 + 0.25 = 1.75
  CHECK(chain == 1.75f);
  // Partials start at +0: an empty or cancelling sum is +0, never -0.
  hush::detail::gabor_point_sum<float> cancel;
  cancel.add(-0.0f);
  cancel.add(-0.0f);
  CHECK(!std::signbit(cancel.total()));
  CHECK(!std::signbit(hush::detail::gabor_point_sum<float>{}.total()));
}

TEST_CASE("gabor_kernel: an impulse's offset f - (o + u) is rounded once") {
  // detail::gabor_offset: o + u is exact in float (u a multiple of 2^-9, |o| <= 2), so the
  // float offset is the double difference rounded once; (f - o) - u, the former definition,
  // rounds f - o first and differs (here f = 2^-20 + 2^-25: f + 1 loses its last bit).
  for (int o = -2; o <= 2; ++o)
    for (std::uint32_t m = 0; m < 256; m += 17)
      for (float f : {0.0f, 0x1.0p-20f + 0x1.0p-25f, 0.3333333f, 0.5f, 0.99999994f}) {
        const float u = hush::detail::gabor_byte<float>(m << 24, 0);
        const double exact = double(f) - (double(o) + double(u));
        CHECK(hush::detail::gabor_offset(f, o, u) == static_cast<float>(exact));
      }
  const float f = 0x1.0p-20f + 0x1.0p-25f, u = hush::detail::gabor_byte<float>(255u << 24, 0);
  CHECK(hush::detail::gabor_offset(f, -1, u) != (f + 1.0f) - u);
}

TEST_CASE("gabor_kernel: C1 across the taper and the support edge, gradient is the derivative") {
  const hush::gabor_kernel<2> k(0.8, 0.05);
  const hush::dvec2 F{0.9, -0.4};
  hush::rng r(5);
  double worst = 0;
  for (int i = 0; i < 5000; ++i) {
    // Half the points in the taper shell, where the derivative has its extra term.
    const double rad =
        (i % 2 ? r.uniform<double>(0.85, 1.0) : r.uniform<double>(0.0, 1.0)) * k.radius();
    const double ang = r.uniform<double>(0, 2 * kPi);
    const hush::dvec2 x{rad * std::cos(ang), rad * std::sin(ang)};
    const auto vg = k.value_and_gradient(x, F);
    for (int ax = 0; ax < 2; ++ax) {
      const double h = 1e-6;
      hush::dvec2 xp = x, xm = x;
      xp[ax] += h;
      xm[ax] -= h;
      const double fd = (k.value(xp, F) - k.value(xm, F)) / (2 * h);
      worst = std::fmax(worst, std::fabs(fd - vg.gradient[ax]));
    }
  }
  CHECK(worst < 1e-7);  // central differences: O(h^2 g''') plus rounding 1e-16 / h
  // At the edge the value and the gradient both tend to 0 (C1).
  const double e = k.radius() * (1 - 1e-9);
  const auto edge = k.value_and_gradient(hush::dvec2{e, 0.0}, F);
  CHECK(std::fabs(edge.value) < 1e-15);
  CHECK(std::fabs(edge.gradient.x) < 1e-6);
}

TEST_CASE(
    "gabor_kernel: float evaluation is within 2^-21 (1 + 2 pi |Phi|) of the double reference") {
  // Per axis the offset d = x / r is rounded once (2^-24 |d|); exp_neg and
  // sincos_turns stay within 2^-22 and 2^-23 (elementary_test); the phase
  // Phi d carries the offset's rounding times 2 pi |Phi|; a dozen products and
  // sums of values below 1 add 2^-24 each. Added at their worst that exceeds
  // 2^-21 (1 + 2 pi |Phi|) for small |Phi| (3 exps and sin/cos: up to 4.5x at
  // Phi = 0, docs/gabor.md "Float accuracy"): the bound is the measured one,
  // and a quarter of the frequencies are scaled to |Phi| < 0.02, where it is
  // tightest (measured 0.31 of it there, 0.06 from |Phi| = 1 on).
  hush::rng r(9);
  for (const double a : {0.8, 0.1}) {
    const hush::gabor_kernel<3> k(a, 0.05);
    double worst = 0, ratio = 0;
    for (int i = 0; i < 20000; ++i) {
      const hush::vec3 x{r.uniform<float>(-1, 1) * float(k.radius()),
                         r.uniform<float>(-1, 1) * float(k.radius()),
                         r.uniform<float>(-1, 1) * float(k.radius())};
      hush::dvec3 F{r.uniform<double>(-3, 3) * a, r.uniform<double>(-3, 3) * a,
                    r.uniform<double>(-3, 3) * a};
      if (i % 4 == 0) F = {F.x * 1e-3, F.y * 1e-3, F.z * 1e-3};  // |Phi| < 0.02
      const double phi = std::sqrt(F.x * F.x + F.y * F.y + F.z * F.z) * k.radius();
      const double e = std::fabs(k.value(x, F) - k.value(hush::vec_cast<double>(x), F));
      worst = std::fmax(worst, e);
      ratio = std::fmax(ratio, e / (std::ldexp(1.0, -21) * (1 + 2 * kPi * phi)));
    }
    MESSAGE("a = " << a << ": max |float - double| = " << worst << ", " << ratio
                   << " of the bound");
    CHECK(ratio <= 1.0);
  }
}

TEST_CASE("gabor_kernel: envelope transform and energy equal brute-force quadrature") {
  // Midpoint rule on 600 x 600 cells over the support: error O(h^2) on the
  // smooth part and O(h^2) at the C1 taper, ~1e-5 relative here.
  const double a = 0.8;
  const hush::gabor_kernel<2> k(a, 0.05);
  const double r = k.radius();
  auto envelope = [&](const hush::dvec2& x) {
    return k.value(x, hush::dvec2{0.0, 0.0});  // F = 0: the tapered envelope
  };
  for (const double f : {0.0, 0.3, 1.0, 2.5}) {
    const double brute = square_integral(
        r, 600, [&](const hush::dvec2& x) { return envelope(x) * std::cos(2 * kPi * f * x.x); });
    CHECK(k.envelope_transform(f) ==
          doctest::Approx(brute).epsilon(2e-5).scale(k.envelope_transform(0)));
  }
  for (const double F : {0.0, 0.5, 1.0}) {
    const hush::dvec2 Fv{F * 0.6, F * 0.8};
    const double brute = square_integral(r, 600, [&](const hush::dvec2& x) {
      const double g = k.value(x, Fv);
      return g * g;
    });
    CHECK(k.energy(F) == doctest::Approx(brute).epsilon(2e-5));
  }
}

namespace {

// The quadratures gabor_energy and gabor_truncation_error used before their
// cost was bounded (panels 2 + 4 ceil(phi), the constant and oscillatory parts
// together): the reference the bounded versions are checked against.
template <int D>
double old_ball(double a, double phi, double (*weight)(double)) {
  const double k = 1.0 / (1.0 - kS0);
  const int panels = 2 + 4 * static_cast<int>(std::ceil(phi));
  return 0.5 * hush::detail::ball_integral<D>(
                   [&](double rho) {
                     const double s = rho * rho;
                     return std::exp(-2.0 * a * s) * weight(hush::detail::gabor_taper(s, k)) *
                            (1.0 + hush::detail::angular_average<D>(4.0 * kPi * phi * rho));
                   },
                   panels);
}
template <int D>
double old_energy(double a, double phi) {
  return old_ball<D>(a, phi, [](double tau) { return tau * tau; });
}
template <int D>
double old_truncation_error(double a, double phi) {
  const double full =
      std::pow(kPi / (2.0 * a), 0.5 * D) * 0.5 * (1.0 + std::exp(-2.0 * kPi * kPi * phi * phi / a));
  const double inside_gabor = old_ball<D>(a, phi, [](double) { return 1.0; });
  const double inside_diff = old_ball<D>(a, phi, [](double tau) { return (1 - tau) * (1 - tau); });
  return std::sqrt((inside_diff + (full - inside_gabor)) / full);
}

template <int D>
void check_against_old_quadrature(double a, double phi, double energy_tolerance,
                                  double truncation_tolerance) {
  CAPTURE(D);
  CAPTURE(a);
  CAPTURE(phi);
  CHECK(hush::detail::gabor_energy<D>(a, phi) ==
        doctest::Approx(old_energy<D>(a, phi)).epsilon(energy_tolerance).scale(0));
  // The truncation error is sqrt of a difference of O(1) integrals: about
  // 1e-16 / err^2 relative, times the old sum's growth with its panels (up to
  // 5e-13 measured at t = 0.05, err = 0.06, phi = 500). Compared for t >= 0.05;
  // at t = 1e-9 (err ~ 1e-8) both are rounding noise (docs/gabor.md).
  if (a < 4.0) {
    CHECK(hush::detail::gabor_truncation_error<D>(a, phi) ==
          doctest::Approx(old_truncation_error<D>(a, phi)).epsilon(truncation_tolerance).scale(0));
  }
}

}  // namespace

TEST_CASE("gabor_kernel: energy and truncation error equal the old quadrature, at bounded cost") {
  // Below kGaborAsymptoticCycles (q = 2 phi cycles per cell) the new code
  // integrates the constant part with fixed panels and the oscillatory part
  // with 2 + 4 ceil(phi): both ~1e-13 relative, so they agree to 1e-12.
  for (const double t : {0.5, 0.05, 1e-9})
    for (const double phi : {0.5, 3.0, 30.0, 300.0}) {
      check_against_old_quadrature<2>(-std::log(t), phi, 1e-12, 1e-12);
      check_against_old_quadrature<3>(-std::log(t), phi, 1e-12, 1e-12);
    }
  // Just above it (phi = 513, the leading asymptotic term's worst place: its
  // remainder falls as q^-4.5 in 2D, q^-5 in 3D) and further up, the
  // asymptotic term replaces the quadrature within the 2e-13 that
  // constants.hpp states (measured 1.3e-13 at t = 0.5, phi = 513, 2D); t = 0.5
  // has the largest taper jump, e^{-2A s0} = t^1.6.
  for (const double t : {0.5, 0.05})
    for (const double phi : {513.0, 700.0}) {
      check_against_old_quadrature<2>(-std::log(t), phi, 2e-13, 1e-12);
      check_against_old_quadrature<3>(-std::log(t), phi, 2e-13, 1e-12);
    }
}

TEST_CASE("gabor_kernel: the envelope transform's asymptotic term continues its quadrature") {
  // H(xi) by the quadrature (kept below kGaborAsymptoticCycles) against the
  // leading term above it, relative to H(0) as the spectra use it.
  for (const double t : {0.5, 0.05}) {
    const double a = -std::log(t);
    const double k = 1.0 / (1.0 - kS0);
    const double dw2[2] = {-6.0 * k * k, -6.0 * k * k};
    auto taper = [k](double s) { return hush::detail::gabor_taper(s, k); };
    auto quadrature = [&](auto dim, double xi) {
      constexpr int D = decltype(dim)::value;
      const int panels = 2 + 2 * static_cast<int>(std::ceil(xi));
      return hush::detail::ball_integral<D>(
          [&](double rho) {
            return std::exp(-a * rho * rho) * taper(rho * rho) *
                   hush::detail::angular_average<D>(2.0 * kPi * xi * rho);
          },
          panels);
    };
    for (const double xi : {1025.0, 1400.0}) {
      const double h2 = hush::detail::gabor_envelope_transform<2>(a, 0.0);
      const double h3 = hush::detail::gabor_envelope_transform<3>(a, 0.0);
      CHECK(hush::detail::radial_transform_tail<2>(a, xi, dw2) ==
            doctest::Approx(quadrature(std::integral_constant<int, 2>{}, xi)).scale(h2).epsilon(2e-13));
      CHECK(hush::detail::radial_transform_tail<3>(a, xi, dw2) ==
            doctest::Approx(quadrature(std::integral_constant<int, 3>{}, xi)).scale(h3).epsilon(2e-13));
    }
  }
}

TEST_CASE("gabor: construction at the highest frequency finishes (bounded kernel statistics)") {
  // F0 = 1e6, a = 0.3 is ~3e6 cycles per cell: the quadratures took ~30 min
  // here before the asymptotic term; now a handful of exp and cos. Every kind.
  for (const auto kind : {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic,
                          hush::gabor_kind::hybrid}) {
    hush::gabor<2>::params p2;
    p2.kind = kind;
    p2.frequency = 1e6;
    p2.bandwidth = 0.3;
    p2.frequency_spread = kind == hush::gabor_kind::hybrid ? 1e6 : 0.0;
    p2.orientation_spread = kind == hush::gabor_kind::hybrid ? 1.0 : 0.0;
    const hush::gabor<2> g2(p2);
    hush::gabor<3>::params p3;
    p3.kind = kind;
    p3.frequency = 1e6;
    p3.bandwidth = 0.3;
    p3.frequency_spread = p2.frequency_spread;
    p3.orientation_spread = p2.orientation_spread;
    const hush::gabor<3> g3(p3);
    // At ~6e6 cycles per cell the oscillatory part is < 1e-25 of the energy:
    // the mean energy is the constant part, half the F = 0 energy's.
    const double a = g2.kernel().envelope_exponent();
    const double k = 1.0 / (1.0 - kS0);
    auto w = [k](double s) {
      const double tau = hush::detail::gabor_taper(s, k);
      return tau * tau;
    };
    CHECK(g2.mean_energy() == doctest::Approx(0.5 * hush::detail::radial_mean<2>(2 * a, w)).epsilon(1e-12).scale(0));
    CHECK(std::isfinite(g2.bound()));
    CHECK(std::isfinite(g3.bound()));
    CHECK(std::isfinite(g2.kernel().truncation_error(1e6)));
    CHECK(std::isfinite(g3.kernel().envelope_transform(1e6)));
  }
}

TEST_CASE("gabor_kernel: the power spectra are the squared transforms, and tend to each other") {
  // Tapered: (H(f - F) + H(f + F))^2 / 4. As t -> 0 the taper sits where the
  // envelope is e^{-A s0} ~ 0, and the spectrum becomes the untruncated
  // closed form a^-2D (e^{-pi|f-F|^2/a^2} + e^{-pi|f+F|^2/a^2})^2 / 4.
  const double a = 0.8;
  const hush::dvec2 F{0.6, 0.5};
  const hush::gabor_kernel<2> wide(a, 1e-9), k(a, 0.05);
  for (const hush::dvec2 f :
       {hush::dvec2{0.6, 0.5}, hush::dvec2{0.0, 0.0}, hush::dvec2{1.0, -0.3}}) {
    const double exact = wide.untruncated_power_spectrum(f, F);
    CHECK(wide.power_spectrum(f, F) ==
          doctest::Approx(exact).epsilon(1e-6).scale(1.0 / (a * a * a * a)));
    double lo = 0, hi = 0;
    for (int i = 0; i < 2; ++i) {
      lo += (f[i] - F[i]) * (f[i] - F[i]);
      hi += (f[i] + F[i]) * (f[i] + F[i]);
    }
    const double h =
        0.5 * (k.envelope_transform(std::sqrt(lo)) + k.envelope_transform(std::sqrt(hi)));
    CHECK(k.power_spectrum(f, F) == doctest::Approx(h * h).epsilon(1e-15));
  }
  // Plancherel for the untruncated kernel: int |g^|^2 df = int g^2 dx
  // = (1 + e^{-2 pi |F|^2 / a^2}) / (4 a^2), by the midpoint rule over +-4a
  // around the two blobs (the rest is below e^{-32 pi}).
  const double df = 0.01;
  double sum = 0;
  const int cells = 600;  // 6 / df, counted in an integer (clang-analyzer FloatLoopCounter)
  for (int iy = 0; iy < cells; ++iy)
    for (int ix = 0; ix < cells; ++ix)
      sum += wide.untruncated_power_spectrum({-3 + (ix + 0.5) * df, -3 + (iy + 0.5) * df}, F);
  const double f2 = F.x * F.x + F.y * F.y;
  CHECK(sum * df * df ==
        doctest::Approx((1 + std::exp(-2 * kPi * f2 / (a * a))) / (4 * a * a)).epsilon(1e-6));
}

TEST_CASE(
    "gabor_kernel: truncation error matches brute force (2D) and the closed forms' tail (3D)") {
  const double a = 0.8, F = 1.0;
  const hush::gabor_kernel<2> k(a, 0.05);
  const hush::dvec2 Fv{F, 0.0};
  // int (g - g_Gabor)^2 over a square 3x the support (the Gabor tail beyond is
  // below e^{-18 A}), relative to the closed-form int g_Gabor^2.
  const double r = k.radius();
  const double diff = square_integral(3 * r, 1800, [&](const hush::dvec2& x) {
    const double d = k.value(x, Fv) - gabor_pure(a, x, Fv);
    return d * d;
  });
  const double full = (1 + std::exp(-2 * kPi * F * F / (a * a))) / (4 * a * a);
  CHECK(k.truncation_error(F) == doctest::Approx(std::sqrt(diff / full)).epsilon(1e-3));
  MESSAGE("truncation error, t = 0.05: 2D " << k.truncation_error(F) << ", 3D "
                                            << hush::gabor_kernel<3>(a, 0.05).truncation_error(F));
  // Smaller t, smaller error; F >> a: the error hardly depends on F.
  CHECK(hush::gabor_kernel<2>(a, 0.01).truncation_error(F) < k.truncation_error(F));
  CHECK(hush::gabor_kernel<3>(a, 0.01).truncation_error(F) <
        hush::gabor_kernel<3>(a, 0.05).truncation_error(F));
}

TEST_CASE("gabor_filter: the closed form is the Gabor kernel convolved with the pixel's Gaussian") {
  // Brute force: int g_Gabor(x - y) N(y; 0, sigma^2 S) dy by the midpoint rule
  // on a 401 x 401 grid over +-7 standard deviations of the Gaussian along its
  // axes (tail below 1e-11); the closed form in noise units is
  // sqrt(det Q) e^{-pi F^T (I - Q) F / a^2} e^{-pi a^2 x^T Q x} cos(2 pi <Q F, x>).
  const double a = 0.8, sigma = hush::detail::constants::kPixelFilterSigma;
  const hush::gabor_kernel<2> k(a, 0.05);
  const double A = k.envelope_exponent(), r = k.radius();
  const hush::dvec2 F{0.9, 0.35};
  const hush::dvec2 dpdx{0.3, 0.1}, dpdy{-0.05, 0.6};  // an anisotropic pixel
  const auto fp = hush::footprint<2>::from_derivatives(dpdx, dpdy);
  const hush::gabor_filter<2> flt(fp, A, 1.0 / r);
  // The Gaussian's covariance C = sigma^2 S and its principal axes.
  double c[2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) c[i][j] = sigma * sigma * fp.covariance(i, j);
  const double tr = c[0][0] + c[1][1], det = c[0][0] * c[1][1] - c[0][1] * c[1][0];
  const double l1 = 0.5 * tr + std::sqrt(0.25 * tr * tr - det), l2 = det / l1;
  const double th = 0.5 * std::atan2(2 * c[0][1], c[0][0] - c[1][1]);
  const double ux = std::cos(th), uy = std::sin(th);
  for (const hush::dvec2 x :
       {hush::dvec2{0.0, 0.0}, hush::dvec2{0.3, -0.2}, hush::dvec2{0.7, 0.5}}) {
    const int n = 401;
    const double s1 = std::sqrt(l1), s2 = std::sqrt(l2), h1 = 14 * s1 / n, h2 = 14 * s2 / n;
    double brute = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double p = -7 * s1 + (i + 0.5) * h1, q = -7 * s2 + (j + 0.5) * h2;
        const double w = std::exp(-0.5 * (p * p / l1 + q * q / l2)) / (2 * kPi * s1 * s2);
        const hush::dvec2 y{p * ux - q * uy, p * uy + q * ux};
        brute += w * gabor_pure(a, hush::dvec2{x.x - y.x, x.y - y.y}, F) * h1 * h2;
      }
    // The closed form from gabor_filter's cell-unit constants: Phi = F r, d = x / r.
    const hush::dvec2 phi{F.x * r, F.y * r}, d{x.x / r, x.y / r};
    double att = 0, env = 0, theta = 0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        att += phi[i] * flt.m[i][j] * phi[j];
        env += d[i] * flt.q[i][j] * d[j];
        theta += flt.q[i][j] * phi[j] * d[i];
      }
    const double closed =
        flt.amplitude * std::exp(-att) * std::exp(-A * env) * std::cos(2 * kPi * theta);
    CHECK(closed == doctest::Approx(brute).epsilon(1e-9).scale(1.0));
  }
}

namespace {
// gabor_filter of fp for envelopes A from 1e-6 to 1e6: finite Q and M, amplitude in (0, 1].
template <int D>
void check_filter_finite(const hush::footprint<D>& fp) {
  for (const double a : {1e-6, 0.8, 1e6}) {
    const hush::gabor_kernel<D> k(a, 0.05);
    const hush::gabor_filter<D> f(fp, k.envelope_exponent(), 1.0 / k.radius());
    CHECK(std::isfinite(f.amplitude));
    CHECK(f.amplitude > 0.0);
    CHECK(f.amplitude <= 1.0);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) {
        CHECK(std::isfinite(f.q[i][j]));
        CHECK(std::isfinite(f.m[i][j]));
      }
  }
}
}  // namespace

TEST_CASE(
    "gabor_filter: degenerate footprints give finite Q and an amplitude in 0 ... 1 (HARD_CASES row 12)") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const hush::footprint<3> cases[] = {
      hush::footprint<3>{},
      hush::footprint<3>::from_derivatives(hush::dvec3{1, 2, 3}, hush::dvec3{0, 0, 0}),  // rank 1
      hush::footprint<3>::from_derivatives(hush::dvec3{1e-15, 0, 0}, hush::dvec3{0, 1e-15, 0}),
      hush::footprint<3>::from_derivatives(hush::dvec3{1e15, 3e14, 0}, hush::dvec3{0, 1e15, 2e14}),
      hush::footprint<3>::from_derivatives(hush::dvec3{nan, 0, 0}, hush::dvec3{0, 1, 0}),
      hush::footprint<3>::isotropic(1e300)};
  for (const auto& fp : cases) check_filter_finite(fp);
  // The same in 2D, where gabor_filter<2> takes the closed form (adj / det).
  const hush::footprint<2> cases2[] = {
      hush::footprint<2>{},
      hush::footprint<2>::from_derivatives(hush::dvec2{1, 2}, hush::dvec2{0, 0}),  // rank 1
      hush::footprint<2>::from_derivatives(hush::dvec2{1e-15, 0}, hush::dvec2{0, 1e-15}),
      hush::footprint<2>::from_derivatives(hush::dvec2{1e15, 3e14}, hush::dvec2{3e14, 9e13}),
      hush::footprint<2>::from_derivatives(hush::dvec2{1e15, 3e14}, hush::dvec2{-3e14, 1e15}),
      hush::footprint<2>::from_derivatives(hush::dvec2{nan, 0}, hush::dvec2{0, 1}),
      hush::footprint<2>::isotropic(1e300)};
  for (const auto& fp : cases2) check_filter_finite(fp);
  // A point footprint leaves the kernel as it is.
  const hush::gabor_filter<2> none(hush::footprint<2>{}, 3.0, 1.0);
  CHECK(none.amplitude == 1.0);
  CHECK(none.q[0][0] == 1.0);
  CHECK(none.q[0][1] == 0.0);
  CHECK(none.m[1][1] == 0.0);
}

TEST_CASE(
    "gabor_filter<2>: the closed form equals the eigensystem's; an S off the positive "
    "semi-definite matrices is filtered as its projection, a NaN entry as 0") {
  const double a = 0.8, inv_r = 0.7;
  const double k = 2.0 * a * hush::detail::constants::kPixelFilterSigma *
                   hush::detail::constants::kPixelFilterSigma * inv_r * inv_r;
  const double mk = hush::detail::constants::kPi * hush::detail::constants::kPi / a;
  // S = R diag(l0, l1) R^T at angle t; the expected filter from the eigensystem directly:
  // Q = R diag(1 / (1 + k l+)) R^T, M = R diag(mk k l+ / (1 + k l+)) R^T, l+ = max(l, 0).
  auto check = [&](double t, double l0, double l1) {
    CAPTURE(t);
    CAPTURE(l0);
    CAPTURE(l1);
    const double c = std::cos(t), sn = std::sin(t);
    const double v[2][2] = {{c, -sn}, {sn, c}};  // columns: the eigenvectors
    const double l[2] = {l0, l1};
    double cov[2][2], q[2][2], m[2][2], det_q = 1;
    double qd[2], md[2];
    for (int e = 0; e < 2; ++e) {
      const double kl = k * std::max(l[e], 0.0);
      qd[e] = 1 / (1 + kl);
      md[e] = mk * kl / (1 + kl);
      det_q *= qd[e];
    }
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        cov[i][j] = q[i][j] = m[i][j] = 0;
        for (int e = 0; e < 2; ++e) {
          cov[i][j] += v[i][e] * l[e] * v[j][e];
          q[i][j] += v[i][e] * qd[e] * v[j][e];
          m[i][j] += v[i][e] * md[e] * v[j][e];
        }
      }
    const hush::gabor_filter<2> f(cov, a, inv_r);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        CHECK(f.q[i][j] == doctest::Approx(q[i][j]).epsilon(1e-12).scale(1.0));
        CHECK(f.m[i][j] == doctest::Approx(m[i][j]).epsilon(1e-12).scale(mk));
      }
    CHECK(f.amplitude == doctest::Approx(std::sqrt(det_q)).epsilon(1e-12));
  };
  for (const double t : {0.0, 0.3, 1.1, 2.5})
    for (const double l0 : {0.0, 1e-3, 0.7, 4.0, 50.0})
      for (const double l1 : {0.0, 0.2, 3.0, -0.5, -20.0}) check(t, l0, l1);
  check(0.4, -1.0, -3.0);  // negative definite: projected to 0, the kernel as it is
  // A NaN entry counts as 0.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double with_nan[2][2] = {{nan, 0.0}, {0.0, 2.0}}, zeroed[2][2] = {{0.0, 0.0}, {0.0, 2.0}};
  const hush::gabor_filter<2> fn(with_nan, a, inv_r), fz(zeroed, a, inv_r);
  CHECK(fn.amplitude == fz.amplitude);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      CHECK(fn.q[i][j] == fz.q[i][j]);
      CHECK(fn.m[i][j] == fz.m[i][j]);
    }
}

TEST_CASE(
    "gabor_filter_coefs: the upper triangles with M's off-diagonal doubled give Q's and M's "
    "quadratic forms") {
  // What filtered_pair reads in every backend: d^T Q d, <Phi, Q d> and Phi^T M Phi from
  // q (upper triangle) and m2 (M's, off-diagonal doubled), against the full double
  // matrices. Anisotropic footprints (off-diagonal entries), the coefficients in double:
  // only double rounding (16 ulp of the terms' magnitude) separates the two; a missing
  // doubling or a wrong entry is off by O(1).
  hush::rng r(91);
  const double ulp = std::ldexp(1.0, -52);
  for (int trial = 0; trial < 200; ++trial) {
    const hush::dvec3 du{r.uniform<double>(-2.0, 2.0), r.uniform<double>(-2.0, 2.0), r.uniform<double>(-2.0, 2.0)};
    const hush::dvec3 dv{r.uniform<double>(-2.0, 2.0), r.uniform<double>(-2.0, 2.0), r.uniform<double>(-2.0, 2.0)};
    const hush::gabor_filter<3> f(hush::footprint<3>::from_derivatives(du, dv), 2.5, 1.3);
    const hush::detail::gabor_filter_coefs<double, 3> c(f);
    CHECK(c.amplitude == f.amplitude);
    double d[3], phi[3];
    for (int i = 0; i < 3; ++i) {
      d[i] = r.uniform<double>(-1.0, 1.0);
      phi[i] = r.uniform<double>(-3.0, 3.0);
    }
    double dqd = 0, dqd_sym = 0, th = 0, th_sym = 0, att = 0, att_sym = 0, scale = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        dqd += d[i] * f.q[i][j] * d[j];
        th += phi[i] * f.q[i][j] * d[j];
        att += phi[i] * f.m[i][j] * phi[j];
        scale += std::fabs(phi[i] * f.m[i][j] * phi[j]) + std::fabs(phi[i] * f.q[i][j] * d[j]);
        const int k = hush::detail::gabor_sym<3>(i, j);
        dqd_sym += d[i] * c.q[k] * d[j];
        th_sym += phi[i] * c.q[k] * d[j];
        if (i <= j) att_sym += c.m2[k] * (phi[i] * phi[j]);
      }
    const double tol = 16 * ulp * (scale + 1);
    CHECK(std::fabs(dqd_sym - dqd) <= tol);
    CHECK(std::fabs(th_sym - th) <= tol);
    CHECK(std::fabs(att_sym - att) <= tol);
  }
  // gabor_sym: row by row, each entry once.
  CHECK(hush::detail::gabor_sym<2>(0, 1) == 1);
  CHECK(hush::detail::gabor_sym<2>(1, 0) == 1);
  CHECK(hush::detail::gabor_sym<2>(1, 1) == 2);
  CHECK(hush::detail::gabor_sym<3>(1, 1) == 3);
  CHECK(hush::detail::gabor_sym<3>(2, 1) == 4);
  CHECK(hush::detail::gabor_sym<3>(2, 2) == 5);
}

namespace {

// The orientation average of ((h(|xi - Phi|) + h(|xi + Phi|)) / 2)^2 by brute
// force, the way hush computed it before the window (cost ~ |Phi| in 2D,
// |Phi| |xi| in 3D), with 16 times the nodes in 2D (the trapezoidal rule
// there was at 3e-7 of the peak for t = 0.05, 4e-5 for t = 0.5).
template <int D, class H>
double brute_mean(double x, double ph, H h) {
  auto pair = [&](double cg) {
    const double base = x * x + ph * ph, cross = 2.0 * x * ph * cg;
    const double v = 0.5 * (h(std::sqrt(std::fmax(base - cross, 0.0))) + h(std::sqrt(base + cross)));
    return v * v;
  };
  if constexpr (D == 2) {
    const int n = 16 * (32 + static_cast<int>(std::ceil(32.0 * ph)));
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += pair(std::cos(2.0 * kPi * i / n));
    return sum / n;
  } else {
    const int panels = 2 + static_cast<int>(std::ceil(4.0 * ph * (x + 1.0)));
    return 0.5 * hush::detail::integrate(pair, -1.0, 1.0, panels);
  }
}

template <int D>
void check_window_equals_full(double cycles_per_cell, double truncation) {
  typename hush::gabor<D>::params p;
  const double frequency = cycles_per_cell / hush::gabor_kernel<D>(0.8, truncation).radius();
  p.frequency = frequency;
  p.bandwidth = 0.8;
  p.truncation = truncation;
  const hush::gabor<D> g(p);
  const double r = g.kernel().radius(), A = g.kernel().envelope_exponent(), phi = frequency * r;
  long calls = 0;
  auto h = counted_stand_in<D>(A, calls);
  const double inf = std::numeric_limits<double>::infinity();
  // spectrum_with = factor * mean; with h = 1 and no window the mean is 1.
  auto factor = [&](const hush::vec<double, D>& f) {
    return g.spectrum_with(f, [](double) { return 1.0; }, inf);
  };
  hush::vec<double, D> ring{};
  ring[0] = frequency;
  const double peak = factor(ring) * brute_mean<D>(phi, phi, h);
  // Near the ring, on it, inside and outside, and at the centre (f = 0).
  for (const double dx : {0.0, 0.3, -0.7, 3.0, 12.0, -40.0, -phi}) {
    CAPTURE(D);
    CAPTURE(phi);
    CAPTURE(truncation);
    CAPTURE(dx);
    hush::vec<double, D> f{};
    f[0] = 0.6 * (phi + dx) / r;  // off the axes: the mean is rotation invariant
    f[1] = 0.8 * (phi + dx) / r;
    const double brute = factor(f) * brute_mean<D>(phi + dx, phi, h);
    calls = 0;
    const double windowed = g.spectrum_with(f, h);
    // 16 nodes per panel, at most 10 + window / 2 panels, two calls of h each.
    CHECK(calls <= 2 * 16 * (10 + 32));
    // What the window leaves out (derivation in docs/gabor.md "Cost of the
    // spectra"): ~1.7 window^-6 = 2.5e-11 of the peak in 2D, less in 3D.
    CHECK(std::fabs(windowed - brute) <= 1e-10 * peak);
    // Without the window (every orientation): the quadratures alone (the
    // brute force's own error, ~1e-11 of the peak on the ring in 3D, where its
    // uniform panels in cos gamma cross H's core in a 4 / |Phi|^2 sliver).
    CHECK(std::fabs(g.spectrum_with(f, h, inf) - brute) <= 3e-11 * peak);
  }
}

}  // namespace

TEST_CASE("gabor: isotropic spectra over the orientation window equal the full average (bounded nodes)") {
  // |Phi| = 70, 100 cycles per cell: the full average is still affordable, and
  // |Phi| > window puts every f below on the windowed path.
  for (const double t : {0.05, 0.5}) {
    check_window_equals_full<2>(70.0, t);
    check_window_equals_full<2>(100.0, t);
    check_window_equals_full<3>(70.0, t);
  }
}

TEST_CASE("gabor: spectra at F0 = 1e6 are bounded and integrate to the variance") {
  // F0 = 1e6, a = 0.3: |Phi| ~ 3e6 cycles per cell. Before the window a call
  // took ~1e8 nodes and gabor_spectrum 1.6 GB. Parseval: the spectrum of the
  // unit-variance noise integrates to 1 over all f; isotropic noise's is a
  // ring, so int 2 pi f S(f) df (2D) and int 4 pi f^2 S(f) df (3D) across the
  // ring (what the window keeps) are 1 within gabor_spectrum's interpolation
  // (3e-5 of the peak at each f, the ring's profile summed at its own nodes:
  // a 1e-4 tolerance) plus what the window leaves out (< 1e-10).
  auto ring_integral = [](const auto& g, auto spectrum, int dim) {
    const double r = g.kernel().radius(), f0 = g.parameters().frequency;
    const double step = 1.0 / (64.0 * r), half = 70.0 / r;
    double sum = 0;
    const int n = static_cast<int>(std::ceil(2.0 * half / step));
    for (int i = 0; i <= n; ++i) {
      const double f = f0 - half + i * step;
      sum += (dim == 2 ? 2 * kPi * f : 4 * kPi * f * f) * spectrum(f) * step;
    }
    return sum;
  };
  hush::gabor<2>::params p2;
  p2.frequency = 1e6;
  p2.bandwidth = 0.3;
  const hush::gabor<2> g2(p2);
  const hush::gabor_spectrum<2> s2(g2, 1e6 + 100.0 / g2.kernel().radius());
  CHECK(ring_integral(g2, [&](double f) { return s2(hush::dvec2{f, 0.0}); }, 2) ==
        doctest::Approx(1.0).epsilon(1e-4));
  hush::gabor<3>::params p3;
  p3.frequency = 1e6;
  p3.bandwidth = 0.3;
  const hush::gabor<3> g3(p3);
  const hush::gabor_spectrum<3> s3(g3, 1e6 + 100.0 / g3.kernel().radius());
  CHECK(ring_integral(g3, [&](double f) { return s3(hush::dvec3{0.0, f, 0.0}); }, 3) ==
        doctest::Approx(1.0).epsilon(1e-4));
  // The exact power_spectrum: bounded node counts, and on the ring it equals
  // the tabulated one (within the table's 3e-5 of the peak).
  long calls = 0;
  const double a2 = g2.kernel().envelope_exponent();
  const double exact = g2.spectrum_with(hush::dvec2{0.0, 1e6}, [&](double k) {
    ++calls;
    return hush::detail::gabor_envelope_transform<2>(a2, k);
  });
  CHECK(calls <= 2 * 16 * (10 + 32));
  CHECK(exact == doctest::Approx(g2.power_spectrum(hush::dvec2{1e6, 0.0})).epsilon(1e-12));
  CHECK(exact == doctest::Approx(s2(hush::dvec2{1e6, 0.0})).epsilon(3e-5));
  CHECK(std::isfinite(g3.power_spectrum(hush::dvec3{0.0, 0.0, 1e6})));
  // Hybrid 2D (|Phi| 3e6 +- 1.5e6 cycles per cell, a 1 rad arc around 0):
  // bounded windows; positive on the arc, 0 far from it (both blobs further
  // than the window from f).
  hush::gabor<2>::params ph = p2;
  ph.kind = hush::gabor_kind::hybrid;
  ph.frequency_spread = 1e6;
  ph.orientation_spread = 1.0;
  const hush::gabor<2> gh(ph);
  const hush::gabor_spectrum<2> sh(gh, 2e6);
  CHECK(sh(hush::dvec2{1e6, 0.0}) > 0.0);
  CHECK(std::isfinite(sh(hush::dvec2{1e6, 0.0})));
  CHECK(sh(hush::dvec2{0.0, 1e6}) == 0.0);
  CHECK(g3.power_spectrum(hush::dvec3{0.0, 0.0, 1e6}) ==
        doctest::Approx(s3(hush::dvec3{0.0, 0.0, 1e6})).epsilon(3e-5));
}

TEST_CASE("gabor: hybrid 2D spectra over the frequency and orientation windows equal the full average") {
  // |Phi| = 66 +- 10 cycles per cell, orientation spread 1 rad (and 0) around
  // 30 degrees: the full average (the old node counts, ~|Phi|^2) is still
  // affordable with the stand-in H. f on the arc's middle, near its end,
  // opposite (the -Phi blob), at |Phi|'s ends and at 0. What the windows leave
  // out is pointwise below the tail's square at the window, (1.7 W^-3.5)^2 =
  // 6.6e-13 of H(0)^2; the hybrid peak is spread over the frequency range and
  // the arc, so relative to it that is ~3e-10 here (f = 0: H(|Phi|)^2 for the
  // |Phi| beyond W): a 1e-9 tolerance.
  for (const double spread : {1.0, 0.0}) {
    hush::gabor<2>::params p;
    p.kind = hush::gabor_kind::hybrid;
    const double r = hush::gabor_kernel<2>(0.8, 0.05).radius();
    p.frequency = 66.0 / r;
    p.frequency_spread = 20.0 / r;
    p.orientation = 0.5236;
    p.orientation_spread = spread;
    const hush::gabor<2> g(p);
    const double A = g.kernel().envelope_exponent();
    long calls = 0;
    auto h = counted_stand_in<2>(A, calls);
    const double inf = std::numeric_limits<double>::infinity();
    auto at = [&](double cycles, double angle) {
      return hush::dvec2{cycles / r * std::cos(angle), cycles / r * std::sin(angle)};
    };
    const double peak = g.spectrum_with(at(66.0, 0.5236), h, inf);
    for (const double cycles : {0.0, 66.3, 90.0}) {
      for (const double angle : {0.5236, 0.5236 + 0.49, 0.5236 + 3.1416}) {
        CAPTURE(spread);
        CAPTURE(cycles);
        CAPTURE(angle);
        const hush::dvec2 f = at(cycles, angle);
        calls = 0;
        const double windowed = g.spectrum_with(f, h);
        CHECK(calls <= 6000000);
        CHECK(std::fabs(windowed - g.spectrum_with(f, h, inf)) <= 1e-9 * peak);
      }
    }
  }
}


TEST_CASE("gabor: hybrid power_spectrum at F0 = 1e6 is bounded and equals the frequency density") {
  // F0 = 1e6, a = 0.3 (|Phi| ~ 3e6 cycles per cell), frequency spread 1e6,
  // orientation spread 1 rad: before, hybrid 3D took hours per value and 2D
  // minutes. Independent value: where H's blob (~1 cycle per cell wide) is
  // tiny against the range, the mean over Phi of ((H(k-) + H(k+)) / 2)^2 is
  // p(xi) int H^2 / 4 (p: the density of Phi in cell frequencies, locally
  // constant; int H^2 = the envelope's energy, Parseval) and the energy of
  // each kernel is half the envelope's (cos^2), so S(f) = r^D p(xi) / 2 with
  // p = 1 / (dphi arc |xi|) (2D) and 1 / (dphi 2 pi (1 - cos cap) |xi|^2)
  // (3D). What that leaves out: the windows' tails (~W^-5 relative), p's
  // change across the blob (~|Phi|^-2) and the table's asymptotic term
  // beyond W in the far blob (< 3e-8 H(0)): a 1e-8 tolerance (measured 2e-11
  // in 2D, -3.1e-10 in 3D).
  auto check = [](const auto& g, const auto& f, double density, long bound) {
    using V = std::decay_t<decltype(f)>;
    const double a = g.kernel().envelope_exponent(), r = g.kernel().radius();
    constexpr int D = sizeof(V) / sizeof(double);
    const auto table = g.transform_table(f);
    CHECK(table.calls() <= 64 * 19 + 1);
    long calls = 0;
    const double s = g.spectrum_with(f, [&](double k) {
      ++calls;
      return k <= 64.0 ? table(k) : hush::detail::gabor_envelope_transform_tail<D>(a, k);
    });
    CHECK(calls <= bound);
    CHECK(std::isfinite(s));
    CHECK(s == g.power_spectrum(f));
    const double limit = std::pow(r, D) * density / 2;
    MESSAGE(D << "D: S / (r^D p / 2) - 1 = " << s / limit - 1.0 << ", calls of H " << calls);
    CHECK(s == doctest::Approx(limit).epsilon(1e-8));
  };
  auto at_1e6 = [](auto p) {
    p.kind = hush::gabor_kind::hybrid;
    p.frequency = 1e6;
    p.bandwidth = 0.3;
    p.frequency_spread = 1e6;
    p.orientation = 0.5236;
    p.elevation = 0.3;  // 3D only
    p.orientation_spread = 1.0;
    return p;
  };
  const hush::gabor<2> g2(at_1e6(hush::gabor<2>::params{}));
  const double r2 = g2.kernel().radius(), f0 = 1.2e6;  // inside the band, off its centre
  const hush::dvec2 f2{f0 * std::cos(0.7), f0 * std::sin(0.7)};
  check(g2, f2, 1.0 / (g2.marks().dphi() * 1.0 * f0 * r2), 6600000L);
  const hush::gabor<3> g3(at_1e6(hush::gabor<3>::params{}));
  // f further than the window beyond the band, infinite or NaN: 0 (what the
  // windows leave out), every kind of hybrid noise; before, 2D gave NaN.
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double bad : {nan, inf, -inf, 1e300}) {
    CHECK(g2.power_spectrum(hush::dvec2{bad, 0.0}) == 0.0);
    CHECK(g3.power_spectrum(hush::dvec3{0.0, bad, 0.0}) == 0.0);
  }
  const double r3 = g3.kernel().radius();
  const hush::dvec3 xi3 = off_axis(g3, f0 * r3, 0.3);
  const double cap = g3.marks().cos_cap();
  check(g3, hush::dvec3{xi3.x / r3, xi3.y / r3, xi3.z / r3},
        1.0 / (g3.marks().dphi() * 2.0 * kPi * (1.0 - cap) * (f0 * r3) * (f0 * r3)),
        1296L * 2 * 1072 * 2);
}

TEST_CASE("gabor: hybrid 3D spectra near the cap's rim and gabor_spectrum<3> at F0 = 1e-6") {
  // Cap of 1 rad (half-angle 0.5), f at angles beta from its axis on both sides of the rim and
  // on it: before the rim cuts (gabor<3>::rim_cuts) one piece of cap_mean's rule spanned a
  // rim close to a pole and the exact spectrum was off by up to 2.3e-6 of the value (beta -
  // theta = 3e-3). gabor_spectrum<3> interpolates H (Catmull-Rom every 1/64 cycle per cell)
  // within 1.4e-6 H(0) in 3D (t <= 0.5; docs/gabor.md "Exact statistics"): G = ((H(k-) +
  // H(k+)) / 2)^2 within 2 * 1.4e-6 H(0)^2 + its square, so within 3e-6 of the peak H(0)^2.
  const double theta = 0.5;
  const double betas[] = {0.0, theta - 0.3, theta - 1e-2, theta - 3e-3, theta - 1e-4, theta,
                          theta + 1e-3, theta + 3e-2, 2.0};
  // F0 = 1e-6 (|Phi| ~ 1.2e-6 cycles per cell): S(f) = r^3 s^2 mu E[w^2] H(|f| r)^2 up to
  // O(|Phi|^2 H'' / H) ~ 1e-11 of the value (measured 9.4e-12 at |f| r = 0.1, every beta).
  hush::gabor<3>::params p;
  p.kind = hush::gabor_kind::hybrid;
  p.frequency = 1e-6;
  p.frequency_spread = 2e-6;
  p.orientation = 0.5236;
  p.elevation = 0.3;
  p.orientation_spread = 2 * theta;
  const hush::gabor<3> g(p);
  const double r = g.kernel().radius(), a = g.kernel().envelope_exponent();
  const double norm = r * r * r * g.scale() * g.scale() * g.table().exact_mean() *
                      hush::gabor<3>::weight_moment();
  auto limit = [&](double k) {
    const double h = hush::detail::gabor_envelope_transform<3>(a, k);
    return norm * h * h;
  };
  const double peak = limit(0.0);
  const hush::gabor_spectrum<3> table(g, 8.0 / r);
  for (const double k : {0.0, 0.1, 0.37, 1.0, 2.5}) {
    for (const double beta : betas) {
      CAPTURE(k);
      CAPTURE(beta);
      const hush::dvec3 xi = off_axis(g, k, beta);
      const hush::dvec3 f{xi.x / r, xi.y / r, xi.z / r}, minus{-f.x, -f.y, -f.z};
      if (k == 0.1 || k == 1.0)  // the exact spectrum (a table of H per call: a few ms each)
        CHECK(g.power_spectrum(f) == doctest::Approx(limit(k)).epsilon(1e-10));
      const double s = table(f);
      CHECK(std::isfinite(s));
      CHECK(s >= 0.0);
      CHECK(std::fabs(s - limit(k)) <= 3e-6 * peak);
      CHECK(table(minus) == doctest::Approx(s).epsilon(1e-12));  // S(-f) = S(f)
    }
  }
}

TEST_CASE("gabor: hybrid 3D gabor_spectrum at F0 = 1e6 equals the density, near the rim too") {
  // As "hybrid power_spectrum at F0 = 1e6 ..." above: where H's blob (~1 cycle per cell) is
  // tiny against the band (|Phi| 3.6e6 +- 1.8e6 cycles per cell) and the cap's rim (3e-3 rad:
  // ~1e4 cycles per cell away), S(f) = r^3 p / 2 with p = 1 / (dphi 2 pi (1 - cos theta)
  // |xi|^2), within 1e-8 for power_spectrum (measured -3.1e-10, both angles). The table's H
  // (within delta = 1.4e-6 H(0), see above) enters S through the mean over the blob of
  // (H + e)^2 - H^2: at most 2 delta H(0) int |H| / int H^2 relative to S (the ratio a few in
  // 3D's k dk measure): tolerance 1e-5 (measured 2.3e-8: the interpolation's errors alternate
  // in sign across the blob). Outside the cap (0.1 rad beyond the rim) and further than the
  // window from the band (f = 0): 0.
  hush::gabor<3>::params p;
  p.kind = hush::gabor_kind::hybrid;
  p.frequency = 1e6;
  p.bandwidth = 0.3;
  p.frequency_spread = 1e6;
  p.orientation = 0.5236;
  p.elevation = 0.3;
  p.orientation_spread = 1.0;
  const hush::gabor<3> g(p);
  const double r = g.kernel().radius(), f0 = 1.2e6;
  const double density =
      1.0 / (g.marks().dphi() * 2.0 * kPi * (1.0 - g.marks().cos_cap()) * (f0 * r) * (f0 * r));
  const double limit = r * r * r * density / 2;
  const hush::gabor_spectrum<3> table(g, 2e6);
  for (const double beta : {0.3, 0.5 - 3e-3}) {
    CAPTURE(beta);
    const hush::dvec3 xi = off_axis(g, f0 * r, beta);
    const hush::dvec3 f{xi.x / r, xi.y / r, xi.z / r};
    const double s = table(f);
    MESSAGE("beta " << beta << ": gabor_spectrum / (r^3 p / 2) - 1 = " << s / limit - 1.0);
    CHECK(std::isfinite(s));
    CHECK(s == doctest::Approx(limit).epsilon(1e-5));
    if (beta > 0.4) {  // the rim cuts on the k path (0.3 rad: the test above)
      const double exact = g.power_spectrum(f);
      MESSAGE("power_spectrum / (r^3 p / 2) - 1 = " << exact / limit - 1.0);
      CHECK(exact == doctest::Approx(limit).epsilon(1e-8));
    }
  }
  const hush::dvec3 out = off_axis(g, f0 * r, 0.6);
  CHECK(table(hush::dvec3{out.x / r, out.y / r, out.z / r}) == 0.0);
  CHECK(table(hush::dvec3{0.0, 0.0, 0.0}) == 0.0);
}
