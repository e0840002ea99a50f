// Tests of the G-buffer files (examples/scene/gbuffer_io.hpp): a round trip keeps every
// bit, the .npy headers have the documented dtype and (H, W[, C]) shape, previews are
// written, and a missing or corrupt file fails with an error naming it.
#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "gbuffer_io.hpp"
#include "hush/core/error.hpp"
#include "raster_cpu.hpp"
#include "scene_test_util.hpp"

namespace {

namespace hs = hush::scene;
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
