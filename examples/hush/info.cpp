// hush — the `hush` program: `hush info`.
#include <iostream>
#include <string>

#include "commands.hpp"
#include "hush/config.hpp"
#include "image.hpp"
#include "noises.hpp"
#include "spectrum.hpp"

namespace hush_cli {
namespace {

std::string compiler() {
#if defined(__clang__)
  return "Clang " __clang_version__;
#elif defined(__GNUC__)
  return "GCC " __VERSION__;
#elif defined(_MSC_VER)
  return "MSVC " + std::to_string(_MSC_VER);
#else
  return "unknown compiler";
#endif
}

std::string standard() {
  const long v = __cplusplus;
  const char* name = v > 202002L    ? "C++23"
                     : v >= 202002L ? "C++20"
                     : v >= 201703L ? "C++17"
                                    : "C++?";
  return std::string(name) + " (__cplusplus = " + std::to_string(v) + "L)";
}

std::string build_type() {
  const std::string type = HUSH_CLI_BUILD_TYPE;  // CMake's configuration, "" when unset
#if defined(NDEBUG)
  const char* asserts = "assertions off";
#else
  const char* asserts = "assertions on";
#endif
  return (type.empty() ? "(none)" : type) + " (" + asserts + ")";
}

const char* yes_no(bool b) { return b ? "yes" : "no"; }

// "dynamic dispatch; compiled: AVX3 AVX2 ...; chosen: AVX2", or why there is none.
std::string simd_status() {
#if HUSH_CONFIG_SIMD
  std::string compiled;
  for (const std::string& t : hush::simd::compiled_targets())
    compiled += (compiled.empty() ? "" : " ") + t;
  return std::string("yes, ") + hush::simd::dispatch_mode() + " dispatch; compiled: " + compiled +
         "; chosen: " + hush::simd::chosen_target();
#else
  return "no (built without Highway; exec::simd runs the scalar loop)";
#endif
}

std::string gallery_status() {
  if (!png_supported()) return "no (needs stb_image_write.h: apt-get install libstb-dev)";
  if (!spectrum_supported()) return "no (needs Eigen3's FFT: apt-get install libeigen3-dev)";
  return std::string("yes (") + spectrum_library() + ", stb_image_write)";
}

}  // namespace

int run_info(const std::vector<std::string>& args) {
  if (!args.empty()) throw usage_error("takes no arguments; got '" + args[0] + "'");
  std::ostream& os = std::cout;
  os << "hush " << HUSH_VERSION_STRING << '\n'
     << "compiler:     " << compiler() << ", " << standard() << '\n'
     << "build type:   " << build_type() << '\n'
#if defined(__SANITIZE_ADDRESS__)
     << "sanitizers:   AddressSanitizer\n"
#endif
     << "glm interop:  " << yes_no(HUSH_CONFIG_GLM) << " (HUSH_CONFIG_GLM = " << HUSH_CONFIG_GLM
     << ")\n"
     << "strict fp:    " << yes_no(HUSH_CONFIG_STRICT_FP)
     << " (HUSH_CONFIG_STRICT_FP = " << HUSH_CONFIG_STRICT_FP << ")\n"
     << "noises:       " << noise_names() << '\n'
     << "backends:\n"
     << "  scalar:     yes\n"
     << "  simd:       " << simd_status() << '\n'
     << "  glsl:       " << glsl_status() << '\n'
     << "png output:   "
     << (png_supported() ? "yes (stb_image_write)" : "no (stb_image_write.h not found)") << '\n'
     << "gallery:      " << gallery_status() << '\n';
  return 0;
}

}  // namespace hush_cli
