// hush — the `hush` program: wavelet noise's gallery images (gallery_wavelet.hpp).
#include "gallery_wavelet.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "hush/hush.hpp"
#include "image.hpp"
#include "spectrum.hpp"

namespace hush_cli {
namespace {

// Fig. 8: 256^2 samples at 1/8 unit (32 units: 32 band-0 coefficients across), seed 7.
constexpr std::size_t kFigSize = 256;
constexpr double kFigStep = 0.125;
constexpr double kFigSliceZ = 0.375;  // the slice plane, off the lattice
constexpr double kShownRange = 3;     // unit variance shown over +-3

// Rows stacked top to bottom (equal widths).
gray_image stack(const std::vector<gray_image>& rows) {
  gray_image out(rows[0].width, 0);
  for (const gray_image& r : rows) {
    out.pixels.insert(out.pixels.end(), r.pixels.begin(), r.pixels.end());
    out.height += r.height;
  }
  return out;
}

template <class Eval>
gray_image noise_and_spectrum(Eval eval) {
  std::vector<float> v(kFigSize * kFigSize);
  for (std::size_t j = 0; j < kFigSize; ++j)
    for (std::size_t i = 0; i < kFigSize; ++i)
      v[j * kFigSize + i] = static_cast<float>(
          eval(static_cast<double>(i) * kFigStep, static_cast<double>(j) * kFigStep));
  return side_by_side(to_gray_image(v, kFigSize, kFigSize, -kShownRange, kShownRange),
                      log_power_spectrum(v, kFigSize, kFigSize));
}

// Perlin 2D, wavelet 2D, a slice of 3D wavelet noise, the same projected onto the slice
// plane (normal z, exact projection); each beside its log power spectrum.
std::vector<gray_image> fig8() {
  const hush::perlin<2> perlin(7);
  const hush::wavelet<2> w2(7);
  const hush::wavelet<3> w3(7);
  const hush::footprint<3> point{};
  // Perlin noise has variance ~0.1 (hush/perlin.hpp): scaled by 3 to share the grey scale.
  return {stack({noise_and_spectrum([&](double x, double y) {
                   return 3 * perlin(hush::dvec2{x, y});
                 }),
                 noise_and_spectrum([&](double x, double y) {
                   return w2(hush::dvec2{x, y});
                 }),
                 noise_and_spectrum([&](double x, double y) {
                   return w3(hush::dvec3{x, y, kFigSliceZ});
                 }),
                 noise_and_spectrum([&](double x, double y) {
                   return w3.sample(hush::dvec3{x, y, kFigSliceZ}, hush::dvec3{0, 0, 1}, point);
                 })})};
}

// The receding plane: kPlaneW x kPlaneH pixels of the ground below a pinhole camera, pixel
// (i, j) at kScale (u / v, 1 / v), u in (-1, 1) across, v in (kV0, 1] from the horizon down;
// one sample per pixel (wavelet: 8 bands, weights 2^-b, footprint from the map's
// derivatives; Perlin fBm: 8 octaves, gain 1/2, unit variance, no filter) beside the
// kSuper x kSuper box-supersampled reference of each.
constexpr std::size_t kPlaneW = 384, kPlaneH = 192;
constexpr int kSuper = 16, kBands = 8;
constexpr double kV0 = 0.02, kScale = 4.0;

hush::dvec2 plane(double i, double j) {
  const double u = 2 * i / static_cast<double>(kPlaneW) - 1;
  const double v = kV0 + (1 - kV0) * j / static_cast<double>(kPlaneH);
  return {kScale * u / v, kScale / v};
}

std::string& plane_errors() {
  static std::string text;
  return text;
}

std::vector<gray_image> receding_plane() {
  hush::wavelet<2>::params wp;
  wp.seed = 11;
  wp.weights.clear();
  for (int b = 0; b < kBands; ++b) wp.weights.push_back(std::ldexp(1.0, -b));
  const hush::wavelet<2> wave(wp);
  hush::fractal<hush::perlin<2>>::params fp;
  fp.seed = 11;
  fp.octaves = kBands;
  const hush::fractal<hush::perlin<2>> fbm(fp);
  constexpr std::size_t n = kPlaneW * kPlaneH;
  std::vector<float> one_w(n), ref_w(n), one_f(n), ref_f(n);
  for (std::size_t j = 0; j < kPlaneH; ++j)
    for (std::size_t i = 0; i < kPlaneW; ++i) {
      const double ci = static_cast<double>(i) + 0.5, cj = static_cast<double>(j) + 0.5;
      const hush::dvec2 c = plane(ci, cj);
      const double h = 1e-3;  // the footprint from central differences of the exact map
      const hush::dvec2 px = plane(ci + h, cj), mx = plane(ci - h, cj);
      const hush::dvec2 py = plane(ci, cj + h), my = plane(ci, cj - h);
      const hush::dvec2 dx{(px[0] - mx[0]) * (0.5 / h), (px[1] - mx[1]) * (0.5 / h)};
      const hush::dvec2 dy{(py[0] - my[0]) * (0.5 / h), (py[1] - my[1]) * (0.5 / h)};
      one_w[j * kPlaneW + i] =
          static_cast<float>(wave.sample(c, hush::footprint<2>::from_derivatives(dx, dy)));
      one_f[j * kPlaneW + i] = static_cast<float>(fbm(c));
      double sw = 0, sf = 0;
      for (int b = 0; b < kSuper; ++b)
        for (int a = 0; a < kSuper; ++a) {
          const hush::dvec2 q = plane(static_cast<double>(i) + (a + 0.5) / kSuper,
                                      static_cast<double>(j) + (b + 0.5) / kSuper);
          sw += wave(q);
          sf += fbm(q);
        }
      ref_w[j * kPlaneW + i] = static_cast<float>(sw / (kSuper * kSuper));
      ref_f[j * kPlaneW + i] = static_cast<float>(sf / (kSuper * kSuper));
    }
  const auto rms = [](const std::vector<float>& a, const std::vector<float>& b) {
    double e = 0;
    for (std::size_t k = 0; k < n; ++k) e += (double(a[k]) - b[k]) * (double(a[k]) - b[k]);
    return std::sqrt(e / static_cast<double>(n));
  };
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "RMS error vs 16x16 reference: wavelet + footprint %.3f, Perlin fBm %.3f",
                rms(one_w, ref_w), rms(one_f, ref_f));
  plane_errors() = buf;
  std::fprintf(stderr, "gallery: wavelet_plane.png: %s\n", buf);
  const auto show = [](const std::vector<float>& v) {
    return to_gray_image(v, kPlaneW, kPlaneH, -kShownRange, kShownRange);
  };
  return {stack({side_by_side(show(one_w), show(ref_w)), side_by_side(show(one_f), show(ref_f))})};
}

// Fig. 9: bands b = 0, 1, 2 (frequencies 1, 2, 4) sampled kFigSize^2 at kFig9Step, so the
// finest band has 4 samples per unit (wavelet band 2 lies below the sampling Nyquist
// frequency; Perlin's octave 2 reaches it, as Perlin's spectrum has no upper edge).
constexpr double kFig9Step = 1.0 / 16;
constexpr int kFig9Bands = 3;
constexpr double kFig9Decades = 3;  // each band's top 3 decades: its main lobe, not its tails

// How much adjacent bands overlap in frequency: each band's power normalised to sum 1,
// the overlap of bands b and b + 1 is sum over bins of min(p_b, p_b+1) (0 for disjoint
// spectra, 1 for equal ones), averaged over the pairs (0, 1) and (1, 2).
double band_overlap(const std::vector<std::vector<double>>& power) {
  double overlap = 0;
  for (std::size_t b = 0; b + 1 < power.size(); ++b) {
    double lo = 0, hi = 0, shared = 0;
    for (std::size_t n = 0; n < power[b].size(); ++n) {
      lo += power[b][n];
      hi += power[b + 1][n];
    }
    for (std::size_t n = 0; n < power[b].size(); ++n)
      shared += std::min(power[b][n] / lo, power[b + 1][n] / hi);
    overlap += shared;
  }
  return overlap / static_cast<double>(power.size() - 1);
}

// The three bands' log power spectra as red, green, blue; their band_overlap in `overlap`.
template <class Band>
rgb_image band_spectra(Band band, double& overlap) {
  std::vector<gray_image> shown;
  std::vector<std::vector<double>> power;
  for (int b = 0; b < kFig9Bands; ++b) {
    const auto eval = band(b);
    std::vector<float> v(kFigSize * kFigSize);
    for (std::size_t j = 0; j < kFigSize; ++j)
      for (std::size_t i = 0; i < kFigSize; ++i)
        v[j * kFigSize + i] = static_cast<float>(eval(
            hush::dvec2{static_cast<double>(i) * kFig9Step, static_cast<double>(j) * kFig9Step}));
    shown.push_back(log_power_spectrum(v, kFigSize, kFigSize, kFig9Decades));
    power.push_back(power_spectrum(v, kFigSize, kFigSize));
  }
  overlap = band_overlap(power);
  return compose_rgb(shown[0], shown[1], shown[2]);
}

}  // namespace

void write_wavelet_fig9(const std::string& dir, std::vector<std::string>& written) {
  const char* file = "wavelet_fig9.png";
  std::fprintf(stderr, "gallery: %s\n", file);
  const hush::perlin<2> perlin(7);
  double perlin_overlap = 0, wavelet_overlap = 0;
  const rgb_image left = band_spectra(
      [&](int b) {
        const double f = std::ldexp(1.0, b);  // Perlin's octave b: the noise at frequency 2^b
        return [&perlin, f](hush::dvec2 p) { return perlin(hush::dvec2{f * p[0], f * p[1]}); };
      },
      perlin_overlap);
  const rgb_image right = band_spectra(
      [](int b) {
        hush::wavelet<2>::params prm;  // one band, b
        prm.seed = 7;
        prm.first_band = b;
        return hush::wavelet<2>(prm);
      },
      wavelet_overlap);
  rgb_image image(left.width + right.width, left.height);
  for (std::size_t y = 0; y < image.height; ++y) {
    const auto row = [&](const rgb_image& from) {
      return from.pixels.begin() + static_cast<std::ptrdiff_t>(3 * y * from.width);
    };
    std::copy(row(left), row(left) + static_cast<std::ptrdiff_t>(3 * left.width), image.at(0, y));
    std::copy(row(right), row(right) + static_cast<std::ptrdiff_t>(3 * right.width),
              image.at(left.width, y));
  }
  write_png((std::filesystem::path(dir) / file).string(), image);
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "adjacent bands' spectral overlap (0 disjoint, 1 equal): Perlin %.3f, wavelet "
                "%.3f",
                perlin_overlap, wavelet_overlap);
  std::fprintf(stderr, "gallery: %s: %s\n", file, buf);
  written.push_back(
      std::string(file) + " (" + std::to_string(image.width) + "x" + std::to_string(image.height) +
      "): Cook & DeRose Fig. 9, log power spectra (top 3 decades) of bands 0, 1, 2 as red, green, "
      "blue: Perlin | wavelet\n    " +
      buf);
}

std::vector<gallery_item> wavelet_gallery_items() {
  return {{"wavelet_fig8.png",
           "Cook & DeRose Fig. 8, rows: Perlin 2D (x3), wavelet 2D, wavelet 3D slice z = 0.375, "
           "wavelet 3D projected onto that plane; noise [-3, 3] | log power spectrum",
           fig8},
          {"wavelet_plane.png",
           "receding plane, one sample per pixel | 16x16 supersampled: wavelet (8 bands, "
           "footprint fade) top, Perlin fBm (8 octaves) bottom",
           receding_plane}};
}

}  // namespace hush_cli
