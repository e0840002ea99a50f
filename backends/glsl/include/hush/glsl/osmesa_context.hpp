// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// A headless OpenGL 4.5 core context through Mesa's OSMesa (llvmpipe), for
// tests, CI and command-line tools on machines without a GPU or display.
//
//   hush::glsl::osmesa_context ctx;          // created and made current
//   hush::glsl::device dev{ctx.loader()};    // GL runner on this context
//
// Needs libOSMesa (Debian: libosmesa6-dev; CMake target hush::glsl_osmesa).
// The context renders into a small RGBA8 buffer it owns; compute work and
// framebuffer objects do not need it to be large. Not copyable; the context
// is destroyed with the object. Throws std::runtime_error when OSMesa cannot
// create a GL >= 4.3 core context (compute shaders need 4.3).
//
// hush/glsl/headless.hpp bundles a context of this kind or EGL's with a
// hush::glsl::device on it, for programs that own no GL context of their own.
#ifndef HUSH_GLSL_OSMESA_CONTEXT_HPP
#define HUSH_GLSL_OSMESA_CONTEXT_HPP

#include <GL/osmesa.h>

#include "hush/core/error.hpp"
#include "hush/glsl/device.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace hush {
namespace glsl {

class osmesa_context {
 public:
  // Loader signature the GL runner takes: name -> function address.
  using loader_fn = void* (*)(const char*);

  // Throws hush::invalid_argument when width or height is outside 1 ... 16384.
  explicit osmesa_context(int width = 16, int height = 16, int depth_bits = 24)
      : width_(checked_size("width", width)),
        height_(checked_size("height", height)),
        pixels_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4u) {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           depth_bits,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_)
      hush::detail::raise_error<std::runtime_error>(
          "hush::glsl::osmesa_context: OSMesa could not create a GL 4.5 core context");
    make_current();
  }
  osmesa_context(const osmesa_context&) = delete;
  osmesa_context& operator=(const osmesa_context&) = delete;
  ~osmesa_context() {
    if (ctx_) OSMesaDestroyContext(ctx_);
  }

  // Makes this context current on the calling thread.
  void make_current() {
    if (!OSMesaMakeCurrent(ctx_, pixels_.data(), GL_UNSIGNED_BYTE, width_, height_))
      hush::detail::raise_error<std::runtime_error>("hush::glsl::osmesa_context: OSMesaMakeCurrent failed");
  }

  // GL function loader for this context (OSMesaGetProcAddress).
  static loader_fn loader() { return &get_proc; }

 private:
  // Validated before the pixel buffer is sized from it.
  static int checked_size(const char* name, int v) {
    constexpr int kMaxSize = 16384;  // llvmpipe's largest framebuffer side
    hush::detail::require_in_range("hush::glsl::osmesa_context", name, v, 1, kMaxSize,
                                   "1 ... 16384");
    return v;
  }
  static void* get_proc(const char* name) {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
  }

  int width_, height_;
  std::vector<unsigned char> pixels_;
  OSMesaContext ctx_ = nullptr;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_OSMESA_CONTEXT_HPP
