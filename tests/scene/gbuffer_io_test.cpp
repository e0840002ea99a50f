// Tests of the G-buffer files (examples/scene/gbuffer_io.hpp): a round trip keeps every
// bit, the .npy headers have the documented dtype and (H, W[, C]) shape, previews are
// written, and a missing or corrupt file fails with an error naming it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gbuffer_io.hpp"
#include "hush/core/error.hpp"
#include "raster_cpu.hpp"
#include "scene_test_util.hpp"
#include "triangles.hpp"

namespace {

namespace hs = hush_tools::scene;
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(HUSH_SCENE_SCRATCH) / name;
  fs::remove_all(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string error_of(const std::string& dir) {
  try {
    hs::load_gbuffer(dir);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST_CASE("save then load gives the same G-buffer bit for bit") {
  const hs::gbuffer g = hs::render_cpu(hs::make_scene("walkthrough"), 3, 64, 48);
  const std::string dir = hs::frame_directory(scratch("io_roundtrip").string(), 3);
  CHECK(fs::path(dir).filename() == "frame_0003");
  hs::save_gbuffer(g, dir);
  CHECK(hush_scene_test::same_bits(hs::load_gbuffer(dir), g));
}

TEST_CASE("channel files are NPY 1.0 with the documented dtype and shape, data 64-byte aligned") {
  const hs::gbuffer g = hs::render_cpu(hs::make_scene("translate"), 0, 7, 5);
  const fs::path dir = scratch("io_headers");
  hs::save_gbuffer(g, dir.string());
  const struct {
    const char* file;
    const char* header;
    std::size_t values;
  } expected[] = {
      {"depth.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7), }", 35},
      {"velocity.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7, 3), }", 105},
      {"forward_velocity.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7, 3), }",
       105},
      {"object_id.npy", "{'descr': '<u4', 'fortran_order': False, 'shape': (5, 7), }", 35},
      {"triangle_id.npy", "{'descr': '<u4', 'fortran_order': False, 'shape': (5, 7), }", 35},
      {"barycentric.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7, 3), }", 105},
      {"uv.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7, 2), }", 70},
      {"uv_jacobian.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7, 4), }", 140},
      {"normal.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7, 3), }", 105},
      {"position.npy", "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7, 3), }", 105}};
  for (const auto& e : expected) {
    INFO(e.file);
    const std::string bytes = slurp(dir / e.file);
    REQUIRE(bytes.size() > 10);
    CHECK(bytes.compare(0, 6, "\x93NUMPY") == 0);
    const std::size_t len = static_cast<unsigned char>(bytes[8]) |
                            (static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8);
    CHECK((10 + len) % 64 == 0);
    CHECK(bytes.compare(10, std::string(e.header).size(), e.header) == 0);
    CHECK(bytes.size() == 10 + len + 4 * e.values);
  }
  // Row 0 is the top: the first stored depth is pixel (0, 0), little-endian float32.
  const std::string depth = slurp(dir / "depth.npy");
  float first;
  std::memcpy(&first, depth.data() + depth.size() - std::size_t{140}, 4);
  CHECK(first == g.depth[0]);
  if (hs::previews_supported())
    for (const char* p : {"preview_depth.png", "preview_normal.png", "preview_uv.png",
                          "preview_velocity.png", "preview_object_id.png"})
      CHECK(slurp(dir / p).compare(1, 3, "PNG") == 0);
}

TEST_CASE("missing, truncated or mistyped channel files fail with an error naming the file") {
  const hs::gbuffer g = hs::render_cpu(hs::make_scene("translate"), 0, 8, 6);
  const fs::path dir = scratch("io_errors");
  hs::save_gbuffer(g, dir.string());
  fs::remove(dir / "uv.npy");
  CHECK(error_of(dir.string()).find("uv.npy") != std::string::npos);
  hs::save_gbuffer(g, dir.string());
  fs::resize_file(dir / "normal.npy", fs::file_size(dir / "normal.npy") - 4);
  CHECK(error_of(dir.string()).find("normal.npy") != std::string::npos);
  hs::save_gbuffer(g, dir.string());
  fs::copy_file(dir / "depth.npy", dir / "object_id.npy", fs::copy_options::overwrite_existing);
  const std::string wrong_type = error_of(dir.string());
  CHECK(wrong_type.find("object_id.npy") != std::string::npos);
  CHECK(wrong_type.find("<u4") != std::string::npos);
  hs::save_gbuffer(g, dir.string());
  fs::copy_file(dir / "depth.npy", dir / "position.npy", fs::copy_options::overwrite_existing);
  CHECK(error_of(dir.string()).find("position.npy") != std::string::npos);
  CHECK(error_of((dir / "nothing_here").string()).find("depth.npy") != std::string::npos);
}

TEST_CASE("forward velocity is optional: absent on save, absent on load, a stale file removed") {
  hs::gbuffer g = hs::render_cpu(hs::make_scene("rotate"), 2, 9, 7);
  const fs::path dir = scratch("io_forward");
  hs::save_gbuffer(g, dir.string());
  CHECK(fs::exists(dir / "forward_velocity.npy"));
  CHECK(hush_scene_test::same_bits(hs::load_gbuffer(dir.string()), g));
  g.forward_velocity.clear();  // a producer without it
  hs::save_gbuffer(g, dir.string());
  CHECK_FALSE(fs::exists(dir / "forward_velocity.npy"));
  const hs::gbuffer back = hs::load_gbuffer(dir.string());
  CHECK(back.forward_velocity.empty());
  CHECK(hush_scene_test::same_bits(back, g));
  g.forward_velocity.assign(5, 0.0f);  // present but the wrong size
  CHECK_THROWS_AS(hs::save_gbuffer(g, dir.string()), hush::invalid_argument);
}

TEST_CASE("a G-buffer whose channels do not match its size is refused") {
  hs::gbuffer g = hs::make_background(4, 3);
  g.uv.pop_back();
  CHECK_THROWS_AS(hs::save_gbuffer(g, scratch("io_bad").string()), hush::invalid_argument);
}

}  // namespace

// ---- The projected triangles (examples/scene/triangles.hpp) that NPR Gabor noise reads.

TEST_CASE("projected triangles agree with the G-buffer: coverage, depth plane and winding") {
  // The walkthrough's frame 80 has ground triangles crossing the near plane (a vertex behind
  // the camera, its screen position clip xy / w with w < 0): their plane 1/z, affine in
  // screen space through the projected vertices, must still give the pixels' depths.
  for (const auto& [name, frame] :
       {std::pair<const char*, int>{"rotate", 2}, {"walkthrough", 80}}) {
    const std::string scene_name = name;
    CAPTURE(scene_name);
    const hush_tools::scene::scene s = hush_tools::scene::make_scene(name);
    const int w = 80, h = 60;
    std::size_t crossing = 0;
    const hush_tools::scene::gbuffer g = hush_tools::scene::render_cpu(s, frame, w, h);
    const hush_tools::scene::triangle_frame t =
        hush_tools::scene::project_triangles(s, frame, w, h);
    const hush::triangle_list list = t.view();
    REQUIRE_NOTHROW(list.validate("test", 1u << 28));
    CHECK(list.triangles() == s.triangles());
    // (object, triangle) -> index in the list.
    std::vector<std::size_t> first(s.objects.size() + 1, 0);
    for (std::size_t k = 0; k < s.objects.size(); ++k)
      first[k + 1] = first[k] + s.objects[k].shape->triangles();
    std::size_t checked = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = static_cast<std::size_t>(y * w + x);
        if (!g.covered(p)) continue;
        const std::size_t i = first[g.object_id[p] - 1] + g.triangle_id[p];
        REQUIRE(t.triangle_id[i] == g.triangle_id[p]);
        REQUIRE(t.object_id[i] == g.object_id[p]);
        double sx[3], sy[3], z[3];
        for (int v = 0; v < 3; ++v) {
          const std::uint32_t k = t.indices[3 * i + std::size_t(v)];
          sx[v] = t.screen[k].x;
          sy[v] = t.screen[k].y;
          z[v] = t.depth[k];
        }
        REQUIRE(z[0] * z[1] * z[2] != 0);
        const bool behind = !(z[0] > 0 && z[1] > 0 && z[2] > 0);  // clipped by the near plane
        crossing += behind ? 1 : 0;
        // Screen barycentrics of the pixel centre: inside (to float rounding), and the
        // plane's 1/z there (affine in screen space) is the G-buffer's depth.
        const double px = x + 0.5, py = y + 0.5;
        const double cross = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0]);
        const double l1 = ((px - sx[0]) * (sy[2] - sy[0]) - (py - sy[0]) * (sx[2] - sx[0])) / cross;
        const double l2 = ((sx[1] - sx[0]) * (py - sy[0]) - (sy[1] - sy[0]) * (px - sx[0])) / cross;
        const double l0 = 1.0 - l1 - l2;
        // Distance to each edge (l_i times the height over the opposite edge): the
        // rasterizer snaps vertices to 1/256 pixel, so centres may lie that far outside.
        const double e0 = std::hypot(sx[2] - sx[1], sy[2] - sy[1]);
        const double e1 = std::hypot(sx[2] - sx[0], sy[2] - sy[0]);
        const double e2 = std::hypot(sx[1] - sx[0], sy[1] - sy[0]);
        const double a2 = std::fabs(cross);
        if (!behind) CHECK(std::min({l0 * a2 / e0, l1 * a2 / e1, l2 * a2 / e2}) > -1.0 / 128);
        const double inv_z = l0 / z[0] + l1 / z[1] + l2 / z[2];
        CHECK(g.depth[p] * inv_z == doctest::Approx(1.0).epsilon(1e-4));
        // Front faces are clockwise on the y-down screen (GL's counter-clockwise).
        if (s.objects[g.object_id[p] - 1].shape->closed && !behind) CHECK(cross < 0);
        ++checked;
      }
    CHECK(checked > std::size_t(w * h / 4));
    if (scene_name == "walkthrough") CHECK(crossing > 0);
  }
}

TEST_CASE("triangle files round-trip and malformed ones are refused naming the file") {
  const hush_tools::scene::scene s = hush_tools::scene::make_scene("translate");
  const hush_tools::scene::triangle_frame t = hush_tools::scene::project_triangles(s, 1, 32, 24);
  const fs::path dir = scratch("triangles");
  hush_tools::scene::save_triangles(t, dir.string());
  REQUIRE(hush_tools::scene::has_triangles(dir.string()));
  const hush_tools::scene::triangle_frame u = hush_tools::scene::load_triangles(dir.string());
  CHECK(u.indices == t.indices);
  CHECK(u.depth == t.depth);
  CHECK(u.triangle_id == t.triangle_id);
  CHECK(u.object_id == t.object_id);
  REQUIRE(u.screen.size() == t.screen.size());
  for (std::size_t i = 0; i < u.screen.size(); ++i) {
    CHECK(std::memcmp(&u.screen[i].x, &t.screen[i].x, sizeof(float)) == 0);
    CHECK(std::memcmp(&u.screen[i].y, &t.screen[i].y, sizeof(float)) == 0);
  }
  hush_tools::scene::triangle_frame bad = t;
  bad.triangle_id.pop_back();
  hush_tools::scene::save_triangles(bad, dir.string());
  CHECK_THROWS_WITH_AS(hush_tools::scene::load_triangles(dir.string()),
                       doctest::Contains("tri_id.npy"), std::runtime_error);
  bad = t;
  bad.indices[5] = 1u << 30;
  hush_tools::scene::save_triangles(bad, dir.string());
  CHECK_THROWS_WITH_AS(hush_tools::scene::load_triangles(dir.string()),
                       doctest::Contains("tri_indices.npy"), std::runtime_error);
  CHECK_FALSE(hush_tools::scene::has_triangles((dir / "none").string()));
}
