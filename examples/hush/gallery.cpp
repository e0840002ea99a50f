// hush — the `hush` program: `hush gallery [--out DIR]`, the showcase images.
//
// Each image is one noise at a glance: the noise on the left (512 x 512 samples) and its
// log power spectrum on the right (spectrum.hpp), so aliasing, band limits and anisotropy
// are visible next to what they look like. Adding an image is one entry in kEntries.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "caption.hpp"
#include "commands.hpp"
#include "gallery_anisotropic.hpp"
#include "gallery_coherent.hpp"
#include "gallery_npr.hpp"
#include "gallery_wavelet.hpp"
#include "gif/gif.hpp"
#include "image.hpp"
#include "noise_perlin.hpp"
#include "noises.hpp"
#include "spectrum.hpp"

namespace hush_cli {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kSize = 512;  // samples per side of each noise image
constexpr double kStep = 1.0 / 32;  // 32 samples per lattice cell: 16 x 16 cells
// Fractal sums use 4 cells of their first octave across the image, so that the sixth
// octave still has 4 samples per cell (finer octaves would alias).
constexpr double kFractalStep = 1.0 / 128;
// fBm normalised to unit variance is shown over +-3 standard deviations.
constexpr double kFbmShownRange = 3;

// kSize x kSize samples of the z-plane at `z`, from (0, 0, z) with spacing `step`.
std::vector<float> sample_square(const noise_field& field, double step, double z = 0) {
  sample_grid grid;
  grid.origin = {0, 0, z};
  grid.step = {step, step, step};
  grid.size = {kSize, kSize, 1};
  return sample_all(field, grid);
}

// The samples shown over [lo, hi], with their log power spectrum on the right.
gray_image with_spectrum(const std::vector<float>& values, double lo, double hi) {
  return side_by_side(to_gray_image(values, kSize, kSize, lo, hi),
                      log_power_spectrum(values, kSize, kSize));
}

perlin_options octaves(hush::fractal_kind kind) {
  perlin_options o;
  o.fractal = true;
  o.kind = kind;
  o.octaves = 6;
  return o;
}

gray_image perlin2d() {
  return with_spectrum(sample_square(*make_perlin({2, 0}, {}), kStep), -1, 1);
}

gray_image perlin3d_slice() {
  return with_spectrum(sample_square(*make_perlin({3, 0}, {}), kStep, 0.5), -1, 1);
}

gray_image fbm() {
  const auto field = make_perlin({2, 0}, octaves(hush::fractal_kind::fbm));
  return with_spectrum(sample_square(*field, kFractalStep), -kFbmShownRange, kFbmShownRange);
}

gray_image turbulence() {
  const auto field = make_perlin({2, 0}, octaves(hush::fractal_kind::turbulence));
  return with_spectrum(sample_square(*field, kFractalStep), 0, 1);
}

// One period (4 x 4 cells = 128 x 128 samples) repeated 2 x 2: seams would show as lines.
gray_image perlin_periodic_tiled() {
  constexpr int kPeriod = 4;
  constexpr std::size_t kTile = static_cast<std::size_t>(kPeriod / kStep);
  perlin_options o;
  o.period = {kPeriod, kPeriod, 0};
  sample_grid grid;
  grid.step = {kStep, kStep, kStep};
  grid.size = {kTile, kTile, 1};
  const std::vector<float> tile = sample_all(*make_perlin({2, 0}, o), grid);
  return repeat(to_gray_image(tile, kTile, kTile, -1, 1), 2, 2);
}

// ---- Gabor noise (hush/gabor.hpp, docs/gabor.md).

constexpr std::size_t kGaborSize = 256;  // samples per side of each Gabor panel
constexpr double kGaborStep = 1.0 / 16;  // Nyquist 8 cycles per unit
constexpr double kGaborShownRange = 3;   // unit variance shown over +-3 standard deviations

// The kinds' parameters in the gallery: F0 = 2 cycles per unit (a ring 32 pixels from the
// centre of a 256-pixel spectrum), a = 0.8, N' = 16, omega0 at 30 degrees.
hush::gabor<2>::params gabor_gallery_params(hush::gabor_kind kind) {
  hush::gabor<2>::params prm;
  prm.kind = kind;
  prm.frequency = 2;
  prm.orientation = hush::detail::constants::kPi / 6;
  if (kind == hush::gabor_kind::hybrid) {
    prm.orientation_spread = hush::detail::constants::kPi / 2;
    prm.frequency_spread = 1;
  }
  return prm;
}

// The analytic power spectrum (gabor_spectrum) on the frequency grid of
// log_power_spectrum's image, shown the same way (log10, the top kSpectrumDecades decades).
// Hybrid noise's spectrum is a quadrature per frequency (~0.3 ms), so it is computed on
// every `stride`-th frequency of each axis and held over stride x stride pixels; spectra
// are even, S(-f) = S(f), so only half of them is computed.
gray_image analytic_spectrum(const hush::gabor<2>& noise, std::size_t n, double step) {
  const std::size_t stride = noise.parameters().kind == hush::gabor_kind::hybrid ? 2 : 1;
  const double nyquist = 0.5 / step;
  const hush::gabor_spectrum<2> spectrum(noise, nyquist * std::sqrt(2.0));
  const auto half = static_cast<std::ptrdiff_t>(n / 2);
  auto freq = [&](std::ptrdiff_t k) {
    return static_cast<double>(k) / (static_cast<double>(n) * step);
  };
  std::vector<double> log_power(n * n, -std::numeric_limits<double>::infinity());
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t y = 0; y < n; y += stride)
    for (std::size_t x = 0; x < n; x += stride) {
      const std::ptrdiff_t kx = static_cast<std::ptrdiff_t>(x) - half;
      const std::ptrdiff_t ky = static_cast<std::ptrdiff_t>(y) - half;
      // The mirror -f, when it is on the image and already computed (earlier in raster order).
      const std::ptrdiff_t mx = half - kx, my = half - ky;
      double v;
      if (mx >= 0 && my >= 0 && mx < static_cast<std::ptrdiff_t>(n) &&
          my < static_cast<std::ptrdiff_t>(n) && my % static_cast<std::ptrdiff_t>(stride) == 0 &&
          mx % static_cast<std::ptrdiff_t>(stride) == 0 &&
          (my < static_cast<std::ptrdiff_t>(y) ||
           (my == static_cast<std::ptrdiff_t>(y) && mx < static_cast<std::ptrdiff_t>(x))))
        v = log_power[static_cast<std::size_t>(my) * n + static_cast<std::size_t>(mx)];
      else
        v = std::log10(spectrum(hush::vec<double, 2>{freq(kx), freq(ky)}));
      for (std::size_t yy = y; yy < std::min(n, y + stride); ++yy)
        for (std::size_t xx = x; xx < std::min(n, x + stride); ++xx) log_power[yy * n + xx] = v;
      top = std::max(top, v);
    }
  gray_image image(n, n);
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x)
      image.at(x, y) = to_gray(log_power[y * n + x], top - kSpectrumDecades, top);
  return image;
}

// One row per kind (isotropic, anisotropic, hybrid): the noise | its measured log power
// spectrum | its analytic one (Lagae et al. 2009, Figs. 4-6).
gray_image gabor_kinds() {
  std::vector<gray_image> rows;
  for (const hush::gabor_kind kind :
       {hush::gabor_kind::isotropic, hush::gabor_kind::anisotropic, hush::gabor_kind::hybrid}) {
    const hush::gabor<2> noise(gabor_gallery_params(kind));
    hush::grid<2> g;
    g.origin = {0, 0};
    g.step = {kGaborStep, kGaborStep};
    g.size = {kGaborSize, kGaborSize};
    std::vector<float> v(g.count());
    hush::evaluate_grid(noise, hush::exec::simd, g, hush::span<float>(v));
    rows.push_back(side_by_side(
        side_by_side(to_gray_image(v, kGaborSize, kGaborSize, -kGaborShownRange, kGaborShownRange),
                     log_power_spectrum(v, kGaborSize, kGaborSize)),
        analytic_spectrum(noise, kGaborSize, kGaborStep)));
  }
  gray_image out(rows[0].width, rows[0].height * rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    std::copy(rows[r].pixels.begin(), rows[r].pixels.end(),
              out.pixels.begin() + static_cast<std::ptrdiff_t>(r * rows[r].pixels.size()));
  return out;
}

// The receding plane: pixel (i, j) of a kPlaneWidth x kPlaneHeight view sees the ground
// point x = (u - 1/2) kPlaneSpan y, y = kPlaneNear / v, with u = (i + 1/2) / width and v
// from 1 (bottom row) to kPlaneHorizon (top row): from kPlaneNear units away at the
// bottom to kPlaneNear / kPlaneHorizon at the top, where pixels span many kernels.
constexpr std::size_t kPlaneWidth = 384, kPlaneHeight = 256;
constexpr double kPlaneNear = 2, kPlaneHorizon = 0.04, kPlaneSpan = 1;
// The reference: kPlaneSuper x kPlaneSuper samples per pixel pitch over +-kPlaneReach
// pixels, weighted by the Gaussian pixel filter (sigma = kPixelFilterSigma pixels).
constexpr int kPlaneSuper = 16;
constexpr double kPlaneReach = 1;

struct plane_view {
  double v_of(double j) const {  // j: pixel row, continuous, 0 at the top edge
    return kPlaneHorizon + (1 - kPlaneHorizon) * j / static_cast<double>(kPlaneHeight);
  }
  hush::vec<double, 2> at(double i, double j) const {
    const double y = kPlaneNear / v_of(j);
    return {(i / static_cast<double>(kPlaneWidth) - 0.5) * kPlaneSpan * y, y};
  }
};

// Unfiltered | analytically filtered | supersampled reference; the RMS errors against the
// reference go to `errors`.
gray_image gabor_plane(std::string& errors) {
  namespace c = hush::detail::constants;
  const hush::gabor<2> noise(gabor_gallery_params(hush::gabor_kind::isotropic));
  const plane_view view;
  const std::size_t w = kPlaneWidth, h = kPlaneHeight, n = w * h;
  std::vector<hush::vec2> pos(n);
  std::vector<hush::footprint<2>> fps(n);
  for (std::size_t j = 0; j < h; ++j)
    for (std::size_t i = 0; i < w; ++i) {
      const double ic = static_cast<double>(i) + 0.5, jc = static_cast<double>(j) + 0.5;
      const hush::vec<double, 2> p = view.at(ic, jc);
      // Screen-to-noise Jacobian by central differences of the exact mapping.
      const hush::vec<double, 2> px1 = view.at(ic + 0.5, jc), px0 = view.at(ic - 0.5, jc);
      const hush::vec<double, 2> py1 = view.at(ic, jc + 0.5), py0 = view.at(ic, jc - 0.5);
      pos[j * w + i] = {static_cast<float>(p[0]), static_cast<float>(p[1])};
      fps[j * w + i] = hush::footprint<2>::from_derivatives(
          hush::vec<double, 2>{px1[0] - px0[0], px1[1] - px0[1]},
          hush::vec<double, 2>{py1[0] - py0[0], py1[1] - py0[1]});
    }
  std::vector<float> plain(n), filtered(n);
  hush::evaluate(noise, hush::exec::simd, hush::span<const hush::vec2>(pos),
                 hush::span<float>(plain));
  hush::evaluate(noise, hush::exec::scalar, hush::samples<2>{pos, fps, {}},
                 hush::span<float>(filtered));
  // Reference: the screen lattice of pitch 1 / (kPlaneSuper / 2 / kPlaneReach) pixels, each
  // screen row one noise-space grid row (x is linear in i along a row).
  const double pitch = 2 * kPlaneReach / kPlaneSuper;
  const auto margin = static_cast<std::size_t>(std::ceil(kPlaneReach / pitch));
  const std::size_t sw = static_cast<std::size_t>(static_cast<double>(w) / pitch) + 2 * margin;
  const std::size_t sh = static_cast<std::size_t>(static_cast<double>(h) / pitch) + 2 * margin;
  std::vector<float> fine(sw * sh);
  const auto margin_d = static_cast<double>(margin);
  auto screen = [&](std::size_t k) { return (static_cast<double>(k) - margin_d + 0.5) * pitch; };
  for (std::size_t r = 0; r < sh; ++r) {
    const hush::vec<double, 2> p0 = view.at(screen(0), screen(r));
    const hush::vec<double, 2> p1 = view.at(screen(1), screen(r));
    hush::grid<2> g;
    g.origin = {p0[0], p0[1]};
    g.step = {p1[0] - p0[0], 1};
    g.size = {sw, 1};
    hush::evaluate_grid(noise, hush::exec::simd, g, hush::span<float>(fine.data() + r * sw, sw));
  }
  std::vector<float> ref(n);
  const double inv2s2 = 1 / (2 * c::kPixelFilterSigma * c::kPixelFilterSigma);
  for (std::size_t j = 0; j < h; ++j)
    for (std::size_t i = 0; i < w; ++i) {
      const double ic = static_cast<double>(i) + 0.5, jc = static_cast<double>(j) + 0.5;
      const auto k0 = static_cast<std::size_t>((ic - kPlaneReach) / pitch + margin_d);
      const auto r0 = static_cast<std::size_t>((jc - kPlaneReach) / pitch + margin_d);
      double sum = 0, wsum = 0;
      for (std::size_t r = r0; r < r0 + kPlaneSuper + 1 && r < sh; ++r)
        for (std::size_t k = k0; k < k0 + kPlaneSuper + 1 && k < sw; ++k) {
          const double du = screen(k) - ic, dv = screen(r) - jc;
          if (du * du + dv * dv > kPlaneReach * kPlaneReach) continue;
          const double wt = std::exp(-(du * du + dv * dv) * inv2s2);
          sum += wt * fine[r * sw + k];
          wsum += wt;
        }
      ref[j * w + i] = static_cast<float>(sum / wsum);
    }
  auto rms = [&](const std::vector<float>& a) {
    double e = 0;
    for (std::size_t k = 0; k < n; ++k) e += (double(a[k]) - ref[k]) * (double(a[k]) - ref[k]);
    return std::sqrt(e / static_cast<double>(n));
  };
  const double rms_plain = rms(plain), rms_filtered = rms(filtered);
  char buf[160];
  std::snprintf(buf, sizeof buf, "RMS error vs reference: unfiltered %.3f, filtered %.3f",
                rms_plain, rms_filtered);
  errors = buf;
  auto show = [&](const std::vector<float>& a) {
    return to_gray_image(a, w, h, -kGaborShownRange, kGaborShownRange);
  };
  // Each image's error against the reference under it, in the image itself.
  char under_plain[48], under_filtered[48], under_ref[48];
  std::snprintf(under_plain, sizeof under_plain, "unfiltered: RMS error %.3f", rms_plain);
  std::snprintf(under_filtered, sizeof under_filtered, "filtered: RMS error %.3f", rms_filtered);
  std::snprintf(under_ref, sizeof under_ref, "reference: %d x %d samples", kPlaneSuper,
                kPlaneSuper);
  return with_captions(side_by_side(side_by_side(show(plain), show(filtered)), show(ref)),
                       {under_plain, under_filtered, under_ref});
}

// The last gabor_filtering() image's errors, printed under its line.
std::string& gabor_plane_errors() {
  static std::string errors;
  return errors;
}
gray_image gabor_filtering() { return gabor_plane(gabor_plane_errors()); }

struct gallery_entry {
  const char* file;
  const char* what;
  gray_image (*render)();
};

const gallery_entry kEntries[] = {
    {"perlin2d.png", "Perlin 2D, seed 0, 16 x 16 cells | log power spectrum", perlin2d},
    {"perlin3d_slice.png", "Perlin 3D, the z = 0.5 plane, 16 x 16 cells | log power spectrum",
     perlin3d_slice},
    {"fbm.png", "fBm of 6 Perlin octaves, unit variance shown over [-3, 3] | log power spectrum",
     fbm},
    {"turbulence.png", "turbulence of 6 Perlin octaves, [0, 1] | log power spectrum", turbulence},
    {"perlin_periodic_tiled.png", "periodic Perlin, period 4 x 4 cells, one period tiled 2 x 2",
     perlin_periodic_tiled},
    {"gabor_kinds.png",
     "Gabor noise, isotropic / anisotropic / hybrid rows: noise [-3, 3] | measured | analytic "
     "log power spectrum",
     gabor_kinds},
    {"gabor_filtering.png",
     "Gabor noise on a receding plane: unfiltered | analytically filtered | 16 x 16 "
     "supersampled reference",
     gabor_filtering},
};

}  // namespace

const std::vector<option_spec>& gallery_options() {
  static const std::vector<option_spec> options = {
      {"--out", "DIR", "directory for the PNG images, created if needed (default: gallery)"},
  };
  return options;
}

int run_gallery(const std::vector<std::string>& args) {
  std::string dir = "gallery";
  arg_reader in(args);
  while (!in.done()) {
    in.option(gallery_options());  // --out is the only one
    dir = in.value();
  }
  if (!png_supported()) throw usage_error(png_unavailable_reason());
  if (!spectrum_supported()) throw usage_error(spectrum_unavailable_reason());

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw run_error("cannot create directory '" + dir + "': " + ec.message());
  const std::size_t count = std::size(kEntries);
  std::vector<std::string> written;
  for (std::size_t n = 0; n < count; ++n) {
    const gallery_entry& e = kEntries[n];
    std::fprintf(stderr, "gallery: [%zu/%zu] %s\n", n + 1, count, e.file);
    const gray_image image = e.render();
    write_png((fs::path(dir) / e.file).string(), image);
    written.push_back(std::string(e.file) + " (" + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + "): " + e.what);
    if (e.render == gabor_filtering) written.back() += "\n    " + gabor_plane_errors();
  }
  // Scene-driven noises: stills as PNG, animations as GIF (examples/gif).
  std::vector<gallery_item> items = coherent_gallery_items();
  for (gallery_item& e : npr_gallery_items()) items.push_back(std::move(e));
  for (gallery_item& e : wavelet_gallery_items()) items.push_back(std::move(e));
  for (std::size_t n = 0; n < items.size(); ++n) {
    const gallery_item& e = items[n];
    std::fprintf(stderr, "gallery: [%zu/%zu] %s\n", n + 1, items.size(), e.file);
    // Gray frames, or colour ones (3 bytes per pixel) for a render_rgb entry.
    std::vector<std::vector<std::uint8_t>> bytes;
    std::size_t width = 0, height = 0;
    if (e.render_rgb) {
      for (rgb_image& f : e.render_rgb()) {
        width = f.width;
        height = f.height;
        bytes.push_back(std::move(f.pixels));
      }
    } else {
      for (gray_image& f : e.render()) {
        width = f.width;
        height = f.height;
        bytes.push_back(std::move(f.pixels));
      }
    }
    const std::string path = (fs::path(dir) / e.file).string();
    if (bytes.size() == 1 && !e.render_rgb) {
      gray_image still(width, height);
      still.pixels = std::move(bytes[0]);
      write_png(path, still);
    } else {
      try {
        (e.render_rgb ? hush_tools::gif::save_rgb : hush_tools::gif::save)(
            path, bytes, static_cast<int>(width), static_cast<int>(height), e.delay_cs);
      } catch (const std::runtime_error& err) {
        throw run_error(err.what());
      }
    }
    written.push_back(std::string(e.file) + " (" + std::to_string(width) + "x" +
                      std::to_string(height) +
                      (bytes.size() > 1 ? ", " + std::to_string(bytes.size()) + " frames" : "") +
                      "): " + e.what);
  }
  write_wavelet_fig9(dir, written);         // RGB: three bands' spectra in three colours
  write_anisotropic_gallery(dir, written);  // the paper's figures, with their errors
  const fs::path absolute = fs::weakly_canonical(fs::absolute(dir));
  std::cout << "wrote " << written.size() << " images to " << absolute.string() << '\n';
  for (const std::string& w : written) std::cout << "  " << w << '\n';
  return 0;
}

}  // namespace hush_cli
