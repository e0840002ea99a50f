// hush::wavelet against Perlin noise where the paper claims it differs (Cook & DeRose
// sec. 1, 3.7, Fig. 8): band limit in 2D, on a 2D slice of 3D noise and projected onto
// that slice's plane. The measure is hush/detail/band_limit.hpp's (its comment states
// the definition and the statistics). Fixed seeds.
#include <doctest/doctest.h>

#include <cstddef>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "hush/detail/band_limit.hpp"
#include "hush/hush.hpp"

namespace {

// One band sampled on a kSize^2 grid at kStep units: 64 units, half the 2D tile and a
// whole 3D tile (the 3D noise's period), ~22 bins to the wavelet band's peak.
constexpr std::size_t kSize = 256;
constexpr double kStep = 0.25;
constexpr double kSliceZ = 0.375;  // the slice plane, off the lattice

double leakage(const std::function<double(double, double)>& eval) {
  std::vector<double> v(kSize * kSize);
  for (std::size_t j = 0; j < kSize; ++j)
    for (std::size_t i = 0; i < kSize; ++i)
      v[j * kSize + i] = eval(static_cast<double>(i) * kStep, static_cast<double>(j) * kStep);
  return hush::detail::band_limit_fraction(v, kSize, kStep).fraction;
}

}  // namespace

TEST_CASE("band_limit_fraction: a pure ring has none below half its peak, white noise a quarter") {
  // A single cosine at 20 bins: all its power (after Hann leakage, which falls as the
  // window's spectrum, < 1e-6 of it 10 bins away) is at the peak.
  std::vector<double> v(kSize * kSize), white(kSize * kSize);
  hush::rng r(5);
  for (std::size_t j = 0; j < kSize; ++j)
    for (std::size_t i = 0; i < kSize; ++i) {
      v[j * kSize + i] = std::cos(2 * hush::detail::constants::kPi *
                                  (20.0 * static_cast<double>(i) + 12.0 * static_cast<double>(j)) /
                                  static_cast<double>(kSize));
      white[j * kSize + i] = r.gaussian<double>();
    }
  const auto ring = hush::detail::band_limit_fraction(v, kSize, 1.0);
  CHECK(ring.peak_frequency ==
        doctest::Approx(std::sqrt(20.0 * 20 + 12 * 12) / static_cast<double>(kSize)).epsilon(0.03));
  CHECK(ring.fraction < 1e-6);
  // White noise: a flat spectrum; any ring may be the peak (noise), and the fraction is the
  // share of bins inside |k| < r*/2 of all bins: between 0 and 1, finite.
  const auto w = hush::detail::band_limit_fraction(white, kSize, 1.0);
  CHECK(w.fraction >= 0);
  CHECK(w.fraction <= 1);
  // Invalid input: NaN, never a throw.
  CHECK(std::isnan(hush::detail::band_limit_fraction(v, 100, 1.0).fraction));
  v[7] = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::isnan(hush::detail::band_limit_fraction(v, kSize, 1.0).fraction));
}

TEST_CASE("wavelet: band 0 leaks far less power below half its peak than Perlin noise, "
          "and projection keeps the band limit the 3D slice loses") {
  const hush::perlin<2> p2(7);
  const hush::perlin<3> p3(7);
  const hush::wavelet<2> w2(7);
  const hush::wavelet<3> w3(7);
  const hush::footprint<3> point{};
  const double perlin2 = leakage([&](double x, double y) { return p2(hush::dvec2{x, y}); });
  const double perlin3 = leakage([&](double x, double y) { return p3(hush::dvec3{x, y, kSliceZ}); });
  const double wave2 = leakage([&](double x, double y) { return w2(hush::dvec2{x, y}); });
  const double slice = leakage([&](double x, double y) { return w3(hush::dvec3{x, y, kSliceZ}); });
  const double projected = leakage([&](double x, double y) {
    return w3.sample(hush::dvec3{x, y, kSliceZ}, hush::dvec3{0, 0, 1}, point);
  });
  MESSAGE("band leakage: perlin 2D " << perlin2 << ", perlin 3D slice " << perlin3
                                     << ", wavelet 2D " << wave2 << ", wavelet 3D slice " << slice
                                     << ", wavelet 3D projected " << projected);
  // The expected figures: wavelet 2D ~0.0002, improved Perlin ~0.02 (a factor 100). The
  // measured fractions have ~10 % relative noise (band_limit.hpp), so a factor 10 sits
  // far outside the noise on both sides.
  CHECK(wave2 < 0.1 * perlin2);
  CHECK(wave2 < 1e-3);
  // A slice of 3D noise integrates the 3D spectrum over f_z: it fills the low frequencies
  // (paper Fig. 8c); projection restores the band limit (Fig. 8d).
  CHECK(slice > 3 * wave2);
  CHECK(projected < 0.25 * slice);
}
