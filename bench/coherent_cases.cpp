// hush — the speed-vs-error benchmark: coherent noise's rows (include/hush/coherent.hpp).
//
// One frame is the workload: 1920 x 1080 pixels (--quick: 192 x 108), one channel, alpha 0.98,
// white input; ns/sample is per pixel and the table adds ms/frame. The scene is a disc turning
// 0.003 rad per frame (up to 1.6 pixels per frame at its rim, sub-pixel inside) on a still
// background, with exact depth, velocity and object ids. Each run() advances the stream one
// frame (the causal filter's steady state); the symmetric rows filter a whole sequence of
// kSequence frames per run(), so their time per sample is per pixel and frame.
//
// Error: the float output against the double reference (basic_coherent_stream<double>) over
// the first kErrorFrames frames. Quality: the standard deviation and the sharpness (mean
// squared neighbour difference over the variance) of the turning disc over those of the still
// background, after kQualityFrames frames (1 and 1 are ideal; the paper's filter fades).
// Peer row: the memory-bound pass (coherent_memory.cpp) over the same bytes, the yardstick of
// the target (causal SIMD within 2x of it).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "hush/coherent.hpp"
#include "hush/exec.hpp"
#include "rows.hpp"

#if HUSH_BENCH_HAVE_HWY
#include "coherent_memory.hpp"
#endif
#if HUSH_BENCH_HAVE_GLSL
#include "gl_timing.hpp"
#include "hush/glsl/coherent/frame.hpp"
#include "hush/glsl/coherent/renderer.hpp"
#include "hush/glsl/detail/gl_resident.hpp"
#include "hush/glsl/device.hpp"
#endif

namespace hush_bench {
namespace {

constexpr double kTurn = 0.003;  // radians per frame
constexpr int kErrorFrames = 8, kQualityFrames = 150, kSequence = 12;
constexpr std::uint32_t kSeed = 7;

// A disc of radius 0.45 min(W, H) turning about the image centre (id 1, depth 1) on a still
// background (id 2, depth 2): velocity and forward velocity exact.
struct turning_disc {
  std::size_t width, height;
  std::vector<float> depth, velocity, forward;
  std::vector<std::uint32_t> ids;
  turning_disc(std::size_t w, std::size_t h)
      : width(w),
        height(h),
        depth(w * h, 2.0f),
        velocity(3 * w * h),
        forward(3 * w * h),
        ids(w * h, 2u) {
    const double cx = double(w) / 2.0, cy = double(h) / 2.0, r = 0.45 * double(std::min(w, h));
    const double c = std::cos(kTurn), s = std::sin(kTurn);
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) {
        const std::size_t p = y * w + x;
        const double dx = double(x) + 0.5 - cx, dy = double(y) + 0.5 - cy;
        if (dx * dx + dy * dy >= r * r) continue;
        ids[p] = 1u;
        depth[p] = 1.0f;
        velocity[3 * p] = float(dx - (c * dx + s * dy));
        velocity[3 * p + 1] = float(dy - (-s * dx + c * dy));
        forward[3 * p] = float((c * dx - s * dy) - dx);
        forward[3 * p + 1] = float((s * dx + c * dy) - dy);
      }
  }
  hush::frame view() const {
    hush::frame f;
    f.depth = {depth.data(), width, height};
    f.velocity = {reinterpret_cast<const hush::vec3*>(velocity.data()), width, height};
    f.forward_velocity = {reinterpret_cast<const hush::vec3*>(forward.data()), width, height};
    f.object_id = {ids.data(), width, height};
    return f;
  }
};

std::string format(const char* fmt, double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

// sd and sharpness of the disc over those of the background, in `out`.
std::string quality(const turning_disc& s, const std::vector<float>& out) {
  double sum[2] = {0, 0}, n[2] = {0, 0}, diff[2] = {0, 0}, pairs[2] = {0, 0};
  for (std::size_t y = 0; y + 1 < s.height; ++y)
    for (std::size_t x = 0; x + 1 < s.width; ++x) {
      const std::size_t p = y * s.width + x;
      const int k = s.ids[p] == 1u ? 0 : 1;
      sum[k] += double(out[p]) * out[p];
      n[k] += 1;
      for (std::size_t q : {p + 1, p + s.width})
        if (s.ids[q] == s.ids[p]) {
          diff[k] += (double(out[q]) - out[p]) * (double(out[q]) - out[p]);
          pairs[k] += 1;
        }
    }
  const double var[2] = {sum[0] / n[0], sum[1] / n[1]};
  return format("quality: sd moving/still %.3f, sharpness moving/still %.3f",
                std::sqrt(var[0] / var[1]),
                (diff[0] / pairs[0] / var[0]) / (diff[1] / pairs[1] / var[1]));
}

hush::coherent_params params(hush::coherent_filter filter, double alpha) {
  hush::coherent_params p;
  p.seed = kSeed;
  p.filter = filter;
  p.alpha = alpha;
  return p;
}

// A causal row: one frame per run(); error and quality measured while preparing.
template <class Exec>
prepared_case prepare_causal(const Exec& ex, const sizes& s, hush::coherent_filter filter,
                             double alpha) {
  auto scene = std::make_shared<turning_disc>(s.frame_width, s.frame_height);
  const std::size_t w = scene->width, h = scene->height;
  auto stream = std::make_shared<hush::coherent_stream>(params(filter, alpha));
  auto out = std::make_shared<std::vector<float>>(w * h);
  prepared_case p;
  p.samples = w * h;
  {
    hush::basic_coherent_stream<double> reference(params(filter, alpha));
    std::vector<double> ref(w * h);
    for (int i = 0; i < kErrorFrames; ++i) {
      stream->advance(ex, scene->view(), hush::image_view<float>(out->data(), w, h));
      reference.advance(hush::exec::scalar, scene->view(),
                        hush::image_view<double>(ref.data(), w, h));
      for (std::size_t k = 0; k < ref.size(); ++k) p.value_error.add((*out)[k], ref[k]);
    }
    for (int i = kErrorFrames; i < kQualityFrames; ++i)
      stream->advance(ex, scene->view(), hush::image_view<float>(out->data(), w, h));
    p.quality = quality(*scene, *out);
  }
  p.run = [ex, scene, stream, out, w, h] {
    stream->advance(ex, scene->view(), hush::image_view<float>(out->data(), w, h));
    benchmark::DoNotOptimize(out->data());
    benchmark::ClobberMemory();
  };
  return p;
}

// The time-symmetric filter over kSequence frames (in memory) per run().
template <class Exec>
prepared_case prepare_symmetric(const Exec& ex, const sizes& s) {
  auto scene = std::make_shared<turning_disc>(s.frame_width, s.frame_height);
  const std::size_t w = scene->width, h = scene->height;
  auto planes = std::make_shared<std::vector<float>>(w * h * kSequence);
  prepared_case p;
  p.samples = w * h * kSequence;
  auto run = [ex, scene, planes, w, h] {
    const std::vector<hush::frame> frames(kSequence, scene->view());
    std::vector<hush::image_view<float>> out;
    out.reserve(kSequence);
    for (int i = 0; i < kSequence; ++i) out.emplace_back(planes->data() + w * h * i, w, h);
    hush::coherent_symmetric(ex, params(hush::coherent_filter::stationary, 0.98),
                             hush::span<const hush::frame>(frames),
                             hush::span<const hush::image_view<float>>(out));
    benchmark::DoNotOptimize(planes->data());
    benchmark::ClobberMemory();
  };
  run();
  {
    const std::vector<hush::frame> frames(kSequence, scene->view());
    std::vector<double> ref(w * h * kSequence);
    std::vector<hush::image_view<double>> out;
    out.reserve(kSequence);
    for (int i = 0; i < kSequence; ++i) out.emplace_back(ref.data() + w * h * i, w, h);
    hush::coherent_symmetric(hush::exec::scalar, params(hush::coherent_filter::stationary, 0.98),
                             hush::span<const hush::frame>(frames),
                             hush::span<const hush::image_view<double>>(out));
    for (std::size_t k = 0; k < ref.size(); ++k) p.value_error.add((*planes)[k], ref[k]);
    const std::vector<float> last(
        planes->begin() + static_cast<std::ptrdiff_t>(w * h * (kSequence - 1)), planes->end());
    p.quality = quality(*scene, last) + "; keeps " +
                std::to_string(hush::coherent_record_bytes<float>(
                    params(hush::coherent_filter::stationary, 0.98), 1, 1)) +
                " bytes per pixel and frame for the backward pass";
  }
  p.run = run;
  return p;
}

#if HUSH_BENCH_HAVE_HWY
prepared_case prepare_memory(const sizes& s, bool contiguous) {
  struct buffers {
    turning_disc scene;
    std::vector<float> history, next, out, depth_copy;
    std::vector<std::uint32_t> ids_copy;
    std::vector<std::uint8_t> flags;
    explicit buffers(const sizes& s)
        : scene(s.frame_width, s.frame_height),
          history(scene.depth.size(), 0.5f),
          next(history.size()),
          out(history.size()),
          depth_copy(history.size()),
          ids_copy(history.size()),
          flags(history.size()) {}
  };
  auto b = std::make_shared<buffers>(s);
  prepared_case p;
  p.samples = b->history.size();
  p.run = [b, contiguous] {
    memory_job j;
    j.contiguous = contiguous;
    j.width = b->scene.width;
    j.height = b->scene.height;
    j.depth = b->scene.depth.data();
    j.motion = b->scene.velocity.data();
    j.ids = b->scene.ids.data();
    j.ref_depth = b->scene.depth.data();
    j.ref_ids = b->scene.ids.data();
    j.history = b->history.data();
    j.next_history = b->next.data();
    j.out = b->out.data();
    j.depth_copy = b->depth_copy.data();
    j.ids_copy = b->ids_copy.data();
    j.flags = b->flags.data();
    coherent_memory_pass(j);
    std::swap(b->history, b->next);
    benchmark::DoNotOptimize(b->out.data());
    benchmark::ClobberMemory();
  };
  p.run();
  return p;
}
#endif

bench_case row(const char* noise, const char* backend, const sizes& s) {
  bench_case c;
  c.noise = noise;
  c.backend = backend;
  c.workload = "frame " + std::to_string(s.frame_width) + "x" + std::to_string(s.frame_height);
  c.frame_pixels = s.frame_width * s.frame_height;
  return c;
}

// The frames pass: scalar and SIMD frames, and the memory-bound pass they are measured against
// (pinned to AVX2 with the other SIMD rows).
void add_coherent_frame_rows(std::vector<bench_case>& cases, const sizes& s) {
  using hush::coherent_filter;
  for (const bool simd : {false, true}) {
    bench_case c = row("coherent causal", simd ? "simd" : "scalar", s);
    c.note = "stationary filter, alpha 0.98, 1 channel, white input";
    if (simd)
      c.prepare = [s] {
        return prepare_causal(hush::exec::simd, s, coherent_filter::stationary, 0.98);
      };
    else
      c.prepare = [s] {
        return prepare_causal(hush::exec::scalar, s, coherent_filter::stationary, 0.98);
      };
    cases.push_back(c);
  }
  bench_case paper = row("coherent causal", "simd", s);
  paper.noise = "coherent causal (paper)";
  paper.note = "Kass & Pesare eq. 7, alpha 0.98, 1 channel";
  paper.prepare = [s] { return prepare_causal(hush::exec::simd, s, coherent_filter::paper, 0.98); };
  cases.push_back(paper);
  bench_case slow_decay = row("coherent causal (alpha 0.999)", "simd", s);
  slow_decay.note = "stationary filter: no denormal slow-down as alpha -> 1";
  slow_decay.prepare = [s] {
    return prepare_causal(hush::exec::simd, s, coherent_filter::stationary, 0.999);
  };
  cases.push_back(slow_decay);
  bench_case symmetric = row("coherent symmetric", "simd", s);
  symmetric.note = "stationary filter, alpha 0.98, " + std::to_string(kSequence) +
                   " frames in memory per run: time per pixel and frame";
  symmetric.prepare = [s] { return prepare_symmetric(hush::exec::simd, s); };
  cases.push_back(symmetric);
#if HUSH_BENCH_HAVE_HWY
  bench_case memory = row("coherent causal", "memory-bound pass", s);
  memory.peer = true;
  memory.reference = error_reference::none;
  memory.note =
      "reads depth, velocity, ids; gathers 4 taps of depth, ids, history; writes "
      "output, history, depth and id copies, a flag (the yardstick)";
  memory.prepare = [s] { return prepare_memory(s, false); };
  cases.push_back(memory);
  bench_case loads = row("coherent causal", "memory-bound pass, loads", s);
  loads.peer = true;
  loads.reference = error_reference::none;
  loads.note = "the same bytes, adjacent taps loaded instead of gathered (as hush's kernel does)";
  loads.prepare = [s] { return prepare_memory(s, true); };
  cases.push_back(loads);
#endif
}

#if HUSH_BENCH_HAVE_GLSL
// The resident row: the scene's G-buffer in textures (uploaded once: the frames are alike),
// hush::glsl::coherent_gl_stream into an R32F texture; run() is one advance and a glFinish (the
// wall clock then holds the GPU's work). While preparing: the error and quality from the
// output texture read back, and over kTimedFrames frames the host time of advance() alone and
// the GPU time of each frame's pass, then the host time with the GPU's work skipped and the GL
// calls per frame (gl_timing.hpp), medians, into the quality text. The stream runs on
// bench_resident_device() (its GL calls counted).
constexpr int kTimedFrames = 20;

prepared_case prepare_resident(hush::glsl::device& dev, const sizes& s) {
  namespace d = hush::glsl::detail;
  struct resources {
    const d::gl_api& gl;
    void(HUSH_GLAPI* GetTexImage)(d::gl_enum, d::gl_int, d::gl_enum, d::gl_enum, void*) = nullptr;
    d::gl_uint tex[4] = {0, 0, 0, 0};  // depth, velocity, ids, output
    std::unique_ptr<hush::glsl::coherent_gl_stream> stream;
    hush::glsl::coherent_gl_frame frame;
    explicit resources(hush::glsl::device& dv) : gl(dv.gl()) {
      d::gl_api::load(gl.loader, GetTexImage, "glGetTexImage");
      gl.GenTextures(4, tex);
    }
    resources(const resources&) = delete;
    resources& operator=(const resources&) = delete;
    ~resources() {
      stream.reset();
      gl.DeleteTextures(4, tex);
    }
    void read(std::vector<float>& out) const {
      gl.BindTexture(d::kGlTexture2d, tex[3]);
      gl.PixelStorei(0x0D05, 4);  // GL_PACK_ALIGNMENT
      GetTexImage(d::kGlTexture2d, 0, d::kGlRedChannel, d::kGlFloat, out.data());
      gl.BindTexture(d::kGlTexture2d, 0);
    }
  };
  const turning_disc scene(s.frame_width, s.frame_height);
  const std::size_t w = scene.width, h = scene.height;
  auto r = std::make_shared<resources>(dev);
  const d::gl_resident_api gr(r->gl.loader);
  const hush::frame f = scene.view();
  d::allocate_texture(r->gl, r->tex[0], w, h, d::kGlR32fFormat, d::kGlRedChannel, d::kGlFloat);
  d::allocate_texture(r->gl, r->tex[1], w, h, d::kGlRgb32fFormat, d::kGlRgbChannels, d::kGlFloat);
  d::allocate_texture(r->gl, r->tex[2], w, h, d::kGlR32uiFormat, d::kGlRedInteger,
                      d::kGlUnsignedInt);
  d::allocate_texture(r->gl, r->tex[3], w, h, d::kGlR32fFormat, d::kGlRedChannel, d::kGlFloat);
  d::upload_view(r->gl, gr, r->tex[0], f.depth, d::kGlRedChannel, d::kGlFloat);
  d::upload_view(r->gl, gr, r->tex[1], f.velocity, d::kGlRgbChannels, d::kGlFloat);
  d::upload_view(r->gl, gr, r->tex[2], f.object_id, d::kGlRedInteger, d::kGlUnsignedInt);
  r->frame = {r->tex[0], r->tex[1], r->tex[2], static_cast<std::uint32_t>(w),
              static_cast<std::uint32_t>(h)};
  r->stream = std::make_unique<hush::glsl::coherent_gl_stream>(
      dev, params(hush::coherent_filter::stationary, 0.98), static_cast<std::uint32_t>(w),
      static_cast<std::uint32_t>(h));
  prepared_case p;
  p.samples = w * h;
  std::vector<float> out(w * h);
  {
    hush::basic_coherent_stream<double> reference(params(hush::coherent_filter::stationary, 0.98));
    std::vector<double> ref(w * h);
    for (int i = 0; i < kErrorFrames; ++i) {
      r->stream->advance(r->frame, r->tex[3]);
      r->read(out);
      reference.advance(hush::exec::scalar, f, hush::image_view<double>(ref.data(), w, h));
      for (std::size_t k = 0; k < ref.size(); ++k) p.value_error.add(out[k], ref[k]);
    }
    for (int i = kErrorFrames; i < kQualityFrames; ++i) r->stream->advance(r->frame, r->tex[3]);
    r->read(out);
    p.quality = quality(scene, out);
  }
  const auto advance = [&] { r->stream->advance(r->frame, r->tex[3]); };
  const gl_timing timing(r->gl);
  p.quality += "; resident: " + timing.measure(advance, kTimedFrames, "advance()") + "; " +
               timing.host_only(advance);
  p.run = [r] {
    r->stream->advance(r->frame, r->tex[3]);
    r->gl.Finish();
  };
  return p;
}

void add_coherent_glsl_row(std::vector<bench_case>& cases, const sizes& s,
                           hush::glsl::device& device) {
  bench_case c = row("coherent causal", "glsl", s);
  c.wall_clock = true;
  c.note = "stationary filter, alpha 0.98; uploads the frame, reads the output back";
  hush::glsl::device* dev = &device;
  c.prepare = [s, dev] {
    return prepare_causal(hush::exec::glsl<hush::glsl::device>{*dev}, s,
                          hush::coherent_filter::stationary, 0.98);
  };
  cases.push_back(c);
  bench_case resident = row("coherent causal", "glsl resident", s);
  resident.wall_clock = true;
  resident.note =
      "stationary filter, alpha 0.98; G-buffer and output in GL textures "
      "(coherent_gl_stream), a glFinish per frame, no read-back";
  resident.prepare = [s] { return prepare_resident(bench_resident_device(), s); };
  cases.push_back(resident);
}
#endif

}  // namespace

void add_coherent_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  if (pass == bench_pass::frames) add_coherent_frame_rows(cases, s);
#if HUSH_BENCH_HAVE_GLSL
  if (pass == bench_pass::glsl) add_coherent_glsl_row(cases, s, bench_glsl_device());
#endif
}

}  // namespace hush_bench
