// The plain GL calls an engine makes to run a hush kit in its own fragment shader
// (examples/shader_perlin.cpp, shader_fractal.cpp, shader_wavelet.cpp): load the entry
// points through the context's loader, compile and link, upload and bind each of the kit's
// resources at its binding (a std140 block, R32F textures), draw a full-screen triangle
// into RGBA32F colour attachments and read them back. No hush GL code is used here.
#ifndef HUSH_EXAMPLES_SHADER_GL_CALLS_HPP
#define HUSH_EXAMPLES_SHADER_GL_CALLS_HPP

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <type_traits>
#include <vector>

#include <hush/glsl/shader.hpp>

namespace example_gl {

using GLenum = unsigned;
using GLuint = unsigned;
using GLint = int;
using GLsizei = int;

constexpr GLenum kVertexShader = 0x8B31, kFragmentShader = 0x8B30, kCompileStatus = 0x8B81,
                 kLinkStatus = 0x8B82, kUniformBuffer = 0x8A11, kStaticDraw = 0x88E4,
                 kTexture2d = 0x0DE1, kTexture3d = 0x806F, kTexture0 = 0x84C0, kR32f = 0x822E,
                 kRed = 0x1903, kFloat = 0x1406, kMinFilter = 0x2801, kMagFilter = 0x2800,
                 kNearest = 0x2600, kWrapS = 0x2802, kWrapT = 0x2803, kWrapR = 0x8072,
                 kRepeat = 0x2901, kClampToEdge = 0x812F, kFramebuffer = 0x8D40,
                 kColorAttachment0 = 0x8CE0, kRgba32f = 0x8814, kRgba = 0x1908,
                 kTriangles = 0x0004, kUnpackAlignment = 0x0CF5, kMax3dTextureSize = 0x8073;

// The GL 4.3 entry points the examples call.
struct gl {
#define EXAMPLE_GL_FN(ret, name, ...) ret (*name)(__VA_ARGS__) = nullptr;
  EXAMPLE_GL_FN(GLuint, CreateShader, GLenum)
  EXAMPLE_GL_FN(void, ShaderSource, GLuint, GLsizei, const char* const*, const GLint*)
  EXAMPLE_GL_FN(void, CompileShader, GLuint)
  EXAMPLE_GL_FN(void, GetShaderiv, GLuint, GLenum, GLint*)
  EXAMPLE_GL_FN(void, GetShaderInfoLog, GLuint, GLsizei, GLsizei*, char*)
  EXAMPLE_GL_FN(GLuint, CreateProgram, void)
  EXAMPLE_GL_FN(void, AttachShader, GLuint, GLuint)
  EXAMPLE_GL_FN(void, LinkProgram, GLuint)
  EXAMPLE_GL_FN(void, GetProgramiv, GLuint, GLenum, GLint*)
  EXAMPLE_GL_FN(void, UseProgram, GLuint)
  EXAMPLE_GL_FN(void, GenBuffers, GLsizei, GLuint*)
  EXAMPLE_GL_FN(void, BindBuffer, GLenum, GLuint)
  EXAMPLE_GL_FN(void, BufferData, GLenum, std::ptrdiff_t, const void*, GLenum)
  EXAMPLE_GL_FN(void, BindBufferBase, GLenum, GLuint, GLuint)
  EXAMPLE_GL_FN(void, GenTextures, GLsizei, GLuint*)
  EXAMPLE_GL_FN(void, ActiveTexture, GLenum)
  EXAMPLE_GL_FN(void, BindTexture, GLenum, GLuint)
  EXAMPLE_GL_FN(void, TexParameteri, GLenum, GLenum, GLint)
  EXAMPLE_GL_FN(void, PixelStorei, GLenum, GLint)
  EXAMPLE_GL_FN(void, TexImage2D, GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum,
                const void*)
  EXAMPLE_GL_FN(void, TexImage3D, GLenum, GLint, GLint, GLsizei, GLsizei, GLsizei, GLint, GLenum,
                GLenum, const void*)
  EXAMPLE_GL_FN(void, GetIntegerv, GLenum, GLint*)
  EXAMPLE_GL_FN(void, GenFramebuffers, GLsizei, GLuint*)
  EXAMPLE_GL_FN(void, BindFramebuffer, GLenum, GLuint)
  EXAMPLE_GL_FN(void, FramebufferTexture2D, GLenum, GLenum, GLenum, GLuint, GLint)
  EXAMPLE_GL_FN(void, DrawBuffers, GLsizei, const GLenum*)
  EXAMPLE_GL_FN(void, ReadBuffer, GLenum)
  EXAMPLE_GL_FN(void, GenVertexArrays, GLsizei, GLuint*)
  EXAMPLE_GL_FN(void, BindVertexArray, GLuint)
  EXAMPLE_GL_FN(void, Viewport, GLint, GLint, GLsizei, GLsizei)
  EXAMPLE_GL_FN(void, DrawArrays, GLenum, GLint, GLsizei)
  EXAMPLE_GL_FN(void, ReadPixels, GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void*)
#undef EXAMPLE_GL_FN

  template <class Loader>
  explicit gl(Loader loader) {
    auto get = [&](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(loader(name));
      if (!fn) {
        std::fprintf(stderr, "no %s\n", name);
        std::exit(1);
      }
    };
#define EXAMPLE_GL_GET(name) get(name, "gl" #name);
    EXAMPLE_GL_GET(CreateShader) EXAMPLE_GL_GET(ShaderSource) EXAMPLE_GL_GET(CompileShader)
    EXAMPLE_GL_GET(GetShaderiv) EXAMPLE_GL_GET(GetShaderInfoLog) EXAMPLE_GL_GET(CreateProgram)
    EXAMPLE_GL_GET(AttachShader) EXAMPLE_GL_GET(LinkProgram) EXAMPLE_GL_GET(GetProgramiv)
    EXAMPLE_GL_GET(UseProgram) EXAMPLE_GL_GET(GenBuffers) EXAMPLE_GL_GET(BindBuffer)
    EXAMPLE_GL_GET(BufferData) EXAMPLE_GL_GET(BindBufferBase) EXAMPLE_GL_GET(GenTextures)
    EXAMPLE_GL_GET(ActiveTexture) EXAMPLE_GL_GET(BindTexture) EXAMPLE_GL_GET(TexParameteri)
    EXAMPLE_GL_GET(PixelStorei) EXAMPLE_GL_GET(TexImage2D) EXAMPLE_GL_GET(TexImage3D)
    EXAMPLE_GL_GET(GetIntegerv) EXAMPLE_GL_GET(GenFramebuffers) EXAMPLE_GL_GET(BindFramebuffer)
    EXAMPLE_GL_GET(FramebufferTexture2D) EXAMPLE_GL_GET(DrawBuffers) EXAMPLE_GL_GET(ReadBuffer)
    EXAMPLE_GL_GET(GenVertexArrays) EXAMPLE_GL_GET(BindVertexArray) EXAMPLE_GL_GET(Viewport)
    EXAMPLE_GL_GET(DrawArrays) EXAMPLE_GL_GET(ReadPixels)
#undef EXAMPLE_GL_GET
  }

  GLuint shader(GLenum stage, const std::string& text) const {
    const GLuint s = CreateShader(stage);
    const char* src = text.c_str();
    ShaderSource(s, 1, &src, nullptr);
    CompileShader(s);
    GLint ok = 0;
    GetShaderiv(s, kCompileStatus, &ok);
    if (!ok) {
      char log[4096];
      GetShaderInfoLog(s, sizeof log, nullptr, log);
      std::fprintf(stderr, "shader does not compile:\n%s\n", log);
      std::exit(1);
    }
    return s;
  }
  // A program of a full-screen triangle and `fragment`.
  GLuint program(const std::string& fragment) const {
    const GLuint p = CreateProgram();
    AttachShader(p, shader(kVertexShader,
                           "#version 430 core\nvoid main() {\n"
                           "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0,\n"
                           "                float((gl_VertexID & 2) << 1) - 1.0);\n"
                           "  gl_Position = vec4(p, 0.0, 1.0);\n}\n"));
    AttachShader(p, shader(kFragmentShader, fragment));
    LinkProgram(p);
    GLint ok = 0;
    GetProgramiv(p, kLinkStatus, &ok);
    if (!ok) {
      std::fprintf(stderr, "program does not link\n");
      std::exit(1);
    }
    return p;
  }

  // Uploads each resource of the kit and binds it at its binding: blocks as uniform
  // buffers, textures (R32F here) on texture unit `binding`, filtering and wrap as stated.
  void bind_kit(const hush::glsl::shader_kit& kit) const {
    for (const hush::glsl::shader_resource& r : kit.resources) {
      if (r.kind == hush::glsl::resource_kind::uniform_block) {
        GLuint buf = 0;
        GenBuffers(1, &buf);
        BindBuffer(kUniformBuffer, buf);
        BufferData(kUniformBuffer, std::ptrdiff_t(r.words.size() * 4), r.words.data(), kStaticDraw);
        BindBufferBase(kUniformBuffer, r.binding, buf);
        continue;
      }
      const bool three = r.kind == hush::glsl::resource_kind::texture_3d;
      const GLenum target = three ? kTexture3d : kTexture2d;
      if (three) {  // the tile must fit this GL's 3D texture limit
        GLint most = 0;
        GetIntegerv(kMax3dTextureSize, &most);
        if (GLint(r.width) > most) std::fprintf(stderr, "%s exceeds GL_MAX_3D_TEXTURE_SIZE\n", r.name.c_str());
      }
      GLuint tex = 0;
      GenTextures(1, &tex);
      ActiveTexture(kTexture0 + r.binding);
      BindTexture(target, tex);
      PixelStorei(kUnpackAlignment, 4);
      if (three)
        TexImage3D(target, 0, GLint(kR32f), GLsizei(r.width), GLsizei(r.height), GLsizei(r.depth),
                   0, kRed, kFloat, r.words.data());
      else
        TexImage2D(target, 0, GLint(kR32f), GLsizei(r.width), GLsizei(r.height), 0, kRed, kFloat,
                   r.words.data());
      const GLint wrap = GLint(r.repeat ? kRepeat : kClampToEdge);
      TexParameteri(target, kMinFilter, GLint(kNearest));
      TexParameteri(target, kMagFilter, GLint(kNearest));
      TexParameteri(target, kWrapS, wrap);
      TexParameteri(target, kWrapT, wrap);
      if (three) TexParameteri(target, kWrapR, wrap);
    }
    ActiveTexture(kTexture0);
  }

  // Draws `program` into `outputs` RGBA32F attachments of size x size and returns each
  // one's pixels (RGBA, row 0 at the bottom).
  std::vector<std::vector<float>> draw(GLuint prog, int size, int outputs) const {
    GLuint fbo = 0, vao = 0;
    GenFramebuffers(1, &fbo);
    BindFramebuffer(kFramebuffer, fbo);
    std::vector<GLenum> bufs;
    for (int i = 0; i < outputs; ++i) {
      GLuint tex = 0;
      GenTextures(1, &tex);
      BindTexture(kTexture2d, tex);
      TexImage2D(kTexture2d, 0, GLint(kRgba32f), size, size, 0, kRgba, kFloat, nullptr);
      FramebufferTexture2D(kFramebuffer, kColorAttachment0 + GLenum(i), kTexture2d, tex, 0);
      bufs.push_back(kColorAttachment0 + GLenum(i));
    }
    DrawBuffers(outputs, bufs.data());
    GenVertexArrays(1, &vao);
    BindVertexArray(vao);
    Viewport(0, 0, size, size);
    UseProgram(prog);
    DrawArrays(kTriangles, 0, 3);
    std::vector<std::vector<float>> out;
    for (int i = 0; i < outputs; ++i) {
      out.emplace_back(std::size_t(size) * std::size_t(size) * 4u);
      ReadBuffer(kColorAttachment0 + GLenum(i));
      ReadPixels(0, 0, size, size, kRgba, kFloat, out.back().data());
    }
    return out;
  }
};

}  // namespace example_gl

#endif  // HUSH_EXAMPLES_SHADER_GL_CALLS_HPP
