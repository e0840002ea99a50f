// hush — the `hush` program: the GL device `--backend glsl` runs on.
#ifndef HUSH_CLI_GLSL_DEVICE_HPP
#define HUSH_CLI_GLSL_DEVICE_HPP

#ifndef HUSH_CLI_HAVE_GLSL
#define HUSH_CLI_HAVE_GLSL 0  // 1 when OSMesa or EGL is found (examples/CMakeLists.txt)
#endif

#if HUSH_CLI_HAVE_GLSL
#include "hush/glsl/device.hpp"

namespace hush_cli {

// One headless GL 4.5 context (OSMesa or EGL: HUSH_GL_CONTEXT, hush/glsl/headless.hpp) and its
// hush::glsl::device for the whole process, created on first use. Throws run_error when no GL
// context can be created.
hush::glsl::device& glsl_device();

}  // namespace hush_cli
#endif

#endif  // HUSH_CLI_GLSL_DEVICE_HPP
