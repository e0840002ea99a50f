// hush — the speed-vs-error benchmark: anisotropic noise's rows (include/hush/anisotropic.hpp).
//
// The workload: one frame of a receding plane (1920 x 1080; every pixel sees the
// plane, out to the horizon's grazing angles), K = 4 and 8 orientations, 3 scales, the
// centre heuristic's filtering weights per pixel from the screen-to-texture Jacobian. Error
// columns: the float path against the double reference at the same inputs. The quality
// metric, in the note: RMS against each pixel's supersampled Gaussian reference
// (examples/anisotropic, every 97th pixel), and the unfiltered noise's for comparison.
// And the least-squares preprocessing: compensation weights for distinct triangle maps. With a
// GL context, the GPU-resident frame too (hush/glsl/anisotropic/frame.hpp): host and GPU time.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "cases.hpp"
#include "figures.hpp"
#include "hush/exec.hpp"
#include "hush/hush.hpp"
#include "rows.hpp"

#if HUSH_BENCH_HAVE_GLSL
#include <algorithm>
#include <chrono>

#include "gl_timing.hpp"
#include "hush/glsl/anisotropic/frame.hpp"
#include "hush/glsl/device.hpp"
#endif

namespace hush_bench {

namespace {

constexpr std::uint32_t kSeed = 7;
constexpr double kFrequency = 2.0;  // octave 0, cycles per world unit of the plane
constexpr std::size_t kQualityStride = 97;

hush::anisotropic make_noise(int k, hush::weight_rule compensation = hush::weight_rule::centre) {
  hush::anisotropic::params p;
  p.seed = kSeed;
  p.orientations = k;
  p.scales = 3;
  p.octaves = 3;
  p.frequency = kFrequency;
  p.compensation = compensation;
  return hush::anisotropic(p);
}

struct frame_buffers {
  hush_tools::aniso::receding_plane plane;
  std::vector<float> out;
};

// The quality note: RMS of the filtered and the unfiltered float noise against the
// supersampled reference over every kQualityStride-th pixel.
std::string quality_note(const hush::anisotropic& noise, const frame_buffers& b) {
  std::vector<std::size_t> pixels;
  for (std::size_t q = 0; q < b.out.size(); q += kQualityStride) pixels.push_back(q);
  const std::vector<double> ref = hush_tools::aniso::supersampled(noise, b.plane, pixels);
  double e = 0, eu = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const std::size_t q = pixels[i];
    const double v = noise.sample(b.plane.positions[q], b.plane.footprints[q]);
    e += (v - ref[i]) * (v - ref[i]);
    const double u = noise(b.plane.positions[q]);
    eu += (u - ref[i]) * (u - ref[i]);
  }
  char text[160];
  std::snprintf(text, sizeof text,
                "receding plane, %zu x %zu; RMS vs supersampled Gaussian %.4f (unfiltered %.4f)",
                b.plane.width, b.plane.height, std::sqrt(e / double(pixels.size())),
                std::sqrt(eu / double(pixels.size())));
  return text;
}

template <class Exec>
void add_frame_rows(std::vector<bench_case>& cases, const sizes& s, const Exec& ex,
                    const std::shared_ptr<const frame_buffers>& shared) {
  for (int k : {4, 8}) {
    bench_case c;
    c.noise = "anisotropic K=" + std::to_string(k);
    c.backend = Exec::name;
    c.wall_clock = std::string(Exec::name) == "glsl";
    c.workload = "frame " + std::to_string(s.frame_width) + "x" + std::to_string(s.frame_height);
    const hush::anisotropic noise = make_noise(k);
    c.note = quality_note(noise, *shared) + "; 3 scales, centre heuristic per pixel";
    c.prepare = [noise, ex, shared] {
      auto b = std::make_shared<frame_buffers>(*shared);
      prepared_case p;
      p.samples = b->out.size();
      p.run = [noise, ex, b] {
        hush::samples<2> smp;
        smp.positions = b->plane.positions;
        smp.footprints = b->plane.footprints;
        hush::evaluate(noise, ex, smp, hush::span<float>(b->out));
        benchmark::DoNotOptimize(b->out.data());
        benchmark::ClobberMemory();
      };
      p.run();
      for (std::size_t q = 0; q < b->out.size(); ++q)
        p.value_error.add(b->out[q], noise.sample(hush::vec_cast<double>(b->plane.positions[q]),
                                                  b->plane.footprints[q]));
      return p;
    };
    cases.push_back(c);
  }
}

#if HUSH_BENCH_HAVE_GLSL
// The GPU-resident frame (hush/glsl/anisotropic/frame.hpp): the plane's uv and Jacobian as
// RGBA32F textures, the noise into an R32F texture, no read-back. A run is one render() and
// glFinish (the table's wall time); the quality column has the host's time of render() alone
// (glFinish excluded) and the GPU's time from a GL_TIME_ELAPSED query, best of 3 frames each,
// then the host time with the GPU's work skipped and the GL calls per frame (gl_timing.hpp,
// medians), on bench_resident_device() (its GL calls counted). Errors: the read-back image
// against the double reference at the same uv and Jacobian.
struct resident_frame {
  using gl_uint = hush::glsl::detail::gl_uint;
  const hush::glsl::detail::gl_api& gl;
  hush::glsl::anisotropic_frame frame;
  gl_uint tex[3] = {0, 0, 0};  // uv, Jacobian, output
  int w, h;
  void(HUSH_GLAPI* GenQueries)(hush::glsl::detail::gl_sizei, gl_uint*) = nullptr;
  void(HUSH_GLAPI* DeleteQueries)(hush::glsl::detail::gl_sizei, const gl_uint*) = nullptr;
  void(HUSH_GLAPI* BeginQuery)(hush::glsl::detail::gl_enum, gl_uint) = nullptr;
  void(HUSH_GLAPI* EndQuery)(hush::glsl::detail::gl_enum) = nullptr;
  void(HUSH_GLAPI* GetQueryObjectui64v)(gl_uint, hush::glsl::detail::gl_enum,
                                        unsigned long long*) = nullptr;
  static constexpr hush::glsl::detail::gl_enum kTimeElapsed = 0x88BF;
  static constexpr hush::glsl::detail::gl_enum kQueryResult = 0x8866;

  resident_frame(const hush::anisotropic& noise, const std::vector<float>& uv,
                 const std::vector<float>& jac, int width, int height)
      : gl(bench_resident_device().gl()), frame(gl.loader, noise), w(width), h(height) {
    using namespace hush::glsl::detail;
    gl_api::load(gl.loader, GenQueries, "glGenQueries");
    gl_api::load(gl.loader, DeleteQueries, "glDeleteQueries");
    gl_api::load(gl.loader, BeginQuery, "glBeginQuery");
    gl_api::load(gl.loader, EndQuery, "glEndQuery");
    gl_api::load(gl.loader, GetQueryObjectui64v, "glGetQueryObjectui64v");
    gl.GenTextures(3, tex);
    for (int t = 0; t < 3; ++t) {
      gl.BindTexture(kGlTexture2d, tex[t]);
      if (t < 2)
        gl.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlRgba32f), w, h, 0, kGlRgba, kGlFloat,
                      (t == 0 ? uv : jac).data());
      else
        gl.TexImage2D(kGlTexture2d, 0, static_cast<gl_int>(kGlR32fFormat), w, h, 0, kGlRedFormat,
                      kGlFloat, nullptr);
      gl.TexParameteri(kGlTexture2d, kGlTextureMinFilter, static_cast<gl_int>(kGlNearestFilter));
      gl.TexParameteri(kGlTexture2d, kGlTextureMagFilter, static_cast<gl_int>(kGlNearestFilter));
    }
    gl.BindTexture(kGlTexture2d, 0u);
  }
  resident_frame(const resident_frame&) = delete;
  resident_frame& operator=(const resident_frame&) = delete;
  ~resident_frame() { gl.DeleteTextures(3, tex); }
  void render() { frame.render({tex[0], tex[1], 0u}, tex[2], w, h); }
  // Best of n: the host's ms of render() (glFinish excluded) and the GPU's ms of its draw.
  std::pair<double, double> times(int n) {
    gl_uint q = 0;
    GenQueries(1, &q);
    double host = 1e300, gpu = 1e300;
    for (int r = 0; r < n; ++r) {
      BeginQuery(kTimeElapsed, q);
      const auto t0 = std::chrono::steady_clock::now();
      render();
      const auto t1 = std::chrono::steady_clock::now();
      EndQuery(kTimeElapsed);
      gl.Finish();
      unsigned long long ns = 0;
      GetQueryObjectui64v(q, kQueryResult, &ns);
      host = std::min(host, std::chrono::duration<double, std::milli>(t1 - t0).count());
      gpu = std::min(gpu, double(ns) * 1e-6);
    }
    DeleteQueries(1, &q);
    return {host, gpu};
  }
};

void add_resident_rows(std::vector<bench_case>& cases, const sizes& s,
                       const std::shared_ptr<const frame_buffers>& shared) {
  for (int k : {4, 8}) {
    bench_case c;
    c.noise = "anisotropic K=" + std::to_string(k);
    c.backend = "glsl";
    c.wall_clock = true;
    c.workload =
        "resident frame " + std::to_string(s.frame_width) + "x" + std::to_string(s.frame_height);
    c.frame_pixels = s.frame_width * s.frame_height;
    const hush::anisotropic noise = make_noise(k);
    c.note =
        "hush::glsl::anisotropic_frame: uv and Jacobian textures in, R32F texture out, no "
        "read-back; 3 scales, centre heuristic per pixel in the shader";
    c.prepare = [noise, shared] {
      const hush_tools::aniso::receding_plane& plane = shared->plane;
      const std::size_t n = plane.width * plane.height;
      // The plane's uv and Jacobian (central differences of the exact map, as
      // make_receding_plane forms the footprints), as float textures and a hush::frame.
      std::vector<float> uv(4 * n, 0.0f), jac(4 * n), depth(n, 1.0f);
      std::vector<hush::vec2> uv2(n);
      std::vector<hush::vec4> jac4(n);
      const double d = 1e-3;
      for (std::size_t y = 0; y < plane.height; ++y)
        for (std::size_t x = 0; x < plane.width; ++x) {
          const std::size_t q = y * plane.width + x;
          const double cx = double(x) + 0.5, cy = double(y) + 0.5;
          const hush::dvec2 ax = plane.at(cx + d, cy), bx = plane.at(cx - d, cy);
          const hush::dvec2 ay = plane.at(cx, cy + d), by = plane.at(cx, cy - d);
          uv2[q] = plane.positions[q];
          jac4[q] = {float((ax.x - bx.x) / (2 * d)), float((ay.x - by.x) / (2 * d)),
                     float((ax.y - bx.y) / (2 * d)), float((ay.y - by.y) / (2 * d))};
          uv[4 * q] = uv2[q].x;
          uv[4 * q + 1] = uv2[q].y;
          uv[4 * q + 3] = 1.0f;
          jac[4 * q] = jac4[q].x;
          jac[4 * q + 1] = jac4[q].y;
          jac[4 * q + 2] = jac4[q].z;
          jac[4 * q + 3] = jac4[q].w;
        }
      const int w = static_cast<int>(plane.width), h = static_cast<int>(plane.height);
      auto st = std::make_shared<resident_frame>(noise, uv, jac, w, h);
      prepared_case p;
      p.samples = n;
      hush::frame f;
      f.depth = {depth.data(), plane.width, plane.height};
      f.uv = {uv2.data(), plane.width, plane.height};
      f.uv_jacobian = {jac4.data(), plane.width, plane.height};
      const std::vector<float> img = st->frame.render_image(f);
      for (std::size_t q = 0; q < n; ++q) {
        const hush::dvec2 dx{jac4[q].x, jac4[q].z}, dy{jac4[q].y, jac4[q].w};
        p.value_error.add(img[q], noise.sample(hush::vec_cast<double>(uv2[q]),
                                               hush::footprint<2>::from_derivatives(dx, dy)));
      }
      const std::pair<double, double> t = st->times(3);
      char text[160];
      std::snprintf(text, sizeof text,
                    "per frame: host %.3f ms (render(), glFinish excluded), GPU %.3f ms "
                    "(GL_TIME_ELAPSED)",
                    t.first, t.second);
      p.quality = text + ("; " + gl_timing(st->gl).host_only([&] { st->render(); }));
      p.run = [st] {
        st->render();
        st->gl.Finish();
      };
      return p;
    };
    cases.push_back(c);
  }
}
#endif

}  // namespace

// Its rows are all in the frames pass: the frame rows on every backend (their SIMD rows pinned
// to AVX2 with the others), then the least-squares weights.
void add_anisotropic_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  if (pass != bench_pass::frames) return;
  auto shared = std::make_shared<frame_buffers>();
  shared->plane = hush_tools::aniso::make_receding_plane(s.frame_width, s.frame_height);
  shared->out.assign(s.frame_width * s.frame_height, 0.0f);
  add_frame_rows(cases, s, hush::exec::scalar, shared);
  add_frame_rows(cases, s, hush::exec::simd, shared);
#if HUSH_BENCH_HAVE_GLSL
  add_frame_rows(cases, s, hush::exec::glsl<hush::glsl::device>{bench_glsl_device()}, shared);
  add_resident_rows(cases, s, shared);
#endif
  // Least-squares compensation weights: 2 octaves, 5 scales, K = 4 (the paper's fig. 6
  // set-up), one fit per octave and distinct triangle map (maps never repeat, so the
  // noise's per-map cache never hits).
  bench_case c;
  c.noise = "anisotropic K=4";
  c.backend = "scalar";
  c.workload = "triangles " + std::to_string(s.triangles);
  c.reference = error_reference::weights;
  c.note = "least-squares compensation weights per triangle (2 octaves, 5 scales)";
  const std::size_t n = s.triangles;
  c.prepare = [n] {
    hush::anisotropic::params p;
    p.seed = kSeed;
    p.scales = 5;
    p.base_scale = 1;
    p.octaves = 2;
    p.compensation = hush::weight_rule::least_squares;
    auto noise = std::make_shared<hush::anisotropic>(p);
    auto counter = std::make_shared<std::uint32_t>(0);
    prepared_case r;
    r.samples = n;
    r.run = [noise, counter, n] {
      float w[hush::detail::constants::kAnisoMaxScales * hush::anisotropic::kMaxChannels];
      for (std::size_t t = 0; t < n; ++t) {
        hush::rng g(kSeed, (*counter)++);
        hush::sample_input<2> in;
        in.has_map = true;
        in.map = hush::surface_map::from_matrix(g.uniform(0.5, 2.0), g.uniform(-0.5, 0.5),
                                                g.uniform(-0.5, 0.5), g.uniform(0.5, 2.0));
        noise->weights<float>(in, w);
        benchmark::DoNotOptimize(w);
      }
    };
    return r;
  };
  cases.push_back(c);
}

}  // namespace hush_bench
