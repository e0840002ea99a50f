// hush — test scenes: G-buffer files (see gbuffer_io.hpp).
#include "gbuffer_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hush/core/error.hpp"
#include "npy/npy.hpp"
#include "png_write.hpp"

namespace hush_tools {
namespace scene {
namespace {

namespace fs = std::filesystem;

// One channel file: the field, its name, its channel count.
template <class T>
struct channel {
  const char* name;
  std::vector<T> gbuffer::*field;
  std::size_t components;
};

const channel<float> kFloatChannels[] = {{"depth", &gbuffer::depth, 1},
                                         {"velocity", &gbuffer::velocity, 3},
                                         {"barycentric", &gbuffer::barycentric, 3},
                                         {"uv", &gbuffer::uv, 2},
                                         {"uv_jacobian", &gbuffer::uv_jacobian, 4},
                                         {"normal", &gbuffer::normal, 3},
                                         {"position", &gbuffer::position, 3}};
// Optional: written when present (non-empty), read when its file exists (G-buffers from
// before it existed, or made without it, have none).
const channel<float> kOptionalFloatChannels[] = {
    {"forward_velocity", &gbuffer::forward_velocity, 3}};
const channel<std::uint32_t> kUintChannels[] = {{"object_id", &gbuffer::object_id, 1},
                                                {"triangle_id", &gbuffer::triangle_id, 1}};

std::vector<std::size_t> channel_shape(const gbuffer& g, std::size_t components) {
  std::vector<std::size_t> shape = {static_cast<std::size_t>(g.height),
                                    static_cast<std::size_t>(g.width)};
  if (components > 1) shape.push_back(components);
  return shape;
}

template <class T>
void write_npy(const fs::path& path, const std::vector<T>& values, const gbuffer& g,
               std::size_t components) {
  try {
    npy::save(path.string(), channel_shape(g, components), values);
  } catch (const std::runtime_error&) {
    throw std::runtime_error("cannot write G-buffer file '" + path.string() + "'");
  }
}

[[noreturn]] void bad_file(const fs::path& path, const std::string& why) {
  throw std::runtime_error("G-buffer file '" + path.string() + "': " + why);
}

// Reads one channel file; npy::load's message "'<path>': <what>" gets the G-buffer prefix.
template <class T>
std::vector<T> read_npy(const fs::path& path, std::vector<std::size_t>& shape) {
  npy::array<T> a;
  try {
    a = npy::load<T>(path.string());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("G-buffer file ") + e.what());
  }
  if (a.shape.size() < 2 || a.shape.size() > 3)
    bad_file(path, "shape " + npy::shape_text(a.shape) + " is not (H, W) or (H, W, C)");
  shape = std::move(a.shape);
  return std::move(a.values);
}

std::uint8_t to_byte(double v) {  // [0, 1] -> 0 ... 255, NaN -> 0
  if (!(v > 0.0)) return 0;
  return static_cast<std::uint8_t>(std::lround(std::min(v, 1.0) * 255.0));
}

void preview(const fs::path& path, const gbuffer& g, int channels,
             const std::vector<std::uint8_t>& pixels) {
  if (!detail::write_png(path.string(), g.width, g.height, channels, pixels))
    throw std::runtime_error("cannot write G-buffer preview '" + path.string() + "'");
}

void write_previews(const gbuffer& g, const fs::path& dir) {
  const std::size_t n = g.pixels();
  float near = INFINITY, far = 0.0f, vmax = 0.0f;
  for (std::size_t p = 0; p < n; ++p)
    if (g.covered(p)) {
      near = std::min(near, g.depth[p]);
      far = std::max(far, g.depth[p]);
      for (int c = 0; c < 3; ++c) {
        const float v = std::fabs(g.velocity[3 * p + c]);
        if (std::isfinite(v)) vmax = std::max(vmax, v);
      }
    }
  std::vector<std::uint8_t> gray(n, 0), rgb(3 * n, 0);
  for (std::size_t p = 0; p < n; ++p)  // near bright, far dark, background black
    if (g.covered(p))
      gray[p] = to_byte(far > near ? 0.2 + 0.8 * (far - g.depth[p]) / (far - near) : 1.0);
  preview(dir / "preview_depth.png", g, 1, gray);
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c)
      rgb[3 * p + c] = g.covered(p) ? to_byte(0.5 + 0.5 * g.normal[3 * p + c]) : 0;
  preview(dir / "preview_normal.png", g, 3, rgb);
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c) {
      const double v = c < 2 ? g.uv[2 * p + c] : 0.0;
      rgb[3 * p + c] = g.covered(p) ? to_byte(v - std::floor(v)) : 0;
    }
  preview(dir / "preview_uv.png", g, 3, rgb);
  for (std::size_t p = 0; p < n; ++p)
    for (int c = 0; c < 3; ++c)
      rgb[3 * p + c] =
          g.covered(p) ? to_byte(0.5 + (vmax > 0.0f ? g.velocity[3 * p + c] / (2.0 * vmax) : 0.0))
                       : 0;
  preview(dir / "preview_velocity.png", g, 3, rgb);
  for (std::size_t p = 0; p < n; ++p) {
    // A fixed bright colour per object: the id's bits through an integer hash.
    std::uint32_t h = g.object_id[p] * 0x9E3779B1u;
    h ^= h >> 15;
    for (int c = 0; c < 3; ++c)
      rgb[3 * p + c] =
          static_cast<std::uint8_t>(g.covered(p) ? 64u + ((h >> (8 * c)) & 0xbfu) : 0u);
  }
  preview(dir / "preview_object_id.png", g, 3, rgb);
}

}  // namespace

void save_gbuffer(const gbuffer& g, const std::string& frame_dir) {
  const std::size_t n = g.pixels();
  if (g.width < 0 || g.height < 0) throw hush::invalid_argument("save_gbuffer: negative size");
  for (const channel<float>& c : kFloatChannels)
    if ((g.*c.field).size() != n * c.components)
      throw hush::invalid_argument(std::string("save_gbuffer: channel ") + c.name +
                                   " has the wrong number of values for the size");
  for (const channel<std::uint32_t>& c : kUintChannels)
    if ((g.*c.field).size() != n * c.components)
      throw hush::invalid_argument(std::string("save_gbuffer: channel ") + c.name +
                                   " has the wrong number of values for the size");
  for (const channel<float>& c : kOptionalFloatChannels)
    if (!(g.*c.field).empty() && (g.*c.field).size() != n * c.components)
      throw hush::invalid_argument(std::string("save_gbuffer: channel ") + c.name +
                                   " has the wrong number of values for the size");
  const fs::path dir(frame_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    throw std::runtime_error("cannot create G-buffer directory '" + frame_dir +
                             "': " + ec.message());
  for (const channel<float>& c : kFloatChannels)
    write_npy(dir / (std::string(c.name) + ".npy"), g.*c.field, g, c.components);
  for (const channel<std::uint32_t>& c : kUintChannels)
    write_npy(dir / (std::string(c.name) + ".npy"), g.*c.field, g, c.components);
  for (const channel<float>& c : kOptionalFloatChannels) {
    const fs::path path = dir / (std::string(c.name) + ".npy");
    if (!(g.*c.field).empty()) {
      write_npy(path, g.*c.field, g, c.components);
    } else {
      std::error_code ignored;  // a stale file from an earlier save must not be read back
      fs::remove(path, ignored);
    }
  }
  if (detail::png_available() && n > 0) write_previews(g, dir);
}

gbuffer load_gbuffer(const std::string& frame_dir) {
  const fs::path dir(frame_dir);
  gbuffer g;
  std::vector<std::size_t> shape;
  g.depth = read_npy<float>(dir / "depth.npy", shape);
  if (shape.size() != 2) bad_file(dir / "depth.npy", "shape is not (H, W)");
  g.height = static_cast<int>(shape[0]);
  g.width = static_cast<int>(shape[1]);
  for (const channel<float>& c : kFloatChannels) {
    const fs::path path = dir / (std::string(c.name) + ".npy");
    g.*c.field = read_npy<float>(path, shape);
    if (shape != channel_shape(g, c.components))
      bad_file(path, "shape " + npy::shape_text(shape) + " is not " +
                         npy::shape_text(channel_shape(g, c.components)));
  }
  for (const channel<std::uint32_t>& c : kUintChannels) {
    const fs::path path = dir / (std::string(c.name) + ".npy");
    g.*c.field = read_npy<std::uint32_t>(path, shape);
    if (shape != channel_shape(g, c.components))
      bad_file(path, "shape " + npy::shape_text(shape) + " is not " +
                         npy::shape_text(channel_shape(g, c.components)));
  }
  for (const channel<float>& c : kOptionalFloatChannels) {
    const fs::path path = dir / (std::string(c.name) + ".npy");
    if (!fs::exists(path)) continue;
    g.*c.field = read_npy<float>(path, shape);
    if (shape != channel_shape(g, c.components))
      bad_file(path, "shape " + npy::shape_text(shape) + " is not " +
                         npy::shape_text(channel_shape(g, c.components)));
  }
  return g;
}

std::string frame_directory(const std::string& dir, int frame) {
  if (frame < 0)
    throw hush::invalid_argument("frame_directory: frame = " + std::to_string(frame) +
                                 " is out of range; valid: >= 0");
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d", frame);
  return (fs::path(dir) / name).string();
}

bool previews_supported() { return detail::png_available(); }

}  // namespace scene
}  // namespace hush_tools
