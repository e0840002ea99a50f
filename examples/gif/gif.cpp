// hush — animated GIF files (see gif.hpp). GIF89a: header, logical screen with a 256-entry
// global colour table, the NETSCAPE2.0 looping extension, then per frame a graphic control
// extension (delay), an image descriptor and the LZW-coded pixels (minimum code size 8, codes
// of 9 ... 12 bits, a clear code whenever the 4096-entry table is full), in 255-byte
// sub-blocks; the trailer ends the file.
#include "gif/gif.hpp"

#include <array>
#include <string>
#include <unordered_map>

#include "hush/core/error.hpp"
#include "npy/output_file.hpp"

namespace hush {
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

}  // namespace

std::vector<std::uint8_t> encode(const std::vector<std::vector<std::uint8_t>>& frames, int width,
                                 int height, int delay_cs) {
  const char* where = "hush::gif::encode";
  if (frames.empty()) throw hush::invalid_argument(std::string(where) + ": no frames");
  hush::detail::require_in_range(where, "width", width, 1, kMaxSide, "1 ... 65535");
  hush::detail::require_in_range(where, "height", height, 1, kMaxSide, "1 ... 65535");
  hush::detail::require_in_range(where, "delay_cs", delay_cs, 0, kMaxSide, "0 ... 65535");
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  for (std::size_t f = 0; f < frames.size(); ++f)
    if (frames[f].size() != n)
      hush::detail::throw_out_of_range(where, "frames[" + std::to_string(f) + "].size()",
                                       frames[f].size(), "width * height bytes");
  std::vector<std::uint8_t> out = {'G', 'I', 'F', '8', '9', 'a'};
  put16(out, static_cast<unsigned>(width));
  put16(out, static_cast<unsigned>(height));
  out.push_back(0xf7);  // global colour table, 8 bits of colour resolution, 2^(7+1) entries
  out.push_back(0);     // background colour index
  out.push_back(0);     // square pixels
  for (unsigned g = 0; g < 256; ++g)
    out.insert(out.end(), {static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(g),
                           static_cast<std::uint8_t>(g)});
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

void save(const std::string& path, const std::vector<std::vector<std::uint8_t>>& frames, int width,
          int height, int delay_cs) {
  const std::vector<std::uint8_t> bytes = encode(frames, width, height, delay_cs);
  hush::npy::output_file f(path);
  f.write(bytes.data(), bytes.size());
  f.close();
}

}  // namespace gif
}  // namespace hush
