// Tests of `hush sample` options that shape what is shown or sampled: per-command help, the
// PNG display range (--range and the per-noise default), exact positions with per-sample
// inputs (--footprint, --normal) at far origins, and the normal and weight checks.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "run_hush.hpp"

#if HUSH_CLI_TEST_DECODE
#include "stb_image.h"  // the implementation is cli_test.cpp's
#endif

namespace {

namespace fs = std::filesystem;
using hush_cli_test::result;
using hush_cli_test::run_hush;
using hush_cli_test::scratch;
using hush_cli_test::slurp;

// The float32 values of an .npy file the program wrote (NPY 1.0, little-endian host).
std::vector<float> npy_values(const fs::path& path) {
  const std::string bytes = slurp(path);
  REQUIRE(bytes.size() >= 10);
  const std::size_t len = static_cast<unsigned char>(bytes[8]) |
                          static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8;
  REQUIRE((bytes.size() - 10 - len) % 4 == 0);
  std::vector<float> v((bytes.size() - 10 - len) / 4);
  std::memcpy(v.data(), bytes.data() + 10 + len, 4 * v.size());
  return v;
}

std::size_t distinct(const std::vector<float>& v) { return std::set<float>(v.begin(), v.end()).size(); }

}  // namespace

TEST_CASE("COMMAND --help prints that command's part of the usage, shorter than hush --help") {
  const fs::path dir = scratch("command_help");
  const result all = run_hush("--help", dir);
  REQUIRE(all.exit_code == 0);
  struct want {
    std::string args, has, lacks;
  };
  const want cases[] = {{"sample wavelet --help", "--footprint", "--octaves"},
                        {"sample wavelet --help", "--range", "hush bench"},
                        {"sample --help", "--octaves", "Times every noise"},
                        {"bench --help", "--quick", "--tile-size"},
                        {"gallery --help", "hush gallery", "--tile-size"},
                        {"scene --help", "hush scene render", "NOISE wavelet"},
                        {"render coherent --help", "hush render", "NOISE wavelet"}};
  for (const want& c : cases) {
    CAPTURE(c.args);
    const result r = run_hush(c.args, dir);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find(c.has) != std::string::npos);
    CHECK(r.out.find(c.lacks) == std::string::npos);
    CHECK(r.out.size() < all.out.size());
  }
  // One noise's part: its own options only.
  const result w = run_hush("sample wavelet --help", dir);
  CHECK(w.out.find("NOISE wavelet") != std::string::npos);
  CHECK(w.out.find("NOISE perlin") == std::string::npos);
}

TEST_CASE("sample wavelet keeps double positions with --footprint and --normal at far origins") {
  // A 16-sample row 1/32 apart at x = 1e7 and 1e9: float positions there are 1 and 64 apart
  // (5 and 1 distinct values); the options must not change how many values the row has.
  const fs::path dir = scratch("wavelet_far_samples");
  for (const char* origin : {"1e7,0,0", "1e9,0,0"})
    for (const char* backend : {"scalar", "simd"}) {
#if !HUSH_CLI_TEST_SIMD
      if (std::string(backend) == "simd") continue;
#endif
      CAPTURE(origin);
      CAPTURE(backend);
      const std::string base = std::string("sample wavelet --dim 3 --size 16x1 --origin ") +
                               origin + " --backend " + backend + " --out '";
      const fs::path plain = dir / "plain.npy", surface = dir / "surface.npy";
      REQUIRE(run_hush(base + plain.string() + "'", dir).exit_code == 0);
      REQUIRE(run_hush(base + surface.string() + "' --normal 1,2,3 --footprint 0.001", dir)
                  .exit_code == 0);
      CHECK(distinct(npy_values(plain)) == 16);
      CHECK(distinct(npy_values(surface)) == 16);
    }
}

TEST_CASE("sample wavelet --normal keeps its direction at any scale; bad weights exit 2") {
  const fs::path dir = scratch("wavelet_normal_scale");
  const std::string base = "sample wavelet --dim 3 --size 8x4 --seed 2 --out '";
  struct same {
    const char *normal, *unit;
  };
  for (const same& c : {same{"1e-50,0,0", "1,0,0"}, same{"1e39,1e39,0", "1,1,0"},
                        same{"0,-1e-310,0", "0,-1,0"}}) {
    CAPTURE(c.normal);
    const fs::path a = dir / "a.npy", b = dir / "b.npy";
    REQUIRE(run_hush(base + a.string() + "' --normal " + c.normal, dir).exit_code == 0);
    REQUIRE(run_hush(base + b.string() + "' --normal " + c.unit, dir).exit_code == 0);
    CHECK(npy_values(a) == npy_values(b));
  }
  // Weights whose squares overflow or underflow a double: refused, not NaN images.
  for (const char* w : {"1e308,1e308", "1e-200", "1e151"}) {
    CAPTURE(w);
    const result r = run_hush(base + (dir / "w.npy").string() + "' --weights " + w, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--weights") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("sample --range is validated: finite, lo < hi, PNG output only") {
  const fs::path dir = scratch("range_bad");
  for (const char* range : {"1,0", "0,0", "nan,1", "0,inf", "-1e308,1e308", "1", "a,b"}) {
    CAPTURE(range);
    const result r = run_hush(std::string("sample perlin --size 4 --range ") + range + " --out '" +
                                  (dir / "x.png").string() + "'",
                              dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--range") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  const result npy =
      run_hush("sample perlin --size 4 --range -1,1 --out '" + (dir / "x.npy").string() + "'", dir);
  CHECK(npy.exit_code == 2);
  CHECK(npy.err.find("--range") != std::string::npos);
}

#if HUSH_CLI_TEST_PNG && HUSH_CLI_TEST_DECODE
TEST_CASE("sample PNG: --range maps lo..hi to black..white; the default clips under 1 %") {
  const fs::path dir = scratch("range_png");
  auto pixels = [&](const std::string& args, const fs::path& png) {
    REQUIRE(run_hush(args + " --out '" + png.string() + "'", dir).exit_code == 0);
    int w = 0, h = 0, channels = 0;
    unsigned char* data = stbi_load(png.string().c_str(), &w, &h, &channels, 1);
    REQUIRE(data != nullptr);
    std::vector<int> p(data, data + w * h);
    stbi_image_free(data);
    return p;
  };
  // --range: pixel = round(255 (v - lo) / (hi - lo)), clamped.
  const std::string few = "sample wavelet --size 32x16 --seed 4";
  REQUIRE(run_hush(few + " --out '" + (dir / "v.npy").string() + "'", dir).exit_code == 0);
  const std::vector<float> v = npy_values(dir / "v.npy");
  const std::vector<int> p = pixels(few + " --range -0.5,2", dir / "r.png");
  REQUIRE(p.size() == v.size());
  int worst = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double g = std::clamp(255.0 * (v[i] + 0.5) / 2.5, 0.0, 255.0);
    worst = std::max(worst, static_cast<int>(std::abs(p[i] - g) + 0.5));
  }
  CHECK(worst <= 1);
  // The default range of unit-variance noise: clipped (black or white) pixels under 1 % on
  // 65536 samples 1/2 apart (many correlation lengths: one wavelet band's coefficients are
  // 1 apart, Gabor's kernels and the fBm's first octave span about 1 unit). [-1, 1] would
  // clip about 32 % of each.
  for (const char* noise :
       {"wavelet", "perlin --octaves 6", "gabor --kind anisotropic", "gabor --kind isotropic"}) {
    CAPTURE(noise);
    const std::vector<int> q =
        pixels(std::string("sample ") + noise + " --size 256 --step 0.5 --seed 9", dir / "d.png");
    const auto clipped = std::count_if(q.begin(), q.end(), [](int g) { return g == 0 || g == 255; });
    CHECK(static_cast<double>(clipped) / static_cast<double>(q.size()) < 0.01);
  }
}
#endif
