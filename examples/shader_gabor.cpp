// Gabor noise in your own fragment shader (hush/glsl/gabor/shader.hpp): a ground plane seen
// towards the horizon, textured with anisotropic Gabor noise filtered over each pixel's
// footprint from the shader's own dFdx / dFdy. The program binds hush's one resource (the
// std140 block hush_gabor_params) with plain GL calls, as an engine would, renders into a
// float framebuffer, reads it back and prints the largest difference from the CPU's
// gabor<2>::sample(p, footprint) of the same pixel, and how filtering calms the far rows.
#include <hush/gabor.hpp>
#include <hush/glsl/gabor/shader.hpp>
#include <hush/glsl/osmesa_context.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

// A GL failure: the message, exit code 1 (the program builds with or without exceptions).
[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "shader_gabor: %s\n", what.c_str());
  std::exit(1);
}

// The few GL 4.3 entry points and enums this program uses, loaded by name.
using GLenum = unsigned;
using GLuint = unsigned;
using GLint = int;
using GLsizei = int;
constexpr GLenum kVertexShader = 0x8B31, kFragmentShader = 0x8B30, kCompileStatus = 0x8B81,
                 kLinkStatus = 0x8B82, kUniformBuffer = 0x8A11, kStaticDraw = 0x88E4,
                 kTexture2d = 0x0DE1, kRgba32f = 0x8814, kRgba = 0x1908, kFloat = 0x1406,
                 kFramebuffer = 0x8D40, kColorAttachment0 = 0x8CE0, kTriangles = 0x0004;

struct gl_functions {
  GLuint (*CreateShader)(GLenum);
  void (*ShaderSource)(GLuint, GLsizei, const char* const*, const GLint*);
  void (*CompileShader)(GLuint);
  void (*GetShaderiv)(GLuint, GLenum, GLint*);
  void (*GetShaderInfoLog)(GLuint, GLsizei, GLsizei*, char*);
  GLuint (*CreateProgram)();
  void (*AttachShader)(GLuint, GLuint);
  void (*LinkProgram)(GLuint);
  void (*GetProgramiv)(GLuint, GLenum, GLint*);
  void (*UseProgram)(GLuint);
  void (*GenBuffers)(GLsizei, GLuint*);
  void (*BindBuffer)(GLenum, GLuint);
  void (*BufferData)(GLenum, std::ptrdiff_t, const void*, GLenum);
  void (*BindBufferBase)(GLenum, GLuint, GLuint);
  void (*GenTextures)(GLsizei, GLuint*);
  void (*BindTexture)(GLenum, GLuint);
  void (*TexImage2D)(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void*);
  void (*GenFramebuffers)(GLsizei, GLuint*);
  void (*BindFramebuffer)(GLenum, GLuint);
  void (*FramebufferTexture2D)(GLenum, GLenum, GLenum, GLuint, GLint);
  void (*DrawBuffers)(GLsizei, const GLenum*);
  void (*GenVertexArrays)(GLsizei, GLuint*);
  void (*BindVertexArray)(GLuint);
  void (*Viewport)(GLint, GLint, GLsizei, GLsizei);
  void (*DrawArrays)(GLenum, GLint, GLsizei);
  void (*ReadBuffer)(GLenum);
  void (*ReadPixels)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void*);
  GLenum (*GetError)();

  template <class F>
  static void load(void* (*loader)(const char*), F& f, const char* name) {
    f = reinterpret_cast<F>(loader(name));
    if (!f) fail(std::string("no GL function ") + name);
  }
  explicit gl_functions(void* (*l)(const char*)) {
    load(l, CreateShader, "glCreateShader");
    load(l, ShaderSource, "glShaderSource");
    load(l, CompileShader, "glCompileShader");
    load(l, GetShaderiv, "glGetShaderiv");
    load(l, GetShaderInfoLog, "glGetShaderInfoLog");
    load(l, CreateProgram, "glCreateProgram");
    load(l, AttachShader, "glAttachShader");
    load(l, LinkProgram, "glLinkProgram");
    load(l, GetProgramiv, "glGetProgramiv");
    load(l, UseProgram, "glUseProgram");
    load(l, GenBuffers, "glGenBuffers");
    load(l, BindBuffer, "glBindBuffer");
    load(l, BufferData, "glBufferData");
    load(l, BindBufferBase, "glBindBufferBase");
    load(l, GenTextures, "glGenTextures");
    load(l, BindTexture, "glBindTexture");
    load(l, TexImage2D, "glTexImage2D");
    load(l, GenFramebuffers, "glGenFramebuffers");
    load(l, BindFramebuffer, "glBindFramebuffer");
    load(l, FramebufferTexture2D, "glFramebufferTexture2D");
    load(l, DrawBuffers, "glDrawBuffers");
    load(l, GenVertexArrays, "glGenVertexArrays");
    load(l, BindVertexArray, "glBindVertexArray");
    load(l, Viewport, "glViewport");
    load(l, DrawArrays, "glDrawArrays");
    load(l, ReadBuffer, "glReadBuffer");
    load(l, ReadPixels, "glReadPixels");
    load(l, GetError, "glGetError");
  }
};

GLuint compile(const gl_functions& gl, GLenum stage, const std::string& text) {
  const GLuint s = gl.CreateShader(stage);
  const char* src = text.c_str();
  gl.ShaderSource(s, 1, &src, nullptr);
  gl.CompileShader(s);
  GLint ok = 0;
  gl.GetShaderiv(s, kCompileStatus, &ok);
  if (!ok) {
    char log[4096] = {};
    gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
    fail(std::string("shader: ") + log);
  }
  return s;
}

// The user's shaders: a full-screen triangle, and the ground plane. The camera sits 1 unit
// above the plane looking at the horizon (row 0 at the bottom, the horizon at the top);
// p is the plane point in noise units. Target 0: filtered and point noise, p; target 1:
// the derivatives the filter used.
constexpr const char* kVertex = R"(#version 430 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)";
constexpr const char* kFragment = R"(
layout(location = 0) out vec4 noise_out;
layout(location = 1) out vec4 derivatives_out;
uniform vec2 size;
void main() {
  vec2 uv = gl_FragCoord.xy / size;
  float t = 1.0 / (0.015 + 0.985 * (1.0 - uv.y));  // distance along the ground
  vec2 p = 3.0 * t * vec2(2.0 * uv.x - 1.0, 1.0);
  vec2 dx = dFdx(p), dy = dFdy(p);
  noise_out = vec4(hush_gabor2_filtered(p, dx, dy), hush_gabor2(p), p);
  derivatives_out = vec4(dx, dy);
}
)";

}  // namespace

int main() {
  const int width = 128, height = 96;
  hush::glsl::osmesa_context context;  // or any current GL >= 4.3 context
  const gl_functions gl(context.loader());

  hush::gabor<2>::params prm;
  prm.kind = hush::gabor_kind::anisotropic;
  prm.orientation = 0.25 * 3.14159265358979;
  prm.frequency = 1.5;
  const hush::gabor<2> noise{prm};
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);

  // The program: #version, then hush's kit source, then the user's fragment shader.
  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, compile(gl, kVertexShader, kVertex));
  gl.AttachShader(program,
                  compile(gl, kFragmentShader, "#version 430 core\n" + kit.source + kFragment));
  gl.LinkProgram(program);
  GLint linked = 0;
  gl.GetProgramiv(program, kLinkStatus, &linked);
  if (!linked) fail("link failed");

  // hush's data: one uniform block, its std140 words at its binding (HUSH_GABOR_PARAMS_BINDING).
  for (const hush::glsl::shader_resource& r : kit.resources) {
    if (r.kind != hush::glsl::resource_kind::uniform_block)
      fail("this example binds uniform blocks only");
    GLuint buffer = 0;
    gl.GenBuffers(1, &buffer);
    gl.BindBuffer(kUniformBuffer, buffer);
    gl.BufferData(kUniformBuffer, static_cast<std::ptrdiff_t>(r.words.size() * 4), r.words.data(),
                  kStaticDraw);
    gl.BindBufferBase(kUniformBuffer, r.binding, buffer);
  }

  // Two RGBA32F targets.
  GLuint fbo = 0, targets[2] = {};
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(kFramebuffer, fbo);
  gl.GenTextures(2, targets);
  for (int k = 0; k < 2; ++k) {
    gl.BindTexture(kTexture2d, targets[k]);
    gl.TexImage2D(kTexture2d, 0, static_cast<GLint>(kRgba32f), width, height, 0, kRgba, kFloat,
                  nullptr);
    gl.FramebufferTexture2D(kFramebuffer, kColorAttachment0 + GLenum(k), kTexture2d, targets[k], 0);
  }
  const GLenum draw_buffers[2] = {kColorAttachment0, kColorAttachment0 + 1};
  gl.DrawBuffers(2, draw_buffers);
  GLuint vao = 0;
  gl.GenVertexArrays(1, &vao);
  gl.BindVertexArray(vao);
  gl.Viewport(0, 0, width, height);
  gl.UseProgram(program);
  auto* uniform2f =
      reinterpret_cast<void (*)(GLint, float, float)>(context.loader()("glUniform2f"));
  auto* location =
      reinterpret_cast<GLint (*)(GLuint, const char*)>(context.loader()("glGetUniformLocation"));
  uniform2f(location(program, "size"), float(width), float(height));
  gl.DrawArrays(kTriangles, 0, 3);

  std::vector<float> noise_px(std::size_t(width) * height * 4), deriv_px(noise_px.size());
  gl.ReadBuffer(kColorAttachment0);
  gl.ReadPixels(0, 0, width, height, kRgba, kFloat, noise_px.data());
  gl.ReadBuffer(kColorAttachment0 + 1);
  gl.ReadPixels(0, 0, width, height, kRgba, kFloat, deriv_px.data());
  if (gl.GetError() != 0) fail("GL error");

  // The CPU: the same sample, footprint from the shader's own derivatives.
  double worst = 0, x = 0;
  double near_point = 0, near_filtered = 0, far_point = 0, far_filtered = 0;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float* n = &noise_px[4 * std::size_t(j * width + i)];
      const float* d = &deriv_px[4 * std::size_t(j * width + i)];
      const hush::vec2 p{n[2], n[3]};
      const auto fp =
          hush::footprint<2>::from_derivatives(hush::vec2{d[0], d[1]}, hush::vec2{d[2], d[3]});
      worst = std::max(worst, std::fabs(double(n[0]) - noise.sample(p, fp)));
      worst = std::max(worst, std::fabs(double(n[1]) - noise(p)));
      x = std::max({x, std::fabs(double(p.x)), std::fabs(double(p.y))});
      // Mean squares of the bottom (near) and top (far) quarters.
      if (j < height / 4) {
        near_point += n[1] * n[1];
        near_filtered += n[0] * n[0];
      } else if (j >= 3 * height / 4) {
        far_point += n[1] * n[1];
        far_filtered += n[0] * n[0];
      }
    }
  // shader.hpp's bound at x = max |p_i| / r, the float budget counted twice (GPU and the
  // CPU's float path): scale (N' + 1) [2 2^-21 (1 + 2 pi Phi) F + (2^-24 + 2^-33 x) (2A + 2 pi
  // Phi + k)],
  // F = 1 + 2 pi Phi + pi^2 Phi^2 / A the filter's factor.
  const double two_pi = 2 * 3.14159265358979, phi = noise.marks().phi0() + noise.marks().dphi();
  const double a = noise.kernel().envelope_exponent();
  const double f = 1 + two_pi * phi + two_pi * two_pi / 4 * phi * phi / a;
  const double k = 3 / (1 - hush::detail::constants::kGaborTaperStart);
  x *= noise.inverse_cell();
  const double bound = noise.scale() * (prm.impulses + 1) *
                       (2 * std::ldexp(1.0, -21) * (1 + two_pi * phi) * f +
                        (std::ldexp(1.0, -24) + std::ldexp(x, -33)) * (2 * a + two_pi * phi + k));
  const int quarter_rows = height / 4;  // whole rows
  const double q = double(width) * double(quarter_rows);
  std::printf(
      "hush_gabor2_filtered in a %dx%d fragment shader: largest |GPU - CPU| %.3g "
      "(bound %.3g at %.0f cells from the origin)\n",
      width, height, worst, bound, x);
  std::printf("rms near rows: point %.3f, filtered %.3f; far rows: point %.3f, filtered %.3f\n",
              std::sqrt(near_point / q), std::sqrt(near_filtered / q), std::sqrt(far_point / q),
              std::sqrt(far_filtered / q));
  // A wrong impulse would move a value by about a whole kernel, far beyond the bound.
  return worst <= bound ? 0 : 1;
}
