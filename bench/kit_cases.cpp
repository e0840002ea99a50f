// hush — the speed-vs-error benchmark: each noise's shader kit (hush/glsl/shader.hpp) in a user's
// own fragment shader, the rows "<noise>, glsl kit, fragment W x H".
//
// The workload is what examples/shader_<noise>.cpp do, at the frame's size: hush's kit source
// pasted into a fragment shader whose main() computes a receding ground plane's position p
// from gl_FragCoord (a perspective map: 1 to kFar units away from the bottom row to the top),
// evaluates the noise there (the filtered noises over the pixel's footprint from the shader's
// own dFdx(p), dFdy(p)) and writes it to an R32F texture of the frame's size. The kit's
// resources are uploaded once by hush::glsl::bound_kit; a frame is bound_kit::bind(), the
// program and one full-screen triangle. run() is a frame and a glFinish (the table's wall
// time, as the "glsl resident" rows); the quality note adds the host's time of the frame's
// calls alone and the GPU's time of its commands (GL_TIME_ELAPSED, gl_timing.hpp), medians.
//
// Error, outside the timing: the output texture read back once, at kCheckPixels pixels spread
// evenly over the frame, against the CPU's double reference at the same float position and
// derivatives, which a second draw of the same shader (HUSH_BENCH_CHECK: two more colour
// attachments) writes out. One table (kit_rows) lists the rows; the GL plumbing is one
// struct (kit_frame) for all of them.
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "gl_timing.hpp"
#include "hush/glsl/anisotropic/shader.hpp"
#include "hush/glsl/detail/gl.hpp"
#include "hush/glsl/detail/gl_raster.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/fractal/shader.hpp"
#include "hush/glsl/gabor/shader.hpp"
#include "hush/glsl/perlin/shader.hpp"
#include "hush/glsl/shader.hpp"
#include "hush/glsl/wavelet/shader.hpp"
#include "hush/hush.hpp"
#include "rows.hpp"

namespace hush_bench {
namespace {

namespace d = hush::glsl::detail;

// The ground plane: the bottom row 1 unit away, the top row kFar units (the horizon is out of
// view, so footprints grow kFar-fold across the frame and stay finite); kPlaneScale noise
// units per plane unit, the bottom row kPlaneScale * 2 * aspect units wide. Positions stay
// within |p| <= kPlaneScale * kFar * aspect (57 at 16:9), where every kit's float error is
// near its floor.
constexpr double kFar = 16;
constexpr double kPlaneScale = 2;
// The error's subsample: this many pixels, evenly spread over the frame in row-major order.
constexpr std::size_t kCheckPixels = 4096;
// Frames in the host and GPU medians of the note (llvmpipe takes seconds per 1080p Gabor frame).
constexpr int kTimedFrames = 5;

// One row: the noise, its kit, the expression the user's shader evaluates (of vec2 p and the
// footprint's vec2 dx, dy) and the CPU's double reference at the same float p, dx, dy.
struct kit_row {
  std::string noise;
  std::string note;
  std::function<hush::glsl::shader_kit()> kit;
  std::string call;
  std::function<double(const hush::vec2& p, const hush::vec2& dx, const hush::vec2& dy)> reference;
};

// A row of a point noise (no footprint): the reference is value<double>(p).
template <class Noise>
kit_row point_row(std::string noise, std::string note, Noise n, std::string call) {
  auto held = std::make_shared<const Noise>(std::move(n));
  return {std::move(noise), std::move(note), [held] { return hush::glsl::shader_for(*held); },
          std::move(call),
          [held](const hush::vec2& p, const hush::vec2&, const hush::vec2&) {
            return held->template value<double>(hush::vec_cast<double>(p));
          }};
}

// A row of a filtered noise: the reference is sample(p, footprint::from_derivatives(dx, dy)).
template <class Noise>
kit_row filtered_row(std::string noise, std::string note, Noise n, std::string call) {
  auto held = std::make_shared<const Noise>(std::move(n));
  return {std::move(noise), std::move(note), [held] { return hush::glsl::shader_for(*held); },
          std::move(call),
          [held](const hush::vec2& p, const hush::vec2& dx, const hush::vec2& dy) {
            return held->sample(hush::vec_cast<double>(p),
                                hush::footprint<2>::from_derivatives(dx, dy));
          }};
}

// The rows: the noises of the other rows' files, with their parameters.
std::vector<kit_row> kit_rows() {
  std::vector<kit_row> rows;
  rows.push_back(point_row("perlin 2D", "seed 7", hush::perlin<2>(kNoiseSeed), "hush_perlin2(p)"));
  hush::fractal<hush::perlin<2>>::params fbm;
  fbm.seed = kNoiseSeed;
  fbm.octaves = kFbmOctaves;
  rows.push_back(point_row("fbm 2D", std::to_string(kFbmOctaves) + " octaves of Perlin noise",
                           hush::fractal<hush::perlin<2>>(fbm), "hush_fractal_perlin2(p)"));
  hush::wavelet<2>::params wavelet;
  wavelet.seed = kNoiseSeed;
  wavelet.weights = {1.0, 0.5, 0.25};
  rows.push_back(filtered_row("wavelet 2D filtered",
                              "3 bands, weights 1, 1/2, 1/4; footprints from dFdx/dFdy",
                              hush::wavelet<2>(wavelet), "hush_wavelet2_filtered(p, dx, dy)"));
  hush::gabor<2>::params gabor;
  gabor.seed = kNoiseSeed;
  gabor.impulses = 16;
  rows.push_back(filtered_row("gabor 2D filtered", "N' = 16; footprints from dFdx/dFdy",
                              hush::gabor<2>(gabor), "hush_gabor2_filtered(p, dx, dy)"));
  hush::anisotropic::params aniso;  // as anisotropic_cases.cpp's K = 4 rows
  aniso.seed = kNoiseSeed;
  aniso.orientations = 4;
  aniso.scales = 3;
  aniso.octaves = 3;
  aniso.frequency = 2.0;
  rows.push_back(filtered_row("anisotropic K=4",
                              "3 scales, centre heuristic; lambda from the Jacobian dFdx/dFdy",
                              hush::anisotropic(aniso), "hush_anisotropic(p, dx, dy)"));
  return rows;
}

// The user's vertex shader: one full-screen triangle from gl_VertexID, no vertex buffers.
constexpr const char* kVertexShader = R"glsl(#version 430 core
void main() {
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";

// The user's fragment shader after the kit's source: `call` evaluated at the plane's p.
std::string fragment_shader(const hush::glsl::shader_kit& kit, const std::string& call,
                            std::size_t width, std::size_t height, bool check) {
  char plane[256];
  std::snprintf(plane, sizeof plane,
                "const vec2 kFrame = vec2(%zu.0, %zu.0);\n"
                "const float kRecede = %.17g, kScale = %.17g, kAspect = %.17g;\n",
                width, height, 1.0 - 1.0 / kFar, kPlaneScale,
                static_cast<double>(width) / static_cast<double>(height));
  return std::string("#version 430 core\n") + (check ? "#define HUSH_BENCH_CHECK 1\n" : "") +
         kit.source + plane +
         "layout(location = 0) out float noise_out;\n"
         "#ifdef HUSH_BENCH_CHECK\n"
         "layout(location = 1) out vec4 position_out;     // p, 0, 0\n"
         "layout(location = 2) out vec4 derivatives_out;  // dFdx(p), dFdy(p)\n"
         "#endif\n"
         "void main() {\n"
         "  vec2 s = gl_FragCoord.xy / kFrame;\n"
         "  float t = 1.0 / (1.0 - kRecede * s.y);  // distance along the ground\n"
         "  vec2 p = kScale * t * vec2((2.0 * s.x - 1.0) * kAspect, 1.0);\n"
         "  vec2 dx = dFdx(p), dy = dFdy(p);\n"
         "  noise_out = " +
         call +
         ";\n"
         "#ifdef HUSH_BENCH_CHECK\n"
         "  position_out = vec4(p, 0.0, 0.0);\n"
         "  derivatives_out = vec4(dx, dy);\n"
         "#endif\n"
         "}\n";
}

// The GL objects of one row: the kit's resources (bound_kit), the program and its check
// variant, the output texture and the check's two, a framebuffer each and a vertex array.
class kit_frame {
 public:
  kit_frame(const d::gl_api& gl, const kit_row& row, std::size_t width, std::size_t height)
      : gl_(gl), gr_(gl.loader), kit_(row.kit()), bound_(gl.loader, kit_), w_(width), h_(height) {
    for (const bool check : {false, true})
      program_[check ? 1 : 0] = d::link_program(
          gl_, {{d::kGlVertexShader, kVertexShader},
                {d::kGlFragmentShader, fragment_shader(kit_, row.call, w_, h_, check)}});
    gl_.GenTextures(4, tex_);
    d::allocate_texture(gl_, tex_[0], w_, h_, d::kGlR32fFormat, d::kGlRedChannel, d::kGlFloat);
    d::allocate_texture(gl_, tex_[1], w_, h_, d::kGlR32fFormat, d::kGlRedChannel, d::kGlFloat);
    for (int t = 2; t < 4; ++t)
      d::allocate_texture(gl_, tex_[t], w_, h_, d::kGlRgba32f, d::kGlRgba, d::kGlFloat);
    gr_.GenFramebuffers(2, fbo_);
    for (int f = 0; f < 2; ++f) {
      gr_.BindFramebuffer(d::kGlFramebuffer, fbo_[f]);
      const int attachments = f == 0 ? 1 : 3;  // the timed frame: tex_[0]; the check: tex_[1..3]
      d::gl_enum bufs[3];
      for (int a = 0; a < attachments; ++a) {
        bufs[a] = d::kGlColorAttachment0 + static_cast<d::gl_enum>(a);
        gr_.FramebufferTexture2D(d::kGlFramebuffer, bufs[a], d::kGlTexture2d, tex_[f == 0 ? 0 : 1 + a], 0);
      }
      gr_.DrawBuffers(attachments, bufs);
      if (gr_.CheckFramebufferStatus(d::kGlFramebuffer) != d::kGlFramebufferComplete)
        throw std::runtime_error("hush bench: a kit row's framebuffer is incomplete");
    }
    gr_.BindFramebuffer(d::kGlFramebuffer, 0u);
    gr_.GenVertexArrays(1, &vao_);
    gl_.check("hush bench: setting up a kit row");
  }
  kit_frame(const kit_frame&) = delete;
  kit_frame& operator=(const kit_frame&) = delete;
  ~kit_frame() {
    gr_.DeleteVertexArrays(1, &vao_);
    gr_.DeleteFramebuffers(2, fbo_);
    gl_.DeleteTextures(4, tex_);
  }

  // One frame as an engine draws it: the kit's resources bound, the program, a full-screen
  // triangle into the R32F output (the check variant: into its three attachments). Issues the
  // commands and returns (no glFinish). Leaves the default framebuffer and no program bound.
  void draw(bool check = false) const {
    gr_.BindFramebuffer(d::kGlFramebuffer, fbo_[check ? 1 : 0]);
    gr_.Viewport(0, 0, static_cast<d::gl_sizei>(w_), static_cast<d::gl_sizei>(h_));
    bound_.bind();
    gl_.UseProgram(program_[check ? 1 : 0].id());
    gr_.BindVertexArray(vao_);
    gr_.DrawArrays(d::kGlTriangles, 0, 3);
    gr_.BindVertexArray(0u);
    gl_.UseProgram(0u);
    gr_.BindFramebuffer(d::kGlFramebuffer, 0u);
  }

  // Texture t's texels (t = 0: the output; 1 ... 3: the check's noise, p and derivatives).
  std::vector<float> read(int t) const {
    std::vector<float> texels(w_ * h_ * (t >= 2 ? 4u : 1u));
    gl_.BindTexture(d::kGlTexture2d, tex_[t]);
    gl_.PixelStorei(d::kGlPackAlignment, 4);
    gr_.GetTexImage(d::kGlTexture2d, 0, t >= 2 ? d::kGlRgba : d::kGlRedChannel, d::kGlFloat,
                 texels.data());
    gl_.BindTexture(d::kGlTexture2d, 0u);
    gl_.check("hush bench: reading a kit row's textures");
    return texels;
  }

  const d::gl_api& gl() const { return gl_; }

 private:
  const d::gl_api& gl_;
  d::gl_raster_api gr_;
  hush::glsl::shader_kit kit_;
  hush::glsl::bound_kit bound_;
  std::size_t w_, h_;
  d::gl_program program_[2];  // the timed shader, its check variant
  d::gl_uint tex_[4] = {0, 0, 0, 0};
  d::gl_uint fbo_[2] = {0, 0};
  d::gl_uint vao_ = 0;
};

prepared_case prepare_kit_row(hush::glsl::device& dev, const kit_row& row, const sizes& s) {
  auto f = std::make_shared<kit_frame>(dev.gl(), row, s.frame_width, s.frame_height);
  const std::size_t n = s.frame_width * s.frame_height;
  prepared_case p;
  p.samples = n;
  p.run = [f] {
    f->draw();
    f->gl().Finish();
  };
  // The error: the timed shader's output at the check pixels, against the reference at the
  // p, dx, dy the check variant computed there.
  p.run();
  const std::vector<float> out = f->read(0);
  f->draw(true);
  const std::vector<float> pos = f->read(2), der = f->read(3);
  const std::size_t checked = n < kCheckPixels ? n : kCheckPixels;
  for (std::size_t k = 0; k < checked; ++k) {
    const std::size_t q = (2 * k + 1) * n / (2 * checked);  // the middle of the k-th n/checked
    const hush::vec2 pq{pos[4 * q], pos[4 * q + 1]};
    const hush::vec2 dx{der[4 * q], der[4 * q + 1]}, dy{der[4 * q + 2], der[4 * q + 3]};
    p.value_error.add(out[q], row.reference(pq, dx, dy));
  }
  p.quality =
      "error at " + std::to_string(checked) + " pixels; " +
      gl_timing(f->gl()).measure([&f] { f->draw(); }, kTimedFrames, "bind() + glDrawArrays");
  return p;
}

}  // namespace

void add_kit_cases(std::vector<bench_case>& cases, const sizes& s) {
  hush::glsl::device* dev = &bench_glsl_device();
  for (kit_row& r : kit_rows()) {
    bench_case c;
    c.noise = r.noise;
    c.backend = "glsl kit";
    c.wall_clock = true;
    c.workload = "fragment " + std::to_string(s.frame_width) + "x" + std::to_string(s.frame_height);
    c.frame_pixels = s.frame_width * s.frame_height;
    c.note =
        "shader_for(noise) in a fragment shader, bound_kit, a receding plane into R32F "
        "(a glFinish per frame, no read-back); " +
        r.note;
    auto row = std::make_shared<const kit_row>(std::move(r));
    c.prepare = [dev, row, s] { return prepare_kit_row(*dev, *row, s); };
    cases.push_back(c);
  }
}

}  // namespace hush_bench
