// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// A headless GL 4.5 core context of whichever kind this build has, and a
// hush::glsl::device on it, for programs that own no GL context of their own
// (the hush program, tests, benchmarks):
//
//   hush::glsl::headless_device h;           // context current, device ready
//   hush::evaluate(p, hush::exec::glsl{h.device}, points, out);
//
// The kinds: OSMesa (hush/glsl/osmesa_context.hpp: llvmpipe, no GPU needed) and
// EGL (hush/glsl/egl_context.hpp: the machine's GPU). The CMake target
// hush::glsl_headless defines HUSH_GLSL_HAVE_OSMESA and HUSH_GLSL_HAVE_EGL for
// those it found. The environment variable HUSH_GL_CONTEXT picks one at run
// time: "osmesa" or "egl"; unset or empty, OSMesa where the build has it (the
// deterministic CI rasterizer), else EGL. A kind this build lacks, or any other
// value, throws hush::invalid_argument naming the variable and the values
// this build accepts; a kind that cannot make a context throws its
// std::runtime_error. Not copyable; create once per thread that evaluates.
#ifndef HUSH_GLSL_HEADLESS_HPP
#define HUSH_GLSL_HEADLESS_HPP

#if !defined(HUSH_GLSL_HAVE_OSMESA) && !defined(HUSH_GLSL_HAVE_EGL)
#error "hush/glsl/headless.hpp needs OSMesa or EGL: link hush::glsl_headless"
#endif

#include <cstdlib>
#include <memory>
#include <string>

#include "hush/core/error.hpp"
#include "hush/glsl/device.hpp"
#if defined(HUSH_GLSL_HAVE_OSMESA)
#include "hush/glsl/osmesa_context.hpp"
#endif
#if defined(HUSH_GLSL_HAVE_EGL)
#include "hush/glsl/egl_context.hpp"
#endif

namespace hush {
namespace glsl {

class headless_context {
 public:
  using loader_fn = void* (*)(const char*);

  // The kind HUSH_GL_CONTEXT names (see the file comment), created and made current.
  headless_context() : headless_context(kind_from_environment()) {}

  // kind: "osmesa" or "egl", one this build has.
  explicit headless_context(const std::string& kind) {
#if defined(HUSH_GLSL_HAVE_OSMESA)
    if (kind == "osmesa") {
      osmesa_ = std::make_unique<osmesa_context>();
      kind_ = kind;
      return;
    }
#endif
#if defined(HUSH_GLSL_HAVE_EGL)
    if (kind == "egl") {
      egl_ = std::make_unique<egl_context>();
      kind_ = kind;
      return;
    }
#endif
    hush::detail::raise_error("hush::glsl::headless_context: HUSH_GL_CONTEXT = \"" + kind +
                                 "\"; this build accepts " + accepted());
  }

  // "osmesa" or "egl".
  const std::string& kind() const { return kind_; }

  // The GL function loader of this context's kind.
  loader_fn loader() const {
#if defined(HUSH_GLSL_HAVE_OSMESA)
    if (osmesa_) return osmesa_context::loader();
#endif
#if defined(HUSH_GLSL_HAVE_EGL)
    if (egl_) return egl_context::loader();
#endif
    return nullptr;  // unreachable: the constructor made one
  }

  // Makes this context current on the calling thread.
  void make_current() {
#if defined(HUSH_GLSL_HAVE_OSMESA)
    if (osmesa_) osmesa_->make_current();
#endif
#if defined(HUSH_GLSL_HAVE_EGL)
    if (egl_) egl_->make_current();
#endif
  }

  // HUSH_GL_CONTEXT's value, or this build's default where it is unset or empty.
  static std::string kind_from_environment() {
    const char* v = std::getenv("HUSH_GL_CONTEXT");  // NOLINT(concurrency-mt-unsafe): read once
    if (v && *v) return v;
#if defined(HUSH_GLSL_HAVE_OSMESA)
    return "osmesa";
#else
    return "egl";
#endif
  }

 private:
  static const char* accepted() {
#if defined(HUSH_GLSL_HAVE_OSMESA) && defined(HUSH_GLSL_HAVE_EGL)
    return "\"osmesa\" or \"egl\"";
#elif defined(HUSH_GLSL_HAVE_OSMESA)
    return "\"osmesa\" (built without EGL)";
#else
    return "\"egl\" (built without OSMesa)";
#endif
  }

  std::string kind_;
#if defined(HUSH_GLSL_HAVE_OSMESA)
  std::unique_ptr<osmesa_context> osmesa_;
#endif
#if defined(HUSH_GLSL_HAVE_EGL)
  std::unique_ptr<egl_context> egl_;
#endif
};

// A headless context and a device on it, destroyed in the right order (device first).
struct headless_device {
  headless_context context;
  hush::glsl::device device{context.loader()};
};

}  // namespace glsl
}  // namespace hush

#endif  // HUSH_GLSL_HEADLESS_HPP
