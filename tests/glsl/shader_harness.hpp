// Helpers for the suites that test a noise inside a user-written shader (hush/glsl/shader.hpp):
// draw a user fragment shader over a float framebuffer and read it back, and compile a
// shader text with glslangValidator for a given dialect.
#ifndef HUSH_TESTS_GLSL_SHADER_HARNESS_HPP
#define HUSH_TESTS_GLSL_SHADER_HARNESS_HPP

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <unistd.h>
#include <string>
#include <utility>
#include <vector>

#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_raster.hpp"
#include "hush/glsl/shader.hpp"

namespace hush_glsl_test {

// Draws `fragment_source` (a complete fragment shader, #version line included) over a
// width x height RGBA32F framebuffer with one full-screen triangle, after binding `kit`'s
// resources, and returns the pixels, RGBA, row 0 at the bottom (gl_FragCoord.y = 0.5).
// Throws std::runtime_error with the compiler's log when the shader does not compile.
// `set_uniforms`, when given, runs with the program in use before the draw.
class fragment_harness {
 public:
  explicit fragment_harness(hush::glsl::detail::loader_fn gl_loader)
      : loader_(gl_loader), gl_(gl_loader), gr_(gl_loader) {
  }

  const hush::glsl::detail::gl_api& gl() const { return gl_; }
  hush::glsl::detail::loader_fn loader() const { return loader_; }

  template <class SetUniforms>
  std::vector<float> draw(const std::string& fragment_source, const hush::glsl::shader_kit& kit,
                          int width, int height, SetUniforms&& set_uniforms) {
    using namespace hush::glsl::detail;
    const std::string vs =
        "#version 430 core\n"
        "void main() {\n"
        "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);\n"
        "  gl_Position = vec4(p, 0.0, 1.0);\n"
        "}\n";
    gl_program prog = link_program(gl_, {{kGlVertexShader, vs}, {kGlFragmentShader, fragment_source}});
    hush::glsl::bound_kit bound(loader_, kit);
    gl_uint tex = 0, fbo = 0, vao = 0;
    gl_.GenTextures(1, &tex);
    gl_.BindTexture(kGlTexture2d, tex);
    gl_.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlRgba32f), width, height, 0, kGlRgba,
                   kGlFloat, nullptr);
    gr_.GenFramebuffers(1, &fbo);
    gr_.BindFramebuffer(kGlFramebuffer, fbo);
    gr_.FramebufferTexture2D(kGlFramebuffer, kGlColorAttachment0, kGlTexture2d, tex, 0);
    const bool complete = gr_.CheckFramebufferStatus(kGlFramebuffer) == kGlFramebufferComplete;
    std::vector<float> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4u);
    if (complete) {
      gr_.GenVertexArrays(1, &vao);
      gr_.BindVertexArray(vao);
      gr_.Viewport(0, 0, width, height);
      gl_.UseProgram(prog.id());
      bound.bind();
      set_uniforms(prog.id());
      gr_.DrawArrays(kGlTriangles, 0, 3);
      gl_.PixelStorei(kGlPackAlignment, 4);
      gr_.ReadPixels(0, 0, width, height, kGlRgba, kGlFloat, pixels.data());
      gl_.UseProgram(0u);
      gr_.BindVertexArray(0u);
      gr_.DeleteVertexArrays(1, &vao);
    }
    gr_.BindFramebuffer(kGlFramebuffer, 0u);
    gr_.DeleteFramebuffers(1, &fbo);
    gl_.DeleteTextures(1, &tex);
    if (!complete) throw std::runtime_error("fragment_harness: the framebuffer is incomplete");
    gl_.check("fragment_harness::draw");
    return pixels;
  }

  std::vector<float> draw(const std::string& fragment_source, const hush::glsl::shader_kit& kit,
                          int width, int height) {
    return draw(fragment_source, kit, width, height, [](hush::glsl::detail::gl_uint) {});
  }

 private:
  using gl_enum = hush::glsl::detail::gl_enum;
  using gl_uint = hush::glsl::detail::gl_uint;
  using gl_int = hush::glsl::detail::gl_int;
  using gl_sizei = hush::glsl::detail::gl_sizei;

  hush::glsl::detail::loader_fn loader_;
  hush::glsl::detail::gl_api gl_;
  hush::glsl::detail::gl_raster_api gr_;
};

// The GLSL dialects a kit is compiled for by glslangValidator.
enum class dialect { gl430, vulkan450, es300 };

inline const char* dialect_name(dialect d) {
  return d == dialect::gl430 ? "#version 430 core" : d == dialect::vulkan450 ? "Vulkan 450" : "#version 300 es";
}

// The result of one glslangValidator run: whether it compiled, and its output.
struct glslang_result {
  bool ok = false;
  std::string log;
};

// Compiles `body` (a shader without a #version line) as a fragment shader of dialect d with
// glslangValidator (HUSH_GLSLANG_VALIDATOR, the path CMake found; tests that need it are not
// built without it). The version line and, for ES, nothing else is prepended; `name` names
// the temporary file.
inline glslang_result glslang_compile(const std::string& body, dialect d, const std::string& name) {
#ifndef HUSH_GLSLANG_VALIDATOR
  (void)body;
  (void)d;
  (void)name;
  return {false, "glslangValidator was not found when the tests were configured"};
#else
  const std::string version = d == dialect::gl430 ? "#version 430 core\n"
                              : d == dialect::vulkan450 ? "#version 450\n"
                                                        : "#version 300 es\n";
  // The process id keeps suites that CTest runs side by side apart.
  const std::string file = name + "." + std::to_string(getpid()) + (d == dialect::gl430 ? ".gl" : d == dialect::vulkan450 ? ".vk" : ".es") + ".frag";
  {
    std::ofstream out(file, std::ios::binary);
    out << version << body;
  }
  const std::string cmd = std::string(HUSH_GLSLANG_VALIDATOR) +
                          (d == dialect::vulkan450 ? " -V -o " + file + ".spv " : " ") + file + " 2>&1";
  glslang_result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return {false, "cannot run " + cmd};
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) r.log += buf;
  r.ok = pclose(p) == 0;
  std::remove(file.c_str());
  if (d == dialect::vulkan450) std::remove((file + ".spv").c_str());
  return r;
#endif
}

}  // namespace hush_glsl_test

#endif  // HUSH_TESTS_GLSL_SHADER_HARNESS_HPP
