// Tests of `hush scene` (examples/hush/scene_cmd.cpp): they run the built program, then
// read back what it wrote with load_gbuffer and compare it, bit for bit, with the
// library's own rasterizers; every bad option fails with exit code 2 and one line naming it.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/run_hush.hpp"
#include "gbuffer_io.hpp"
#include "raster_cpu.hpp"
#include "scene_test_util.hpp"
#if HUSH_SCENE_HAVE_GL
#include "raster_gl.hpp"
#endif

namespace {

namespace fs = std::filesystem;
namespace hs = hush_tools::scene;

using hush_cli_test::result;
using hush_cli_test::run_hush;
using hush_cli_test::scratch;

std::size_t lines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST_CASE("scene list prints every registered scene with its description") {
  const fs::path dir = scratch("cli_list");
  const result r = run_hush("scene list", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(lines(r.out) == hs::scene_list().size());
  for (const hs::scene_info& s : hs::scene_list()) {
    CHECK(r.out.find(s.name) != std::string::npos);
    CHECK(r.out.find(s.description) != std::string::npos);
  }
}

TEST_CASE("scene render writes frames 0 ... N-1 equal to render_cpu bit for bit, with progress") {
  const fs::path dir = scratch("cli_render");
  const result r = run_hush(
      "scene render --scene rotate --frames 3 --size 48x32 --out '" + (dir / "seq").string() + "'",
      dir);
  CHECK(r.exit_code == 0);
  CHECK(lines(r.err) == 3u);  // one progress line per frame
  CHECK(r.out.find("wrote 3 frames") != std::string::npos);
  const hs::scene s = hs::make_scene("rotate");
  for (int f = 0; f < 3; ++f) {
    const std::string frame_dir = hs::frame_directory((dir / "seq").string(), f);
    CHECK(hush_scene_test::same_bits(hs::load_gbuffer(frame_dir), hs::render_cpu(s, f, 48, 32)));
    if (hs::previews_supported()) CHECK(fs::exists(fs::path(frame_dir) / "preview_velocity.png"));
  }
  CHECK_FALSE(fs::exists(dir / "seq" / "frame_0003"));
}

#if HUSH_SCENE_HAVE_GL
TEST_CASE("scene render --backend gl writes the GL rasterizer's G-buffer") {
  const fs::path dir = scratch("cli_render_gl");
  const result r =
      run_hush("scene render --scene zoom --frames 2 --size 40x30 --backend gl --out '" +
                   (dir / "seq").string() + "'",
               dir);
  CHECK(r.exit_code == 0);
  hs::gl_rasterizer gl;
  const hs::gbuffer expected = gl.render(hs::make_scene("zoom"), 1, 40, 30);
  CHECK(hush_scene_test::same_bits(hs::load_gbuffer(hs::frame_directory((dir / "seq").string(), 1)),
                                   expected));
}
#endif

TEST_CASE("scene rejects each bad input with exit code 2 and one line naming the option") {
  const fs::path dir = scratch("cli_bad");
  const std::string out = " --out '" + (dir / "o").string() + "'";
  const struct {
    std::string args, names;
  } cases[] = {
      {"scene", "list"},
      {"scene draw", "render"},
      {"scene list extra", "list"},
      {"scene render --scene nope" + out, "--scene"},
      {"scene render --scene dense:12" + out, "--scene"},
      {"scene render" + out, "--scene"},
      {"scene render --scene zoom", "--out"},
      {"scene render --scene zoom --frames 0" + out, "--frames"},
      {"scene render --scene zoom --frames 10001" + out, "--frames"},
      {"scene render --scene zoom --frames 2.5" + out, "--frames"},
      {"scene render --scene zoom --size 64" + out, "--size"},
      {"scene render --scene zoom --size 0x10" + out, "--size"},
      {"scene render --scene zoom --size 16385x10" + out, "--size"},
      {"scene render --scene zoom --backend vulkan" + out, "--backend"},
      {"scene render --scene zoom --fov 2" + out, "--fov"},
  };
  for (const auto& c : cases) {
    INFO(c.args);
    const result r = run_hush(c.args, dir);
    CHECK(r.exit_code == 2);
    CHECK(lines(r.err) == 1u);
    CHECK(r.err.find(c.names) != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "o"));
}

TEST_CASE(
    "scene render fails with exit code 1 naming the file for an unreadable OBJ or an unwritable "
    "directory") {
  const fs::path dir = scratch("cli_fail");
  const std::string missing = (dir / "missing.obj").string();
  const result a = run_hush(
      "scene render --scene 'obj:" + missing + "' --out '" + (dir / "o").string() + "'", dir);
  CHECK(a.exit_code == 1);
  CHECK(a.err.find(missing) != std::string::npos);
  std::ofstream(dir / "a_file") << "x";
  const result b = run_hush(
      "scene render --scene zoom --size 8x8 --out '" + (dir / "a_file").string() + "'", dir);
  CHECK(b.exit_code == 1);
  CHECK(b.err.find("a_file") != std::string::npos);
  CHECK(lines(b.err) == 1u);
}

}  // namespace
