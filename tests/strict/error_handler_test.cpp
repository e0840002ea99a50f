// hush's error handler in a build without exceptions (tests/strict/CMakeLists.txt compiles
// this file with -fno-exceptions and runs it through run_expect.cmake). argv[1] picks the case:
//   handler  a handler set with hush::set_error_handler gets the message naming the bad
//            parameter (wavelet tile_size = 0) and ends the program with exit code 3;
//   default  without a handler, the message goes to stderr and the program aborts;
//   returns  a handler that returns: hush aborts after it.
// Each case fails if hush returns from the bad construction (exit code 1).
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "hush/wavelet.hpp"

static_assert(HUSH_CONFIG_EXCEPTIONS == 0, "compile this test with -fno-exceptions");

namespace {

void exit_3(const char* message) {
  std::fprintf(stderr, "handler got: %s\n", message);
  std::_Exit(3);
}

void returns(const char* message) { std::fprintf(stderr, "handler returns: %s\n", message); }

}  // namespace

int main(int argc, char** argv) {
  const char* mode = argc > 1 ? argv[1] : "";
  if (std::strcmp(mode, "handler") == 0) {
    // The first call returns the default handler, never null.
    if (hush::set_error_handler(exit_3) == nullptr || hush::get_error_handler() != exit_3) {
      std::fprintf(stderr, "set_error_handler / get_error_handler disagree\n");
      return 2;
    }
  } else if (std::strcmp(mode, "returns") == 0) {
    hush::set_error_handler(returns);
  } else if (std::strcmp(mode, "default") != 0) {
    std::fprintf(stderr, "usage: error_handler_test handler|default|returns\n");
    return 2;
  }
  hush::wavelet<2>::params p;
  p.tile_size = 0;
  const hush::wavelet<2> bad(p);
  std::fprintf(stderr, "no error reported for tile_size = 0 (%d)\n", bad.parameters().tile_size);
  return 1;
}
