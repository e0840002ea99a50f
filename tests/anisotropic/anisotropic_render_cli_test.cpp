// `hush render anisotropic` (examples/hush/noise_anisotropic.cpp): the program's frames equal
// the library's anisotropic noise on the same G-buffers (examples/anisotropic/scene_render.hpp)
// bit for bit, with and without --scene compensation, and bad options fail with exit code 2 and
// one line naming the option.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cli/run_hush.hpp"
#include "gbuffer_io.hpp"
#include "npy/npy.hpp"
#include "scene.hpp"
#include "scene_render.hpp"

namespace {

namespace fs = std::filesystem;
namespace hs = hush_tools::scene;
using hush_cli_test::result;
using hush_cli_test::run_hush;
using hush_cli_test::scratch;

constexpr int kW = 48, kH = 27, kFrames = 2;

std::vector<hs::gbuffer> walkthrough_frames(const fs::path& dir) {
  const result r = run_hush("scene render --scene walkthrough --frames " + std::to_string(kFrames) +
                                " --size " + std::to_string(kW) + "x" + std::to_string(kH) +
                                " --out '" + (dir / "g").string() + "'",
                            dir);
  REQUIRE(r.exit_code == 0);
  std::vector<hs::gbuffer> g;
  for (int i = 0; i < kFrames; ++i)
    g.push_back(hs::load_gbuffer(hs::frame_directory((dir / "g").string(), i)));
  return g;
}

std::vector<float> frame_file(const fs::path& dir, int i) {
  char name[16];
  std::snprintf(name, sizeof name, "%04d.npy", i);
  const hush_tools::npy::array<float> a = hush_tools::npy::load<float>((dir / name).string());
  REQUIRE(a.shape == std::vector<std::size_t>{std::size_t(kH), std::size_t(kW)});
  return a.values;
}

bool same(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("render anisotropic writes the library's frames bit for bit, compensated or not") {
  const fs::path dir = scratch("render_anisotropic");
  const std::vector<hs::gbuffer> g = walkthrough_frames(dir);
  hush::anisotropic::params p;
  p.seed = 5;
  p.orientations = 8;
  p.scales = 5;
  p.base_scale = 1;
  p.octaves = 2;
  p.frequency = 2;
  p.tile_size = 64;
  const hush::anisotropic noise(p);
  const auto maps = hush_tools::aniso::scene_surface_maps(hs::make_scene("walkthrough"));
  const std::string common = " --gbuffer '" + (dir / "g").string() +
                             "' --seed 5 --orientations 8 --scales 5 --base-scale 1 --octaves 2 "
                             "--frequency 2 --tile-size 64";
  for (const bool compensate : {true, false}) {
    CAPTURE(compensate);
    const fs::path out = dir / (compensate ? "c" : "u");
    const result r = run_hush("render anisotropic" + common + " --out '" + out.string() + "'" +
                                  (compensate ? " --scene walkthrough" : ""),
                              dir);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("wrote 2 anisotropic frames (48x27, 1 channel, scalar)") != std::string::npos);
    for (int i = 0; i < kFrames; ++i) {
      const std::vector<float> expect = hush_tools::aniso::render_gbuffer(
          noise, g[std::size_t(i)], maps, hush::exec::scalar, compensate);
      CHECK(same(frame_file(out, i), expect));
    }
  }
  // The two differ: compensation changes the noise on the scene's objects.
  CHECK_FALSE(same(frame_file(dir / "c", 0), frame_file(dir / "u", 0)));
}

TEST_CASE("render anisotropic: bad options exit 2 with one line naming the option") {
  const fs::path dir = scratch("render_anisotropic_errors");
  walkthrough_frames(dir);
  const std::string base = "render anisotropic --gbuffer '" + (dir / "g").string() + "' --out '" +
                           (dir / "n").string() + "'";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --scene nowhere", "--scene 'nowhere'"},
      {" --orientations 9", "--orientations '9'"},
      {" --tile-size 100", "--tile-size '100'"},
      {" --filtering sharp", "--filtering 'sharp'"},
      {" --map 1,0,0,1", "--map"},  // per triangle from --scene, not one map
      {" --filtering least_squares --backend glsl", "--backend 'glsl'"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.first);
    const result r = run_hush(base + c.first, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.second) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}
