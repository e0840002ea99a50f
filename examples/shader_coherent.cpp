// Coherent noise from an engine's own G-buffer, resident on the GPU: the program owns the
// depth, velocity and object-id textures (here filled from an analytic scene: a disc turning
// over a still background) and an R32F output texture; hush::glsl::coherent_gl_stream reads
// the first and writes the second each frame, keeping its history on the GPU. The output is
// read back here only to print its largest difference from the CPU (exec::scalar) on the same
// frames. Runs on whichever headless context the machine has (EGL on a GPU, else OSMesa).
#include <hush/glsl/coherent/frame.hpp>
#include <hush/glsl/headless.hpp>
#include <hush/hush.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

// Named (not anonymous): example programs share translation units in tools/tidy.sh.
namespace shader_coherent_example {

// The GL calls this program makes itself (GL 4.3 core), through the context's loader.
using GLuint = unsigned int;
using GLenum = unsigned int;
constexpr GLenum kTexture2d = 0x0DE1, kR32f = 0x822E, kRgb32f = 0x8815, kR32ui = 0x8236,
                 kRed = 0x1903, kRgb = 0x1907, kRedInteger = 0x8D94, kFloat = 0x1406,
                 kUnsignedInt = 0x1405, kPackAlignment = 0x0D05;
struct gl_calls {
  void(HUSH_GLAPI* GenTextures)(int, GLuint*);
  void(HUSH_GLAPI* DeleteTextures)(int, const GLuint*);
  void(HUSH_GLAPI* BindTexture)(GLenum, GLuint);
  void(HUSH_GLAPI* TexImage2D)(GLenum, int, int, int, int, int, GLenum, GLenum, const void*);
  void(HUSH_GLAPI* TexSubImage2D)(GLenum, int, int, int, int, int, GLenum, GLenum, const void*);
  void(HUSH_GLAPI* GetTexImage)(GLenum, int, GLenum, GLenum, void*);
  void(HUSH_GLAPI* PixelStorei)(GLenum, int);
  template <class F>
  static void load(hush::glsl::detail::loader_fn loader, F& f, const char* name) {
    f = reinterpret_cast<F>(loader(name));
  }
  explicit gl_calls(hush::glsl::detail::loader_fn l) {
    load(l, GenTextures, "glGenTextures");
    load(l, DeleteTextures, "glDeleteTextures");
    load(l, BindTexture, "glBindTexture");
    load(l, TexImage2D, "glTexImage2D");
    load(l, TexSubImage2D, "glTexSubImage2D");
    load(l, GetTexImage, "glGetTexImage");
    load(l, PixelStorei, "glPixelStorei");
  }
  GLuint texture(GLenum internal, int w, int h, GLenum layout, GLenum type) const {
    GLuint t = 0;
    GenTextures(1, &t);
    BindTexture(kTexture2d, t);
    TexImage2D(kTexture2d, 0, static_cast<int>(internal), w, h, 0, layout, type, nullptr);
    return t;
  }
  void fill(GLuint t, int w, int h, GLenum layout, GLenum type, const void* data) const {
    BindTexture(kTexture2d, t);
    TexSubImage2D(kTexture2d, 0, 0, 0, w, h, layout, type, data);
  }
};

// Frame i's G-buffer: a disc of radius 0.4 min(w, h) at depth 2 turning by `omega` radians a
// frame about the image centre, over a background at depth 4 (object ids 1 and 2).
struct gbuffer {
  std::vector<float> depth, velocity;
  std::vector<std::uint32_t> ids;
  gbuffer(int w, int h, double omega) {
    const double cx = 0.5 * w, cy = 0.5 * h, r = 0.4 * std::min(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
        const bool disc = dx * dx + dy * dy < r * r;
        // Backward velocity: the point now at p was at p - v last frame.
        const double px = cx + std::cos(omega) * dx + std::sin(omega) * dy,
                     py = cy - std::sin(omega) * dx + std::cos(omega) * dy;
        depth.push_back(disc ? 2.0f : 4.0f);
        velocity.insert(velocity.end(), {disc ? static_cast<float>(x + 0.5 - px) : 0.0f,
                                         disc ? static_cast<float>(y + 0.5 - py) : 0.0f, 0.0f});
        ids.push_back(disc ? 1u : 2u);
      }
  }
};

int run() {
  hush::glsl::headless_device gpu;  // or hush::glsl::device on your own current context
  const gl_calls gl(gpu.context.loader());
  const int w = 160, h = 120, frames = 8;
  hush::coherent_params prm;
  prm.alpha = 0.9;
  // The engine's textures: the G-buffer it renders each frame, and the noise's target.
  const GLuint depth = gl.texture(kR32f, w, h, kRed, kFloat);
  const GLuint velocity = gl.texture(kRgb32f, w, h, kRgb, kFloat);
  const GLuint ids = gl.texture(kR32ui, w, h, kRedInteger, kUnsignedInt);
  const GLuint noise = gl.texture(kR32f, w, h, kRed, kFloat);
  hush::glsl::coherent_gl_stream stream(gpu.device, prm, w, h);
  hush::coherent_stream cpu(prm);  // the same frames on the CPU, for the comparison
  std::vector<float> expected(static_cast<std::size_t>(w) * h), got(expected.size());
  double worst = 0;
  for (int i = 0; i < frames; ++i) {
    const gbuffer g(w, h, 0.03);
    gl.fill(depth, w, h, kRed, kFloat, g.depth.data());
    gl.fill(velocity, w, h, kRgb, kFloat, g.velocity.data());
    gl.fill(ids, w, h, kRedInteger, kUnsignedInt, g.ids.data());
    hush::glsl::coherent_gl_frame frame;  // the G-buffer's texture names and size
    frame.depth = depth;
    frame.velocity = velocity;
    frame.ids = ids;
    frame.width = w;
    frame.height = h;
    stream.advance(frame, noise);  // one dispatch, nothing read back
    // The comparison: the CPU's frame, and the texture read back.
    hush::frame f;
    f.depth = {g.depth.data(), std::size_t(w), std::size_t(h)};
    f.velocity = {reinterpret_cast<const hush::vec3*>(g.velocity.data()), std::size_t(w),
                  std::size_t(h)};
    f.object_id = {g.ids.data(), std::size_t(w), std::size_t(h)};
    cpu.advance(hush::exec::scalar, f, hush::image_view<float>(expected.data(), w, h));
    gl.BindTexture(kTexture2d, noise);
    gl.PixelStorei(kPackAlignment, 4);
    gl.GetTexImage(kTexture2d, 0, kRed, kFloat, got.data());
    for (std::size_t p = 0; p < got.size(); ++p)
      worst = std::max(worst, double(std::fabs(got[p] - expected[p])));
  }
  // The blends' float rounding on both sides, contracting by alpha (docs/coherent.md): for
  // outputs of magnitude <= 8, 2 (12 / (1 - alpha) + 1) 2^-24 8.
  const double bound = 2 * (12 / (1 - prm.alpha) + 1) * std::ldexp(1.0, -24) * 8;
  std::printf("coherent noise from GL textures, %d frames of %dx%d on %s\n", frames, w, h,
              gpu.device.renderer().c_str());
  std::printf("max |gpu - cpu| = %.3g (bound %.3g)\n", worst, bound);
  const GLuint names[4] = {depth, velocity, ids, noise};
  gl.DeleteTextures(4, names);
  return worst <= bound ? 0 : 1;
}

}  // namespace shader_coherent_example

int main() { return shader_coherent_example::run(); }
