// hush — the `hush` program: `hush gallery [--out DIR]`, the showcase images.
//
// Each image is one noise at a glance: the noise on the left (512 x 512 samples) and its
// log power spectrum on the right (spectrum.hpp), so aliasing, band limits and anisotropy
// are visible next to what they look like. Adding an image is one entry in kEntries.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

#include "commands.hpp"
#include "gallery_anisotropic.hpp"
#include "gallery_coherent.hpp"
#include "gif/gif.hpp"
#include "image.hpp"
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
  }
  // Scene-driven noises: stills as PNG, animations as GIF (examples/gif).
  const std::vector<gallery_item> items = coherent_gallery_items();
  for (std::size_t n = 0; n < items.size(); ++n) {
    const gallery_item& e = items[n];
    std::fprintf(stderr, "gallery: [%zu/%zu] %s\n", n + 1, items.size(), e.file);
    const std::vector<gray_image> frames = e.render();
    const std::string path = (fs::path(dir) / e.file).string();
    if (frames.size() == 1) {
      write_png(path, frames[0]);
    } else {
      std::vector<std::vector<std::uint8_t>> bytes;
      bytes.reserve(frames.size());
      for (const gray_image& f : frames) bytes.push_back(f.pixels);
      try {
        hush::gif::save(path, bytes, static_cast<int>(frames[0].width),
                        static_cast<int>(frames[0].height), e.delay_cs);
      } catch (const std::runtime_error& err) {
        throw run_error(err.what());
      }
    }
    written.push_back(std::string(e.file) + " (" + std::to_string(frames[0].width) + "x" +
                      std::to_string(frames[0].height) +
                      (frames.size() > 1 ? ", " + std::to_string(frames.size()) + " frames" : "") +
                      "): " + e.what);
  }
  write_anisotropic_gallery(dir, written);  // the paper's figures, with their errors
  const fs::path absolute = fs::weakly_canonical(fs::absolute(dir));
  std::cout << "wrote " << written.size() << " images to " << absolute.string() << '\n';
  for (const std::string& w : written) std::cout << "  " << w << '\n';
  return 0;
}

}  // namespace hush_cli
