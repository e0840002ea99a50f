// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// A headless OpenGL 4.5 core context through EGL, with no window system: on a
// machine's GPU (NVIDIA's or Mesa's driver through libglvnd) or, where none is,
// on Mesa's software device (llvmpipe).
//
//   hush::glsl::egl_context ctx;             // created and made current
//   hush::glsl::device dev{ctx.loader()};    // GL runner on this context
//
// Needs libEGL (Debian: libegl-dev; CMake target hush::glsl_egl). The display
// is the first EGL device (EGL_EXT_platform_device) that initializes, hardware
// devices before software ones (EGL_MESA_device_software); without device
// enumeration, EGL's default display. The context is current without a surface
// (EGL_KHR_surfaceless_context) or, where that is missing, on a 16 x 16 pbuffer:
// compute work and framebuffer objects need no default framebuffer. Not
// copyable; the context is destroyed with the object (its display stays initialized: EGL
// displays are shared by the whole process). Throws std::runtime_error
// naming the EGL call that failed when no GL >= 4.5 core context can be made.
#ifndef HUSH_GLSL_EGL_CONTEXT_HPP
#define HUSH_GLSL_EGL_CONTEXT_HPP

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "hush/core/error.hpp"

namespace hush {
namespace glsl {

class egl_context {
 public:
  // Loader signature the GL runner takes: name -> function address.
  using loader_fn = void* (*)(const char*);

  egl_context() {
    display_ = open_display();
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
    const bool surfaceless =
        has_extension(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context");
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                     surfaceless ? EGLint{0} : EGLint{EGL_PBUFFER_BIT},
                                     EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &count) || count < 1)
      fail("eglChooseConfig (an OpenGL-renderable config)");
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attribs);
    if (context_ == EGL_NO_CONTEXT) fail("eglCreateContext (OpenGL 4.5 core)");
    if (!surfaceless) {
      const EGLint pbuffer_attribs[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
      surface_ = eglCreatePbufferSurface(display_, config, pbuffer_attribs);
      if (surface_ == EGL_NO_SURFACE) fail("eglCreatePbufferSurface (16 x 16)");
    }
    make_current();
  }
  egl_context(const egl_context&) = delete;
  egl_context& operator=(const egl_context&) = delete;
  ~egl_context() { release(); }

  // Makes this context current on the calling thread.
  void make_current() {
    if (!eglMakeCurrent(display_, surface_, surface_, context_)) fail("eglMakeCurrent");
  }

  // GL function loader for this context: eglGetProcAddress, which EGL 1.5 defines for the
  // client API's core functions too.
  static loader_fn loader() { return &get_proc; }

 private:
  static void* get_proc(const char* name) {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
  }

  static bool has_extension(const char* list, const char* name) {
    if (!list) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
      if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
  }

  // The first initializable device display, hardware before software; else the default one.
  static EGLDisplay open_display() {
    const auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    const auto query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    const auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (query_devices && platform_display) {
      constexpr EGLint kMaxDevices = 16;
      EGLDeviceEXT devices[kMaxDevices] = {};
      EGLint n = 0;
      if (query_devices(kMaxDevices, devices, &n) && n > 0) {
        for (int pass = 0; pass < 2; ++pass) {  // pass 0: hardware devices; pass 1: software
          for (EGLint i = 0; i < n; ++i) {
            const char* ext =
                query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : nullptr;
            if (has_extension(ext, "EGL_MESA_device_software") != (pass == 1)) continue;
            EGLDisplay d = platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            EGLint major = 0, minor = 0;
            if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
          }
        }
      }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    EGLint major = 0, minor = 0;
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor))
      hush::detail::raise_error<std::runtime_error>(
          "hush::glsl::egl_context: no EGL display (no device display initialized, nor the "
          "default one; EGL error " +
          hex(eglGetError()) + ")");
    return d;
  }

  static std::string hex(EGLint v) {
    static const char digits[] = "0123456789abcdef";
    std::string s = "0x";
    for (int shift = 12; shift >= 0; shift -= 4) s += digits[(v >> shift) & 0xf];
    return s;
  }

  [[noreturn]] void fail(const char* what) {
    const EGLint error = eglGetError();
    release();
    hush::detail::raise_error<std::runtime_error>(std::string("hush::glsl::egl_context: ") + what +
                             " failed (EGL error " + hex(error) + ")");
  }

  void release() noexcept {
    if (display_ == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    // No eglTerminate: a display is one per process and device, and terminating it would
    // destroy every other context on it too.
    display_ = EGL_NO_DISPLAY;
    surface_ = EGL_NO_SURFACE;
    context_ = EGL_NO_CONTEXT;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLSurface surface_ = EGL_NO_SURFACE;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_EGL_CONTEXT_HPP
