// NPR Gabor noise from an engine's own G-buffer and triangle buffers, resident on the GPU: the
// program owns the depth, object-id and triangle-id textures, the vertex and triangle storage
// buffers (here filled from an analytic scene: a plane of 2 x 7 x 5 triangles facing the
// camera over an empty background) and an R32F output texture; hush::glsl::npr_gabor_gl_render
// runs both stages of the noise from them into the output. The output is read back here only
// to print its largest difference from the CPU (exec::scalar). Runs on whichever headless
// context the machine has (EGL on a GPU, else OSMesa).
#include <hush/glsl/headless.hpp>
#include <hush/glsl/npr_gabor/frame.hpp>
#include <hush/hush.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

// Named (not anonymous): example programs share translation units in tools/tidy.sh.
namespace shader_npr_gabor_example {

// The GL calls this program makes itself (GL 4.3 core), through the context's loader.
using GLuint = unsigned int;
using GLenum = unsigned int;
constexpr GLenum kTexture2d = 0x0DE1, kR32f = 0x822E, kR32ui = 0x8236, kRed = 0x1903,
                 kRedInteger = 0x8D94, kFloat = 0x1406, kUnsignedInt = 0x1405,
                 kPackAlignment = 0x0D05, kShaderStorageBuffer = 0x90D2, kStaticDraw = 0x88E4;
struct gl_calls {
  void(HUSH_GLAPI* GenTextures)(int, GLuint*);
  void(HUSH_GLAPI* DeleteTextures)(int, const GLuint*);
  void(HUSH_GLAPI* BindTexture)(GLenum, GLuint);
  void(HUSH_GLAPI* TexImage2D)(GLenum, int, int, int, int, int, GLenum, GLenum, const void*);
  void(HUSH_GLAPI* GetTexImage)(GLenum, int, GLenum, GLenum, void*);
  void(HUSH_GLAPI* PixelStorei)(GLenum, int);
  void(HUSH_GLAPI* GenBuffers)(int, GLuint*);
  void(HUSH_GLAPI* DeleteBuffers)(int, const GLuint*);
  void(HUSH_GLAPI* BindBuffer)(GLenum, GLuint);
  void(HUSH_GLAPI* BufferData)(GLenum, std::ptrdiff_t, const void*, GLenum);
  template <class F>
  static void load(hush::glsl::detail::loader_fn loader, F& f, const char* name) {
    f = reinterpret_cast<F>(loader(name));
  }
  explicit gl_calls(hush::glsl::detail::loader_fn l) {
    load(l, GenTextures, "glGenTextures");
    load(l, DeleteTextures, "glDeleteTextures");
    load(l, BindTexture, "glBindTexture");
    load(l, TexImage2D, "glTexImage2D");
    load(l, GetTexImage, "glGetTexImage");
    load(l, PixelStorei, "glPixelStorei");
    load(l, GenBuffers, "glGenBuffers");
    load(l, DeleteBuffers, "glDeleteBuffers");
    load(l, BindBuffer, "glBindBuffer");
    load(l, BufferData, "glBufferData");
  }
  GLuint texture(GLenum internal, int w, int h, GLenum layout, GLenum type,
                 const void* data) const {
    GLuint t = 0;
    GenTextures(1, &t);
    BindTexture(kTexture2d, t);
    TexImage2D(kTexture2d, 0, static_cast<int>(internal), w, h, 0, layout, type, data);
    return t;
  }
  GLuint buffer(const void* data, std::size_t bytes) const {
    GLuint b = 0;
    GenBuffers(1, &b);
    BindBuffer(kShaderStorageBuffer, b);
    BufferData(kShaderStorageBuffer, static_cast<std::ptrdiff_t>(bytes), data, kStaticDraw);
    return b;
  }
};

int run() {
  hush::glsl::headless_device gpu;  // or hush::glsl::device on your own current context
  const gl_calls gl(gpu.context.loader());
  const int w = 128, h = 96, nx = 7, ny = 5;
  const double x0 = 8.0, y0 = 6.0, cell = 16.0;
  const float z = 3.0f;  // the plane's depth
  // The scene: vertices (screen x, y; depth), two triangles per cell (clockwise on the y-down
  // screen: front-facing), object 1; the G-buffer per pixel centre.
  std::vector<hush::vec2> screen;
  std::vector<float> vdepth;
  std::vector<std::uint32_t> indices, tri_id, obj_id;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      screen.push_back({static_cast<float>(x0 + cell * i), static_cast<float>(y0 + cell * j)});
      vdepth.push_back(z);
    }
  auto v = [&](int i, int j) { return static_cast<std::uint32_t>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const auto q = static_cast<std::uint32_t>(j * nx + i);
      indices.insert(indices.end(), {v(i, j), v(i, j + 1), v(i + 1, j)});
      indices.insert(indices.end(), {v(i + 1, j), v(i, j + 1), v(i + 1, j + 1)});
      tri_id.insert(tri_id.end(), {2 * q, 2 * q + 1});
      obj_id.insert(obj_id.end(), {1u, 1u});
    }
  const std::size_t n = static_cast<std::size_t>(w) * h;
  std::vector<float> depth(n, std::numeric_limits<float>::infinity());
  std::vector<std::uint32_t> object(n, 0u), triangle(n, 0xFFFFFFFFu);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double fx = (x + 0.5 - x0) / cell, fy = (y + 0.5 - y0) / cell;
      if (!(fx >= 0 && fy >= 0 && fx < nx && fy < ny)) continue;
      const int i = static_cast<int>(fx), j = static_cast<int>(fy);
      const auto q = static_cast<std::uint32_t>(j * nx + i);
      const std::size_t p =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      depth[p] = z;
      object[p] = 1u;
      triangle[p] = (fx - i) + (fy - j) < 1.0 ? 2 * q : 2 * q + 1;
    }
  hush::triangle_list tris;
  tris.indices = indices;
  tris.screen = screen;
  tris.depth = vdepth;
  tris.triangle_id = tri_id;
  tris.object_id = obj_id;
  // The engine's GL objects: G-buffer textures, the triangles in the two buffer layouts
  // (hush/glsl/npr_gabor/gl_frame.hpp), the target.
  std::vector<float> vertex_words;
  std::vector<std::uint32_t> triangle_words;
  hush::glsl::npr_gabor_gl_pack(tris, vertex_words, triangle_words);
  hush::glsl::npr_gabor_gl_frame f;
  f.depth = gl.texture(kR32f, w, h, kRed, kFloat, depth.data());
  f.object_id = gl.texture(kR32ui, w, h, kRedInteger, kUnsignedInt, object.data());
  f.triangle_id = gl.texture(kR32ui, w, h, kRedInteger, kUnsignedInt, triangle.data());
  f.width = w;
  f.height = h;
  f.vertices = gl.buffer(vertex_words.data(), vertex_words.size() * 4);
  f.triangles = gl.buffer(triangle_words.data(), triangle_words.size() * 4);
  f.vertex_count = static_cast<std::uint32_t>(tris.vertices());
  f.triangle_count = static_cast<std::uint32_t>(tris.triangles());
  const GLuint out = gl.texture(kR32f, w, h, kRed, kFloat, nullptr);
  hush::npr_gabor::params prm;
  prm.frequency = 0.12;
  prm.bandwidth = 0.2;
  prm.impulses = 16;
  const hush::npr_gabor noise(prm);
  hush::glsl::npr_gabor_gl_render(gpu.device, noise, f, out);  // both stages; no image read-back
  // The comparison: the CPU on the same frame, and the texture read back.
  hush::frame cpu_frame;
  cpu_frame.depth = {depth.data(), std::size_t(w), std::size_t(h)};
  cpu_frame.object_id = {object.data(), std::size_t(w), std::size_t(h)};
  cpu_frame.triangle_id = {triangle.data(), std::size_t(w), std::size_t(h)};
  std::vector<float> expected(n), got(n);
  noise.render(hush::exec::scalar, cpu_frame, tris,
               hush::image_view<float>(expected.data(), std::size_t(w), std::size_t(h)));
  gl.BindTexture(kTexture2d, out);
  gl.PixelStorei(kPackAlignment, 4);
  gl.GetTexImage(kTexture2d, 0, kRed, kFloat, got.data());
  double worst = 0, largest = 0;
  for (std::size_t p = 0; p < n; ++p) {
    worst = std::max(worst, double(std::fabs(got[p] - expected[p])));
    largest = std::max(largest, double(std::fabs(expected[p])));
  }
  // The float kernels' rounding (hush/glsl/npr_gabor/renderer.hpp derives the bound per
  // pixel): well below 1e-4 of the largest value for these parameters.
  const double bound = 1e-4 * largest;
  std::printf("NPR Gabor noise from GL textures and buffers, %dx%d, %u triangles, on %s\n", w, h,
              f.triangle_count, gpu.device.renderer().c_str());
  std::printf("max |gpu - cpu| = %.3g (largest |cpu| %.3g, bound %.3g)\n", worst, largest, bound);
  const GLuint textures[4] = {f.depth, f.object_id, f.triangle_id, out};
  const GLuint buffers[2] = {f.vertices, f.triangles};
  gl.DeleteTextures(4, textures);
  gl.DeleteBuffers(2, buffers);
  return worst <= bound ? 0 : 1;
}

}  // namespace shader_npr_gabor_example

int main() { return shader_npr_gabor_example::run(); }
