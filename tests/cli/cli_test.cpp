// Tests of the `hush` program (DESIGN.md, "The `hush` program"): each test runs the built
// binary (HUSH_CLI_EXE), then checks what it wrote against the library itself: .npy samples
// bit for bit against hush::perlin / hush::fractal, PNG headers and pixels, the periodic
// option, the gallery, and that every bad input fails with one line naming the option.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "caption.hpp"
#include "hush/hush.hpp"
#include "run_hush.hpp"

#if HUSH_CLI_TEST_DECODE
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include "stb_image.h"
#endif

namespace {

namespace fs = std::filesystem;

// ---- Running the program (run_hush.hpp).

using hush_cli_test::result;
using hush_cli_test::run_hush;
using hush_cli_test::scratch;
using hush_cli_test::slurp;

// ---- Reading .npy files (NPY 1.0, as numpy.lib.format defines it).

struct npy_file {
  std::string header;  // the dict literal, padding and '\n' included
  std::size_t data_offset = 0;
  std::vector<std::size_t> shape;
  std::vector<float> values;  // C order
};

npy_file read_npy(const fs::path& path) {
  const std::string bytes = slurp(path);
  npy_file f;
  REQUIRE(bytes.size() >= 10);
  REQUIRE(bytes.compare(0, 6, "\x93NUMPY") == 0);
  REQUIRE(bytes[6] == 1);  // version 1.0
  REQUIRE(bytes[7] == 0);
  const std::size_t len = static_cast<unsigned char>(bytes[8]) |
                          static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8;
  f.data_offset = 10 + len;
  REQUIRE(bytes.size() >= f.data_offset);
  f.header = bytes.substr(10, len);
  const std::size_t open = f.header.find("'shape': (");
  REQUIRE(open != std::string::npos);
  std::size_t at = open + 10;
  while (f.header[at] != ')') {
    std::size_t used = 0;
    f.shape.push_back(std::stoul(f.header.substr(at), &used));
    at += used;
    while (f.header[at] == ',' || f.header[at] == ' ') ++at;
  }
  std::size_t count = 1;
  for (std::size_t n : f.shape) count *= n;
  REQUIRE(bytes.size() == f.data_offset + 4 * count);
  f.values.resize(count);
  for (std::size_t n = 0; n < count; ++n) {
    std::uint32_t bits = 0;  // little-endian, whatever the host's byte order
    for (int b = 0; b < 4; ++b)
      bits |= std::uint32_t(static_cast<unsigned char>(bytes[f.data_offset + 4 * n + b]))
              << (8 * b);
    std::memcpy(&f.values[n], &bits, 4);
  }
  return f;
}

std::uint32_t bits(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, 4);
  return b;
}

// Counts the samples of `f` (shape (nz,) ny, nx) that differ, bit for bit, from
// expected(i, j, k), which gets the indices as doubles (as the program converts them).
template <class Expected>
std::size_t count_mismatches(const npy_file& f, Expected expected) {
  const std::size_t nx = f.shape.back(), ny = f.shape[f.shape.size() - 2];
  const std::size_t nz = f.shape.size() == 3 ? f.shape[0] : 1;
  std::size_t bad = 0;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        if (bits(f.values[(k * ny + j) * nx + i]) !=
            bits(expected(static_cast<double>(i), static_cast<double>(j), static_cast<double>(k))))
          ++bad;
  return bad;
}

#if HUSH_CLI_TEST_PNG
// ---- Reading PNG files: the signature and IHDR; pixels through stb_image when available.

struct png_header {
  std::uint32_t width = 0, height = 0;
  int bit_depth = 0, color_type = 0;
};

png_header read_png_header(const fs::path& path) {
  const std::string bytes = slurp(path);
  REQUIRE(bytes.size() >= 33);
  REQUIRE(bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  REQUIRE(bytes.compare(12, 4, "IHDR") == 0);  // the first chunk, as the PNG spec requires
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int b = 0; b < 4; ++b) v = v << 8 | static_cast<unsigned char>(bytes[at + b]);
    return v;
  };
  png_header h;
  h.width = be32(16);
  h.height = be32(20);
  h.bit_depth = static_cast<unsigned char>(bytes[24]);
  h.color_type = static_cast<unsigned char>(bytes[25]);
  return h;
}

#if HUSH_CLI_TEST_DECODE
struct gray_pixels {
  int width = 0, height = 0;
  std::vector<int> pixels;  // row-major, row 0 at the top
  int at(int x, int y) const { return pixels[static_cast<std::size_t>(y * width + x)]; }
};

gray_pixels decode_png(const fs::path& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.string().c_str(), &w, &h, &channels, 1);
  REQUIRE(data != nullptr);
  gray_pixels g{w, h, std::vector<int>(data, data + w * h)};
  stbi_image_free(data);
  return g;
}
#endif
#endif  // HUSH_CLI_TEST_PNG

const char* const kSampleArgs2d = "--dim 2 --size 16x8 --origin 1.5,-2 --step 0.25 --seed 7";

}  // namespace

// ---- (a) .npy output: format and bit-exact values.

TEST_CASE("sample 2D writes an NPY 1.0 float32 file of shape (ny, nx), 64-byte aligned") {
  const fs::path dir = scratch("npy_format");
  const result r = run_hush(
      std::string("sample perlin ") + kSampleArgs2d + " --out '" + (dir / "x.npy").string() + "'",
      dir);
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(r.out.empty());
  const npy_file f = read_npy(dir / "x.npy");
  CHECK(f.data_offset % 64 == 0);
  CHECK(f.header.back() == '\n');
  CHECK(f.header.find("'descr': '<f4'") != std::string::npos);
  CHECK(f.header.find("'fortran_order': False") != std::string::npos);
  CHECK(f.header.find("'shape': (8, 16)") != std::string::npos);
  CHECK(f.shape == std::vector<std::size_t>{8, 16});
}

TEST_CASE(
    "sample 2D values equal hush::perlin<2>::value<float> at origin + step * (i, j), bit for bit") {
  const fs::path dir = scratch("npy_2d_values");
  const fs::path out = dir / "x.npy";
  const result r = run_hush(
      std::string("sample perlin ") + kSampleArgs2d + " --out '" + out.string() + "'", dir);
  REQUIRE(r.exit_code == 0);
  const npy_file f = read_npy(out);
  REQUIRE(f.shape == std::vector<std::size_t>{8, 16});
  const hush::perlin<2> p{7};
  CHECK(count_mismatches(f, [&](double i, double j, double) {
          return p.value<float>(hush::dvec2{1.5 + 0.25 * i, -2.0 + 0.25 * j});
        }) == 0);
  // Not trivially zero: the noise varies over the grid.
  CHECK(f.values[1] != f.values[2]);
}

TEST_CASE("sample 3D volume has shape (nz, ny, nx) and equals hush::perlin<3>, bit for bit") {
  const fs::path dir = scratch("npy_3d_values");
  const fs::path out = dir / "v.npy";
  // --origin before --dim: options are read in dependency order, not command-line order.
  const result r = run_hush(
      "sample perlin --origin -1,2.5,0.75 --dim 3 --size 5x4x3 --step 0.3 "
      "--seed=123 --out '" +
          out.string() + "'",
      dir);
  REQUIRE(r.exit_code == 0);
  const npy_file f = read_npy(out);
  REQUIRE(f.shape == std::vector<std::size_t>{3, 4, 5});
  CHECK(f.header.find("'shape': (3, 4, 5)") != std::string::npos);
  const hush::perlin<3> p{123};
  CHECK(count_mismatches(f, [&](double i, double j, double k) {
          return p.value<float>(hush::dvec3{-1.0 + 0.3 * i, 2.5 + 0.3 * j, 0.75 + 0.3 * k});
        }) == 0);
}

TEST_CASE("sample 3D --size N is a cube and --size NxM is the z-plane at the origin's z") {
  const fs::path dir = scratch("npy_3d_sizes");
  const hush::perlin<3> p{0};
  SUBCASE("N") {
    REQUIRE(run_hush("sample perlin --dim 3 --size 6 --out '" + (dir / "c.npy").string() + "'", dir)
                .exit_code == 0);
    const npy_file f = read_npy(dir / "c.npy");
    REQUIRE(f.shape == std::vector<std::size_t>{6, 6, 6});
    CHECK(count_mismatches(f, [&](double i, double j, double k) {
            return p.value<float>(hush::dvec3{i / 32.0, j / 32.0, k / 32.0});  // default step
          }) == 0);
  }
  SUBCASE("NxM") {
    REQUIRE(run_hush("sample perlin --dim 3 --size 7x5 --origin 0,0,0.4 --out '" +
                         (dir / "s.npy").string() + "'",
                     dir)
                .exit_code == 0);
    const npy_file f = read_npy(dir / "s.npy");
    REQUIRE(f.shape == std::vector<std::size_t>{5, 7});
    CHECK(count_mismatches(f, [&](double i, double j, double) {
            return p.value<float>(hush::dvec3{i / 32.0, j / 32.0, 0.4});
          }) == 0);
  }
}

TEST_CASE("sample 2D defaults: 256 x 256 samples from the origin, step 1/32, seed 0") {
  const fs::path dir = scratch("npy_defaults");
  REQUIRE(run_hush("sample perlin --out '" + (dir / "d.npy").string() + "'", dir).exit_code == 0);
  const npy_file f = read_npy(dir / "d.npy");
  REQUIRE(f.shape == std::vector<std::size_t>{256, 256});
  const hush::perlin<2> p{0};
  CHECK(count_mismatches(f, [&](double i, double j, double) {
          return p.value<float>(hush::dvec2{i * 0.03125, j * 0.03125});
        }) == 0);
}

TEST_CASE("sample with fractal options equals hush::fractal<hush::perlin<D>>, bit for bit") {
  const fs::path dir = scratch("npy_fractal");
  const fs::path out = dir / "f.npy";
  SUBCASE("fBm, default lacunarity, gain and normalisation (unit variance)") {
    REQUIRE(run_hush(std::string("sample perlin ") + kSampleArgs2d + " --octaves 5 --out '" +
                         out.string() + "'",
                     dir)
                .exit_code == 0);
    hush::fractal<hush::perlin<2>>::params prm;
    prm.seed = 7;
    prm.octaves = 5;
    const hush::fractal<hush::perlin<2>> fbm{prm};
    CHECK(count_mismatches(read_npy(out), [&](double i, double j, double) {
            return fbm.value<float>(hush::dvec2{1.5 + 0.25 * i, -2.0 + 0.25 * j});
          }) == 0);
  }
  SUBCASE("turbulence with every option given, 3D") {
    REQUIRE(run_hush("sample perlin --dim 3 --size 6x5x4 --origin 3,-1,2 --step 0.21 --seed 9 "
                     "--octaves 4 --lacunarity 2.5 --gain 0.6 --fractal turbulence --norm none "
                     "--out '" +
                         out.string() + "'",
                     dir)
                .exit_code == 0);
    hush::fractal<hush::perlin<3>>::params prm;
    prm.seed = 9;
    prm.kind = hush::fractal_kind::turbulence;
    prm.octaves = 4;
    prm.lacunarity = 2.5;
    prm.gain = 0.6;
    prm.norm = hush::normalization::none;
    const hush::fractal<hush::perlin<3>> turb{prm};
    CHECK(count_mismatches(read_npy(out), [&](double i, double j, double k) {
            return turb.value<float>(hush::dvec3{3 + 0.21 * i, -1 + 0.21 * j, 2 + 0.21 * k});
          }) == 0);
  }
  SUBCASE("turbulence defaults to unit_range normalisation") {
    REQUIRE(run_hush(std::string("sample perlin ") + kSampleArgs2d +
                         " --octaves 3 --fractal turbulence --out '" + out.string() + "'",
                     dir)
                .exit_code == 0);
    hush::fractal<hush::perlin<2>>::params prm;
    prm.seed = 7;
    prm.kind = hush::fractal_kind::turbulence;
    prm.octaves = 3;
    prm.norm = hush::normalization::unit_range;
    const hush::fractal<hush::perlin<2>> turb{prm};
    const npy_file f = read_npy(out);
    CHECK(count_mismatches(f, [&](double i, double j, double) {
            return turb.value<float>(hush::dvec2{1.5 + 0.25 * i, -2.0 + 0.25 * j});
          }) == 0);
    for (float v : f.values) CHECK((v >= 0 && v <= 1));
  }
}

// ---- (b) The periodic option.

TEST_CASE("sample --period repeats exactly: plain and fractal, 2D and 3D") {
  const fs::path dir = scratch("periodic");
  const fs::path out = dir / "p.npy";
  // Period 4 cells at step 1/32 = 128 samples along x; 2 cells = 64 samples along y.
  auto repeats = [](const npy_file& f, std::size_t px, std::size_t py) {
    const std::size_t nx = f.shape[1], ny = f.shape[0];
    std::size_t bad = 0;
    for (std::size_t j = 0; j + py < ny; ++j)
      for (std::size_t i = 0; i + px < nx; ++i) {
        const float v = f.values[j * nx + i];
        if (bits(v) != bits(f.values[j * nx + i + px])) ++bad;
        if (bits(v) != bits(f.values[(j + py) * nx + i])) ++bad;
      }
    return bad;
  };
  SUBCASE("plain Perlin") {
    REQUIRE(
        run_hush("sample perlin --size 256x160 --seed 3 --period 4,2 --out '" + out.string() + "'",
                 dir)
            .exit_code == 0);
    const npy_file f = read_npy(out);
    CHECK(repeats(f, 128, 64) == 0);
    hush::perlin<2>::params prm;
    prm.seed = 3;
    prm.period = {4, 2};
    const hush::perlin<2> p{prm};
    CHECK(count_mismatches(f, [&](double i, double j, double) {
            return p.value<float>(hush::dvec2{i / 32.0, j / 32.0});
          }) == 0);
  }
  SUBCASE("fBm of 3 octaves") {
    REQUIRE(run_hush("sample perlin --size 256x160 --seed 3 --period 4,2 --octaves 3 --out '" +
                         out.string() + "'",
                     dir)
                .exit_code == 0);
    CHECK(repeats(read_npy(out), 128, 64) == 0);
  }
  SUBCASE("without --period the same grid does not repeat") {
    REQUIRE(run_hush("sample perlin --size 256x160 --seed 3 --out '" + out.string() + "'", dir)
                .exit_code == 0);
    CHECK(repeats(read_npy(out), 128, 64) > 1000);
  }
  SUBCASE("3D, periodic in x and z only") {
    REQUIRE(run_hush("sample perlin --dim 3 --size 16x6x8 --step 0.25 --period 2,0,1 --out '" +
                         out.string() + "'",
                     dir)
                .exit_code == 0);
    const npy_file f = read_npy(out);
    REQUIRE(f.shape == std::vector<std::size_t>{8, 6, 16});
    std::size_t bad = 0;
    for (std::size_t k = 0; k < 8; ++k)
      for (std::size_t j = 0; j < 6; ++j)
        for (std::size_t i = 0; i < 16; ++i) {
          const float v = f.values[(k * 6 + j) * 16 + i];
          if (i + 8 < 16 && bits(v) != bits(f.values[(k * 6 + j) * 16 + i + 8])) ++bad;
          if (k + 4 < 8 && bits(v) != bits(f.values[((k + 4) * 6 + j) * 16 + i])) ++bad;
        }
    CHECK(bad == 0);
  }
}

// ---- (c) PNG output.

#if HUSH_CLI_TEST_PNG
TEST_CASE("sample to .png writes an 8-bit grayscale PNG of nx x ny pixels, j = 0 at the top") {
  const fs::path dir = scratch("png");
  const fs::path out = dir / "x.png";
  REQUIRE(
      run_hush(std::string("sample perlin ") + kSampleArgs2d + " --out '" + out.string() + "'", dir)
          .exit_code == 0);
  const png_header h = read_png_header(out);
  CHECK(h.width == 16);
  CHECK(h.height == 8);
  CHECK(h.bit_depth == 8);
  CHECK(h.color_type == 0);  // grayscale
#if HUSH_CLI_TEST_DECODE
  // Pixel (i, j) shows v = noise(origin + step * (i, j)) as 255 * (v + 1) / 2.
  const gray_pixels g = decode_png(out);
  const hush::perlin<2> p{7};
  int worst = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 16; ++i) {
      const float v = p.value<float>(hush::dvec2{1.5 + 0.25 * i, -2.0 + 0.25 * j});
      const double expected = 255.0 * (v + 1.0) / 2.0;
      worst = std::max(worst, static_cast<int>(std::abs(g.at(i, j) - expected) + 0.5));
    }
  CHECK(worst <= 1);
#endif
}

TEST_CASE("sample to .png takes a 3D noise's single z-plane (NxM or NxMx1)") {
  const fs::path dir = scratch("png_3d_plane");
  REQUIRE(
      run_hush("sample perlin --dim 3 --size 12x10x1 --out '" + (dir / "a.png").string() + "'", dir)
          .exit_code == 0);
  const png_header h = read_png_header(dir / "a.png");
  CHECK(h.width == 12);
  CHECK(h.height == 10);
}

#if HUSH_CLI_TEST_DECODE
TEST_CASE("sample to .png shows turbulence (values >= 0) over [0, 1]") {
  const fs::path dir = scratch("png_turbulence");
  const fs::path out = dir / "t.png";
  REQUIRE(run_hush("sample perlin --size 20x20 --octaves 3 --fractal turbulence --out '" +
                       out.string() + "'",
                   dir)
              .exit_code == 0);
  hush::fractal<hush::perlin<2>>::params prm;
  prm.octaves = 3;
  prm.kind = hush::fractal_kind::turbulence;
  prm.norm = hush::normalization::unit_range;
  const hush::fractal<hush::perlin<2>> turb{prm};
  const gray_pixels g = decode_png(out);
  int worst = 0;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i) {
      const float v = turb.value<float>(hush::dvec2{i / 32.0, j / 32.0});
      worst = std::max(worst, static_cast<int>(std::abs(g.at(i, j) - 255.0 * v) + 0.5));
    }
  CHECK(worst <= 1);
}
#endif
#else
TEST_CASE("sample to .png in a build without stb_image_write fails, saying what is missing") {
  const fs::path dir = scratch("png_missing");
  const result r = run_hush("sample perlin --out '" + (dir / "x.png").string() + "'", dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("stb_image_write") != std::string::npos);
  CHECK(r.err.find(".npy") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "x.png"));
}
#endif

// ---- (d) Bad input: one line on stderr naming the option, non-zero exit, no output file.

TEST_CASE("sample gabor equals hush::gabor<D>::grid_sample with the options, bit for bit") {
  // A grid takes the separable form on every backend (hush::gabor::grid_sample; random points
  // the point form, within docs/gabor.md's bound of it).
  const fs::path dir = scratch("npy_gabor");
  const fs::path out = dir / "g.npy";
  SUBCASE("2D hybrid, every option given (angles in degrees)") {
    REQUIRE(run_hush(std::string("sample gabor ") + kSampleArgs2d +
                         " --kind hybrid --frequency 1.5 --bandwidth 0.9 --orientation 30 "
                         "--orientation-spread 90 --frequency-spread 0.5 --impulses 24 "
                         "--truncation 0.02 --out '" +
                         out.string() + "'",
                     dir)
                .exit_code == 0);
    hush::gabor<2>::params prm;
    prm.seed = 7;
    prm.kind = hush::gabor_kind::hybrid;
    prm.frequency = 1.5;
    prm.bandwidth = 0.9;
    prm.orientation = 30 * hush::detail::constants::kPi / 180;
    prm.orientation_spread = 90 * hush::detail::constants::kPi / 180;
    prm.frequency_spread = 0.5;
    prm.impulses = 24;
    prm.truncation = 0.02;
    const hush::gabor<2> g{prm};
    CHECK(count_mismatches(read_npy(out), [&](double i, double j, double) {
            return g.grid_sample<float>(hush::dvec2{1.5 + 0.25 * i, -2.0 + 0.25 * j}).value;
          }) == 0);
  }
  SUBCASE("3D anisotropic with an elevation") {
    REQUIRE(run_hush("sample gabor --dim 3 --size 6x5x4 --origin 3,-1,2 --step 0.21 --seed 9 "
                     "--kind anisotropic --orientation -45 --elevation 20 --out '" +
                         out.string() + "'",
                     dir)
                .exit_code == 0);
    hush::gabor<3>::params prm;
    prm.seed = 9;
    prm.kind = hush::gabor_kind::anisotropic;
    prm.orientation = -45 * hush::detail::constants::kPi / 180;
    prm.elevation = 20 * hush::detail::constants::kPi / 180;
    const hush::gabor<3> g{prm};
    CHECK(count_mismatches(read_npy(out), [&](double i, double j, double k) {
            return g.grid_sample<float>(hush::dvec3{3 + 0.21 * i, -1 + 0.21 * j, 2 + 0.21 * k})
                .value;
          }) == 0);
  }
  SUBCASE("3D surface noise: --normal gives every sample that normal (Lagae 2009 sec. 4.3)") {
    // A slanted normal of length 3 (the program scales it to a largest component of 1, the
    // library normalises it); the scalar backend evaluates each double position itself
    // (examples/hush/noises.hpp). Solid noise (no normal) differs: the option counts.
    const std::string args = "sample gabor --dim 3 --size 6x5x2 --origin 3,-1,2 --step 0.21 "
                             "--seed 9 --kind anisotropic --orientation 30 --out '" +
                             out.string() + "'";
    REQUIRE(run_hush(args + " --normal 1,2,2", dir).exit_code == 0);
    hush::gabor<3>::params prm;
    prm.seed = 9;
    prm.kind = hush::gabor_kind::anisotropic;
    prm.orientation = 30 * hush::detail::constants::kPi / 180;
    const hush::gabor<3> g{prm};
    auto surface = [&](double i, double j, double k) {
      hush::sample_input<3> in;
      in.position = hush::dvec3{3 + 0.21 * i, -1 + 0.21 * j, 2 + 0.21 * k};
      in.normal = hush::dvec3{0.5, 1, 1};
      in.has_normal = true;
      return g.sample_value<float>(in);
    };
    const npy_file f = read_npy(out);
    CHECK(count_mismatches(f, surface) == 0);
    REQUIRE(run_hush(args, dir).exit_code == 0);
    CHECK(count_mismatches(read_npy(out), surface) > f.values.size() / 2);
  }
}

TEST_CASE("sample gabor rejects each bad option with exit code 2, naming it") {
  const fs::path dir = scratch("bad_gabor");
  const std::string out = " --out '" + (dir / "never.npy").string() + "'";
  struct bad {
    const char* args;
    const char* names;
  };
  const bad cases[] = {{"--kind radial", "--kind"},
                       {"--frequency -1", "--frequency"},
                       {"--bandwidth 0", "--bandwidth"},
                       {"--impulses 300", "--impulses"},
                       {"--truncation 0.9", "--truncation"},
                       {"--orientation 400", "--orientation"},
                       {"--elevation 91", "--elevation"},
                       {"--orientation-spread -1", "--orientation-spread"},
                       {"--frequency-spread 3", "--frequency-spread"},
                       {"--normal 0,0,1", "--normal"},  // needs --dim 3
                       {"--dim 3 --normal 0,1", "--normal"},
                       {"--dim 3 --normal 0,nan,1", "--normal"},
                       {"--dim 3 --normal 0,0,0", "--normal"}};
  for (const bad& c : cases) {
    CAPTURE(c.args);
    const result r = run_hush(std::string("sample gabor ") + c.args + out, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.names) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  CHECK_FALSE(fs::exists(dir / "never.npy"));
}

TEST_CASE("sample rejects each bad input with exit code 2 and one line naming the option") {
  const fs::path dir = scratch("bad_input");
  const std::string out = " --out '" + (dir / "never.npy").string() + "'";
  struct bad {
    std::string args;   // after "sample"
    std::string names;  // must appear in the message
  };
  const bad cases[] = {
      {"perlin --dim 4" + out, "--dim"},
      {"perlin --dim" + out, "--dim"},  // the value is missing (the next token is an option)
      {"perlin --size 0" + out, "--size"},
      {"perlin --size 16x0" + out, "--size"},
      {"perlin --size 16x" + out, "--size"},
      {"perlin --size 65536x65536" + out, "--size"},   // 2^32 samples
      {"perlin --dim 3 --size 2048" + out, "--size"},  // 2^33 samples
      {"perlin --size 4x4x4" + out, "--size"},         // NxMxK needs --dim 3
      {"perlin --seed -1" + out, "--seed"},
      {"perlin --seed 4294967296" + out, "--seed"},
      {"perlin --seed 1.5" + out, "--seed"},
      {"perlin --seed 7x" + out, "--seed"},
      {"perlin --seed ''" + out, "--seed"},
      {"perlin --backend cuda" + out, "--backend"},
      {"perlin --period -3,1" + out, "--period"},
      {"perlin --period 4" + out, "--period"},  // one value per dimension
      {"perlin --period 99999999999,1" + out, "--period"},
      {"perlin --octaves 0" + out, "--octaves"},
      {"perlin --octaves 33" + out, "--octaves"},
      {"perlin --octaves 3 --lacunarity 1" + out, "--lacunarity"},  // the library refuses it
      {"perlin --octaves 3 --lacunarity 2.5 --period 4,4" + out, "--lacunarity"},
      {"perlin --octaves 3 --gain 0" + out, "--gain"},
      {"perlin --fractal brownian" + out, "--fractal"},
      {"perlin --fractal turbulence --norm unit_variance" + out, "--norm"},
      {"perlin --norm unit" + out, "--norm"},
      {"perlin --step 0" + out, "--step"},
      {"perlin --step nan" + out, "--step"},
      {"perlin --step inf" + out, "--step"},
      {"perlin --step 1/32" + out, "--step"},
      {"perlin --origin 1,2,3" + out, "--origin"},  // 3 values for --dim 2
      {"perlin --origin 1,nan" + out, "--origin"},
      {"perlin --bogus 3" + out, "--bogus"},
      {"perlin --seed 1 --seed 2" + out, "--seed"},
      {"perlin --out x.txt", "--out"},
      {"perlin --out x", "--out"},
      {"perlin", "--out"},
      {"perlin --dim 3 --size 4x4x4 --out '" + (dir / "v.png").string() + "'", ".npy"},
      {"perlin --seed" + out + " --seed", "--seed"},  // the value is missing at the end
      {"", "NOISE"},
      {"simplex" + out, "simplex"},
  };
  for (const bad& c : cases) {
    CAPTURE(c.args);
    const result r = run_hush("sample " + c.args, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.names) != std::string::npos);
    CHECK(r.err.rfind("hush sample: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);  // exactly one line
    CHECK(r.out.empty());
  }
  CHECK_FALSE(fs::exists(dir / "never.npy"));
  CHECK_FALSE(fs::exists(dir / "v.png"));
}

// The largest |difference| between `hush sample` on `backend` and on scalar, over the same
// (off-lattice, negative-origin) grid of dimension `dim`.
double backend_vs_scalar(const std::string& backend, int dim, const fs::path& dir) {
  const std::string common =
      "sample perlin --dim " + std::to_string(dim) +
      (dim == 2 ? " --size 37x5 --origin -3.3,7.1" : " --size 37x5x3 --origin -3.3,7.1,0.2") +
      " --step 0.173 --seed 9 ";
  const fs::path out = dir / (backend + ".npy");
  REQUIRE(
      run_hush(common + "--backend " + backend + " --out '" + out.string() + "'", dir).exit_code ==
      0);
  REQUIRE(run_hush(common + "--backend scalar --out '" + (dir / "scalar.npy").string() + "'", dir)
              .exit_code == 0);
  const npy_file a = read_npy(out), b = read_npy(dir / "scalar.npy");
  REQUIRE(a.values.size() == b.values.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.values.size(); ++i)
    worst = std::max(worst, std::fabs(double(a.values[i]) - b.values[i]));
  return worst;
}

TEST_CASE("sample --backend simd equals scalar sampling within the SIMD budget, 2D and 3D") {
  const fs::path dir = scratch("backend");
  // Both are within the float budget 2^-16 of the double reference
  // (hush/perlin/simd-inl.h), hence within 2^-15 of each other; bit for bit
  // under HUSH_STRICT_FP (tests/perlin/perlin_simd_test.cpp).
  for (int dim : {2, 3}) CHECK(backend_vs_scalar("simd", dim, dir) <= std::ldexp(1.0, -15));
#if !HUSH_CLI_TEST_SIMD
  // Without Highway the program says so instead of silently running scalar code.
  const result r =
      run_hush("sample perlin --backend simd --out '" + (dir / "x.npy").string() + "'", dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("Highway") != std::string::npos);
#endif
}

#if HUSH_CLI_TEST_GLSL
TEST_CASE("sample --backend glsl equals scalar sampling within the GLSL budget, 2D and 3D") {
  const fs::path dir = scratch("backend_glsl");
  // Within 2^-15 of the CPU float path (backends/glsl, hush/glsl/device.hpp).
  for (int dim : {2, 3}) CHECK(backend_vs_scalar("glsl", dim, dir) <= std::ldexp(1.0, -15));
}
#endif

#if HUSH_CLI_TEST_GLSL
TEST_CASE("sample --backend glsl with --octaves equals scalar sampling within the GLSL budget") {
  const fs::path dir = scratch("backend_glsl_fractal");
  for (int dim : {2, 3})
    for (const char* kind : {"fbm", "turbulence"}) {
      const std::string common =
          "sample perlin --dim " + std::to_string(dim) +
          (dim == 2 ? " --size 37x5 --origin -3.3,7.1" : " --size 37x5x3 --origin -3.3,7.1,0.2") +
          " --step 0.173 --seed 9 --octaves 6 --fractal " + kind + " ";
      REQUIRE(run_hush(common + "--backend glsl --out '" + (dir / "glsl.npy").string() + "'", dir)
                  .exit_code == 0);
      REQUIRE(
          run_hush(common + "--backend scalar --out '" + (dir / "scalar.npy").string() + "'", dir)
              .exit_code == 0);
      const npy_file a = read_npy(dir / "glsl.npy"), b = read_npy(dir / "scalar.npy");
      REQUIRE(a.values.size() == b.values.size());
      // Within twice the fractal budget of the CPU float path
      // (tests/fractal/glsl_fractal_test.cpp): bound() (2^-16 + (octaves + 4) 2^-24),
      // bound() = K sum |w_i|.
      hush::fractal<hush::perlin<2>>::params prm;
      prm.octaves = 6;
      if (std::string(kind) == "turbulence") {
        prm.kind = hush::fractal_kind::turbulence;
        prm.norm = hush::normalization::unit_range;
      }
      const double budget = 2 * hush::fractal<hush::perlin<2>>(prm).bound() *
                            (std::ldexp(1.0, -16) + (6 + 4) * std::ldexp(1.0, -24));
      double worst = 0;
      for (std::size_t i = 0; i < a.values.size(); ++i)
        worst = std::max(worst, std::fabs(double(a.values[i]) - b.values[i]));
      CHECK_MESSAGE(worst <= budget, dim << "D " << kind << ": " << worst);
    }
}
#endif

TEST_CASE("sample to an unwritable file fails with exit code 1 and names the file") {
  const fs::path dir = scratch("unwritable");
  const std::string path = (dir / "no_such_dir" / "x.npy").string();
  const result r = run_hush("sample perlin --out '" + path + "'", dir);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find(path) != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

TEST_CASE(
    "usage: no command fails with exit code 2, --help succeeds, an unknown command is named") {
  const fs::path dir = scratch("usage");
  const result none = run_hush("", dir);
  CHECK(none.exit_code == 2);
  CHECK(none.err.find("hush sample") != std::string::npos);
  const result help = run_hush("--help", dir);
  CHECK(help.exit_code == 0);
  CHECK(help.out.find("hush sample NOISE") != std::string::npos);
  CHECK(help.out.find("--period") != std::string::npos);  // noise options come from the table
  const result sample_help = run_hush("sample --help", dir);
  CHECK(sample_help.exit_code == 0);
  const result unknown = run_hush("frobnicate", dir);
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("frobnicate") != std::string::npos);
  CHECK(unknown.err.find("sample") != std::string::npos);  // lists the valid commands
}

// ---- (e) hush info.

TEST_CASE("info exits 0 and prints the version, the standard and the backends") {
  const fs::path dir = scratch("info");
  const result r = run_hush("info", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find(std::string("hush ") + HUSH_VERSION_STRING) != std::string::npos);
  CHECK(r.out.find("C++17") != std::string::npos);
  CHECK(r.out.find("scalar:     yes") != std::string::npos);
  CHECK(r.out.find(HUSH_CLI_TEST_SIMD
                       ? "simd:       yes, dynamic dispatch; compiled: "
                       : "simd:       no (built without Highway") != std::string::npos);
  CHECK((r.out.find("glsl:       yes (") != std::string::npos ||
         r.out.find("glsl:       unavailable: ") != std::string::npos));
  CHECK(r.out.find(HUSH_CLI_TEST_GALLERY ? "gallery:      yes" : "gallery:      no") !=
        std::string::npos);
  CHECK(run_hush("info --verbose", dir).exit_code == 2);
}

// ---- (f) hush gallery.

#if HUSH_CLI_TEST_GALLERY
TEST_CASE("gallery writes its PNGs with the expected sizes and lists them") {
  const fs::path dir = scratch("gallery");
  const fs::path out = dir / "images" / "nested";  // created, parents included
  const result r = run_hush("gallery --out '" + out.string() + "'", dir);
  REQUIRE(r.exit_code == 0);
  struct expected {
    const char* file;
    std::uint32_t width, height;
  };
  const expected images[] = {{"perlin2d.png", 1024, 512},
                             {"perlin3d_slice.png", 1024, 512},
                             {"fbm.png", 1024, 512},
                             {"turbulence.png", 1024, 512},
                             {"perlin_periodic_tiled.png", 256, 256},
                             {"gabor_kinds.png", 768, 768},
                             {"gabor_filtering.png", 1152, 256 + 30},  // the captions' strip
                             {"wavelet_fig8.png", 512, 1024},
                             {"wavelet_plane.png", 768, 384}};
  for (const expected& e : images) {
    CAPTURE(e.file);
    const png_header h = read_png_header(out / e.file);
    CHECK(h.width == e.width);
    CHECK(h.height == e.height);
    CHECK(h.bit_depth == 8);
    CHECK(h.color_type == 0);
    CHECK(r.out.find(e.file) != std::string::npos);
  }
  CHECK(r.out.find(fs::canonical(out).string()) != std::string::npos);  // the absolute directory
  CHECK(r.err.find("gallery: [2/7] perlin3d_slice.png") != std::string::npos);
  // The receding plane's errors against its supersampled reference, printed under it.
  CHECK(r.out.find("RMS error vs reference: unfiltered") != std::string::npos);
  CHECK(r.err.find("wavelet_plane.png: RMS error vs 16x16 reference: wavelet + footprint") !=
        std::string::npos);
  {  // Fig. 9 is RGB (three bands' spectra as red, green, blue), Perlin | wavelet.
    const png_header h = read_png_header(out / "wavelet_fig9.png");
    CHECK(h.width == 512);
    CHECK(h.height == 256);
    CHECK(h.bit_depth == 8);
    CHECK(h.color_type == 2);  // truecolour
    CHECK(r.out.find("wavelet_fig9.png (512x256)") != std::string::npos);
    // The printed overlap of adjacent bands' normalised spectra: wavelet bands are
    // band-limited (paper sec. 3), Perlin octaves are not, so wavelet's must be the smaller.
    // (Fixed seed; measured Perlin 0.233, wavelet 0.093: the margin is wide.)
    const std::string key =
        "wavelet_fig9.png: adjacent bands' spectral overlap (0 disjoint, 1 equal): ";
    const std::size_t at = r.err.find(key);
    REQUIRE(at != std::string::npos);
    double perlin = -1, wavelet = -1;
    REQUIRE(std::sscanf(r.err.c_str() + at + key.size(), "Perlin %lf, wavelet %lf", &perlin,
                        &wavelet) == 2);
    CHECK(wavelet > 0);
    CHECK(wavelet < perlin);
  }

#if HUSH_CLI_TEST_DECODE
  SUBCASE("the spectrum half is brightest around zero frequency, at its centre") {
    const gray_pixels g = decode_png(out / "perlin2d.png");
    auto mean = [&](int x0, int y0, int size) {
      double sum = 0;
      for (int y = y0; y < y0 + size; ++y)
        for (int x = x0; x < x0 + size; ++x) sum += g.at(x, y);
      return sum / (size * size);
    };
    CHECK(mean(512 + 256 - 8, 256 - 8, 16) > 150);  // the centre of the right half
    CHECK(mean(512, 0, 64) < 20);                   // its highest frequencies (a corner)
  }
  SUBCASE("wavelet Fig. 8: band 0's spectrum is dark at its centre, the 3D slice's is not") {
    // Rows of 256 pixels: Perlin, wavelet 2D, 3D slice, projected; spectra on the right,
    // zero frequency at (384, 128 + 256 row). The 8x8 centre without the zero bin itself.
    const gray_pixels g = decode_png(out / "wavelet_fig8.png");
    auto centre = [&](int row) {
      double sum = 0;
      for (int y = -4; y < 4; ++y)
        for (int x = -4; x < 4; ++x)
          if (x != 0 || y != 0) sum += g.at(384 + x, 128 + 256 * row + y);
      return sum / 63;
    };
    CHECK(centre(1) < centre(2));  // wavelet 2D below the slice of 3D
    CHECK(centre(3) < centre(2));  // projection empties the centre again
  }
  SUBCASE("the receding plane's images carry the printed errors under them") {
    // The strip under the three 384 x 256 images is exactly the captions redrawn from the
    // errors the program printed (caption_test checks the drawing itself).
    const std::string key = "RMS error vs reference: unfiltered ";
    const std::size_t at = r.out.find(key);
    REQUIRE(at != std::string::npos);
    double plain = -1, filtered = -1;
    REQUIRE(std::sscanf(r.out.c_str() + at + key.size(), "%lf, filtered %lf", &plain, &filtered) ==
            2);
    char under_plain[48], under_filtered[48];
    std::snprintf(under_plain, sizeof under_plain, "unfiltered: RMS error %.3f", plain);
    std::snprintf(under_filtered, sizeof under_filtered, "filtered: RMS error %.3f", filtered);
    const hush_cli::gray_image want =
        hush_cli::with_captions(hush_cli::gray_image(1152, 256),
                                {under_plain, under_filtered, "reference: 16 x 16 samples"});
    const gray_pixels g = decode_png(out / "gabor_filtering.png");
    REQUIRE(g.height == static_cast<int>(want.height));
    int differing = 0, ink = 0;
    for (int y = 256; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) {
        const int w = want.at(static_cast<std::size_t>(x), static_cast<std::size_t>(y));
        differing += g.at(x, y) != w;
        ink += w == 0;
      }
    CHECK(differing == 0);
    CHECK(ink > 0);
  }
  SUBCASE("the checked-in gallery images are what the program draws") {
    // docs/gallery holds the images of the README and docs/gallery.md: each PNG there must
    // match the one just drawn, to within the last bits of float noise (a gray level or two
    // where a value sits at a rounding boundary; the SIMD target and compiler may move them),
    // so that a changed noise whose images were not regenerated fails here.
    int compared = 0;
    for (const auto& entry : fs::directory_iterator(HUSH_CLI_DOCS_GALLERY)) {
      if (entry.path().extension() != ".png") continue;
      const fs::path drawn = out / entry.path().filename();
      CAPTURE(entry.path().filename().string());
      REQUIRE(fs::exists(drawn));
      const gray_pixels want = decode_png(entry.path()), got = decode_png(drawn);
      REQUIRE(got.width == want.width);
      REQUIRE(got.height == want.height);
      int worst = 0;
      std::size_t differing = 0;
      for (std::size_t k = 0; k < got.pixels.size(); ++k) {
        const int d = std::abs(got.pixels[k] - want.pixels[k]);
        worst = std::max(worst, d);
        differing += d != 0;
      }
      CHECK(worst <= 3);
      CHECK(differing * 200 <= got.pixels.size());  // at most 0.5% of the pixels
      ++compared;
    }
    CHECK(compared >= 10);
  }
  SUBCASE("the periodic tiles meet without a seam") {
    const gray_pixels g = decode_png(out / "perlin_periodic_tiled.png");
    // Neighbours across the seams (x or y = 128) differ no more than neighbours inside a
    // tile: the largest step between adjacent pixels, in each class.
    int inside = 0, seam = 0;
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x) {
        if (x > 0) {
          const int d = std::abs(g.at(x, y) - g.at(x - 1, y));
          (x == 128 ? seam : inside) = std::max(x == 128 ? seam : inside, d);
        }
        if (y > 0) {
          const int d = std::abs(g.at(x, y) - g.at(x, y - 1));
          (y == 128 ? seam : inside) = std::max(y == 128 ? seam : inside, d);
        }
      }
    CHECK(inside > 0);
    CHECK(seam <= inside);
  }
#endif
}
#else
TEST_CASE("gallery in a build without stb_image_write or Eigen fails, saying what is missing") {
  const fs::path dir = scratch("gallery_missing");
  const result r = run_hush("gallery --out '" + (dir / "g").string() + "'", dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("not available in this build") != std::string::npos);
}
#endif

// ---- (f) hush bench: its options (the timing runs themselves are the bench_quick_json and
// bench_interleave_json smoke tests, tests/cli/check_bench.py, in Release builds only).

TEST_CASE("bench rejects each bad option with exit code 2 and one line naming it") {
  const fs::path dir = scratch("bench_bad_input");
  struct bad {
    std::string args;   // after "bench"
    std::string names;  // must appear in the message
  };
  const bad cases[] = {
      {"--repetitions 0", "--repetitions"},
      {"--repetitions 101", "--repetitions"},
      {"--repetitions 2.5", "--repetitions"},
      {"--plot x.png", "--plot"},
      {"--plot .svg", "--plot"},
      {"--quick=1", "--quick"},
      {"--quick 3", "'3'"},  // a flag takes no value: 3 is an argument of its own
      {"--interleave=1", "--interleave"},
      {"--interleave=", "--interleave"},
      {"--interleave 3", "'3'"},
      {"--json", "--json"},  // the value is missing
      {"--bogus 3", "--bogus"},
      {"--json a.json --json b.json", "--json"},
      {"extra", "extra"},
  };
  for (const bad& c : cases) {
    CAPTURE(c.args);
    const result r = run_hush("bench " + c.args, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.names) != std::string::npos);
    CHECK(r.err.rfind("hush bench: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.out.empty());
  }
}

TEST_CASE("bench --interleave is a flag: parsed with the other options, listed in --help") {
  const fs::path dir = scratch("bench_interleave");
  // Accepted anywhere among the options (the --filter then fails before measuring).
  for (const char* args : {"--interleave --quick --filter no_such_case",
                           "--quick --filter no_such_case --interleave"}) {
    CAPTURE(args);
    const result r = run_hush(std::string("bench ") + args, dir);
    CHECK(r.exit_code == 2);
#if HUSH_CLI_TEST_BENCH
    CHECK(r.err.find("--filter") != std::string::npos);
#else
    CHECK(r.err.find("libbenchmark-dev") != std::string::npos);
#endif
    CHECK(r.err.find("--interleave") == std::string::npos);
  }
  // The help says what it costs: every matched case's buffers at once.
  const result help = run_hush("bench --help", dir);
  CHECK(help.exit_code == 0);
  const std::size_t at = help.out.find("  --interleave");
  REQUIRE(at != std::string::npos);
  std::string entry;  // its help, unwrapped: runs of spaces and line breaks as one space
  for (const char ch : help.out.substr(at, help.out.find("\n  --", at + 1) - at))
    if (!(std::isspace(static_cast<unsigned char>(ch)) && !entry.empty() && entry.back() == ' '))
      entry += std::isspace(static_cast<unsigned char>(ch)) ? ' ' : ch;
  CHECK(entry.find("random order") != std::string::npos);
  CHECK(entry.find("buffers") != std::string::npos);
  CHECK(entry.find("--filter") != std::string::npos);
  CHECK(entry.find("takes no value") != std::string::npos);
}

TEST_CASE("bench --filter matching no case and an uncreatable output fail before measuring") {
  const fs::path dir = scratch("bench_filter");
  const result none = run_hush("bench --quick --filter no_such_case", dir);
#if HUSH_CLI_TEST_BENCH
  CHECK(none.exit_code == 2);
  CHECK(none.err.find("--filter") != std::string::npos);
#else
  CHECK(none.exit_code == 2);  // not in this build: says what is missing
  CHECK(none.err.find("libbenchmark-dev") != std::string::npos);
#endif
  CHECK(std::count(none.err.begin(), none.err.end(), '\n') == 1);
  CHECK(none.out.empty());
  // Several texts separated by '|': none matching, or an empty one (it would match every case).
  for (const char* filter : {"no_such_case|nor_this", "perlin2D/simd/grid|", "|perlin2D"}) {
    CAPTURE(filter);
    const result r = run_hush(std::string("bench --quick --filter '") + filter + "'", dir);
    CHECK(r.exit_code == 2);
#if HUSH_CLI_TEST_BENCH
    CHECK(r.err.find("--filter") != std::string::npos);
#endif
    CHECK(r.out.empty());
  }
  const std::string path = (dir / "no_such_dir" / "b.json").string();
  const result unwritable = run_hush("bench --quick --json '" + path + "'", dir);
  CHECK(unwritable.exit_code == 1);
  CHECK(unwritable.err.find(path) != std::string::npos);
  CHECK(unwritable.out.empty());  // nothing was measured
}

// ---- `hush sample wavelet` (examples/hush/noise_wavelet.cpp).

TEST_CASE("sample wavelet 2D with --bands equals hush::wavelet<2>::value<float>, bit for bit") {
  const fs::path dir = scratch("wavelet_2d");
  const fs::path out = dir / "w.npy";
  const result r =
      run_hush(std::string("sample wavelet ") + kSampleArgs2d +
                   " --tile-size 32 --first-band -1 --bands 3 --out '" + out.string() + "'",
               dir);
  REQUIRE(r.exit_code == 0);
  const npy_file f = read_npy(out);
  hush::wavelet<2>::params prm;
  prm.seed = 7;
  prm.tile_size = 32;
  prm.first_band = -1;
  prm.weights = {1, 0.5, 0.25};
  const hush::wavelet<2> w{prm};
  CHECK(count_mismatches(f, [&](double i, double j, double) {
          return w.value<float>(hush::dvec2{1.5 + 0.25 * i, -2.0 + 0.25 * j});
        }) == 0);
  CHECK(f.values[1] != f.values[2]);
}

TEST_CASE("sample wavelet 3D --normal --footprint: scalar sample_value at the double position") {
  const fs::path dir = scratch("wavelet_3d_samples");
  const fs::path out = dir / "w.npy";
  const result r = run_hush(
      "sample wavelet --dim 3 --size 6x5 --origin 0.5,1,2 --step 0.3 "
      "--seed 3 --tile-size 16 --weights 1,-0.5 --normal 1,2,0.5 "
      "--footprint 0.7 --out '" +
          out.string() + "'",
      dir);
  REQUIRE(r.exit_code == 0);
  const npy_file f = read_npy(out);
  hush::wavelet<3>::params prm;
  prm.seed = 3;
  prm.tile_size = 16;
  prm.weights = {1, -0.5};
  const hush::wavelet<3> w{prm};
  // hush::evaluate's scalar step (sample_value<float>) at the exact double position (inside
  // the first period, so not reduced), the normal scaled to a largest component of 1.
  CHECK(count_mismatches(f, [&](double i, double j, double) {
          hush::sample_input<3> in;
          in.position = {0.5 + 0.3 * i, 1 + 0.3 * j, 2.0};
          in.fp = hush::footprint<3>::isotropic(0.7);
          in.normal = {0.5, 1, 0.25};
          in.has_normal = true;
          return w.sample_value<float>(in);
        }) == 0);
}

TEST_CASE("sample wavelet refuses bad options with exit 2 naming the option") {
  const fs::path dir = scratch("wavelet_bad");
  const std::string o = " --out '" + (dir / "x.npy").string() + "'";
  struct bad {
    std::string args, names;
  };
  const bad cases[] = {{"--tile-size 17", "--tile-size '17'"},
                       {"--tile-size 8", "--tile-size '8'"},
                       {"--normal 0,0,1", "--normal needs --dim 3"},
                       {"--dim 3 --normal 0,0,0", "--normal '0,0,0'"},
                       {"--dim 3 --normal 1,x,0", "--normal"},
                       {"--bands 0", "--bands '0'"},
                       {"--bands 2 --weights 1,2", "--bands and --weights"},
                       {"--weights 0,0", "--weights"},
                       {"--footprint -1", "--footprint '-1'"},
                       {"--first-band 40", "--first-band '40'"},
                       {"--variants 99", "--variants '99'"},
                       {"--widen maybe", "--widen 'maybe'"},
                       {"--projection fast", "--projection 'fast'"},
                       {"--distribution table", "--distribution 'table'"}};
  for (const bad& c : cases) {
    CAPTURE(c.args);
    const result r = run_hush("sample wavelet " + c.args + o, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.names) != std::string::npos);
    CHECK(r.err.rfind("hush sample: ", 0) == 0);
  }
}

// ---- hush sample anisotropic.

TEST_CASE("sample anisotropic: every backend agrees with scalar, with footprints and a map") {
  const fs::path dir = scratch("anisotropic_backends");
  const std::string common =
      "sample anisotropic --size 40x7 --origin -3.3,7.1 --step 0.173 --seed 9 --tile-size 64 "
      "--orientations 6 --footprint pixel --map 1.5,0.2,-0.3,0.7 ";
  REQUIRE(run_hush(common + "--backend scalar --out '" + (dir / "scalar.npy").string() + "'", dir)
              .exit_code == 0);
  const npy_file ref = read_npy(dir / "scalar.npy");
  REQUIRE(ref.values.size() == 280);
  hush::anisotropic::params prm;
  prm.seed = 9;
  prm.tile_size = 64;
  prm.orientations = 6;
  const hush::anisotropic noise(prm);
  // SIMD: both within one float budget (with maps) of the double reference.
  // GLSL: 8-bit bilinear weights on some GPUs, 2^-8 of the largest texel step
  // per subband (anisotropic_program.hpp), bounded here over every weight.
  const double simd_budget = 2 * noise.float_budget() * noise.bound_with_maps() / noise.bound();
  double steps = 0;
  for (int i = 0; i < 6; ++i) steps += noise.tile().max_step(i);
  const double glsl_budget = simd_budget + std::ldexp(steps, -8) * noise.bound_with_maps() /
                                               (noise.bound() / noise.octave_weight(0));
  std::vector<std::pair<std::string, double>> backends = {{"simd", simd_budget}};
#if HUSH_CLI_TEST_GLSL
  backends.emplace_back("glsl", glsl_budget);
#endif
  for (const auto& [backend, budget] : backends) {
    CAPTURE(backend);
    const fs::path out = dir / (backend + ".npy");
    REQUIRE(run_hush(common + "--backend " + backend + " --out '" + out.string() + "'", dir)
                .exit_code == 0);
    const npy_file a = read_npy(out);
    REQUIRE(a.values.size() == ref.values.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.values.size(); ++i)
      worst = std::max(worst, std::fabs(double(a.values[i]) - ref.values[i]));
    CHECK(worst <= budget);
  }
}

TEST_CASE("sample anisotropic: bad options exit 2 with one line naming the option") {
  const fs::path dir = scratch("anisotropic_bad");
  const std::string out = " --out '" + (dir / "never.npy").string() + "'";
  struct bad {
    std::string args, names;
  };
  const bad cases[] = {
      {"anisotropic --dim 3" + out, "--dim 3"},
      {"anisotropic --orientations 9" + out, "--orientations '9'"},
      {"anisotropic --scales 0" + out, "--scales '0'"},
      {"anisotropic --base-scale 3" + out, "--base-scale '3'"},
      {"anisotropic --scales 2 --octaves 3" + out, "--octaves '3'"},
      {"anisotropic --tile-size 100" + out, "power of two"},
      {"anisotropic --gain 0" + out, "--gain '0'"},
      {"anisotropic --frequency nan" + out, "--frequency"},
      {"anisotropic --filtering gaussian" + out, "--filtering"},
      {"anisotropic --footprint -1" + out, "--footprint '-1'"},
      {"anisotropic --map 1,2,3" + out, "--map"},
  };
  for (const bad& c : cases) {
    CAPTURE(c.args);
    const result r = run_hush("sample " + c.args, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.names) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  CHECK_FALSE(fs::exists(dir / "never.npy"));
#if HUSH_CLI_TEST_GLSL
  const result lsq =
      run_hush("sample anisotropic --backend glsl --filtering least_squares" + out, dir);
  CHECK(lsq.exit_code == 2);
  CHECK(lsq.err.find("least-squares") != std::string::npos);
#endif
}

// ---- --region: one block of the --size grid (hush::grid::block).

namespace {

// The data bytes of an .npy file (after its header).
std::string npy_data(const fs::path& path) {
  const npy_file f = read_npy(path);
  return slurp(path).substr(f.data_offset);
}

// `hush sample <args>` over the whole grid, and over the blocks `regions` (each a --region
// value) that tile it, concatenated along the slowest axis they split: the blocks' data, put
// back in place, equal the whole file's data byte for byte.
void check_regions(const std::string& args, const std::vector<std::string>& regions,
                   const fs::path& dir) {
  CAPTURE(args);
  const fs::path whole = dir / "whole.npy";
  REQUIRE(run_hush("sample " + args + " --out '" + whole.string() + "'", dir).exit_code == 0);
  const npy_file w = read_npy(whole);
  const std::string want = npy_data(whole);
  std::string got(want.size(), '\x55');
  std::size_t covered = 0;
  for (std::size_t b = 0; b < regions.size(); ++b) {
    CAPTURE(regions[b]);
    const fs::path part = dir / ("part" + std::to_string(b) + ".npy");
    const result r =
        run_hush("sample " + args + " --region " + regions[b] + " --out '" + part.string() + "'",
                 dir);
    REQUIRE(r.exit_code == 0);
    // Where the block sits: "x0,y0[,z0]:nx,ny[,nz]".
    std::vector<std::size_t> v;
    std::string s = regions[b];
    for (char& c : s)
      if (c == ':') c = ',';
    std::size_t at = 0;
    while (at < s.size()) {
      std::size_t used = 0;
      v.push_back(std::stoul(s.substr(at), &used));
      at += used + 1;
    }
    const std::size_t axes = v.size() / 2;
    REQUIRE(axes == w.shape.size());
    const npy_file f = read_npy(part);
    std::vector<std::size_t> shape(v.rbegin(), v.rbegin() + static_cast<std::ptrdiff_t>(axes));
    CHECK(f.shape == shape);
    const std::string data = npy_data(part);
    const std::size_t nx = w.shape.back(), ny = w.shape[axes - 2];
    const std::size_t bx = v[axes], by = v[axes + 1], bz = axes == 3 ? v[5] : 1;
    const std::size_t x0 = v[0], y0 = v[1], z0 = axes == 3 ? v[2] : 0;
    for (std::size_t k = 0; k < bz; ++k)
      for (std::size_t j = 0; j < by; ++j)
        got.replace(4 * (((z0 + k) * ny + y0 + j) * nx + x0), 4 * bx, data,
                    4 * ((k * by + j) * bx), 4 * bx);
    covered += bx * by * bz;
  }
  CHECK(covered == w.values.size());
  CHECK(got == want);
}

}  // namespace

TEST_CASE("sample --region: blocks of the grid equal the whole grid's file, byte for byte") {
  const fs::path dir = scratch("regions");
  // Far from the origin, an origin that is not a multiple of the step, a step that rounds.
  const std::string far2 = " --dim 2 --size 37x21 --origin 100000.1,-7.3 --step 0.3333333333333333";
  const std::string far3 =
      " --dim 3 --size 13x9x7 --origin 100000.1,-7.3,2.9 --step 0.3333333333333333";
  const std::vector<std::string> halves_y = {"0,0:37,11", "0,11:37,10"};
  const std::vector<std::string> halves_x = {"0,0:17,21", "17,0:20,21"};
  const std::vector<std::string> quarters = {"0,0:5,3", "5,0:32,3", "0,3:5,18", "5,3:32,18"};
  const std::vector<std::string> octants = {"0,0,0:13,9,3", "0,0,3:7,5,4", "7,0,3:6,5,4",
                                            "0,5,3:13,4,4"};
  std::vector<std::string> backends = {"scalar"};
  if (HUSH_CONFIG_SIMD) backends.push_back("simd");
  for (const std::string& b : backends) {
    const std::string on = " --backend " + b;
    for (const char* noise : {"perlin", "perlin --octaves 4", "wavelet --tile-size 32 --bands 3", "gabor",
                              "anisotropic"}) {
      check_regions(noise + far2 + on, halves_y, dir);
      check_regions(noise + far2 + on, halves_x, dir);
      check_regions(noise + far2 + on, quarters, dir);
    }
    for (const char* noise : {"perlin", "perlin --octaves 3", "wavelet --tile-size 16", "gabor"})
      check_regions(noise + far3 + on, octants, dir);
  }
  // A negative step, and a 3D noise's z-plane (NxM with --dim 3: two axes in --region).
  check_regions("perlin --dim 2 --size 30x12 --origin -5e4,3.7 --step -0.07",
                {"0,0:11,5", "11,0:19,5", "0,5:30,7"}, dir);
  check_regions("perlin --dim 3 --size 30x12 --origin 1.1,2.2,3.3 --step 0.1",
                {"0,0:30,7", "0,7:30,5"}, dir);
}

TEST_CASE("sample --region: a bad region exits 2 with one line naming --region") {
  const fs::path dir = scratch("bad_regions");
  const std::string out = " --out '" + (dir / "never.npy").string() + "'";
  const char* const bad[] = {
      "--size 8x4 --region 0,0:9,4",          // past the grid along x
      "--size 8x4 --region 5,0:4,4",          // first + extent past the grid
      "--size 8x4 --region 0,4:8,1",          // starts past the last row
      "--size 8x4 --region 0,0:0,4",          // an empty block
      "--size 8x4 --region 0,0:8",            // too few numbers
      "--size 8x4 --region 0,0,0:8,4,1",      // three axes for a 2D grid
      "--dim 3 --size 4 --region 0,0:4,4",    // two axes for a 3D grid
      "--size 8x4 --region -1,0:2,2",         // a negative index
      "--size 8x4 --region 0,0",              // no extents
      "--size 8x4 --region 0,0:2,2:2,2",      // two colons
      "--size 8x4 --region a,0:2,2",          // not a number
      "--size 8x4 --region 0,0:99999999999999999999,1",  // out of range
  };
  for (const char* args : bad) {
    CAPTURE(args);
    const result r = run_hush(std::string("sample perlin ") + args + out, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--region") != std::string::npos);
    CHECK(r.err.rfind("hush sample: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.out.empty());
  }
  CHECK_FALSE(fs::exists(dir / "never.npy"));
}
