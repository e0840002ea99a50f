// hush — animated GIF files (see gif.hpp). GIF89a: header, logical screen with a 256-entry
// global colour table (gray ramp, or the fixed RGB palette with ordered dithering), the NETSCAPE2.0 looping extension, then per frame a graphic control
// extension (delay), an image descriptor and the LZW-coded pixels (minimum code size 8, codes
// of 9 ... 12 bits, a clear code whenever the 4096-entry table is full), in 255-byte
// sub-blocks; the trailer ends the file.
#include "gif/gif.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <unordered_map>

#include "hush/core/error.hpp"
#include "npy/output_file.hpp"

namespace hush_tools {
namespace gif {
namespace {

constexpr int kMinCodeSize = 8;  // 256 gray levels
constexpr unsigned kClear = 1u << kMinCodeSize, kEnd = kClear + 1;
constexpr unsigned kMaxCodes = 4096;  // 12-bit codes
constexpr int kMaxSide = 65535;

void put16(std::vector<std::uint8_t>& out, unsigned v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xffu));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

// Codes packed least-significant bit first, cut into sub-blocks of at most 255 bytes.
class bit_writer {
 public:
  explicit bit_writer(std::vector<std::uint8_t>& out) : out_(out) {}
  void put(unsigned code, int bits) {
    acc_ |= static_cast<std::uint32_t>(code) << used_;
    used_ += bits;
    while (used_ >= 8) {
      byte(static_cast<std::uint8_t>(acc_ & 0xffu));
      acc_ >>= 8;
      used_ -= 8;
    }
  }
  void finish() {
    if (used_ > 0) byte(static_cast<std::uint8_t>(acc_ & 0xffu));
    flush();
    out_.push_back(0);  // block terminator
  }

 private:
  void byte(std::uint8_t b) {
    block_[size_++] = b;
    if (size_ == block_.size()) flush();
  }
  void flush() {
    if (size_ == 0) return;
    out_.push_back(static_cast<std::uint8_t>(size_));
    out_.insert(out_.end(), block_.begin(), block_.begin() + static_cast<std::ptrdiff_t>(size_));
    size_ = 0;
  }
  std::vector<std::uint8_t>& out_;
  std::uint32_t acc_ = 0;
  int used_ = 0;
  std::array<std::uint8_t, 255> block_{};
  std::size_t size_ = 0;
};

// LZW of one frame's pixels.
void lzw(const std::vector<std::uint8_t>& pixels, std::vector<std::uint8_t>& out) {
  out.push_back(kMinCodeSize);
  bit_writer bits(out);
  std::unordered_map<std::uint32_t, unsigned> table;  // (prefix code << 8 | byte) -> code
  table.reserve(kMaxCodes);
  unsigned next = kEnd + 1;
  int width = kMinCodeSize + 1;
  bits.put(kClear, width);
  unsigned prefix = pixels[0];
  for (std::size_t i = 1; i < pixels.size(); ++i) {
    const std::uint32_t key = (prefix << 8) | pixels[i];
    const auto it = table.find(key);
    if (it != table.end()) {
      prefix = it->second;
      continue;
    }
    bits.put(prefix, width);
    if (next < kMaxCodes) {
      // A decoder adds this entry after reading the next code: when `next` reaches the width's
      // limit, codes from now on need one bit more.
      if (next == (1u << width) && width < 12) ++width;
      table.emplace(key, next++);
    } else {
      bits.put(kClear, width);  // table full: start afresh
      table.clear();
      next = kEnd + 1;
      width = kMinCodeSize + 1;
    }
    prefix = pixels[i];
  }
  bits.put(prefix, width);
  bits.put(kEnd, width);
  bits.finish();
}

constexpr int kRedLevels = 6, kGreenLevels = 7, kBlueLevels = 6;

// Checks the arguments; `bytes_per_pixel` 1 (gray) or 3 (RGB).
void check(const char* where, const std::vector<std::vector<std::uint8_t>>& frames, int width,
           int height, int delay_cs, std::size_t bytes_per_pixel) {
  if (frames.empty()) throw hush::invalid_argument(std::string(where) + ": no frames");
  hush::detail::require_in_range(where, "width", width, 1, kMaxSide, "1 ... 65535");
  hush::detail::require_in_range(where, "height", height, 1, kMaxSide, "1 ... 65535");
  hush::detail::require_in_range(where, "delay_cs", delay_cs, 0, kMaxSide, "0 ... 65535");
  const std::size_t n =
      bytes_per_pixel * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (frames[f].size() != n)
      hush::detail::throw_out_of_range(
          where, "frames[" + std::to_string(f) + "].size()", frames[f].size(),
          bytes_per_pixel == 1 ? "width * height bytes" : "3 * width * height bytes");
}

// The file for frames of palette indices (checked) and a 256-entry colour table.
std::vector<std::uint8_t> encode_indexed(const std::vector<std::vector<std::uint8_t>>& frames,
                                         int width, int height, int delay_cs,
                                         const std::vector<std::uint8_t>& table) {
  std::vector<std::uint8_t> out = {'G', 'I', 'F', '8', '9', 'a'};
  put16(out, static_cast<unsigned>(width));
  put16(out, static_cast<unsigned>(height));
  out.push_back(0xf7);  // global colour table, 8 bits of colour resolution, 2^(7+1) entries
  out.push_back(0);     // background colour index
  out.push_back(0);     // square pixels
  out.insert(out.end(), table.begin(), table.end());
  const std::string netscape = "NETSCAPE2.0";
  out.insert(out.end(), {0x21, 0xff, 11});
  out.insert(out.end(), netscape.begin(), netscape.end());
  out.insert(out.end(), {3, 1, 0, 0, 0});  // loop forever
  for (const std::vector<std::uint8_t>& frame : frames) {
    out.insert(out.end(), {0x21, 0xf9, 4, 0x04});  // keep the frame (disposal 1), no transparency
    put16(out, static_cast<unsigned>(delay_cs));
    out.insert(out.end(), {0, 0});
    out.push_back(0x2c);  // image descriptor: the whole screen, no local table
    put16(out, 0);
    put16(out, 0);
    put16(out, static_cast<unsigned>(width));
    put16(out, static_cast<unsigned>(height));
    out.push_back(0);
    lzw(frame, out);
  }
  out.push_back(0x3b);
  return out;
}

// One channel's level: min(L - 1, floor(c (L - 1) / 255 + t)). *Mean over a 4 x 4 block* (the
// 16 thresholds t_k = (k + 1/2) / 16, each once): with v = c (L - 1) / 255 = m + f, the level
// is m + 1 for the t_k >= 1 - f, i.e. for 16 - ceil(16 (1 - f) - 1/2) of them, which is 16 f
// within 1/2: the block's mean level is v within 1/32 (the top level, v = L - 1, is exact).
// The palette's values are rounded to bytes, 1/2 more.
int level(std::uint8_t c, int levels, double t) {
  const double v = static_cast<double>(c) * (levels - 1) / 255.0 + t;
  return std::min(levels - 1, static_cast<int>(v));
}

void write(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  hush_tools::npy::output_file f(path);
  f.write(bytes.data(), bytes.size());
  f.close();
}

}  // namespace

std::vector<std::uint8_t> encode(const std::vector<std::vector<std::uint8_t>>& frames, int width,
                                 int height, int delay_cs) {
  check("hush_tools::gif::encode", frames, width, height, delay_cs, 1);
  std::vector<std::uint8_t> gray;
  for (unsigned g = 0; g < 256; ++g)
    gray.insert(gray.end(), {static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(g),
                             static_cast<std::uint8_t>(g)});
  return encode_indexed(frames, width, height, delay_cs, gray);
}

const std::vector<std::uint8_t>& palette() {
  static const std::vector<std::uint8_t> table = [] {
    std::vector<std::uint8_t> t(std::size_t{3} * 256, 0);
    auto value = [](int l, int levels) {
      return static_cast<std::uint8_t>(std::lround(255.0 * l / (levels - 1)));
    };
    for (int r = 0; r < kRedLevels; ++r)
      for (int g = 0; g < kGreenLevels; ++g)
        for (int b = 0; b < kBlueLevels; ++b) {
          const int index = (r * kGreenLevels + g) * kBlueLevels + b;
          const std::size_t i = static_cast<std::size_t>(index);
          t[3 * i] = value(r, kRedLevels);
          t[3 * i + 1] = value(g, kGreenLevels);
          t[3 * i + 2] = value(b, kBlueLevels);
        }
    return t;
  }();
  return table;
}

std::uint8_t dither(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::size_t x, std::size_t y) {
  static constexpr int kBayer[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
  const double t = (kBayer[y % 4][x % 4] + 0.5) / 16.0;
  return static_cast<std::uint8_t>(
      (level(r, kRedLevels, t) * kGreenLevels + level(g, kGreenLevels, t)) * kBlueLevels +
      level(b, kBlueLevels, t));
}

std::vector<std::uint8_t> encode_rgb(const std::vector<std::vector<std::uint8_t>>& frames,
                                     int width, int height, int delay_cs) {
  check("hush_tools::gif::encode_rgb", frames, width, height, delay_cs, 3);
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  std::vector<std::vector<std::uint8_t>> indices(frames.size(), std::vector<std::uint8_t>(w * h));
  for (std::size_t f = 0; f < frames.size(); ++f)
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const std::uint8_t* c = &frames[f][3 * (y * w + x)];
        indices[f][y * w + x] = dither(c[0], c[1], c[2], x, y);
      }
  return encode_indexed(indices, width, height, delay_cs, palette());
}

void save(const std::string& path, const std::vector<std::vector<std::uint8_t>>& frames, int width,
          int height, int delay_cs) {
  write(path, encode(frames, width, height, delay_cs));
}

void save_rgb(const std::string& path, const std::vector<std::vector<std::uint8_t>>& frames,
              int width, int height, int delay_cs) {
  write(path, encode_rgb(frames, width, height, delay_cs));
}

}  // namespace gif
}  // namespace hush_tools
