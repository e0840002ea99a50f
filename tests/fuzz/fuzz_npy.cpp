// libFuzzer target: the NPY reader (examples/npy) on arbitrary bytes. Property: it returns an
// array whose values match its shape, or throws std::runtime_error; nothing else (no crash,
// no hang, no allocation beyond the file's size, no sanitizer report).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "npy/npy.hpp"

namespace {

template <class T>
void load_one(const std::string& path) {
  try {
    const auto a = hush_tools::npy::load<T>(path);
    if (a.values.size() != hush_tools::npy::element_count(a.shape)) {
      std::fprintf(stderr, "npy::load: %zu values for shape %s\n", a.values.size(),
                   hush_tools::npy::shape_text(a.shape).c_str());
      std::abort();
    }
  } catch (const std::runtime_error&) {
    // The documented answer to a malformed file.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/hush_fuzz_npy_" + std::to_string(getpid()) + ".npy";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  load_one<float>(path);
  load_one<std::uint32_t>(path);
  std::remove(path.c_str());
  return 0;
}
