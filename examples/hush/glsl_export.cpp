// hush — the `hush` program: `hush glsl-export DIR`, and the GL status line of `hush info`.
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

#include "commands.hpp"
#include "hush/glsl/export.hpp"
#include "output_file.hpp"

#if HUSH_CLI_HAVE_GLSL
#include <exception>

#include "hush/glsl/device.hpp"
#include "hush/glsl/headless.hpp"

// Mesa's OSMesa keeps a few hundred bytes of per-process state after its
// context is destroyed; `hush info` under LeakSanitizer would fail on it.
// Only leaks allocated inside libOSMesa are suppressed.
#if defined(__SANITIZE_ADDRESS__)
extern "C" const char* __lsan_default_suppressions() {  // NOLINT: the sanitizer hook's name
  return "leak:libOSMesa.so\n";
}
// ... and without the "Suppressions used" table on stderr, where the program's own one-line
// errors go (tests count those lines).
extern "C" const char* __lsan_default_options() {  // NOLINT: the sanitizer hook's name
  return "print_suppressions=0";
}
#endif
#endif

namespace hush_cli {

namespace fs = std::filesystem;

int run_glsl_export(const std::vector<std::string>& args) {
  if (args.empty())
    throw usage_error(
        "DIR is missing; usage: hush glsl-export DIR (a directory, created if needed)");
  if (args.size() > 1) throw usage_error("takes one DIR; got a second argument '" + args[1] + "'");
  const std::string& dir = args[0];
  if (dir.empty() || dir[0] == '-')
    throw usage_error("DIR = '" + dir + "' is not a directory name; valid: a directory path");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw usage_error("DIR = '" + dir + "' exists and is not a directory; valid: a directory path");
  fs::create_directories(dir, ec);
  if (ec)
    throw usage_error("DIR = '" + dir + "' cannot be created (" + ec.message() +
                      "); valid: a writable directory path");
  const std::vector<hush::glsl::export_file> files = hush::glsl::export_files();
  for (const hush::glsl::export_file& f : files) {
    output_file out((fs::path(dir) / f.name).string());
    out.write(f.content.data(), f.content.size());
    out.close();
  }
  std::cout << "wrote " << files.size() << " GLSL files (hush " HUSH_VERSION_STRING ") to "
            << fs::weakly_canonical(fs::absolute(dir)).string() << '\n';
  for (const hush::glsl::export_file& f : files) std::cout << "  " << f.name << '\n';
  return 0;
}

std::string glsl_status() {
#if HUSH_CLI_HAVE_GLSL
  try {
    hush::glsl::headless_context context;
    const hush::glsl::device dev{context.loader()};
    return "yes (" + context.kind() + ": " + dev.renderer() + ")";
  } catch (const std::exception& e) {
    return std::string("unavailable: ") + e.what();
  }
#else
  return "unavailable: built without OSMesa or EGL (apt-get install libosmesa6-dev); "
         "hush glsl-export still works";
#endif
}

}  // namespace hush_cli
