// hush — NumPy .npy files: the one reader and writer of the hush program, the test scenes'
// G-buffer files and the coherence metrics' noise frames.
//
// The format is NPY version 1.0 (numpy.lib.format): the magic "\x93NUMPY", the version bytes
// 1, 0, a little-endian uint16 header length, and a Python dict literal
//   {'descr': '<f4', 'fortran_order': False, 'shape': (ny, nx), }
// padded with spaces and ended by '\n' so that the data starts at a multiple of 64 bytes (what
// numpy.save writes). The data follows in C order (last axis fastest), little-endian whatever
// the host's byte order. Two element types: float32 ('<f4') and uint32 ('<u4'); any number of
// axes, any sizes (a size may be 0).
//
// Errors: files that cannot be opened, written or read, and files that are not what the
// reader accepts, throw std::runtime_error whose message is "'<path>': <what is wrong>" for the
// reader (so a caller can prefix its own context) and the messages documented per function for
// the writers. Caller mistakes (a value count that disagrees with the shape, a shape whose
// header or byte size cannot be represented) throw hush::invalid_argument.
#ifndef HUSH_NPY_NPY_HPP
#define HUSH_NPY_NPY_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "npy/output_file.hpp"

namespace hush_tools {
namespace npy {

// The element type of an array: its NPY 'descr' is '<f4' or '<u4'.
enum class dtype { float32, uint32 };

// The dtype of a C++ element type: float -> float32, std::uint32_t -> uint32.
template <class T>
constexpr dtype dtype_of();
template <>
constexpr dtype dtype_of<float>() {
  return dtype::float32;
}
template <>
constexpr dtype dtype_of<std::uint32_t>() {
  return dtype::uint32;
}

// The NPY 'descr' text of `type`: "<f4" or "<u4".
const char* descr(dtype type);

// `shape` as a Python tuple, as the header writes it: "(5, 7)", "(3,)", "()".
std::string shape_text(const std::vector<std::size_t>& shape);

// The number of elements of `shape` (1 for the empty shape). Throws hush::invalid_argument when
// the array's byte size (4 bytes per element) does not fit in std::size_t.
std::size_t element_count(const std::vector<std::size_t>& shape);

// The complete NPY 1.0 header, magic to the final '\n', of a C-order array of `type` and
// `shape`; its length is a multiple of 64. Throws hush::invalid_argument when the dict does not
// fit the format's 16-bit header length (a shape of thousands of axes).
std::string header(dtype type, const std::vector<std::size_t>& shape);

// Streams one array into a file, so that an array of any size is written without holding it:
// the header on construction, then the values in C order in blocks of any length. The file is
// complete or absent (output_file.hpp): unless close() succeeds (an error, an exception
// unwinding past the writer), it is removed.
class writer {
 public:
  // Creates or truncates `path` and writes the header. Throws std::runtime_error
  // "cannot open '<path>' for writing: <system reason>" or "cannot write '<path>': <reason>",
  // hush::invalid_argument as header() does.
  writer(std::string path, dtype type, const std::vector<std::size_t>& shape);

  // Appends `count` values in C order. The overload must match the writer's dtype (else
  // hush::invalid_argument). Throws std::runtime_error "cannot write '<path>': <reason>".
  void write(const float* values, std::size_t count);
  void write(const std::uint32_t* values, std::size_t count);

  // Finishes the file. Throws std::runtime_error (and removes the file) when a write failed,
  // "cannot write '<path>': <reason>", or when the number of values written differs from the
  // shape's element count, "internal error: wrote <n> of <m> values to '<path>'".
  void close();

  const std::string& path() const { return file_.path(); }

 private:
  void write_words(const void* values, std::size_t count);

  dtype type_;
  std::size_t expected_ = 1;
  std::size_t written_ = 0;
  output_file file_;
  std::vector<unsigned char> buffer_;  // one block, little-endian
};

// Writes the whole array `values` (C order, element_count(shape) of them) to `path` as a
// writer does; the same errors, and hush::invalid_argument when values.size() differs from
// element_count(shape). T is float or std::uint32_t.
template <class T>
void save(const std::string& path, const std::vector<std::size_t>& shape,
          const std::vector<T>& values);

// An array read from a file: its shape and its values in C order.
template <class T>
struct array {
  std::vector<std::size_t> shape;
  std::vector<T> values;  // element_count(shape) of them
};

// Reads `path` as an NPY 1.0 array of dtype_of<T>() in C order, of any shape. Throws
// std::runtime_error "'<path>': <what>" when the file cannot be opened or read, has a bad
// magic, a version other than 1.0, a truncated or malformed header, another dtype (e.g.
// '>f4', '<f8'), fortran_order True, or a data size that differs from the shape's (truncated
// or trailing bytes). T is float or std::uint32_t.
template <class T>
array<T> load(const std::string& path);

}  // namespace npy
}  // namespace hush_tools

#endif  // HUSH_NPY_NPY_HPP
