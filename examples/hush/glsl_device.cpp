// hush — the `hush` program: the GL device `--backend glsl` runs on (glsl_device.hpp).
#include "glsl_device.hpp"

#if HUSH_CLI_HAVE_GLSL
#include <exception>
#include <memory>
#include <string>

#include "args.hpp"
#include "hush/glsl/headless.hpp"

namespace hush_cli {

hush::glsl::device& glsl_device() {
  static std::unique_ptr<hush::glsl::headless_device> h;
  if (!h) {
    try {
      h = std::make_unique<hush::glsl::headless_device>();
    } catch (const std::exception& e) {
      throw run_error(std::string("--backend glsl: no GL context: ") + e.what());
    }
  }
  return h->device;
}

}  // namespace hush_cli
#endif
