// Tests of the NumPy .npy reader and writers (examples/npy/npy.hpp): round trips keep every bit
// of both dtypes in several shapes, the header is NPY 1.0 with the data 64-byte aligned, the
// streaming and whole-array writers write the same bytes, and every malformed file is refused
// with a std::runtime_error naming the file and the fault.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "hush/core/error.hpp"
#include "npy/npy.hpp"
#include "npy/output_file.hpp"

namespace {

namespace fs = std::filesystem;
namespace npy = hush_tools::npy;

// A fresh scratch directory per test case, so that test cases may run in parallel.
fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(HUSH_NPY_SCRATCH) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void spit(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Values with every byte position non-trivial, NaN, infinities, -0 and denormals included.
std::vector<float> float_values(std::size_t n) {
  std::vector<float> v(n);
  for (std::size_t k = 0; k < n; ++k) v[k] = static_cast<float>(k) * 1.25f - 7.5f;
  const float specials[] = {std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::infinity(), -0.0f,
                            std::numeric_limits<float>::denorm_min(), -3.0e38f};
  for (std::size_t k = 0; k < n && k < 5; ++k) v[k] = specials[k];
  return v;
}

std::vector<std::uint32_t> uint_values(std::size_t n) {
  std::vector<std::uint32_t> v(n);
  for (std::size_t k = 0; k < n; ++k) v[k] = static_cast<std::uint32_t>(k) * 0x9E3779B1u;
  if (n > 0) v[0] = 0xffffffffu;
  return v;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), 4 * a.size()) == 0);
}

// The header's length field and dict text of an NPY 1.0 file's bytes.
std::size_t header_length(const std::string& bytes) {
  return static_cast<unsigned char>(bytes[8]) |
         (static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8);
}

// The message of load<float>(path)'s exception, "" when it does not throw.
std::string load_error(const fs::path& path) {
  try {
    npy::load<float>(path.string());
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// A valid float32 (2, 3) file whose header dict is `dict` (padded to the 64-byte boundary).
std::string file_with_dict(std::string dict, std::size_t data_bytes = 24) {
  while ((10 + dict.size() + 1) % 64 != 0) dict += ' ';
  dict += '\n';
  std::string bytes("\x93NUMPY\x01\x00", 8);
  bytes += static_cast<char>(dict.size() & 0xff);
  bytes += static_cast<char>(dict.size() >> 8);
  return bytes + dict + std::string(data_bytes, '\0');
}

TEST_CASE("float32 and uint32 arrays of several shapes round-trip bit for bit") {
  const fs::path dir = scratch("roundtrip");
  const std::vector<std::vector<std::size_t>> shapes = {{},        {1},          {7}, {5, 7},
                                                        {3, 4, 2}, {2, 3, 2, 2}, {0}, {4, 0, 3}};
  for (const std::vector<std::size_t>& shape : shapes) {
    INFO("shape " << npy::shape_text(shape));
    const std::size_t n = npy::element_count(shape);
    const std::vector<float> f = float_values(n);
    npy::save((dir / "f.npy").string(), shape, f);
    const npy::array<float> af = npy::load<float>((dir / "f.npy").string());
    CHECK(af.shape == shape);
    CHECK(same_bits(af.values, f));
    const std::vector<std::uint32_t> u = uint_values(n);
    npy::save((dir / "u.npy").string(), shape, u);
    const npy::array<std::uint32_t> au = npy::load<std::uint32_t>((dir / "u.npy").string());
    CHECK(au.shape == shape);
    CHECK(au.values == u);
  }
}

TEST_CASE("the header is NPY 1.0 with numpy's dict text and the data starts at a multiple of 64") {
  const fs::path dir = scratch("header");
  const struct {
    std::vector<std::size_t> shape;
    npy::dtype type;
    const char* dict;
  } cases[] = {
      {{5, 7}, npy::dtype::float32, "{'descr': '<f4', 'fortran_order': False, 'shape': (5, 7), }"},
      {{5, 7, 3},
       npy::dtype::uint32,
       "{'descr': '<u4', 'fortran_order': False, 'shape': (5, 7, 3), }"},
      {{9}, npy::dtype::float32, "{'descr': '<f4', 'fortran_order': False, 'shape': (9,), }"},
      {{}, npy::dtype::uint32, "{'descr': '<u4', 'fortran_order': False, 'shape': (), }"},
  };
  for (const auto& c : cases) {
    INFO(std::string(c.dict));
    const std::string h = npy::header(c.type, c.shape);
    REQUIRE(h.size() > 10);
    CHECK(h.compare(0, 8, std::string("\x93NUMPY\x01\x00", 8)) == 0);
    CHECK(h.size() % 64 == 0);
    CHECK(header_length(h) == h.size() - 10);
    CHECK(h.compare(10, std::strlen(c.dict), c.dict) == 0);
    CHECK(h.back() == '\n');
    CHECK(h.find_first_not_of(' ', 10 + std::strlen(c.dict)) == h.size() - 1);  // space padding
  }
  // The file is the header, then 4 little-endian bytes per value.
  npy::save((dir / "a.npy").string(), {2}, std::vector<std::uint32_t>{0x04030201u, 0xa0b0c0d0u});
  const std::string bytes = slurp(dir / "a.npy");
  const std::string h = npy::header(npy::dtype::uint32, {2});
  CHECK(bytes == h + std::string("\x01\x02\x03\x04\xd0\xc0\xb0\xa0", 8));
}

TEST_CASE("the streaming writer writes the whole-array writer's bytes from blocks of any size") {
  const fs::path dir = scratch("stream");
  const std::vector<std::size_t> shape = {6, 5};
  const std::vector<float> v = float_values(30);
  npy::save((dir / "whole.npy").string(), shape, v);
  npy::writer w((dir / "stream.npy").string(), npy::dtype::float32, shape);
  CHECK(w.path() == (dir / "stream.npy").string());
  w.write(v.data(), 7);
  w.write(v.data() + 7, 0);
  w.write(v.data() + 7, 23);
  w.close();
  CHECK(slurp(dir / "stream.npy") == slurp(dir / "whole.npy"));
}

TEST_CASE("an unfinished or miscounted streaming write leaves no file") {
  const fs::path dir = scratch("unfinished");
  const std::vector<float> v = float_values(4);
  {
    npy::writer w((dir / "abandoned.npy").string(), npy::dtype::float32, {2, 2});
    w.write(v.data(), 2);
    CHECK(fs::exists(dir / "abandoned.npy"));
  }  // destroyed without close()
  CHECK_FALSE(fs::exists(dir / "abandoned.npy"));
  npy::writer w((dir / "short.npy").string(), npy::dtype::float32, {2, 2});
  w.write(v.data(), 3);
  CHECK_THROWS_WITH_AS(w.close(), doctest::Contains("wrote 3 of 4 values"), std::runtime_error);
  CHECK_FALSE(fs::exists(dir / "short.npy"));
}

TEST_CASE("an output file is complete after close, absent otherwise, and failures name it") {
  const fs::path dir = scratch("output_file");
  {
    npy::output_file f((dir / "kept.bin").string());
    f.write("abc", 3);
    f.write("", 0);
    f.write("de", 2);
    f.close();
  }
  CHECK(slurp(dir / "kept.bin") == "abcde");
  {
    npy::output_file f((dir / "dropped.bin").string());
    f.write("abc", 3);
  }
  CHECK_FALSE(fs::exists(dir / "dropped.bin"));
  npy::output_file discarded((dir / "discarded.bin").string());
  discarded.discard();
  CHECK_FALSE(fs::exists(dir / "discarded.bin"));
  const std::string after = "cannot write '" + (dir / "discarded.bin").string() + "': ";
  CHECK_THROWS_WITH_AS(discarded.write("x", 1), doctest::Contains(after.c_str()),
                       std::runtime_error);
  CHECK_THROWS_WITH_AS(discarded.close(), doctest::Contains(after.c_str()), std::runtime_error);
  const std::string missing = (dir / "no_such_dir" / "x.bin").string();
  const std::string why = "cannot open '" + missing + "' for writing: ";
  CHECK_THROWS_WITH_AS(npy::output_file{missing}, doctest::Contains(why.c_str()),
                       std::runtime_error);
}

TEST_CASE("writer misuse and unwritable paths throw") {
  const fs::path dir = scratch("misuse");
  CHECK_THROWS_AS(npy::save((dir / "n.npy").string(), {2, 3}, std::vector<float>(5)),
                  hush::invalid_argument);
  CHECK_FALSE(fs::exists(dir / "n.npy"));
  npy::writer w((dir / "t.npy").string(), npy::dtype::uint32, {1});
  const float f = 1.0f;
  CHECK_THROWS_AS(w.write(&f, 1), hush::invalid_argument);
  CHECK_THROWS_AS(npy::element_count({std::numeric_limits<std::size_t>::max(), 2}),
                  hush::invalid_argument);
  const std::string missing = (dir / "no_such_dir" / "x.npy").string();
  const std::string why = "cannot open '" + missing + "' for writing: ";
  CHECK_THROWS_WITH_AS(npy::save(missing, {1}, std::vector<float>{1.0f}),
                       doctest::Contains(why.c_str()), std::runtime_error);
}

TEST_CASE("a bad magic, a version 2.0 header or a truncated header is refused naming the file") {
  const fs::path dir = scratch("bad_header");
  const std::string good =
      file_with_dict("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }");
  spit(dir / "good.npy", good);
  CHECK(npy::load<float>((dir / "good.npy").string()).shape == std::vector<std::size_t>{2, 3});

  std::string magic = good;
  magic[1] = 'n';
  spit(dir / "magic.npy", magic);
  const std::string e_magic = load_error(dir / "magic.npy");
  CHECK(e_magic.find("magic.npy") != std::string::npos);
  CHECK(e_magic.find("bad magic") != std::string::npos);

  std::string v2 = good;
  v2[6] = '\x02';
  spit(dir / "v2.npy", v2);
  const std::string e_v2 = load_error(dir / "v2.npy");
  CHECK(e_v2.find("v2.npy") != std::string::npos);
  CHECK(e_v2.find("version 2.0 is not 1.0") != std::string::npos);

  spit(dir / "short.npy", good.substr(0, 40));
  const std::string e_short = load_error(dir / "short.npy");
  CHECK(e_short.find("short.npy") != std::string::npos);
  CHECK(e_short.find("truncated NPY header") != std::string::npos);

  spit(dir / "tiny.npy", good.substr(0, 5));
  CHECK(load_error(dir / "tiny.npy").find("bad magic") != std::string::npos);

  const std::string e_missing = load_error(dir / "missing.npy");
  CHECK(e_missing.find("missing.npy") != std::string::npos);
  CHECK(e_missing.find("cannot open") != std::string::npos);
}

TEST_CASE("another dtype, Fortran order or a malformed shape is refused naming the file") {
  const fs::path dir = scratch("bad_dict");
  const struct {
    const char* dict;
    const char* why;
  } cases[] = {
      {"{'descr': '>f4', 'fortran_order': False, 'shape': (2, 3), }", "dtype '>f4' is not '<f4'"},
      {"{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", "dtype '<f8' is not '<f4'"},
      {"{'descr': '<f4', 'fortran_order': True, 'shape': (2, 3), }", "Fortran order"},
      {"{'descr': '<f4', 'fortran_order': False, 'shape': (2, x), }", "is not a tuple of sizes"},
      {"{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, }", "unterminated 'shape'"},
      {"{'descr': '<f4', 'fortran_order': False, 'shape': (2 3), }", "is not a tuple of sizes"},
      {"{'descr': '<f4', 'fortran_order': False, 'shape': (99999999999999999999999, 3), }",
       "too large"},
      {"{'descr': '<f4', 'fortran_order': False, }", "has no 'shape'"},
      {"{'fortran_order': False, 'shape': (2, 3), }", "has no 'descr'"},
  };
  for (const auto& c : cases) {
    INFO(std::string(c.dict));
    spit(dir / "bad.npy", file_with_dict(c.dict));
    const std::string e = load_error(dir / "bad.npy");
    CHECK(e.find("bad.npy") != std::string::npos);
    CHECK(e.find(c.why) != std::string::npos);
  }
  // The dtype check is per element type: a '<f4' file is not a '<u4' array.
  npy::save((dir / "f.npy").string(), {2}, std::vector<float>{1.0f, 2.0f});
  CHECK_THROWS_WITH_AS(npy::load<std::uint32_t>((dir / "f.npy").string()),
                       doctest::Contains("dtype '<f4' is not '<u4'"), std::runtime_error);
}

TEST_CASE("truncated data or data that disagrees with the shape's size is refused") {
  const fs::path dir = scratch("bad_data");
  const std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }";
  for (const std::size_t bytes :
       {std::size_t{0}, std::size_t{20}, std::size_t{23}, std::size_t{28}}) {
    INFO(bytes << " data bytes");
    spit(dir / "size.npy", file_with_dict(dict, bytes));
    const std::string e = load_error(dir / "size.npy");
    CHECK(e.find("size.npy") != std::string::npos);
    CHECK(e.find("holds " + std::to_string(bytes) + " data bytes, shape (2, 3) needs 24") !=
          std::string::npos);
  }
  // A file cut short by a failed copy.
  npy::save((dir / "cut.npy").string(), {4, 4}, float_values(16));
  fs::resize_file(dir / "cut.npy", fs::file_size(dir / "cut.npy") - 4);
  CHECK(load_error(dir / "cut.npy").find("needs 64") != std::string::npos);
}

}  // namespace
