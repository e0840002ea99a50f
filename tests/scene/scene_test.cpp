// Tests of the test scenes (examples/scene/mesh.hpp, scene.hpp): mesh generators give
// unit normals, sensible uvs and the stated triangle counts; OBJ files load through
// tinyobjloader; the registry builds every named scene deterministically and refuses
// unknown names.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>

#include "hush/core/error.hpp"
#include "mesh.hpp"
#include "scene.hpp"

namespace {

namespace hs = hush_tools::scene;
namespace fs = std::filesystem;

void check_mesh(const hs::mesh& m) {
  REQUIRE(m.normals.size() == m.vertices());
  REQUIRE(m.uvs.size() == m.vertices());
  REQUIRE(m.indices.size() % 3 == 0);
  for (std::uint32_t i : m.indices) REQUIRE(i < m.vertices());
  for (const glm::vec3& n : m.normals) CHECK(std::fabs(glm::length(n) - 1.0f) < 1e-5f);
  for (const glm::vec3& p : m.positions) CHECK(std::isfinite(p.x + p.y + p.z));
  // Winding: each triangle's geometric normal agrees with its vertex normals.
  for (std::size_t t = 0; t < m.triangles(); ++t) {
    const std::uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
    const glm::vec3 face =
        glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    CHECK(glm::dot(face, m.normals[a] + m.normals[b] + m.normals[c]) > 0.0f);
  }
}

void check_uv_range(const hs::mesh& m, float hi) {
  for (const glm::vec2& uv : m.uvs) {
    CHECK(uv.x >= 0.0f);
    CHECK(uv.x <= hi);
    CHECK(uv.y >= 0.0f);
    CHECK(uv.y <= hi);
  }
}

TEST_CASE("sphere: stated triangle count, points on the sphere, uv by angle in the unit square") {
  const hs::mesh m = hs::make_sphere(2.0f, 16, 8);
  check_mesh(m);
  check_uv_range(m, 1.0f);
  CHECK(m.closed);
  CHECK(m.triangles() == 2u * 16u * 7u);
  for (std::size_t i = 0; i < m.vertices(); ++i) {
    CHECK(std::fabs(glm::length(m.positions[i]) - 2.0f) < 1e-5f);
    // uv.y is the colatitude / pi: y = r cos(pi v).
    CHECK(std::fabs(m.positions[i].y - 2.0f * std::cos(3.14159265f * m.uvs[i].y)) < 1e-5f);
  }
}

TEST_CASE("torus: stated triangle count, points at the tube radius from the centre circle") {
  const hs::mesh m = hs::make_torus(1.0f, 0.25f, 24, 12);
  check_mesh(m);
  check_uv_range(m, 1.0f);
  CHECK(m.triangles() == 2u * 24u * 12u);
  for (const glm::vec3& p : m.positions) {
    const float ring = std::sqrt(p.x * p.x + p.z * p.z) - 1.0f;
    CHECK(std::fabs(std::sqrt(ring * ring + p.y * p.y) - 0.25f) < 1e-5f);
  }
}

TEST_CASE("plane, box and pitcher: valid meshes, planar and per-face uv") {
  const hs::mesh plane = hs::make_plane(4.0f, 2.0f, 4, 2, 1.0f);
  check_mesh(plane);
  CHECK_FALSE(plane.closed);
  CHECK(plane.triangles() == 16u);
  for (std::size_t i = 0; i < plane.vertices(); ++i) {
    CHECK(plane.uvs[i].x == doctest::Approx(plane.positions[i].x / 4.0f + 0.5f));
    CHECK(plane.uvs[i].y == doctest::Approx(plane.positions[i].z / 2.0f + 0.5f));
  }
  const hs::mesh box = hs::make_box(glm::vec3(1.0f, 2.0f, 3.0f));
  check_mesh(box);
  check_uv_range(box, 1.0f);
  CHECK(box.triangles() == 12u);
  const hs::mesh pitcher = hs::make_pitcher(32);
  check_mesh(pitcher);
  check_uv_range(pitcher, 1.0f);
  CHECK(pitcher.closed);
  CHECK(pitcher.triangles() > 1000u);
}

TEST_CASE("bad generator parameters throw hush::invalid_argument") {
  CHECK_THROWS_AS(hs::make_sphere(1.0f, 2, 8), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_sphere(-1.0f, 8, 8), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_torus(0.5f, 1.0f, 8, 8), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_plane(1.0f, 1.0f, 0, 1), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_box(glm::vec3(1.0f, 0.0f, 1.0f)), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_lathe({{0.0f, 0.0f}}, 8), hush::invalid_argument);
}

TEST_CASE("OBJ files load through tinyobjloader, fitted to the unit sphere") {
  const fs::path dir = fs::path(HUSH_SCENE_SCRATCH) / "scene_test_obj";
  fs::create_directories(dir);
  // A tetrahedron without normals or uvs (both are then computed) and a quad with both.
  {
    std::ofstream out(dir / "tetra.obj");
    out << "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream quad(dir / "quad.obj");
    quad << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
            "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
  }
  const hs::mesh tetra = hs::load_obj((dir / "tetra.obj").string());
  CHECK(tetra.triangles() == 4u);
  check_mesh(tetra);
  check_uv_range(tetra, 1.0f);
  float radius = 0.0f;
  for (const glm::vec3& p : tetra.positions) radius = std::max(radius, glm::length(p));
  CHECK(radius == doctest::Approx(1.0f));
  const hs::mesh quad = hs::load_obj((dir / "quad.obj").string());
  CHECK(quad.triangles() == 2u);  // the quad is triangulated
  check_mesh(quad);
  for (std::size_t i = 0; i < quad.vertices(); ++i) {  // the file's uv, at the fitted corner
    CHECK(quad.uvs[i].x == (quad.positions[i].x > 0.0f ? 1.0f : 0.0f));
    CHECK(quad.uvs[i].y == (quad.positions[i].y > 0.0f ? 1.0f : 0.0f));
  }
  const hs::scene s = hs::make_scene("obj:" + (dir / "quad.obj").string());
  CHECK(s.triangles() == 2u);
  const std::string missing = (dir / "missing.obj").string();
  try {
    hs::load_obj(missing);
    FAIL("a missing OBJ file did not throw");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find(missing) != std::string::npos);
  }
}

TEST_CASE("OBJ faces naming a normal or texture coordinate the file lacks are refused") {
  // tinyobjloader keeps such indices; reading them would read past its arrays.
  const fs::path dir = fs::path(HUSH_SCENE_SCRATCH) / "scene_test_obj";
  fs::create_directories(dir);
  const std::pair<const char*, const char*> cases[] = {
      {"bad_uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/3\n"},
      {"bad_normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n"}};
  for (const auto& [name, text] : cases) {
    { std::ofstream(dir / name) << text; }
    try {
      hs::load_obj((dir / name).string());
      FAIL(name << " loaded");
    } catch (const std::runtime_error& e) {
      CHECK(std::string(e.what()).find("index out of range") != std::string::npos);
    }
  }
}

TEST_CASE("every registered scene builds, has triangles and a camera in front of it") {
  int built = 0;
  for (const hs::scene_info& info : hs::scene_list()) {
    CHECK_FALSE(info.description.empty());
    CHECK(info.description.find('\n') == std::string::npos);
    if (info.name.find(':') != std::string::npos) continue;  // obj:PATH
    const hs::scene s = hs::make_scene(info.name);
    CHECK(s.triangles() > 0u);
    for (int f : {0, 1, 50}) {
      const hs::camera_pose p = s.camera(f);
      CHECK(p.near_depth > 0.0);
      CHECK(glm::length(p.target - p.eye) > 0.0);
    }
    ++built;
  }
  CHECK(built == 5);
}

TEST_CASE("dense:N has about N triangles, dense has about 50000") {
  for (long n : {5000L, 50000L, 200000L}) {
    const hs::scene s = hs::make_scene("dense:" + std::to_string(n));
    // The sphere and torus share N; the ground plane adds 32 triangles.
    CHECK(std::fabs(static_cast<double>(s.triangles()) / static_cast<double>(n) - 1.0) < 0.05);
  }
  CHECK(std::fabs(static_cast<double>(hs::make_scene("dense").triangles()) / 50000.0 - 1.0) < 0.05);
}

TEST_CASE("scenes are deterministic functions of the frame index") {
  const hs::scene a = hs::make_scene("walkthrough"), b = hs::make_scene("walkthrough");
  for (int f : {0, 7, 99}) {
    CHECK(hs::view_matrix(a.camera(f)) == hs::view_matrix(b.camera(f)));
    for (std::size_t o = 0; o < a.objects.size(); ++o)
      CHECK(a.objects[o].model(f) == b.objects[o].model(f));
  }
  // The motions move: the translate sphere moves, the zoom camera moves.
  CHECK(hs::make_scene("translate").objects[0].model(1) !=
        hs::make_scene("translate").objects[0].model(0));
  CHECK(hs::make_scene("zoom").camera(1).eye != hs::make_scene("zoom").camera(0).eye);
}

TEST_CASE(
    "unknown scene names and bad dense counts throw hush::invalid_argument naming the valid ones") {
  try {
    hs::make_scene("teapot");
    FAIL("an unknown scene did not throw");
  } catch (const hush::invalid_argument& e) {
    const std::string what = e.what();
    CHECK(what.find("teapot") != std::string::npos);
    CHECK(what.find("walkthrough") != std::string::npos);
  }
  CHECK_THROWS_AS(hs::make_scene("dense:10"), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_scene("dense:abc"), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_scene("dense:"), hush::invalid_argument);
  CHECK_THROWS_AS(hs::make_scene("obj:"), hush::invalid_argument);
}

}  // namespace
