// hush — temporal-coherence metrics: noise frames as NPY files (see frame_io.hpp).
#include "coherence/frame_io.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "hush/core/error.hpp"
#include "npy/npy.hpp"

namespace hush_tools {
namespace coherence {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxSide = std::size_t{1} << 20;  // at most 2^20 pixels on a side

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("'" + path + "': " + what);
}

}  // namespace

noise_frame load_noise_frame(const std::string& path, int& width, int& height) {
  npy::array<float> a = npy::load<float>(path);  // its errors name the file
  const std::vector<std::size_t>& shape = a.shape;
  if (shape.size() != 2 || shape[0] == 0 || shape[1] == 0 || shape[0] > kMaxSide ||
      shape[1] > kMaxSide)
    fail(path, "shape " + npy::shape_text(shape) + " is not (H, W) with H, W >= 1");
  width = static_cast<int>(shape[1]);
  height = static_cast<int>(shape[0]);
  return std::move(a.values);
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
    throw hush::invalid_argument(
        "hush_tools::coherence::save_noise_frame: " + std::to_string(f.size()) + " values for " +
        std::to_string(width) + "x" + std::to_string(height) + " pixels");
  npy::save(path, {static_cast<std::size_t>(height), static_cast<std::size_t>(width)}, f);
}

}  // namespace coherence
}  // namespace hush_tools
