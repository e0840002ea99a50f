// hush — the speed-vs-error benchmark: what every noise's rows are built from (bench/ only).
//
// Each registered noise has one file of rows, bench/<noise>_cases.cpp, defining
// add_<noise>_cases (declared below from HUSH_NOISE_LIST, the registry). all_cases (cases.cpp)
// calls them once per pass, so a new noise adds its file and edits no shared bench file. Here
// are the workloads (every shared constant of the benchmark, once), the row helpers of point
// noises (grids and random points, value and value + gradient, against the double reference)
// and the backends of each pass.
#ifndef HUSH_BENCH_ROWS_HPP
#define HUSH_BENCH_ROWS_HPP

#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cases.hpp"
#include "hush/core/rng.hpp"
#include "hush/exec.hpp"
#include "hush_tools/noise_list.hpp"

#if HUSH_BENCH_HAVE_GLSL
#include "hush/glsl/device.hpp"
#endif

namespace hush_bench {

// ---- The passes. all_cases makes one pass over the noises per entry, in this order, and
// each noise's add_<noise>_cases adds its rows of that pass (none where it has none).
enum class bench_pass {
  scalar,    // hush::exec::scalar
  simd,      // hush::exec::simd
  parallel,  // exec::parallel over exec::simd on kBenchThreads threads (on_parallel_backend)
  frames,    // rows a noise times on every backend at once (frames of scene-driven noises);
             // their SIMD rows are copied pinned to AVX2 after this pass, like the simd pass's
  glsl,      // hush::exec::glsl (builds with a headless context, HUSH_BENCH_HAVE_GLSL)
};

// The rows of every registered noise: add_perlin_cases, add_fractal_cases, ...
#define HUSH_BENCH_DECLARE_CASES(noise) \
  void add_##noise##_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass);
HUSH_NOISE_LIST(HUSH_BENCH_DECLARE_CASES)
#undef HUSH_BENCH_DECLARE_CASES

// The peer libraries' rows (peer_cases.cpp): glm::perlin and libnoise, where found at build
// time, on the point noises' workloads.
void add_peer_cases(std::vector<bench_case>& cases, const sizes& s);

#if HUSH_BENCH_HAVE_GLSL
// The GLSL rows run on one headless context for the whole process (OSMesa's llvmpipe here;
// HUSH_GL_CONTEXT=egl: the machine's GPU).
hush::glsl::device& bench_glsl_device();
// The resident rows' device: on the same context, its GL calls through the wrapped loader
// (tests/glsl/wrapped_loader.hpp), so gl_timing::host_only can count them and skip the GPU's
// work.
hush::glsl::device& bench_resident_device();
// Each noise's shader kit in a user's fragment shader (kit_cases.cpp): the "glsl kit" rows,
// after the glsl pass.
void add_kit_cases(std::vector<bench_case>& cases, const sizes& s);
#endif
// The pool the parallel pass's rows run on (kBenchThreads threads, made on first use).
hush::thread_pool& bench_thread_pool();

// ---- The workloads.

inline constexpr std::uint32_t kNoiseSeed = 7;
inline constexpr int kBenchThreads = 2;            // exec::parallel rows: this machine's cores
inline constexpr std::uint32_t kPointSeed = 2024;  // of the random point sets (hush::rng)
inline constexpr int kFbmOctaves = 4;              // lacunarity 2, gain 0.5: fractal's defaults
// Grid spacing 1/37 lattice units: not a power of two, so sample positions fall at ever
// different fractions and every cell is exercised; the origin is off the lattice too.
inline constexpr double kGridStep = 1.0 / 37;
inline constexpr std::array<double, 3> kGridOrigin = {0.3125, -2.71875, 5.0625};
// Random points fill [-kPointRange, kPointRange)^D.
inline constexpr float kPointRange = 128;

template <int D>
using fvec = hush::vec<float, D>;
template <int D>
using dvec = hush::vec<double, D>;

template <int D>
hush::grid<D> make_grid(const sizes& s) {
  hush::grid<D> g;
  for (int a = 0; a < D; ++a) {
    g.origin[a] = kGridOrigin[a];
    g.step[a] = kGridStep;
    g.size[a] = D == 2 ? s.grid2 : s.grid3;
  }
  return g;
}

template <int D>
std::string grid_name(const hush::grid<D>& g) {
  std::string name = "grid ";
  for (int a = 0; a < D; ++a) name += (a ? "x" : "") + std::to_string(g.size[a]);
  return name;
}

template <int D>
std::vector<fvec<D>> make_points(std::size_t n, float lo = -kPointRange, float hi = kPointRange) {
  hush::rng r(kPointSeed, static_cast<std::uint32_t>(D));
  std::vector<fvec<D>> pts(n);
  for (fvec<D>& p : pts)
    for (int a = 0; a < D; ++a) p[a] = r.uniform(lo, hi);
  return pts;
}

// Calls f(index, position) for every sample of g, in the output's C order (i fastest).
template <int D, class F>
void for_each_sample(const hush::grid<D>& g, F f) {
  const std::size_t nz = D == 3 ? g.size[D - 1] : 1;
  std::size_t idx = 0;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < g.size[1]; ++j)
      for (std::size_t i = 0; i < g.size[0]; ++i, ++idx) {
        std::array<std::size_t, D> ijk{};
        ijk[0] = i;
        ijk[1] = j;
        if constexpr (D == 3) ijk[D - 1] = k;
        f(idx, g.position(ijk));
      }
}

// The buffers a case evaluates into; shared by the case's run() closures.
template <int D>
struct buffers {
  std::vector<fvec<D>> points;
  std::vector<float> out;
  std::vector<fvec<D>> grad;
};

// Keeps the results observable, so the compiler cannot drop the evaluation.
template <class T>
void keep(std::vector<T>& v) {
  benchmark::DoNotOptimize(v.data());
  benchmark::ClobberMemory();
}

// Error of the evaluated (out, grad) against noise's double reference at `pos(idx)`.
template <class Noise, int D>
void measure(const Noise& noise, std::size_t idx, const dvec<D>& pos, const buffers<D>& b,
             prepared_case& p) {
  if (b.grad.empty()) {
    p.value_error.add(b.out[idx], noise.template value<double>(pos));
    return;
  }
  const auto ref = noise.template value_and_gradient<double>(pos);
  p.value_error.add(b.out[idx], ref.value);
  for (int a = 0; a < D; ++a) p.gradient_error.add(b.grad[idx][a], ref.gradient[a]);
}

// ---- Rows of point noises.

template <class Noise, class Exec>
prepared_case prepare_hush_grid(const Noise& noise, const Exec& ex,
                                const hush::grid<Noise::dimension>& g, bool gradient) {
  constexpr int D = Noise::dimension;
  auto b = std::make_shared<buffers<D>>();
  b->out.resize(g.count());
  if (gradient) b->grad.resize(g.count());
  prepared_case p;
  p.samples = g.count();
  p.run = [noise, ex, g, b] {
    if (b->grad.empty())
      hush::evaluate_grid(noise, ex, g, hush::span<float>(b->out));
    else
      hush::evaluate_grid(noise, ex, g, hush::span<float>(b->out), hush::span<fvec<D>>(b->grad));
    keep(b->out);
  };
  p.run();
  for_each_sample(g, [&](std::size_t idx, const dvec<D>& pos) { measure(noise, idx, pos, *b, p); });
  return p;
}

template <class Noise, class Exec>
prepared_case prepare_hush_points(const Noise& noise, const Exec& ex, std::size_t n,
                                  bool gradient, float lo = -kPointRange, float hi = kPointRange) {
  constexpr int D = Noise::dimension;
  auto b = std::make_shared<buffers<D>>();
  b->points = make_points<D>(n, lo, hi);
  b->out.resize(n);
  if (gradient) b->grad.resize(n);
  prepared_case p;
  p.samples = n;
  p.run = [noise, ex, b] {
    const hush::span<const fvec<D>> pts(b->points.data(), b->points.size());
    if (b->grad.empty())
      hush::evaluate(noise, ex, pts, hush::span<float>(b->out));
    else
      hush::evaluate(noise, ex, pts, hush::span<float>(b->out), hush::span<fvec<D>>(b->grad));
    keep(b->out);
  };
  p.run();
  for (std::size_t i = 0; i < n; ++i)
    measure(noise, i, hush::vec_cast<double>(b->points[i]), *b, p);
  return p;
}

// Rows of one noise on one backend: {grid, points} x {value, value + gradient}.
template <class Noise, class Exec>
void add_noise_rows(std::vector<bench_case>& cases, const sizes& s, const std::string& name,
                    const Noise& noise, const Exec& ex) {
  constexpr int D = Noise::dimension;
  const hush::grid<D> g = make_grid<D>(s);
  for (const bool gradient : {false, true}) {
    bench_case c;
    c.noise = name;
    c.backend = Exec::name;
    c.wall_clock = std::string(Exec::name) == "glsl";
    c.gradient = gradient;
    c.workload = grid_name(g);
    c.prepare = [noise, ex, g, gradient] { return prepare_hush_grid(noise, ex, g, gradient); };
    cases.push_back(c);
    const std::size_t n = s.points;
    c.workload = "points " + std::to_string(n);
    c.prepare = [noise, ex, n, gradient] { return prepare_hush_points(noise, ex, n, gradient); };
    cases.push_back(c);
  }
}

// ---- The backends of a pass.

// Calls add(ex) with the hush::exec policy of the scalar, simd and glsl passes (glsl only where
// the build has a headless context); nothing for the other passes.
template <class Add>
void on_backend(bench_pass pass, Add&& add) {
  if (pass == bench_pass::scalar) add(hush::exec::scalar);
  if (pass == bench_pass::simd) add(hush::exec::simd);
#if HUSH_BENCH_HAVE_GLSL
  if (pass == bench_pass::glsl) add(hush::exec::glsl<hush::glsl::device>{bench_glsl_device()});
#endif
}

// For the parallel pass: add(ex) with exec::parallel over exec::simd on bench_thread_pool() (as
// a program with many batches would run it: no thread start per call), the scaling on this
// machine's cores. Its rows are named "simd, N threads" and timed by the wall clock, since the
// work runs on other threads too.
template <class Add>
void on_parallel_backend(std::vector<bench_case>& cases, Add&& add) {
  const std::size_t first = cases.size();
  add(hush::exec::parallel(hush::exec::simd, bench_thread_pool()));
  for (std::size_t i = first; i < cases.size(); ++i) {
    cases[i].backend = "simd, " + std::to_string(kBenchThreads) + " threads";
    cases[i].wall_clock = true;
  }
}

}  // namespace hush_bench

#endif  // HUSH_BENCH_ROWS_HPP
