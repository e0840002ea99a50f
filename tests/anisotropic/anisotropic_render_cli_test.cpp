// `hush render anisotropic` (examples/hush/noise_anisotropic.cpp): the program's frames equal
// the library's anisotropic noise on the same G-buffers (examples/anisotropic/scene_render.hpp)
// bit for bit, with and without --scene compensation; with --backend glsl (whole frames on the
// GPU, hush/glsl/anisotropic/frame.hpp) within the shader's stated tolerance of them; and bad
// options fail with exit code 2 and one line naming the option.
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
#if HUSH_TEST_CLI_GLSL
#include <cmath>

#include "hush/glsl/anisotropic/shader.hpp"
#endif

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

#if HUSH_TEST_CLI_GLSL
// --backend glsl renders each frame through anisotropic_frame: per covered pixel within
// anisotropic_shader_tolerance of the library's scalar frame (same uv, Jacobian and triangle
// map), background 0.
TEST_CASE("render anisotropic --backend glsl: the GPU frames within the shader's tolerance") {
  const fs::path dir = scratch("render_anisotropic_glsl");
  const std::vector<hs::gbuffer> g = walkthrough_frames(dir);
  hush::anisotropic::params p;
  p.seed = 5;
  p.orientations = 6;
  p.scales = 5;
  p.base_scale = 1;
  p.octaves = 2;
  p.frequency = 2;
  p.tile_size = 64;
  const hush::anisotropic noise(p);
  const auto maps = hush_tools::aniso::scene_surface_maps(hs::make_scene("walkthrough"));
  const result r = run_hush("render anisotropic --gbuffer '" + (dir / "g").string() +
                                "' --seed 5 --orientations 6 --scales 5 --base-scale 1 "
                                "--octaves 2 --frequency 2 --tile-size 64 --backend glsl "
                                "--scene walkthrough --out '" +
                                (dir / "gpu").string() + "'",
                            dir);
  REQUIRE(r.exit_code == 0);
  double worst = 0;
  for (int i = 0; i < kFrames; ++i) {
    const hs::gbuffer& gb = g[std::size_t(i)];
    const std::vector<float> cpu =
        hush_tools::aniso::render_gbuffer(noise, gb, maps, hush::exec::scalar);
    const std::vector<float> gpu = frame_file(dir / "gpu", i);
    for (std::size_t q = 0; q < cpu.size(); ++q) {
      if (!gb.covered(q)) {
        CHECK(gpu[q] == 0.0f);
        continue;
      }
      const hush::vec2 uv{gb.uv[2 * q], gb.uv[2 * q + 1]};
      const hush::vec2 dx{gb.uv_jacobian[4 * q], gb.uv_jacobian[4 * q + 2]};
      const hush::vec2 dy{gb.uv_jacobian[4 * q + 1], gb.uv_jacobian[4 * q + 3]};
      const std::uint32_t object = gb.object_id[q], tri = gb.triangle_id[q];
      const hush::surface_map m = object - 1 < maps.size() && tri < maps[object - 1].size()
                                      ? maps[object - 1][tri]
                                      : hush::surface_map::identity();
      const double tol = hush::glsl::anisotropic_shader_tolerance(noise, uv, dx, dy, &m);
      INFO("frame " << i << " pixel " << q << ": cpu " << cpu[q] << " gpu " << gpu[q]);
      CHECK(std::fabs(double(gpu[q]) - cpu[q]) <= tol);
      worst = std::max(worst, std::fabs(double(gpu[q]) - cpu[q]) / tol);
    }
  }
  MESSAGE("render anisotropic --backend glsl: max error / tolerance = " << worst);
}
#endif

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
