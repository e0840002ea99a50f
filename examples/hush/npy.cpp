// hush — the `hush` program: streaming writer of NumPy .npy files (see npy.hpp).
#include "npy.hpp"

#include <cstdint>
#include <cstring>
#include <utility>

#include "args.hpp"

namespace hush_cli {
namespace {

constexpr std::size_t kAlignment = 64;  // numpy.lib.format: data starts at a multiple of 64
constexpr char kMagic[] = "\x93NUMPY";  // 6 bytes, then version 1.0

}  // namespace

std::string npy_header(const std::vector<std::size_t>& shape) {
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (";
  for (std::size_t a = 0; a < shape.size(); ++a) dict += (a ? ", " : "") + std::to_string(shape[a]);
  dict += shape.size() == 1 ? ",), }" : "), }";           // a 1-tuple needs its comma in Python
  const std::size_t prefix = 6 + 2 + 2;                   // magic, version, header length
  const std::size_t unpadded = prefix + dict.size() + 1;  // + the final '\n'
  dict.append((kAlignment - unpadded % kAlignment) % kAlignment, ' ');
  dict += '\n';
  const std::size_t len = dict.size();  // < 65536 for any shape of up to 3 axes
  std::string header(kMagic, 6);
  header += '\x01';
  header += '\x00';
  header += static_cast<char>(len & 0xff);
  header += static_cast<char>(len >> 8);
  return header + dict;
}

npy_writer::npy_writer(const std::string& path, const std::vector<std::size_t>& shape)
    : file_(path) {
  for (std::size_t n : shape) expected_ *= n;
  const std::string header = npy_header(shape);
  file_.write(header.data(), header.size());
}

void npy_writer::write(const float* values, std::size_t count) {
  // Byte by byte from the bit pattern: little-endian whatever the host's byte order.
  buffer_.resize(4 * count);
  for (std::size_t n = 0; n < count; ++n) {
    std::uint32_t bits;
    std::memcpy(&bits, &values[n], 4);
    for (int b = 0; b < 4; ++b) buffer_[4 * n + b] = static_cast<unsigned char>(bits >> (8 * b));
  }
  file_.write(buffer_.data(), buffer_.size());
  written_ += count;
}

void npy_writer::close() {
  if (written_ != expected_)
    throw run_error("internal error: wrote " + std::to_string(written_) + " of " +
                    std::to_string(expected_) + " values to '" + file_.path() + "'");
  file_.close();
}

}  // namespace hush_cli
