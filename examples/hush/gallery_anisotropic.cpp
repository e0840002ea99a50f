// hush — the `hush` program: the gallery's anisotropic-noise images (see gallery_anisotropic.hpp).
#include "gallery_anisotropic.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>

#include "figures.hpp"
#include "image.hpp"
#include "spectrum.hpp"

namespace hush_cli {
namespace {

namespace fs = std::filesystem;

// Shown over +- this many standard deviations.
constexpr double kShownSigmas = 3.0;

double stddev(const hush_tools::aniso::image& im) {
  double s = 0, s2 = 0;
  for (float v : im.v) {
    s += v;
    s2 += double(v) * v;
  }
  const double n = static_cast<double>(im.v.size());
  return std::sqrt(std::max(s2 / n - (s / n) * (s / n), 1e-30));
}

gray_image gray(const hush_tools::aniso::image& im, double half_range) {
  return to_gray_image(im.v, im.width, im.height, -half_range, half_range);
}

// `top` above `bottom` (same width).
gray_image stacked(const gray_image& top, const gray_image& bottom) {
  gray_image out(top.width, top.height + bottom.height);
  std::copy(top.pixels.begin(), top.pixels.end(), out.pixels.begin());
  std::copy(bottom.pixels.begin(), bottom.pixels.end(),
            out.pixels.begin() + static_cast<std::ptrdiff_t>(top.pixels.size()));
  return out;
}

gray_image row(const std::vector<gray_image>& images) {
  gray_image out = images.front();
  for (std::size_t i = 1; i < images.size(); ++i) out = side_by_side(out, images[i]);
  return out;
}

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

// Figures 2 and 3: the four orientation subbands of one scale and their isotropic sum,
// spectra below.
gray_image subbands(std::string& caption) {
  const std::vector<hush_tools::aniso::image> tiles = hush_tools::aniso::figure2(4, 256, 7);
  std::vector<gray_image> top, bottom;
  for (const auto& t : tiles) {
    top.push_back(gray(t, kShownSigmas * stddev(t)));
    bottom.push_back(log_power_spectrum(t.v, t.width, t.height));
  }
  caption =
      "the 4 oriented subbands of one scale (K = 4, 256^2 tile) and their sum, which is "
      "isotropic band-limited noise (paper figs. 2, 3) | log power spectra below";
  return stacked(row(top), row(bottom));
}

// Figure 6: two octaves on a trapezoid: none, least squares, heuristic.
gray_image trapezoid(std::string& caption) {
  const std::vector<hush_tools::aniso::image> v = hush_tools::aniso::figure6(384, 192);
  const double r = kShownSigmas * stddev(v[1]);
  caption =
      "a square of texture on a trapezoid, 2 octaves, K = 4, 5 scales (paper fig. 6): "
      "no compensation | least squares | heuristic";
  return row({gray(v[0], r), gray(v[1], r), gray(v[2], r)});
}

// Figure 8: resampling a high-frequency image under shear and non-uniform scale.
gray_image resampling(std::string& caption) {
  const std::vector<hush_tools::aniso::resampling_result> r = hush_tools::aniso::figure8();
  const double range = kShownSigmas * stddev(r.front().result);
  std::vector<gray_image> panels;
  caption =
      "resampling under shear and non-uniform scale (paper fig. 8), MSE against the "
      "Gaussian reference:";
  for (const auto& x : r) {
    panels.push_back(gray(x.result, range));
    caption += " " + x.name + (x.mse > 0 ? " " + fixed(x.mse, 3) : "") + " |";
  }
  caption.pop_back();
  return row(panels);
}

// Figure 9: a receding plane, 2 octaves.
gray_image receding(std::string& caption) {
  const hush_tools::aniso::receding_result r = hush_tools::aniso::figure9(512, 256);
  const double range = kShownSigmas * stddev(r.unfiltered4);
  caption = "receding plane, 2 octaves (paper fig. 9), top to bottom: K = 4 (RMS " +
            fixed(r.rms4, 3) + " against the reference) | K = 8 (" + fixed(r.rms8, 3) +
            ") | unfiltered (" + fixed(r.rms_unfiltered4, 3) +
            ") | supersampled reference (9 x 9 samples per pixel)";
  return stacked(stacked(gray(r.filtered4, range), gray(r.filtered8, range)),
                 stacked(gray(r.unfiltered4, range), gray(r.reference4, range)));
}

// Figure 13: steered by an orientation field.
gray_image field(std::string& caption) {
  const hush_tools::aniso::image im = hush_tools::aniso::figure13(384, 4.0);
  caption =
      "noise steered by a vortex orientation field, features 4 x longer along it "
      "(paper fig. 13; per-sample targets as surface maps) | log power spectrum";
  return side_by_side(gray(im, kShownSigmas * stddev(im)), log_power_spectrum(im.v, 384, 384));
}

struct entry {
  const char* file;
  gray_image (*render)(std::string& caption);
};
const entry kEntries[] = {
    {"anisotropic_subbands.png", subbands},     {"anisotropic_trapezoid.png", trapezoid},
    {"anisotropic_resampling.png", resampling}, {"anisotropic_receding.png", receding},
    {"anisotropic_field.png", field},
};

}  // namespace

void write_anisotropic_gallery(const std::string& dir, std::vector<std::string>& written) {
  const std::size_t count = std::size(kEntries);
  for (std::size_t n = 0; n < count; ++n) {
    std::fprintf(stderr, "gallery: anisotropic [%zu/%zu] %s\n", n + 1, count, kEntries[n].file);
    std::string caption;
    const gray_image image = kEntries[n].render(caption);
    write_png((fs::path(dir) / kEntries[n].file).string(), image);
    written.push_back(std::string(kEntries[n].file) + " (" + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + "): " + caption);
  }
}

}  // namespace hush_cli
