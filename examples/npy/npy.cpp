// hush — NumPy .npy files (see npy.hpp).
#include "npy/npy.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <utility>

#include "hush/core/error.hpp"

namespace hush_tools {
namespace npy {
namespace {

constexpr std::size_t kAlignment = 64;  // numpy.lib.format: data starts at a multiple of 64
constexpr char kMagic[] = "\x93NUMPY";  // 6 bytes, then the version (1, 0)
constexpr std::size_t kMagicSize = 6;
constexpr std::size_t kPrefix = 10;         // magic, version, uint16 header length
constexpr std::size_t kWordSize = 4;        // both dtypes are 4 bytes wide
constexpr std::size_t kMaxHeader = 0xffff;  // NPY 1.0 stores the header length in 16 bits

// The element count of `shape` in `count`; false when count * kWordSize overflows size_t.
bool checked_count(const std::vector<std::size_t>& shape, std::size_t& count) {
  constexpr std::size_t kMax = std::numeric_limits<std::size_t>::max() / kWordSize;
  count = 1;
  for (std::size_t n : shape) {
    if (n == 0) {
      count = 0;
      return true;  // an empty array, whatever the other axes (numpy allows (0, 2^62))
    }
    if (count > kMax / n) return false;
    count *= n;
  }
  return true;
}

// Little-endian bytes of `count` 32-bit words, byte by byte from the bit pattern so that the
// file is the same on any host.
void encode(const void* words, std::size_t count, unsigned char* out) {
  for (std::size_t n = 0; n < count; ++n) {
    std::uint32_t bits;
    std::memcpy(&bits, static_cast<const unsigned char*>(words) + kWordSize * n, kWordSize);
    for (std::size_t b = 0; b < kWordSize; ++b)
      out[kWordSize * n + b] = static_cast<unsigned char>((bits >> (8 * b)) & 0xffu);
  }
}

void decode(const unsigned char* in, std::size_t count, void* words) {
  for (std::size_t n = 0; n < count; ++n) {
    std::uint32_t bits = 0;
    for (std::size_t b = 0; b < kWordSize; ++b)
      bits |= static_cast<std::uint32_t>(in[kWordSize * n + b]) << (8 * b);
    std::memcpy(static_cast<unsigned char*>(words) + kWordSize * n, &bits, kWordSize);
  }
}

[[noreturn]] void bad_file(const std::string& path, const std::string& what) {
  throw std::runtime_error("'" + path + "': " + what);
}

// The text of key `key`'s value in the header dict: a quoted string with its quotes, a
// parenthesised tuple with its parentheses, or a bare word (False, True).
std::string dict_value(const std::string& dict, const std::string& key, const std::string& path) {
  const std::string tag = "'" + key + "':";
  const std::size_t at = dict.find(tag);
  if (at == std::string::npos) bad_file(path, "NPY header has no '" + key + "'");
  std::size_t begin = at + tag.size();
  while (begin < dict.size() && dict[begin] == ' ') ++begin;
  std::size_t end = begin;
  if (end < dict.size() && (dict[end] == '(' || dict[end] == '\'')) {
    end = dict.find(dict[end] == '(' ? ')' : '\'', end + 1);
    if (end == std::string::npos) bad_file(path, "NPY header: unterminated '" + key + "'");
    return dict.substr(begin, end + 1 - begin);
  }
  while (end < dict.size() && dict[end] != ',' && dict[end] != '}' && dict[end] != ' ') ++end;
  return dict.substr(begin, end - begin);
}

// Parses a Python tuple of non-negative integers: "(5, 7)", "(3,)", "()".
std::vector<std::size_t> parse_shape(const std::string& text, const std::string& path) {
  const auto malformed = [&]() { bad_file(path, "shape " + text + " is not a tuple of sizes"); };
  std::vector<std::size_t> shape;
  std::size_t i = 1;  // text starts with '(' and ends with ')' (dict_value)
  const auto skip_spaces = [&]() {
    while (i < text.size() && text[i] == ' ') ++i;
  };
  if (text.size() < 2 || text.front() != '(' || text.back() != ')') malformed();
  for (skip_spaces(); text[i] != ')';) {
    if (text[i] < '0' || text[i] > '9') malformed();
    std::size_t value = 0;
    for (; text[i] >= '0' && text[i] <= '9'; ++i) {
      const auto digit = static_cast<std::size_t>(text[i] - '0');
      if (value > (std::numeric_limits<std::size_t>::max() - digit) / 10)
        bad_file(path, "shape " + text + " is too large");
      value = 10 * value + digit;
    }
    shape.push_back(value);
    skip_spaces();
    if (text[i] == ',') {
      ++i;
      skip_spaces();
    } else if (text[i] != ')') {
      malformed();
    }
  }
  if (i + 1 != text.size()) malformed();
  return shape;
}

}  // namespace

const char* descr(dtype type) { return type == dtype::float32 ? "<f4" : "<u4"; }

std::string shape_text(const std::vector<std::size_t>& shape) {
  std::string s = "(";
  for (std::size_t a = 0; a < shape.size(); ++a) s += (a ? ", " : "") + std::to_string(shape[a]);
  return s + (shape.size() == 1 ? ",)" : ")");  // a 1-tuple needs its comma in Python
}

std::size_t element_count(const std::vector<std::size_t>& shape) {
  std::size_t count = 0;
  if (!checked_count(shape, count))
    throw hush::invalid_argument("hush_tools::npy: shape " + shape_text(shape) +
                                 " is out of range; valid: at most SIZE_MAX / 4 elements");
  return count;
}

std::string header(dtype type, const std::vector<std::size_t>& shape) {
  std::string dict = std::string("{'descr': '") + descr(type) +
                     "', 'fortran_order': False, 'shape': " + shape_text(shape) + ", }";
  const std::size_t unpadded = kPrefix + dict.size() + 1;  // + the final '\n'
  dict.append((kAlignment - unpadded % kAlignment) % kAlignment, ' ');
  dict += '\n';
  if (dict.size() > kMaxHeader)
    throw hush::invalid_argument("hush_tools::npy: shape of " + std::to_string(shape.size()) +
                                 " axes is out of range; valid: a header of at most 65535 bytes");
  std::string out(kMagic, kMagicSize);
  out += '\x01';  // version 1.0
  out += '\x00';
  out += static_cast<char>(dict.size() & 0xffu);
  out += static_cast<char>(dict.size() >> 8);
  return out + dict;
}

writer::writer(std::string path, dtype type, const std::vector<std::size_t>& shape)
    : type_(type), expected_(element_count(shape)), file_(std::move(path)) {
  // A header that cannot be written throws here; file_'s destructor removes the file.
  const std::string head = header(type, shape);
  file_.write(head.data(), head.size());
}

void writer::write(const float* values, std::size_t count) {
  if (type_ != dtype::float32)
    throw hush::invalid_argument("hush_tools::npy::writer: float values for a '<u4' file");
  write_words(values, count);
}

void writer::write(const std::uint32_t* values, std::size_t count) {
  if (type_ != dtype::uint32)
    throw hush::invalid_argument("hush_tools::npy::writer: uint32 values for a '<f4' file");
  write_words(values, count);
}

void writer::write_words(const void* values, std::size_t count) {
  buffer_.resize(kWordSize * count);
  encode(values, count, buffer_.data());
  file_.write(buffer_.data(), buffer_.size());
  written_ += count;
}

void writer::close() {
  if (written_ != expected_) {
    file_.discard();
    throw std::runtime_error("internal error: wrote " + std::to_string(written_) + " of " +
                             std::to_string(expected_) + " values to '" + file_.path() + "'");
  }
  file_.close();
}

template <class T>
void save(const std::string& path, const std::vector<std::size_t>& shape,
          const std::vector<T>& values) {
  if (values.size() != element_count(shape))
    throw hush::invalid_argument("hush_tools::npy::save: " + std::to_string(values.size()) +
                                 " values for shape " + shape_text(shape) + " of '" + path + "'");
  writer out(path, dtype_of<T>(), shape);
  out.write(values.data(), values.size());
  out.close();
}

template <class T>
array<T> load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) bad_file(path, std::string("cannot open it: ") + std::strerror(errno));
  unsigned char prefix[kPrefix];
  if (!in.read(reinterpret_cast<char*>(prefix), kPrefix) ||
      std::memcmp(prefix, kMagic, kMagicSize) != 0)
    bad_file(path, "not an NPY file (bad magic)");
  if (prefix[6] != 1 || prefix[7] != 0)
    bad_file(path, "NPY version " + std::to_string(prefix[6]) + "." + std::to_string(prefix[7]) +
                       " is not 1.0");
  const std::size_t len = prefix[8] | (static_cast<std::size_t>(prefix[9]) << 8);
  std::string dict(len, '\0');
  if (!in.read(&dict[0], static_cast<std::streamsize>(len))) bad_file(path, "truncated NPY header");

  const std::string type = dict_value(dict, "descr", path);
  const std::string want = std::string("'") + descr(dtype_of<T>()) + "'";
  if (type != want) bad_file(path, "dtype " + type + " is not " + want);
  if (dict_value(dict, "fortran_order", path) != "False")
    bad_file(path, "Fortran order is not supported (fortran_order must be False)");
  array<T> a;
  a.shape = parse_shape(dict_value(dict, "shape", path), path);
  std::size_t count = 0;
  if (!checked_count(a.shape, count))
    bad_file(path, "shape " + shape_text(a.shape) + " is too large");

  // The data must be exactly the shape's bytes: fewer is a truncated file, more is not NPY.
  const std::streamoff data_start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff end = in.tellg();
  if (data_start < 0 || end < data_start) bad_file(path, "cannot read it");
  const auto bytes = static_cast<std::size_t>(end - data_start);
  if (bytes != kWordSize * count)
    bad_file(path, "holds " + std::to_string(bytes) + " data bytes, shape " + shape_text(a.shape) +
                       " needs " + std::to_string(kWordSize * count));
  std::vector<unsigned char> raw(bytes);
  in.seekg(data_start);
  if (!in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(bytes)))
    bad_file(path, "cannot read its data");
  a.values.resize(count);
  decode(raw.data(), count, a.values.data());
  return a;
}

template void save<float>(const std::string&, const std::vector<std::size_t>&,
                          const std::vector<float>&);
template void save<std::uint32_t>(const std::string&, const std::vector<std::size_t>&,
                                  const std::vector<std::uint32_t>&);
template array<float> load<float>(const std::string&);
template array<std::uint32_t> load<std::uint32_t>(const std::string&);

}  // namespace npy
}  // namespace hush_tools
