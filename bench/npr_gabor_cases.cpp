// hush — the speed-vs-error benchmark: NPR Gabor noise's rows (include/hush/npr_gabor.hpp).
//
// The workload: one frame (frame 0) of the `dense` scene (examples/scene: a sphere
// and a torus over a plane) with about 5k, 50k and 200k triangles, rasterized by the CPU
// rasterizer at npr_width x npr_height (1280 x 720), N' = 16 and 32, the default kernel
// (F0 = 1/8 cycle/pixel, a = 0.08/pixel, radius 12.2 pixels), anisotropic, object and depth
// tests; "thin" rows thin the points of triangles with N < 1 (params::thinning), "local"
// rows give every node of the point tree its own count (params::local_density). A row
// times npr_gabor::render (both stages: points and splatting) on one thread;
// ms/frame is its time per frame. Error columns: the float render against render<double> on
// exec::scalar (the reference) over every pixel. The note gives the splat count (points
// emitted) and the triangle count. GLSL rows (with OSMesa; N' = 16; hush/glsl/npr_gabor.hpp):
// render on exec::glsl, both stages on the GPU (the compute passes of stage 1 upload the
// triangles once and write the records, the point sprites splat them; "local" rows: the same
// with params::local_density, a count per node of the walk), and "cpu-points" rows:
// stage 1 on the CPU (make_splats, double), the records uploaded and splatted; in wall time
// like the other GLSL rows (llvmpipe's own threads do the work), read-back included.
#include <cstdio>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "cases.hpp"
#include "hush/exec.hpp"
#include "hush/npr_gabor.hpp"
#include "rows.hpp"

#if HUSH_BENCH_HAVE_SCENE
#include "gbuffer.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"
#include "triangles.hpp"
#endif
#if HUSH_BENCH_HAVE_GLSL
#include "gl_timing.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/npr_gabor/frame.hpp"
#include "hush/glsl/npr_gabor/renderer.hpp"
#endif

namespace hush_bench {

#if HUSH_BENCH_HAVE_SCENE
namespace {

// One rasterized frame of a dense scene, made on first use (rows share it).
struct dense_frame {
  long triangles = 0;
  int width = 0, height = 0;
  hush_tools::scene::gbuffer g;
  hush_tools::scene::triangle_frame t;
  bool ready = false;
  void make() {
    if (ready) return;
    const hush_tools::scene::scene s =
        hush_tools::scene::make_scene("dense:" + std::to_string(triangles));
    g = hush_tools::scene::render_cpu(s, 0, width, height);
    t = hush_tools::scene::project_triangles(s, 0, width, height);
    ready = true;
  }
};

// Which LOD a row uses: the paper's per triangle, with thinning, or per node (local density).
enum class lod { paper, thinning, local_density };

template <class Exec>
void add_rows(std::vector<bench_case>& cases, const sizes& s, const Exec& ex,
              const std::vector<std::shared_ptr<dense_frame>>& frames, lod variant,
              std::initializer_list<double> impulse_counts = {16.0, 32.0},
              bool cpu_points = false) {
  for (const std::shared_ptr<dense_frame>& fr : frames)
    for (double impulses : impulse_counts) {
      bench_case c;
      c.wall_clock = std::string(Exec::name) == "glsl";
      c.noise = "npr-gabor N'=" + std::to_string(static_cast<int>(impulses)) +
                (variant == lod::thinning        ? " thin"
                 : variant == lod::local_density ? " local"
                                                 : "") +
                (cpu_points ? " cpu-points" : "");
      c.backend = Exec::name;
      c.workload = "dense:" + std::to_string(fr->triangles) + " " + std::to_string(s.npr_width) +
                   "x" + std::to_string(s.npr_height);
      c.frame_pixels = s.npr_width * s.npr_height;
      hush::npr_gabor::params prm;
      prm.impulses = impulses;
      prm.orientation = 0.5;
      prm.thinning = variant == lod::thinning;
      prm.local_density = variant == lod::local_density;
      const hush::npr_gabor noise{prm};
      c.prepare = [noise, ex, fr, cpu_points] {
        fr->make();
        const std::size_t w = static_cast<std::size_t>(fr->width);
        const std::size_t h = static_cast<std::size_t>(fr->height);
        auto out = std::make_shared<std::vector<float>>(w * h);
        prepared_case p;
        p.samples = w * h;
        p.run = [noise, ex, fr, out, w, h, cpu_points] {
          const hush::frame f = hush_tools::scene::as_frame(fr->g);
          if (cpu_points) {  // stage 1 here, stage 2 on ex
            std::vector<hush::npr_gabor_splat> splats;
            noise.make_splats(f, fr->t.view(), splats);
            noise.splat(ex, f, splats.data(), splats.size(),
                        hush::image_view<float>(out->data(), w, h));
          } else {
            noise.render(ex, f, fr->t.view(), hush::image_view<float>(out->data(), w, h));
          }
          benchmark::DoNotOptimize(out->data());
          benchmark::ClobberMemory();
        };
        p.run();
        std::vector<double> ref(w * h);
        noise.render(hush::exec::scalar, hush_tools::scene::as_frame(fr->g), fr->t.view(),
                     hush::image_view<double>(ref.data(), w, h));
        for (std::size_t q = 0; q < ref.size(); ++q) p.value_error.add((*out)[q], ref[q]);
        std::vector<hush::npr_gabor_splat> splats;
        noise.make_splats(hush_tools::scene::as_frame(fr->g), fr->t.view(), splats);
        char text[160];
        std::snprintf(text, sizeof text, "%zu triangles, %zu splats; object and depth tests",
                      fr->t.triangle_id.size(), splats.size());
        p.quality = text;
        return p;
      };
      cases.push_back(c);
    }
}

#if HUSH_BENCH_HAVE_GLSL
// "glsl resident" rows (N' = 16): the frame's G-buffer in textures and its triangles in
// buffers (made once, the layouts of hush/glsl/npr_gabor/gl_frame.hpp), npr_gabor_gl_render
// into an R32F texture, a glFinish per run(); error from the texture read back; the note adds
// the host time of the call alone and the GPU time of a frame, then the host time with the
// GPU's work skipped and the GL calls per frame (gl_timing.hpp). On bench_resident_device()
// (its GL calls counted).
void add_resident_rows(std::vector<bench_case>& cases, const sizes& s, hush::glsl::device& dev,
                       const std::vector<std::shared_ptr<dense_frame>>& frames) {
  namespace d = hush::glsl::detail;
  constexpr int kTimedFrames = 10;
  for (const std::shared_ptr<dense_frame>& fr : frames) {
    bench_case c;
    c.wall_clock = true;
    c.noise = "npr-gabor N'=16";
    c.backend = "glsl resident";
    c.workload = "dense:" + std::to_string(fr->triangles) + " " + std::to_string(s.npr_width) +
                 "x" + std::to_string(s.npr_height);
    c.frame_pixels = s.npr_width * s.npr_height;
    hush::npr_gabor::params prm;
    prm.impulses = 16;
    prm.orientation = 0.5;
    const hush::npr_gabor noise{prm};
    hush::glsl::device* device = &dev;
    c.prepare = [noise, fr, device] {
      fr->make();
      const std::size_t w = static_cast<std::size_t>(fr->width);
      const std::size_t h = static_cast<std::size_t>(fr->height);
      // The GL objects, deleted with the case.
      struct objects {
        const d::gl_api& gl;
        d::gl_uint tex[4] = {0, 0, 0, 0};  // depth, object ids, triangle ids, output
        d::gl_uint buf[2] = {0, 0};        // vertices, triangles
        hush::glsl::npr_gabor_gl_frame f;
        explicit objects(const d::gl_api& g) : gl(g) {
          gl.GenTextures(4, tex);
          gl.GenBuffers(2, buf);
        }
        objects(const objects&) = delete;
        objects& operator=(const objects&) = delete;
        ~objects() {
          gl.DeleteTextures(4, tex);
          gl.DeleteBuffers(2, buf);
        }
      };
      auto o = std::make_shared<objects>(device->gl());
      const d::gl_api& gl = o->gl;
      const d::gl_resident_api gr(gl.loader);
      const hush::frame f = hush_tools::scene::as_frame(fr->g);
      d::allocate_texture(gl, o->tex[0], w, h, d::kGlR32fFormat, d::kGlRedChannel, d::kGlFloat);
      for (int k = 1; k < 3; ++k)
        d::allocate_texture(gl, o->tex[k], w, h, d::kGlR32uiFormat, d::kGlRedInteger,
                            d::kGlUnsignedInt);
      d::allocate_texture(gl, o->tex[3], w, h, d::kGlR32fFormat, d::kGlRedChannel, d::kGlFloat);
      d::upload_view(gl, gr, o->tex[0], f.depth, d::kGlRedChannel, d::kGlFloat);
      d::upload_view(gl, gr, o->tex[1], f.object_id, d::kGlRedInteger, d::kGlUnsignedInt);
      d::upload_view(gl, gr, o->tex[2], f.triangle_id, d::kGlRedInteger, d::kGlUnsignedInt);
      std::vector<float> vertices;
      std::vector<std::uint32_t> triangles;
      const hush::triangle_list tris = fr->t.view();
      hush::glsl::npr_gabor_gl_pack(tris, vertices, triangles);
      for (int k = 0; k < 2; ++k) {
        gl.BindBuffer(d::kGlShaderStorageBuffer, o->buf[k]);
        gl.BufferData(
            d::kGlShaderStorageBuffer,
            static_cast<d::gl_sizeiptr>(k == 0 ? vertices.size() * 4 : triangles.size() * 4),
            k == 0 ? static_cast<const void*>(vertices.data()) : triangles.data(),
            d::kGlStaticDraw);
      }
      gl.BindBuffer(d::kGlShaderStorageBuffer, 0);
      o->f = {o->tex[0],
              o->tex[1],
              o->tex[2],
              static_cast<std::uint32_t>(w),
              static_cast<std::uint32_t>(h),
              o->buf[0],
              o->buf[1],
              static_cast<std::uint32_t>(tris.vertices()),
              static_cast<std::uint32_t>(tris.triangles())};
      prepared_case p;
      p.samples = w * h;
      p.run = [noise, device, o] {
        hush::glsl::npr_gabor_gl_render(*device, noise, o->f, o->tex[3]);
        o->gl.Finish();
      };
      p.run();
      std::vector<float> out(w * h);
      void(HUSH_GLAPI * get_tex)(d::gl_enum, d::gl_int, d::gl_enum, d::gl_enum, void*) = nullptr;
      d::gl_api::load(gl.loader, get_tex, "glGetTexImage");
      gl.BindTexture(d::kGlTexture2d, o->tex[3]);
      gl.PixelStorei(0x0D05, 4);  // GL_PACK_ALIGNMENT
      get_tex(d::kGlTexture2d, 0, d::kGlRedChannel, d::kGlFloat, out.data());
      gl.BindTexture(d::kGlTexture2d, 0);
      std::vector<double> ref(w * h);
      noise.render(hush::exec::scalar, f, tris, hush::image_view<double>(ref.data(), w, h));
      for (std::size_t q = 0; q < ref.size(); ++q) p.value_error.add(out[q], ref[q]);
      const auto render = [&] { hush::glsl::npr_gabor_gl_render(*device, noise, o->f, o->tex[3]); };
      const gl_timing timing(gl);
      p.quality = std::to_string(tris.triangles()) +
                  " triangles; G-buffer, triangles and output in GL objects "
                  "(npr_gabor_gl_render); " +
                  timing.measure(render, kTimedFrames, "npr_gabor_gl_render") + "; " +
                  timing.host_only(render);
      return p;
    };
    cases.push_back(c);
  }
}
#endif

}  // namespace
#endif

// Its rows are all in the frames pass (their SIMD rows pinned to AVX2 with the others), where
// the build has the scene library (HUSH_BENCH_HAVE_SCENE); without it, none.
void add_npr_gabor_cases([[maybe_unused]] std::vector<bench_case>& cases,
                         [[maybe_unused]] const sizes& s, [[maybe_unused]] bench_pass pass) {
#if HUSH_BENCH_HAVE_SCENE
  if (pass != bench_pass::frames) return;
  std::vector<std::shared_ptr<dense_frame>> frames;
  for (long n : s.npr_triangles) {
    auto f = std::make_shared<dense_frame>();
    f->triangles = n;
    f->width = static_cast<int>(s.npr_width);
    f->height = static_cast<int>(s.npr_height);
    frames.push_back(f);
  }
  add_rows(cases, s, hush::exec::scalar, frames, lod::paper);
  add_rows(cases, s, hush::exec::simd, frames, lod::paper);
  add_rows(cases, s, hush::exec::simd, frames, lod::thinning);
  add_rows(cases, s, hush::exec::simd, frames, lod::local_density, {16.0});
#if HUSH_BENCH_HAVE_GLSL
  for (const bool cpu_points : {false, true})
    add_rows(cases, s, hush::exec::glsl<hush::glsl::device>{bench_glsl_device()}, frames,
             lod::paper, {16.0}, cpu_points);
  add_rows(cases, s, hush::exec::glsl<hush::glsl::device>{bench_glsl_device()}, frames,
           lod::local_density, {16.0});
  add_resident_rows(cases, s, bench_resident_device(), frames);
#endif
#endif
}

}  // namespace hush_bench
