// hush — test scenes: the triangles of a frame, projected (see triangles.hpp).
#include "triangles.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "hush/core/error.hpp"
#include "npy/npy.hpp"
#include "raster_cpu.hpp"

namespace hush_tools {
namespace scene {
namespace {

namespace fs = std::filesystem;

template <class T>
std::vector<T> read(const fs::path& path, std::vector<std::size_t>& shape) {
  npy::array<T> a;
  try {
    a = npy::load<T>(path.string());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("triangle file ") + e.what());
  }
  shape = a.shape;
  return std::move(a.values);
}

[[noreturn]] void bad(const fs::path& path, const std::string& why) {
  throw std::runtime_error("triangle file '" + path.string() + "': " + why);
}

template <class T>
void write(const fs::path& path, const std::vector<std::size_t>& shape, const std::vector<T>& v) {
  try {
    npy::save(path.string(), shape, v);
  } catch (const std::runtime_error&) {
    throw std::runtime_error("cannot write triangle file '" + path.string() + "'");
  }
}

}  // namespace

triangle_frame project_triangles(const scene& s, int frame, int width, int height) {
  check_render_arguments(frame, width, height);
  if (!s.camera) throw hush::invalid_argument("project_triangles: the scene has no camera");
  const camera_pose pose = s.camera(frame);
  check_scene(s, pose);
  const glm::dmat4 clip_from_world = projection_matrix(pose, width, height) * view_matrix(pose);
  triangle_frame t;
  const double w = width, h = height;
  for (std::size_t k = 0; k < s.objects.size(); ++k) {
    const object& o = s.objects[k];
    const glm::dmat4 m = clip_from_world * o.model(frame);
    const auto base = static_cast<std::uint32_t>(t.screen.size());
    for (const glm::vec3& p : o.shape->positions) {
      const glm::dvec4 c = m * glm::dvec4(p.x, p.y, p.z, 1.0);
      // Behind the camera too (W < 0): (W screen, W) is then clip (X, Y, W) through the
      // viewport, affine in object space, what NPR Gabor noise's near-plane clipping reads.
      if (c.w != 0.0) {
        t.screen.push_back({static_cast<float>((c.x / c.w + 1.0) * w * 0.5),
                            static_cast<float>((1.0 - c.y / c.w) * h * 0.5)});
      } else {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        t.screen.push_back({nan, nan});
      }
      t.depth.push_back(static_cast<float>(c.w));
    }
    for (std::uint32_t i : o.shape->indices) t.indices.push_back(base + i);
    const auto count = static_cast<std::uint32_t>(o.shape->triangles());
    for (std::uint32_t i = 0; i < count; ++i) {
      t.triangle_id.push_back(i);
      t.object_id.push_back(static_cast<std::uint32_t>(k + 1));
    }
  }
  return t;
}

void save_triangles(const triangle_frame& t, const std::string& frame_dir) {
  const fs::path dir(frame_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  std::vector<float> screen;
  screen.reserve(2 * t.screen.size());
  for (const hush::vec2& p : t.screen) {
    screen.push_back(p.x);
    screen.push_back(p.y);
  }
  write(dir / "tri_screen.npy", {t.screen.size(), 2}, screen);
  write(dir / "tri_depth.npy", {t.depth.size()}, t.depth);
  write(dir / "tri_indices.npy", {t.indices.size() / 3, 3}, t.indices);
  write(dir / "tri_id.npy", {t.triangle_id.size()}, t.triangle_id);
  write(dir / "tri_object.npy", {t.object_id.size()}, t.object_id);
}

bool has_triangles(const std::string& frame_dir) {
  return fs::exists(fs::path(frame_dir) / "tri_indices.npy");
}

triangle_frame load_triangles(const std::string& frame_dir) {
  const fs::path dir(frame_dir);
  triangle_frame t;
  std::vector<std::size_t> shape;
  const std::vector<float> screen = read<float>(dir / "tri_screen.npy", shape);
  if (shape.size() != 2 || shape[1] != 2) bad(dir / "tri_screen.npy", "shape is not (V, 2)");
  const std::size_t v = shape[0];
  for (std::size_t i = 0; i < v; ++i) t.screen.push_back({screen[2 * i], screen[2 * i + 1]});
  t.depth = read<float>(dir / "tri_depth.npy", shape);
  if (shape.size() != 1 || shape[0] != v) bad(dir / "tri_depth.npy", "shape is not (V,)");
  t.indices = read<std::uint32_t>(dir / "tri_indices.npy", shape);
  if (shape.size() != 2 || shape[1] != 3) bad(dir / "tri_indices.npy", "shape is not (T, 3)");
  const std::size_t n = shape[0];
  for (std::uint32_t i : t.indices)
    if (i >= v) bad(dir / "tri_indices.npy", "index " + std::to_string(i) + " >= vertex count");
  t.triangle_id = read<std::uint32_t>(dir / "tri_id.npy", shape);
  if (shape.size() != 1 || shape[0] != n) bad(dir / "tri_id.npy", "shape is not (T,)");
  t.object_id = read<std::uint32_t>(dir / "tri_object.npy", shape);
  if (shape.size() != 1 || shape[0] != n) bad(dir / "tri_object.npy", "shape is not (T,)");
  return t;
}

}  // namespace scene
}  // namespace hush_tools
