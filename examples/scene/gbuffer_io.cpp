// hush — test scenes: G-buffer files (see gbuffer_io.hpp).
#include "gbuffer_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "hush/core/error.hpp"
#include "png_write.hpp"

namespace hush {
namespace scene {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kNpyAlignment = 64;  // numpy.lib.format: data starts at a multiple of 64
constexpr char kNpyMagic[] = "\x93NUMPY";  // 6 bytes, then the version (1, 0)
constexpr std::size_t kNpyPrefix = 10;     // magic, version, uint16 header length

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
const channel<std::uint32_t> kUintChannels[] = {{"object_id", &gbuffer::object_id, 1},
                                                {"triangle_id", &gbuffer::triangle_id, 1}};

template <class T>
const char* descr();
template <>
const char* descr<float>() {
  return "<f4";
}
template <>
const char* descr<std::uint32_t>() {
  return "<u4";
}

std::string shape_text(const std::vector<std::size_t>& shape) {
  std::string s = "(";
  for (std::size_t a = 0; a < shape.size(); ++a) s += (a ? ", " : "") + std::to_string(shape[a]);
  return s + (shape.size() == 1 ? ",)" : ")");
}

std::string npy_header(const char* type, const std::vector<std::size_t>& shape) {
  std::string dict = std::string("{'descr': '") + type +
                     "', 'fortran_order': False, 'shape': " + shape_text(shape) + ", }";
  const std::size_t unpadded = kNpyPrefix + dict.size() + 1;  // + the final '\n'
  dict.append((kNpyAlignment - unpadded % kNpyAlignment) % kNpyAlignment, ' ');
  dict += '\n';
  std::string header(kNpyMagic, 6);
  header += '\x01';
  header += '\x00';
  header += static_cast<char>(dict.size() & 0xff);
  header += static_cast<char>(dict.size() >> 8);
  return header + dict;
}

template <class T>
void write_npy(const fs::path& path, const std::vector<T>& values, const gbuffer& g,
               std::size_t components) {
  std::vector<std::size_t> shape = {static_cast<std::size_t>(g.height),
                                    static_cast<std::size_t>(g.width)};
  if (components > 1) shape.push_back(components);
  std::string bytes = npy_header(descr<T>(), shape);
  const std::size_t start = bytes.size();
  bytes.resize(start + 4 * values.size());
  // Byte by byte from the bit pattern: little-endian whatever the host's byte order.
  for (std::size_t n = 0; n < values.size(); ++n) {
    std::uint32_t bits;
    std::memcpy(&bits, &values[n], 4);
    for (std::size_t b = 0; b < 4; ++b)
      bytes[start + 4 * n + b] = static_cast<char>((bits >> (8 * b)) & 0xffu);
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write G-buffer file '" + path.string() + "'");
}

[[noreturn]] void bad_file(const fs::path& path, const std::string& why) {
  throw std::runtime_error("G-buffer file '" + path.string() + "': " + why);
}

// The value of key `key` in the NPY header dict (the text after "'key': ").
std::string dict_value(const std::string& dict, const std::string& key, const fs::path& path) {
  const std::string tag = "'" + key + "':";
  const std::size_t at = dict.find(tag);
  if (at == std::string::npos) bad_file(path, "NPY header has no '" + key + "'");
  std::size_t begin = at + tag.size();
  while (begin < dict.size() && dict[begin] == ' ') ++begin;
  std::size_t end = begin;
  if (end < dict.size() && dict[end] == '(') {
    end = dict.find(')', end);
    if (end == std::string::npos) bad_file(path, "NPY header: unterminated shape");
    return dict.substr(begin, end + 1 - begin);
  }
  while (end < dict.size() && dict[end] != ',' && dict[end] != '}') ++end;
  return dict.substr(begin, end - begin);
}

template <class T>
std::vector<T> read_npy(const fs::path& path, std::vector<std::size_t>& shape) {
  std::ifstream in(path, std::ios::binary);
  if (!in) bad_file(path, "cannot open it");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < kNpyPrefix || bytes.compare(0, 6, kNpyMagic, 6) != 0)
    bad_file(path, "not an NPY file (bad magic)");
  if (bytes[6] != 1 || bytes[7] != 0) bad_file(path, "NPY version is not 1.0");
  const std::size_t len = static_cast<unsigned char>(bytes[8]) |
                          (static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8);
  if (bytes.size() < kNpyPrefix + len) bad_file(path, "truncated NPY header");
  const std::string dict = bytes.substr(kNpyPrefix, len);
  const std::string type = dict_value(dict, "descr", path);
  if (type != std::string("'") + descr<T>() + "'")
    bad_file(path, "dtype " + type + " is not '" + descr<T>() + "'");
  if (dict_value(dict, "fortran_order", path) != "False") bad_file(path, "not in C order");
  const std::string shape_str = dict_value(dict, "shape", path);
  shape.clear();
  std::size_t count = 1;
  for (std::size_t i = 1; i < shape_str.size();) {
    if (shape_str[i] < '0' || shape_str[i] > '9') {
      ++i;
      continue;
    }
    std::size_t value = 0, digits = 0;
    while (i < shape_str.size() && shape_str[i] >= '0' && shape_str[i] <= '9' && digits < 12) {
      value = 10 * value + static_cast<std::size_t>(shape_str[i] - '0');
      ++i;
      ++digits;
    }
    shape.push_back(value);
    count *= value;
  }
  if (shape.size() < 2 || shape.size() > 3)
    bad_file(path, "shape " + shape_str + " is not (H, W) or (H, W, C)");
  const std::size_t data = kNpyPrefix + len;
  if (bytes.size() != data + 4 * count)
    bad_file(path, "holds " + std::to_string(bytes.size() - data) + " data bytes, shape " +
                       shape_str + " needs " + std::to_string(4 * count));
  std::vector<T> values(count);
  for (std::size_t n = 0; n < count; ++n) {
    std::uint32_t bits = 0;
    for (std::size_t b = 0; b < 4; ++b)
      bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[data + 4 * n + b]))
              << (8 * b);
    std::memcpy(&values[n], &bits, 4);
  }
  return values;
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
  const std::vector<std::size_t> hw = shape;
  const auto expected = [&hw](std::size_t components) {
    std::vector<std::size_t> want = hw;
    if (components > 1) want.push_back(components);
    return want;
  };
  for (const channel<float>& c : kFloatChannels) {
    const fs::path path = dir / (std::string(c.name) + ".npy");
    g.*c.field = read_npy<float>(path, shape);
    if (shape != expected(c.components))
      bad_file(path,
               "shape " + shape_text(shape) + " is not " + shape_text(expected(c.components)));
  }
  for (const channel<std::uint32_t>& c : kUintChannels) {
    const fs::path path = dir / (std::string(c.name) + ".npy");
    g.*c.field = read_npy<std::uint32_t>(path, shape);
    if (shape != expected(c.components))
      bad_file(path,
               "shape " + shape_text(shape) + " is not " + shape_text(expected(c.components)));
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
}  // namespace hush
