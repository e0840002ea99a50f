// hush — the `hush` program: streaming writer of NumPy .npy files.
//
// Writes NPY format version 1.0 (numpy.lib.format): the magic "\x93NUMPY", version 1.0, a
// little-endian uint16 header length, and a Python dict literal
//   {'descr': '<f4', 'fortran_order': False, 'shape': (ny, nx), }
// padded with spaces and ended by '\n' so that the data starts at a multiple of 64 bytes.
// The data follows as float32 little-endian in C order (last axis fastest). Values are
// streamed in, so an array of any size is written without holding it in memory.
#ifndef HUSH_CLI_NPY_HPP
#define HUSH_CLI_NPY_HPP

#include <cstddef>
#include <string>
#include <vector>

#include "output_file.hpp"

namespace hush_cli {

// The complete NPY 1.0 header (magic to '\n') for a float32 C-order array of `shape`.
std::string npy_header(const std::vector<std::size_t>& shape);

class npy_writer {
 public:
  // Creates `path` and writes the header; throws run_error when the file cannot be created.
  npy_writer(const std::string& path, const std::vector<std::size_t>& shape);
  // Appends `count` values in C order.
  void write(const float* values, std::size_t count);
  // Finishes the file; throws run_error on I/O failure or when the number of values
  // written differs from the shape's product (the file is then removed).
  void close();

 private:
  output_file file_;
  std::size_t expected_ = 1;
  std::size_t written_ = 0;
  std::vector<unsigned char> buffer_;
};

}  // namespace hush_cli

#endif  // HUSH_CLI_NPY_HPP
