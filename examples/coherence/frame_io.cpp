// hush — temporal-coherence metrics: noise frames as NPY files (see frame_io.hpp).
#include "coherence/frame_io.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "hush/core/error.hpp"

namespace hush {
namespace coherence {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("'" + path + "': " + what);
}

// The value text after 'key': in a NPY header dict, up to the next ',' outside parentheses.
std::string dict_value(const std::string& header, const std::string& key) {
  const std::size_t k = header.find("'" + key + "'");
  if (k == std::string::npos) return "";
  std::size_t p = header.find(':', k);
  if (p == std::string::npos) return "";
  ++p;
  int depth = 0;
  std::string v;
  for (; p < header.size(); ++p) {
    const char c = header[p];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if ((c == ',' && depth == 0) || c == '}') break;
    if (!std::isspace(static_cast<unsigned char>(c))) v += c;
  }
  return v;
}

bool little_endian() {
  const std::uint32_t one = 1;
  unsigned char b = 0;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

}  // namespace

noise_frame load_noise_frame(const std::string& path, int& width, int& height) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, "\x93NUMPY", 6) != 0)
    fail(path, "not a NumPy .npy file");
  std::size_t header_length = 0;
  if (magic[6] == 1) {
    unsigned char l[2];
    if (!in.read(reinterpret_cast<char*>(l), 2)) fail(path, "truncated header");
    header_length = static_cast<std::size_t>(l[0] | (l[1] << 8));
  } else if (magic[6] == 2 || magic[6] == 3) {
    unsigned char l[4];
    if (!in.read(reinterpret_cast<char*>(l), 4)) fail(path, "truncated header");
    header_length = static_cast<std::size_t>(l[0]) | (static_cast<std::size_t>(l[1]) << 8) |
                    (static_cast<std::size_t>(l[2]) << 16) | (static_cast<std::size_t>(l[3]) << 24);
  } else {
    fail(path, "unsupported NPY version " + std::to_string(magic[6]));
  }
  if (header_length > (1u << 20)) fail(path, "NPY header too long");
  std::string header(header_length, '\0');
  if (!in.read(&header[0], static_cast<std::streamsize>(header_length)))
    fail(path, "truncated header");
  const std::string descr = dict_value(header, "descr");
  if (descr != "'<f4'") fail(path, "dtype " + descr + " is not '<f4' (little-endian float32)");
  if (dict_value(header, "fortran_order") != "False") fail(path, "Fortran order is not supported");
  const std::string shape = dict_value(header, "shape");
  long long h = 0, w = 0;
  char tail = 0;
  if (std::sscanf(shape.c_str(), "(%lld,%lld%c", &h, &w, &tail) != 3 || tail != ')' || h <= 0 ||
      w <= 0 || h > (1 << 20) || w > (1 << 20))
    fail(path, "shape " + shape + " is not (H, W) with H, W >= 1");
  const std::size_t n = static_cast<std::size_t>(h) * static_cast<std::size_t>(w);
  noise_frame f(n);
  if (!in.read(reinterpret_cast<char*>(f.data()), static_cast<std::streamsize>(n * sizeof(float))))
    fail(path, "truncated data: expected " + std::to_string(n) + " float32 values");
  if (!little_endian())
    for (float& v : f) {
      unsigned char b[4];
      std::memcpy(b, &v, 4);
      std::swap(b[0], b[3]);
      std::swap(b[1], b[2]);
      std::memcpy(&v, b, 4);
    }
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  return f;
}

std::string noise_frame_path(const std::string& dir, int index) {
  char name[32];
  std::snprintf(name, sizeof name, "%04d.npy", index);
  return (fs::path(dir) / name).string();
}

noise_sequence load_noise_frames(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::runtime_error("'" + dir + "' is not a directory");
  std::map<long long, std::string> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string stem = e.path().stem().string();
    if (e.path().extension() != ".npy" || stem.size() < 4 || stem.size() > 9 ||
        !std::all_of(stem.begin(), stem.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
      continue;
    files[std::stoll(stem)] = e.path().string();
  }
  if (ec) throw std::runtime_error("'" + dir + "': " + ec.message());
  if (files.empty()) throw std::runtime_error("'" + dir + "' holds no NNNN.npy frames");
  noise_sequence s;
  s.first = static_cast<int>(files.begin()->first);
  long long expected = files.begin()->first;
  for (const auto& [index, path] : files) {
    if (index != expected)
      throw std::runtime_error("'" + dir + "': frame indices are not consecutive (" +
                               std::to_string(expected) + " is missing)");
    ++expected;
    int w = 0, h = 0;
    s.frames.push_back(load_noise_frame(path, w, h));
    if (s.frames.size() == 1) {
      s.width = w;
      s.height = h;
    } else if (w != s.width || h != s.height) {
      fail(path, "is " + std::to_string(h) + "x" + std::to_string(w) +
                     " (H x W); the first frame is " + std::to_string(s.height) + "x" +
                     std::to_string(s.width));
    }
  }
  return s;
}

void save_noise_frame(const std::string& path, const noise_frame& f, int width, int height) {
  if (width <= 0 || height <= 0 ||
      f.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw hush::invalid_argument("hush::coherence::save_noise_frame: " + std::to_string(f.size()) +
                                 " values for " + std::to_string(width) + "x" +
                                 std::to_string(height) + " pixels");
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                       std::to_string(height) + ", " + std::to_string(width) + "), }";
  // Magic (6) + version (2) + length (2) + header + '\n' is a multiple of 64 bytes.
  while ((10 + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) fail(path, "cannot create");
  const unsigned char prefix[10] = {0x93,
                                    'N',
                                    'U',
                                    'M',
                                    'P',
                                    'Y',
                                    1,
                                    0,
                                    static_cast<unsigned char>(header.size() & 0xff),
                                    static_cast<unsigned char>(header.size() >> 8)};
  out.write(reinterpret_cast<const char*>(prefix), sizeof prefix);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  noise_frame data(f);
  if (!little_endian())
    for (float& v : data) {
      unsigned char b[4];
      std::memcpy(b, &v, 4);
      std::swap(b[0], b[3]);
      std::swap(b[1], b[2]);
      std::memcpy(&v, b, 4);
    }
  out.write(reinterpret_cast<const char*>(data.data()),
            static_cast<std::streamsize>(data.size() * sizeof(float)));
  out.close();
  if (!out) {
    std::error_code ec;
    fs::remove(path, ec);
    fail(path, "write failed");
  }
}

}  // namespace coherence
}  // namespace hush
