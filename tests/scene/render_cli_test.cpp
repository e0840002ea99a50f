// Tests of `hush render` (examples/hush/render_cmd.cpp, scene_noises.cpp): the program's
// frames equal the library's coherent noise on the same G-buffers bit for bit (causal and
// time-symmetric, one and several channels), progress goes to stderr, and every bad option
// fails with exit code 2 and one line naming it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_hush.hpp"
#include "gbuffer_io.hpp"
#include "hush/coherent.hpp"
#include "hush/core/param_source.hpp"
#include "hush/npr_gabor.hpp"
#include "hush/npr_gabor/style.hpp"
#include "npy/npy.hpp"
#include "raster_cpu.hpp"
#include "triangles.hpp"

#if HUSH_TEST_HAVE_STB_IMAGE
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>
#endif

namespace {

namespace fs = std::filesystem;
namespace hs = hush_tools::scene;

using hush_cli_test::result;
using hush_cli_test::run_hush;
using hush_cli_test::scratch;

constexpr int kW = 40, kH = 30, kFrames = 5;

// G-buffers of the rotate scene written by the program, and the same frames in memory.
std::vector<hs::gbuffer> scene_frames(const fs::path& dir) {
  const result r = run_hush("scene render --scene rotate --frames " + std::to_string(kFrames) +
                                " --size " + std::to_string(kW) + "x" + std::to_string(kH) +
                                " --out '" + (dir / "g").string() + "'",
                            dir);
  REQUIRE(r.exit_code == 0);
  std::vector<hs::gbuffer> g;
  for (int i = 0; i < kFrames; ++i)
    g.push_back(hs::load_gbuffer(hs::frame_directory((dir / "g").string(), i)));
  return g;
}

#if HUSH_TEST_HAVE_STB_IMAGE
// The PNG at `path` as kW x kH RGB bytes.
std::vector<unsigned char> png_rgb(const fs::path& path) {
  const std::string bytes = hush_cli_test::slurp(path);
  int w = 0, h = 0, c = 0;
  unsigned char* px = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                                            static_cast<int>(bytes.size()), &w, &h, &c, 3);
  REQUIRE(px != nullptr);
  REQUIRE(w == kW);
  REQUIRE(h == kH);
  std::vector<unsigned char> rgb(px, px + std::size_t(kW) * kH * 3);
  stbi_image_free(px);
  return rgb;
}
#endif

std::vector<float> frame_file(const fs::path& dir, int i, std::size_t expect_channels) {
  char name[16];
  std::snprintf(name, sizeof name, "%04d.npy", i);
  const hush_tools::npy::array<float> a = hush_tools::npy::load<float>((dir / name).string());
  std::vector<std::size_t> shape = {std::size_t(kH), std::size_t(kW)};
  if (expect_channels > 1) shape.push_back(expect_channels);
  REQUIRE(a.shape == shape);
  return a.values;
}

bool same(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("render coherent writes the library's causal frames bit for bit, with progress") {
  const fs::path dir = scratch("render_causal");
  const std::vector<hs::gbuffer> g = scene_frames(dir);
  const result r = run_hush("render coherent --gbuffer '" + (dir / "g").string() + "' --out '" +
                                (dir / "n").string() + "' --alpha 0.9 --seed 4 --input bandpass",
                            dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("wrote 5 coherent frames (40x30, 1 channel, scalar)") != std::string::npos);
  hush::coherent_params prm;
  prm.alpha = 0.9;
  prm.seed = 4;
  prm.input = hush::coherent_input::bandpass;
  hush::coherent_stream st(prm);
  std::vector<float> out(kW * kH);
  for (int i = 0; i < kFrames; ++i) {
    st.advance(hush::exec::scalar, hs::as_frame(g[std::size_t(i)]),
               hush::image_view<float>(out.data(), kW, kH));
    CHECK(same(frame_file(dir / "n", i, 1), out));
  }
  CHECK_FALSE(fs::exists(dir / "n" / "0005.npy"));
}

TEST_CASE("render coherent --symmetric with channels writes (H, W, C) frames and no scratch") {
  const fs::path dir = scratch("render_symmetric");
  const std::vector<hs::gbuffer> g = scene_frames(dir);
  const result r =
      run_hush("render coherent --symmetric --channels 2 --filter paper --gbuffer '" +
                   (dir / "g").string() + "' --out '" + (dir / "n").string() + "' --frames 4",
               dir);
  CHECK(r.exit_code == 0);
  hush::coherent_params prm;
  prm.channels = 2;
  prm.filter = hush::coherent_filter::paper;
  std::vector<hush::frame> frames;
  for (int i = 0; i < 4; ++i) frames.push_back(hs::as_frame(g[std::size_t(i)]));
  std::vector<float> planes(std::size_t(kW) * kH * 2 * 4);
  std::vector<hush::image_view<float>> out;
  for (int k = 0; k < 8; ++k) out.emplace_back(planes.data() + std::size_t(kW) * kH * k, kW, kH);
  hush::coherent_symmetric(hush::exec::scalar, prm, hush::span<const hush::frame>(frames),
                           hush::span<const hush::image_view<float>>(out));
  for (int i = 0; i < 4; ++i) {
    std::vector<float> interleaved(std::size_t(kW) * kH * 2);
    for (std::size_t p = 0; p < std::size_t(kW) * kH; ++p)
      for (std::size_t c = 0; c < 2; ++c)
        interleaved[2 * p + c] = out[std::size_t(2 * i) + c].data[p];
    CHECK(same(frame_file(dir / "n", i, 2), interleaved));
  }
  for (const auto& e : fs::directory_iterator(dir / "n"))
    CHECK(e.path().extension() == ".npy");  // the forward pass's scratch files are gone
}

TEST_CASE("render: bad options exit 2 with one line naming the option") {
  const fs::path dir = scratch("render_errors");
  scene_frames(dir);
  const std::string g =
      " --gbuffer '" + (dir / "g").string() + "' --out '" + (dir / "n").string() + "'";
  const std::pair<std::string, std::string> cases[] = {
      {"render", "NOISE"},
      {"render perlin" + g, "NOISE 'perlin'"},
      {"render coherent --out x", "--gbuffer"},
      {"render coherent" + g + " --alpha 1", "--alpha"},
      {"render coherent" + g + " --alpha nan", "--alpha"},
      {"render coherent" + g + " --epsilon -1", "--epsilon"},
      {"render coherent" + g + " --channels 5", "--channels"},
      {"render coherent" + g + " --input blue", "--input"},
      {"render coherent" + g + " --filter x", "--filter"},
      {"render coherent" + g + " --smoothing 3", "--smoothing"},
      {"render coherent" + g + " --symmetric --symmetric", "--symmetric"},
      {"render coherent" + g + " --symmetric=yes", "--symmetric"},
      {"render coherent" + g + " --frames 9", "--frames"},
      {"render coherent" + g + " --backend cuda", "--backend"},
      {"render coherent --gbuffer '" + (dir / "nothing").string() + "' --out x", "--gbuffer"},
      {"render npr-gabor" + g + " --frequency 0.7", "--frequency"},
      {"render npr-gabor" + g + " --bandwidth x", "--bandwidth"},
      {"render npr-gabor" + g + " --impulses 0", "--impulses"},
      {"render npr-gabor" + g + " --depth-tolerance 2", "--depth-tolerance"},
      {"render npr-gabor" + g + " --style pencil", "--style"},
      {"render npr-gabor" + g + " --softness 0.5", "--softness"},  // needs --style
      {"render npr-gabor" + g + " --style hatching --softness 9", "--softness"},
      {"render npr-gabor" + g + " --style graphite --grain -1", "--grain"},
      {"render npr-gabor" + g + " --style watercolor --gain 5", "--gain"},
      {"render npr-gabor" + g + " --style hatching --ambient 2", "--ambient"},
      {"render npr-gabor" + g + " --style hatching --light 0,0,0", "--light"},
      {"render npr-gabor" + g + " --style hatching --light 1,2", "--light"},
      {"render npr-gabor" + g + " --style hatching --orientation-field x", "--orientation-field"},
      {"render npr-gabor" + g + " --frequency-field shading:0.1,0.7", "--frequency-field"},
      {"render npr-gabor" + g + " --frequency-field shading:0.1", "--frequency-field"},
      {"render npr-gabor" + g + " --bandwidth-field depth:0,1", "--bandwidth-field"},
      {"render npr-gabor" + g + " --impulses-field depth:8,300", "--impulses-field"},
      {"render npr-gabor" + g + " --impulses-field curvature:1,2", "--impulses-field"},
      {"render npr-gabor" + g + " --impulses-field file:", "--impulses-field"},
      {"render npr-gabor" + g + " --impulses-field file:../x", "--impulses-field"},
      {"render npr-gabor" + g + " --impulses-field file:absent", "absent.npy"},
      {"render npr-gabor" + g + " --field-depth-range 1,2", "--field-depth-range"},
      {"render npr-gabor" + g + " --impulses-field depth:8,9 --field-depth-range 2,1",
       "--field-depth-range"},
      {"render npr-gabor" + g + " --light 1,0,0", "--light"},  // needs a style or shading
  };
  for (const auto& c : cases) {
    CAPTURE(c.first);
    const result r = run_hush(c.first, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.second) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("render npr-gabor writes the library's frames bit for bit from the triangle files") {
  const fs::path dir = scratch("render_npr_gabor");
  const std::vector<hs::gbuffer> g = scene_frames(dir);
  const result r = run_hush("render npr-gabor --gbuffer '" + (dir / "g").string() + "' --out '" +
                                (dir / "n").string() +
                                "' --frequency 0.2 --bandwidth 0.3 --orientation 1 --seed 3 "
                                "--triangle-test --soft-depth",
                            dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("wrote 5 npr-gabor frames (40x30, 1 channel, scalar)") != std::string::npos);
  hush::npr_gabor::params prm;
  prm.frequency = 0.2;
  prm.bandwidth = 0.3;
  prm.orientation = 1;
  prm.seed = 3;
  prm.triangle_test = true;
  prm.soft_depth = true;
  const hush::npr_gabor noise{prm};
  const hs::scene s = hs::make_scene("rotate");
  std::vector<float> out(kW * kH);
  for (int i = 0; i < kFrames; ++i) {
    const hs::triangle_frame t = hs::project_triangles(s, i, kW, kH);
    noise.render(hs::as_frame(g[std::size_t(i)]), t.view(),
                 hush::image_view<float>(out.data(), kW, kH));
    CHECK(same(frame_file(dir / "n", i, 1), out));
    CHECK(std::any_of(out.begin(), out.end(), [](float v) { return v != 0.0f; }));
  }
  // Frame 0 of the library's scalar render with a dense small kernel (the --local-density
  // runs' options), with or without params::local_density.
  const auto dense_frame0 = [&](bool local) {
    hush::npr_gabor::params lp;
    lp.seed = 3;
    lp.bandwidth = 0.3;
    lp.impulses = 64;
    lp.local_density = local;
    const hs::triangle_frame t = hs::project_triangles(s, 0, kW, kH);
    std::vector<float> img(static_cast<std::size_t>(kW) * kH);
    hush::npr_gabor{lp}.render(hs::as_frame(g[0]), t.view(),
                               hush::image_view<float>(img.data(), kW, kH));
    return img;
  };
  const std::string dense_options = " --seed 3 --bandwidth 0.3 --impulses 64 --local-density";
  {  // --local-density: params::local_density, bit for bit (frame 0); a dense small kernel, so
     // that the 40x30 frame's triangles have n > 1/4 and the option changes the image.
    const result l = run_hush("render npr-gabor --gbuffer '" + (dir / "g").string() + "' --out '" +
                                  (dir / "l").string() + "'" + dense_options,
                              dir);
    CHECK(l.exit_code == 0);
    const std::vector<float> local = dense_frame0(true);
    CHECK(same(frame_file(dir / "l", 0, 1), local));
    CHECK(dense_frame0(false) != local);  // the option reached the noise
  }
  // Without the triangle files (G-buffers from before them) it says what is missing.
  for (const char* f :
       {"tri_screen.npy", "tri_depth.npy", "tri_indices.npy", "tri_id.npy", "tri_object.npy"})
    fs::remove(fs::path(hs::frame_directory((dir / "g").string(), 0)) / f);
  const result old = run_hush("render npr-gabor --gbuffer '" + (dir / "g").string() + "' --out '" +
                                  (dir / "m").string() + "'",
                              dir);
  CHECK(old.exit_code == 2);
  CHECK(old.err.find("tri_") != std::string::npos);
  // --backend simd: the tiled SIMD splatting, the same image up to float rounding (the
  // program may fuse multiply-adds: differences of a few ulp of the kernels' sums, far below
  // 1e-4 for unit-variance noise).
  hs::save_triangles(hs::project_triangles(s, 0, kW, kH),
                     hs::frame_directory((dir / "g").string(), 0));
  // Runs `backend` into dir/sub and returns the largest difference from the library's scalar
  // float frames.
  auto worst_against_scalar = [&](const std::string& backend, const char* sub) {
    const result run = run_hush("render npr-gabor --backend " + backend + " --gbuffer '" +
                                    (dir / "g").string() + "' --out '" + (dir / sub).string() +
                                    "' --frequency 0.2 --bandwidth 0.3 --orientation 1 --seed 3 "
                                    "--triangle-test --soft-depth",
                                dir);
    CHECK(run.exit_code == 0);
    CHECK(run.out.find("wrote 5 npr-gabor frames (40x30, 1 channel, " + backend + ")") !=
          std::string::npos);
    double worst = 0;
    for (int i = 0; i < kFrames; ++i) {
      const hs::triangle_frame t = hs::project_triangles(s, i, kW, kH);
      noise.render(hs::as_frame(g[std::size_t(i)]), t.view(),
                   hush::image_view<float>(out.data(), kW, kH));
      const std::vector<float> got = frame_file(dir / sub, i, 1);
      REQUIRE(got.size() == out.size());
      for (std::size_t k = 0; k < out.size(); ++k)
        worst = std::max(worst, std::fabs(double(got[k]) - double(out[k])));
    }
    return worst;
  };
  CHECK(worst_against_scalar("simd", "s") < 1e-4);
#if HUSH_TEST_CLI_HAVE_GLSL
  // --backend glsl: points (stage 1) and splatting as compute passes and point sprites on OSMesa
  // (hush/glsl/npr_gabor.hpp). Float differences from the scalar frames are ~1e-6 (up to ~1e-4
  // where stage 1's float positions span triangles hundreds of pixels wide; the bounds are
  // derived and checked in tests/gabor/glsl_gabor_test.cpp); a wrong pixel,
  // offset or visibility decision would move a pixel by a kernel's amplitude (~0.1), so 1e-3
  // separates the two.
  CHECK(worst_against_scalar("glsl", "l") < 1e-3);
  const result styled =
      run_hush("render npr-gabor --backend glsl --style crosshatch --gbuffer '" +
                   (dir / "g").string() + "' --out '" + (dir / "lp").string() + "'",
               dir);
  CHECK(styled.exit_code == 0);
  CHECK(styled.out.find("3 channels, glsl") != std::string::npos);
  {  // --backend glsl --local-density: GPU stage 1 with a count per node (frame 0) against
     // the library's scalar frame; the same 1e-3 separates float differences from a wrong
     // record (a boundary node, present on one backend only, weighs at most ~1e-3 of a
     // kernel: tests/gabor/glsl_gabor_test.cpp).
    const result l = run_hush("render npr-gabor --backend glsl --gbuffer '" +
                                  (dir / "g").string() + "' --out '" + (dir / "gl").string() +
                                  "'" + dense_options,
                              dir);
    CHECK(l.exit_code == 0);
    const std::vector<float> local = dense_frame0(true), got = frame_file(dir / "gl", 0, 1);
    REQUIRE(got.size() == local.size());
    double worst = 0;
    for (std::size_t k = 0; k < local.size(); ++k)
      worst = std::max(worst, std::fabs(double(got[k]) - double(local[k])));
    CHECK(worst < 1e-3);
  }
#endif
}

// --frequency-field / --bandwidth-field / --impulses-field (examples/hush/npr_fields.hpp): the
// program's frames equal the library's render with the per-pixel and per-vertex sources the
// fields define, computed here from the G-buffers (a wrong direction of LO ... HI, a depth
// range that moves with the frame, a transposed or mis-assigned file would change the
// frames), and the fields change the image.
TEST_CASE("render npr-gabor --frequency-field and friends are the library's per-pixel and "
          "per-vertex sources") {
  const fs::path dir = scratch("render_npr_fields");
  const std::vector<hs::gbuffer> g = scene_frames(dir);
  const hs::scene s = hs::make_scene("rotate");
  const std::string gdir = (dir / "g").string();
  const std::size_t n = std::size_t(kW) * kH;
  const hush::npr_gabor noise{hush::npr_gabor::params{}};
  std::vector<float> out(n), plain(n);
  auto covered = [&](const hs::gbuffer& b, std::size_t p) {
    return b.covered(p) && b.depth[p] > 0 && std::isfinite(b.depth[p]);
  };
  // The depth range of frame 0, fixed for the sequence.
  double z0 = 1e300, z1 = 0;
  for (std::size_t p = 0; p < n; ++p)
    if (covered(g[0], p)) {
      z0 = std::min(z0, double(g[0].depth[p]));
      z1 = std::max(z1, double(g[0].depth[p]));
    }
  REQUIRE(z1 > z0);
  {  // shading:LO,HI and depth:LO,HI
    const result r = run_hush("render npr-gabor --gbuffer '" + gdir + "' --out '" +
                                  (dir / "n").string() +
                                  "' --frequency-field shading:0.3,0.1 --impulses-field depth:24,8",
                              dir);
    REQUIRE(r.exit_code == 0);
    std::vector<float> freq(n), imp(n);
    std::size_t differ = 0;
    for (int i = 0; i < kFrames; ++i) {
      const hs::gbuffer& b = g[std::size_t(i)];
      for (std::size_t p = 0; p < n; ++p) {
        freq[p] = imp[p] = std::nanf("");
        if (!covered(b, p)) continue;
        const hush::dvec3 nn{b.normal[3 * p], b.normal[3 * p + 1], b.normal[3 * p + 2]};
        // The tone as the styles take it (defaults --light 0.4,0.7,0.6, --ambient 0.15), in float.
        const double tone = static_cast<float>(
            hush::style::shading_tone(nn, hush::dvec3{0.4, 0.7, 0.6}, 0.15));
        freq[p] = static_cast<float>(0.3 + (0.1 - 0.3) * std::clamp(tone, 0.0, 1.0));
        const double zs = std::clamp((double(b.depth[p]) - z0) / (z1 - z0), 0.0, 1.0);
        imp[p] = static_cast<float>(24 + (8.0 - 24) * zs);
      }
      hush::npr_gabor::sources src;
      src.frequency = hush::param_source::per_pixel({freq.data(), std::size_t(kW), std::size_t(kH)});
      src.impulses = hush::param_source::per_pixel({imp.data(), std::size_t(kW), std::size_t(kH)});
      const hs::triangle_frame t = hs::project_triangles(s, i, kW, kH);
      noise.render(hs::as_frame(b), t.view(), hush::image_view<float>(out.data(), kW, kH), src);
      CHECK(same(frame_file(dir / "n", i, 1), out));
      noise.render(hs::as_frame(b), t.view(), hush::image_view<float>(plain.data(), kW, kH));
      differ += !same(out, plain);
    }
    CHECK(differ == std::size_t(kFrames));
  }
  {  // depth:LO,HI over a given --field-depth-range (depths outside it clamp to LO or HI)
    char range[80];
    std::snprintf(range, sizeof range, "%.17g,%.17g", z0 + 0.3 * (z1 - z0), z1 - 0.2 * (z1 - z0));
    const double za = z0 + 0.3 * (z1 - z0), zb = z1 - 0.2 * (z1 - z0);
    const result r = run_hush("render npr-gabor --gbuffer '" + gdir + "' --out '" +
                                  (dir / "nd").string() +
                                  "' --bandwidth-field depth:0.3,0.1 --field-depth-range " + range,
                              dir);
    REQUIRE(r.exit_code == 0);
    std::vector<float> band(n);
    for (int i = 0; i < kFrames; ++i) {
      const hs::gbuffer& b = g[std::size_t(i)];
      for (std::size_t p = 0; p < n; ++p) {
        const double zs = std::clamp((double(b.depth[p]) - za) / (zb - za), 0.0, 1.0);
        band[p] = covered(b, p) ? static_cast<float>(0.3 + (0.1 - 0.3) * zs) : std::nanf("");
      }
      hush::npr_gabor::sources src;
      src.bandwidth = hush::param_source::per_pixel({band.data(), std::size_t(kW), std::size_t(kH)});
      const hs::triangle_frame t = hs::project_triangles(s, i, kW, kH);
      noise.render(hs::as_frame(b), t.view(), hush::image_view<float>(out.data(), kW, kH), src);
      CHECK(same(frame_file(dir / "nd", i, 1), out));
    }
  }
  {  // file:NAME per pixel (H, W) and per vertex (V,), and with a style
    std::vector<std::vector<float>> band(kFrames), freq(kFrames);
    for (int i = 0; i < kFrames; ++i) {
      const hs::triangle_frame t = hs::project_triangles(s, i, kW, kH);
      for (std::size_t p = 0; p < n; ++p)  // a left | right step in a, NaN in one corner
        band[std::size_t(i)].push_back(p % kW < kW / 2 ? 0.15f : 0.4f);
      band[std::size_t(i)][0] = std::nanf("");
      for (std::size_t v = 0; v < t.screen.size(); ++v)  // F0 by vertex, moves with the surface
        freq[std::size_t(i)].push_back(0.1f + 0.2f * float(v % 7) / 6);
      const std::string fdir = hs::frame_directory(gdir, i);
      hush_tools::npy::save(fdir + "/my_a.npy", {std::size_t(kH), std::size_t(kW)},
                            band[std::size_t(i)]);
      hush_tools::npy::save(fdir + "/my_f.npy", {t.screen.size()}, freq[std::size_t(i)]);
    }
    const result r = run_hush("render npr-gabor --gbuffer '" + gdir + "' --out '" +
                                  (dir / "nf").string() +
                                  "' --bandwidth-field file:my_a --frequency-field file:my_f",
                              dir);
    REQUIRE(r.exit_code == 0);
    for (int i = 0; i < kFrames; ++i) {
      const hs::triangle_frame t = hs::project_triangles(s, i, kW, kH);
      hush::npr_gabor::sources src;
      src.bandwidth = hush::param_source::per_pixel(
          {band[std::size_t(i)].data(), std::size_t(kW), std::size_t(kH)});
      src.frequency = hush::param_source::per_vertex(freq[std::size_t(i)]);
      noise.render(hs::as_frame(g[std::size_t(i)]), t.view(),
                   hush::image_view<float>(out.data(), kW, kH), src);
      CHECK(same(frame_file(dir / "nf", i, 1), out));
    }
    const result st = run_hush("render npr-gabor --gbuffer '" + gdir + "' --out '" +
                                   (dir / "st").string() +
                                   "' --style graphite --frequency-field file:my_f "
                                   "--bandwidth-field shading:0.1,0.3 --light 1,0,0 --ambient 0.3",
                               dir);
    CHECK(st.exit_code == 0);
    CHECK(st.out.find("wrote 5 npr-gabor frames (40x30, 3 channels, scalar)") != std::string::npos);
    // A file of another shape is refused naming the option and the valid shapes.
    hush_tools::npy::save(hs::frame_directory(gdir, 2) + "/my_a.npy",
                          {std::size_t(kW), std::size_t(kH)}, band[0]);
    const result bad = run_hush("render npr-gabor --gbuffer '" + gdir + "' --out '" +
                                    (dir / "bad").string() + "' --bandwidth-field file:my_a",
                                dir);
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("--bandwidth-field") != std::string::npos);
    CHECK(bad.err.find("(30, 40) per pixel") != std::string::npos);
    CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
  }
}

TEST_CASE("render npr-gabor --style writes one PNG per frame for every style") {
  const fs::path dir = scratch("render_npr_styles");
  const std::vector<hs::gbuffer> g = scene_frames(dir);
  for (const char* style : {"hatching", "stippling", "crosshatch", "graphite", "watercolor"}) {
    CAPTURE(style);
    const fs::path out = dir / style;
    const result r = run_hush("render npr-gabor --gbuffer '" + (dir / "g").string() + "' --out '" +
                                  out.string() + "' --frequency 0.25 --bandwidth 0.3 --style " +
                                  style + (std::string(style) == "hatching" ? " --softness 0" : ""),
                              dir);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("wrote 5 npr-gabor frames (40x30, 3 channels, scalar)") != std::string::npos);
    for (int i = 0; i < kFrames; ++i) {
      char name[16];
      std::snprintf(name, sizeof name, "%04d.png", i);
      const std::string bytes = hush_cli_test::slurp(out / name);
      REQUIRE(bytes.size() > 24);
      CHECK(bytes.compare(1, 3, "PNG") == 0);
#if HUSH_TEST_HAVE_STB_IMAGE
      const std::vector<unsigned char> rgb = png_rgb(out / name);  // kW x kH, or the test stops
      const unsigned char* px = rgb.data();
      std::size_t ink = 0, colour = 0;
      const hs::gbuffer& gb = g[std::size_t(i)];
      for (std::size_t p = 0; p < std::size_t(kW) * kH; ++p) {
        const unsigned char* q = px + 3 * p;
        if (!gb.covered(p)) CHECK(q[0] + q[1] + q[2] == 3 * 255);  // background: paper
        if (q[0] == 0) ++ink;
        if (q[0] != q[1] || q[1] != q[2]) ++colour;
        // Hard step: every pixel is paper or ink.
        if (std::string(style) == "hatching") CHECK((q[0] == 0 || q[0] == 255));
      }
      CHECK(ink + colour > 0);  // something is drawn
      CHECK((colour > 0) == (std::string(style) == "watercolor"));
#endif
    }
  }
  // On the SIMD backend the layers are splatted by exec::simd: the same drawing, except where a
  // noise value within its float budget of the scalar one sits at the hard step's threshold.
  const fs::path simd_out = dir / "hatching_simd";
  const result r = run_hush("render npr-gabor --backend simd --gbuffer '" + (dir / "g").string() +
                                "' --out '" + simd_out.string() +
                                "' --frequency 0.25 --bandwidth 0.3 --style hatching --softness 0",
                            dir);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("3 channels, simd)") != std::string::npos);
  for (int i = 0; i < kFrames; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%04d.png", i);
    REQUIRE(hush_cli_test::slurp(simd_out / name).size() > 24);
#if HUSH_TEST_HAVE_STB_IMAGE
    const std::vector<unsigned char> pa = png_rgb(dir / "hatching" / name);
    const std::vector<unsigned char> pb = png_rgb(simd_out / name);
    std::size_t differ = 0;
    for (std::size_t p = 0; p < pa.size(); ++p) differ += pa[p] != pb[p];
    // A flip needs |noise - threshold| below ~1e-6 (the float budget): over 3600 values, the
    // chance of even one is ~1e-2; allow 3 channels of one pixel.
    CHECK(differ <= 3);
#endif
  }
  // --orientation-field curvature: hatching along the torus's principal curvature, which
  // differs from the projected normal (NaN where the tube faces the camera, where the
  // curvature still has a direction): a hard-step drawing, not the same as the default's.
  const fs::path curv_out = dir / "hatching_curvature";
  const result rc = run_hush("render npr-gabor --gbuffer '" + (dir / "g").string() + "' --out '" +
                                 curv_out.string() +
                                 "' --frequency 0.25 --bandwidth 0.3 --style hatching --softness 0"
                                 " --orientation-field curvature",
                             dir);
  REQUIRE(rc.exit_code == 0);
#if HUSH_TEST_HAVE_STB_IMAGE
  std::size_t differ = 0;
  for (int i = 0; i < kFrames; ++i) {
    char name[16];
    std::snprintf(name, sizeof name, "%04d.png", i);
    const std::vector<unsigned char> pa = png_rgb(dir / "hatching" / name);
    const std::vector<unsigned char> pb = png_rgb(curv_out / name);
    for (std::size_t p = 0; p < pa.size(); ++p) {
      CHECK((pb[p] == 0 || pb[p] == 255));
      differ += pa[p] != pb[p];
    }
  }
  CHECK(differ > 0);
#endif
}

TEST_CASE("render --symmetric refuses G-buffers without forward velocity") {
  const fs::path dir = scratch("render_no_forward");
  std::vector<hs::gbuffer> g = scene_frames(dir);
  for (int i = 0; i < 2; ++i) {
    g[std::size_t(i)].forward_velocity.clear();
    hs::save_gbuffer(g[std::size_t(i)], hs::frame_directory((dir / "old").string(), i));
  }
  const result r = run_hush("render coherent --symmetric --gbuffer '" + (dir / "old").string() +
                                "' --out '" + (dir / "n").string() + "'",
                            dir);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("forward_velocity") != std::string::npos);
  // The causal filter does not need it.
  CHECK(run_hush("render coherent --gbuffer '" + (dir / "old").string() + "' --out '" +
                     (dir / "n").string() + "'",
                 dir)
            .exit_code == 0);
}

TEST_CASE("gallery writes the scene-driven noises' animations (GIF) and their papers' figures") {
  const fs::path dir = scratch("gallery_coherent");
  const result r = run_hush("gallery --out '" + (dir / "g").string() + "'", dir);
  if (r.exit_code == 2) {  // a build without PNG output or Eigen has no gallery at all
    MESSAGE("gallery unavailable in this build: " << r.err);
    return;
  }
  REQUIRE(r.exit_code == 0);
  struct expected {
    const char* file;
    unsigned width, height, frames;
  };
  for (const expected& e : {expected{"coherent_rotate.gif", 256, 192, 32},
                            expected{"coherent_walkthrough.gif", 256, 192, 32},
                            expected{"coherent_fig3a.gif", 128, 96, 32},
                            expected{"coherent_fig3b.gif", 128, 96, 32},
                            expected{"npr_fig1_rotate.gif", 384, 96, 24},
                            expected{"npr_fig1_walkthrough.gif", 384, 96, 24},
                            expected{"npr_styles_rotate.gif", 256, 192, 24},
                            expected{"npr_watercolor_rotate.gif", 128, 96, 24}}) {
    CAPTURE(e.file);
    const std::string bytes = hush_cli_test::slurp(dir / "g" / e.file);
    REQUIRE(bytes.size() > 13);
    CHECK(bytes.compare(0, 6, "GIF89a") == 0);
    const auto u16 = [&](std::size_t at) {
      return unsigned(static_cast<unsigned char>(bytes[at])) |
             unsigned(static_cast<unsigned char>(bytes[at + 1])) << 8;
    };
    CHECK(u16(6) == e.width);
    CHECK(u16(8) == e.height);
    CHECK(bytes.back() == ';');  // the trailer: a complete file
    CHECK(r.out.find(std::string(e.file) + " (" + std::to_string(e.width) + "x" +
                     std::to_string(e.height) + ", " + std::to_string(e.frames) + " frames)") !=
          std::string::npos);
  }
  for (const char* still : {"coherent_fig2.png", "coherent_fig6.png"}) {
    CAPTURE(still);
    CHECK(hush_cli_test::slurp(dir / "g" / still).compare(1, 3, "PNG") == 0);
  }
}
