// Anisotropic noise in your own fragment shader (hush/glsl/anisotropic/shader.hpp): a receding
// plane whose uv the shader computes per pixel, filtered with the shader's own dFdx(uv) and
// dFdy(uv). The engine side is plain GL: the kit's block goes to a uniform buffer at its
// binding, its two tiles to RGBA32F textures at theirs. The program reads the image back and
// prints the largest difference from the CPU's sample at the same uv and derivatives, which a
// second render target carries.
#include <GL/glcorearb.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <hush/glsl/anisotropic/shader.hpp>
#include <hush/glsl/osmesa_context.hpp>
#include <hush/hush.hpp>

namespace {

// The GL entry points this program uses, from the context's loader.
struct gl_functions {
  PFNGLCREATESHADERPROC CreateShader;
  PFNGLSHADERSOURCEPROC ShaderSource;
  PFNGLCOMPILESHADERPROC CompileShader;
  PFNGLGETSHADERIVPROC GetShaderiv;
  PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog;
  PFNGLCREATEPROGRAMPROC CreateProgram;
  PFNGLATTACHSHADERPROC AttachShader;
  PFNGLLINKPROGRAMPROC LinkProgram;
  PFNGLUSEPROGRAMPROC UseProgram;
  PFNGLGENBUFFERSPROC GenBuffers;
  PFNGLBINDBUFFERPROC BindBuffer;
  PFNGLBUFFERDATAPROC BufferData;
  PFNGLBINDBUFFERBASEPROC BindBufferBase;
  PFNGLGENTEXTURESPROC GenTextures;
  PFNGLBINDTEXTUREPROC BindTexture;
  PFNGLACTIVETEXTUREPROC ActiveTexture;
  PFNGLTEXIMAGE2DPROC TexImage2D;
  PFNGLTEXPARAMETERIPROC TexParameteri;
  PFNGLGENFRAMEBUFFERSPROC GenFramebuffers;
  PFNGLBINDFRAMEBUFFERPROC BindFramebuffer;
  PFNGLFRAMEBUFFERTEXTURE2DPROC FramebufferTexture2D;
  PFNGLDRAWBUFFERSPROC DrawBuffers;
  PFNGLREADBUFFERPROC ReadBuffer;
  PFNGLGENVERTEXARRAYSPROC GenVertexArrays;
  PFNGLBINDVERTEXARRAYPROC BindVertexArray;
  PFNGLVIEWPORTPROC Viewport;
  PFNGLDRAWARRAYSPROC DrawArrays;
  PFNGLREADPIXELSPROC ReadPixels;
  explicit gl_functions(void* (*load)(const char*)) {
#define HUSH_EXAMPLE_LOAD(name) name = reinterpret_cast<decltype(name)>(load("gl" #name))
    HUSH_EXAMPLE_LOAD(CreateShader);
    HUSH_EXAMPLE_LOAD(ShaderSource);
    HUSH_EXAMPLE_LOAD(CompileShader);
    HUSH_EXAMPLE_LOAD(GetShaderiv);
    HUSH_EXAMPLE_LOAD(GetShaderInfoLog);
    HUSH_EXAMPLE_LOAD(CreateProgram);
    HUSH_EXAMPLE_LOAD(AttachShader);
    HUSH_EXAMPLE_LOAD(LinkProgram);
    HUSH_EXAMPLE_LOAD(UseProgram);
    HUSH_EXAMPLE_LOAD(GenBuffers);
    HUSH_EXAMPLE_LOAD(BindBuffer);
    HUSH_EXAMPLE_LOAD(BufferData);
    HUSH_EXAMPLE_LOAD(BindBufferBase);
    HUSH_EXAMPLE_LOAD(GenTextures);
    HUSH_EXAMPLE_LOAD(BindTexture);
    HUSH_EXAMPLE_LOAD(ActiveTexture);
    HUSH_EXAMPLE_LOAD(TexImage2D);
    HUSH_EXAMPLE_LOAD(TexParameteri);
    HUSH_EXAMPLE_LOAD(GenFramebuffers);
    HUSH_EXAMPLE_LOAD(BindFramebuffer);
    HUSH_EXAMPLE_LOAD(FramebufferTexture2D);
    HUSH_EXAMPLE_LOAD(DrawBuffers);
    HUSH_EXAMPLE_LOAD(ReadBuffer);
    HUSH_EXAMPLE_LOAD(GenVertexArrays);
    HUSH_EXAMPLE_LOAD(BindVertexArray);
    HUSH_EXAMPLE_LOAD(Viewport);
    HUSH_EXAMPLE_LOAD(DrawArrays);
    HUSH_EXAMPLE_LOAD(ReadPixels);
#undef HUSH_EXAMPLE_LOAD
  }
};

GLuint compile(const gl_functions& gl, GLenum stage, const std::string& text) {
  const GLuint s = gl.CreateShader(stage);
  const char* src = text.c_str();
  gl.ShaderSource(s, 1, &src, nullptr);
  gl.CompileShader(s);
  GLint ok = 0;
  gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.GetShaderInfoLog(s, sizeof log, nullptr, log);
    std::fprintf(stderr, "shader: %s\n", log);
  }
  return s;
}

// The user's fragment shader: the plane's uv per pixel (a camera looking at the ground, the
// horizon at the top), the noise filtered by the pixel's footprint, and the uv and its
// derivatives in a second target for the comparison below.
const char* kUserShader = R"glsl(
layout(location = 0) out vec4 noise_out;  // noise, uv
layout(location = 1) out vec4 jacobian_out;  // dFdx(uv), dFdy(uv)
void main() {
  vec2 s = gl_FragCoord.xy;
  float depth = 1.0 / (1.0 - s.y / 140.0);   // grows towards the horizon (y = 140)
  vec2 uv = vec2((s.x - 128.0) / 32.0, 4.0) * depth;
  float n = hush_anisotropic(uv, dFdx(uv), dFdy(uv));
  noise_out = vec4(n, uv, 0.0);
  jacobian_out = vec4(dFdx(uv), dFdy(uv));
}
)glsl";

}  // namespace

int main() {
  hush::glsl::osmesa_context context;  // or your engine's GL 4.3 context
  const gl_functions gl(context.loader());
  hush::anisotropic::params p;
  p.orientations = 4;
  p.scales = 3;
  p.octaves = 3;
  p.frequency = 2.0;
  const hush::anisotropic noise(p);
  const hush::glsl::shader_kit kit = hush::glsl::shader_for(noise);

  // The kit's resources at their bindings: the block, then the two tiles.
  for (const hush::glsl::shader_resource& r : kit.resources) {
    if (r.kind == hush::glsl::resource_kind::uniform_block) {
      GLuint buffer = 0;
      gl.GenBuffers(1, &buffer);
      gl.BindBuffer(GL_UNIFORM_BUFFER, buffer);
      gl.BufferData(GL_UNIFORM_BUFFER, GLsizeiptr(r.words.size() * 4), r.words.data(),
                    GL_STATIC_DRAW);
      gl.BindBufferBase(GL_UNIFORM_BUFFER, r.binding, buffer);
    } else {  // texture_2d, RGBA32F, read with texelFetch
      GLuint tex = 0;
      gl.GenTextures(1, &tex);
      gl.ActiveTexture(GL_TEXTURE0 + r.binding);
      gl.BindTexture(GL_TEXTURE_2D, tex);
      gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, GLsizei(r.width), GLsizei(r.height), 0, GL_RGBA,
                    GL_FLOAT, r.words.data());
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
      gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
  }

  const GLuint program = gl.CreateProgram();
  gl.AttachShader(program, compile(gl, GL_VERTEX_SHADER,
                                   "#version 430 core\nvoid main() {\n"
                                   "  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0,\n"
                                   "                float((gl_VertexID & 2) << 1) - 1.0);\n"
                                   "  gl_Position = vec4(p, 0.0, 1.0);\n}\n"));
  gl.AttachShader(
      program, compile(gl, GL_FRAGMENT_SHADER, "#version 430 core\n" + kit.source + kUserShader));
  gl.LinkProgram(program);

  // Two RGBA32F targets of 256 x 128 pixels.
  const int w = 256, h = 128;
  GLuint targets[2] = {0, 0}, fbo = 0, vao = 0;
  gl.GenTextures(2, targets);
  gl.GenFramebuffers(1, &fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
  for (int t = 0; t < 2; ++t) {
    gl.BindTexture(GL_TEXTURE_2D, targets[t]);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + t), GL_TEXTURE_2D,
                            targets[t], 0);
  }
  const GLenum draw[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl.DrawBuffers(2, draw);
  gl.GenVertexArrays(1, &vao);
  gl.BindVertexArray(vao);
  gl.Viewport(0, 0, w, h);
  gl.UseProgram(program);
  gl.DrawArrays(GL_TRIANGLES, 0, 3);

  std::vector<float> image(std::size_t(w) * h * 4), jac(image.size());
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, image.data());
  gl.ReadBuffer(GL_COLOR_ATTACHMENT1);
  gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, jac.data());

  // The CPU at the same uv and derivatives.
  double worst = 0, worst_tol = 0, mean_abs = 0;
  for (std::size_t q = 0; q < std::size_t(w) * h; ++q) {
    const hush::vec2 uv{image[4 * q + 1], image[4 * q + 2]};
    const hush::vec2 dx{jac[4 * q], jac[4 * q + 1]}, dy{jac[4 * q + 2], jac[4 * q + 3]};
    const float cpu = noise.sample(uv, hush::footprint<2>::from_derivatives(dx, dy));
    const double e = std::fabs(double(image[4 * q]) - cpu);
    const double tol = hush::glsl::anisotropic_shader_tolerance(noise, uv, dx, dy, nullptr);
    worst = std::max(worst, e);
    worst_tol = std::max(worst_tol, e / tol);
    mean_abs += std::fabs(double(cpu));
  }
  std::printf("%d x %d pixels of anisotropic noise in a user fragment shader\n", w, h);
  std::printf("largest |gpu - cpu| = %.3g (mean |noise| %.3f); largest error / tolerance %.3f\n",
              worst, mean_abs / double(w * h), worst_tol);
  return worst_tol <= 1.0 ? 0 : 1;
}
