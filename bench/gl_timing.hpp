// hush — the speed-vs-error benchmark: host and GPU time of the resident GLSL rows (coherent
// noise's and NPR Gabor noise's "glsl resident" rows, anisotropic noise's resident frame).
// measure() runs a frame `frames` times, each inside a GL_TIME_ELAPSED query: the host's wall
// time of the call alone (no glFinish in it) and the GPU's time of the commands it issued,
// medians, as a note for the row. host_only() times the call with the GPU's work skipped, on
// bench_resident_device() (rows.hpp), whose loader wraps every entry point hush loads.
#ifndef HUSH_BENCH_GL_TIMING_HPP
#define HUSH_BENCH_GL_TIMING_HPP

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "glsl/wrapped_loader.hpp"
#include "hush/glsl/detail/gl.hpp"

namespace hush_bench {

class gl_timing {
 public:
  explicit gl_timing(const hush::glsl::detail::gl_api& gl) : gl_(gl) {
    namespace d = hush::glsl::detail;
    d::gl_api::load(gl.loader, GenQueries_, "glGenQueries");
    d::gl_api::load(gl.loader, DeleteQueries_, "glDeleteQueries");
    d::gl_api::load(gl.loader, BeginQuery_, "glBeginQuery");
    d::gl_api::load(gl.loader, EndQuery_, "glEndQuery");
    d::gl_api::load(gl.loader, GetQueryObjectui64v_, "glGetQueryObjectui64v");
  }

  // "host H ms/frame in <what>, GPU G ms/frame (GL_TIME_ELAPSED), medians of <frames>".
  template <class Frame>
  std::string measure(Frame frame, int frames, const char* what) const {
    namespace d = hush::glsl::detail;
    constexpr d::gl_enum kTimeElapsed = 0x88BF, kQueryResult = 0x8866;
    std::vector<d::gl_uint> queries(static_cast<std::size_t>(frames));
    GenQueries_(frames, queries.data());
    std::vector<double> host(queries.size()), gpu(queries.size());
    gl_.Finish();
    for (std::size_t i = 0; i < queries.size(); ++i) {
      BeginQuery_(kTimeElapsed, queries[i]);
      const auto t0 = std::chrono::steady_clock::now();
      frame();
      const auto t1 = std::chrono::steady_clock::now();
      EndQuery_(kTimeElapsed);
      host[i] = std::chrono::duration<double, std::milli>(t1 - t0).count();
    }
    gl_.Finish();
    for (std::size_t i = 0; i < queries.size(); ++i) {
      std::uint64_t ns = 0;
      GetQueryObjectui64v_(queries[i], kQueryResult, &ns);
      gpu[i] = static_cast<double>(ns) * 1e-6;
    }
    DeleteQueries_(frames, queries.data());
    std::sort(host.begin(), host.end());
    std::sort(gpu.begin(), gpu.end());
    char text[200];
    std::snprintf(text, sizeof text,
                  "host %.3f ms/frame in %s, GPU %.3f ms/frame (GL_TIME_ELAPSED), medians of %d",
                  host[host.size() / 2], what, gpu[gpu.size() / 2], frames);
    return text;
  }

  // "host-only H ms/frame, C GL calls/frame (W of them draws, dispatches or clears, skipped),
  // medians of <frames>": the host's own work per frame. On llvmpipe a dispatch or draw runs
  // inside the call, so measure()'s host time holds the GPU's work; here
  // glDispatchCompute(Indirect), glDrawArrays(Indirect) and glClear return at once and every
  // other call (state, binds, uniforms, buffer allocation, uploads, fences) runs for real.
  // `frame` must call GL only through bench_resident_device() and have run for real before
  // (programs compiled, NPR Gabor's capacities set by its first frame). Frames >= 1.
  static constexpr int kHostOnlyFrames = 20;
  template <class Frame>
  std::string host_only(Frame frame, int frames = kHostOnlyFrames) const {
    std::vector<double> host(static_cast<std::size_t>(frames));
    std::vector<long long> calls(host.size()), work(host.size());
    gl_.Finish();  // the real frames' work done: their fences polled as signalled
    {
      const hush_glsl_test::skipping_gpu_work skip;
      for (std::size_t i = 0; i < host.size(); ++i) {
        const long long work0 = hush_glsl_test::wrapped_gl::gpu_work_calls();
        const auto t0 = std::chrono::steady_clock::now();
        calls[i] = hush_glsl_test::gl_calls_of(frame);
        const auto t1 = std::chrono::steady_clock::now();
        work[i] = hush_glsl_test::wrapped_gl::gpu_work_calls() - work0;
        host[i] = std::chrono::duration<double, std::milli>(t1 - t0).count();
      }
    }
    std::sort(host.begin(), host.end());
    std::sort(calls.begin(), calls.end());
    std::sort(work.begin(), work.end());
    char text[200];
    std::snprintf(text, sizeof text,
                  "host-only %.4f ms/frame, %lld GL calls/frame (%lld of them draws, dispatches "
                  "or clears, skipped), medians of %d",
                  host[host.size() / 2], calls[calls.size() / 2], work[work.size() / 2], frames);
    return text;
  }

 private:
  using uint = hush::glsl::detail::gl_uint;
  using sizei = hush::glsl::detail::gl_sizei;
  using glenum = hush::glsl::detail::gl_enum;
  const hush::glsl::detail::gl_api& gl_;
  void(HUSH_GLAPI* GenQueries_)(sizei, uint*) = nullptr;
  void(HUSH_GLAPI* DeleteQueries_)(sizei, const uint*) = nullptr;
  void(HUSH_GLAPI* BeginQuery_)(glenum, uint) = nullptr;
  void(HUSH_GLAPI* EndQuery_)(glenum) = nullptr;
  void(HUSH_GLAPI* GetQueryObjectui64v_)(uint, glenum, std::uint64_t*) = nullptr;
};

}  // namespace hush_bench

#endif  // HUSH_BENCH_GL_TIMING_HPP
