// hush — the speed-vs-error benchmark's cases (see cases.hpp): the table assembled from every
// noise's rows (bench/<noise>_cases.cpp, rows.hpp) and the peers' (peer_cases.cpp), and the
// Google Benchmark plumbing both the bench program and `hush bench` use.
#include "cases.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "hush/exec.hpp"
#include "hush_tools/noise_list.hpp"
#include "rows.hpp"

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
#include <hwy/targets.h>
#endif
#if HUSH_BENCH_HAVE_GLSL
#include "glsl/wrapped_loader.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/headless.hpp"
#endif

namespace hush_bench {
namespace {

// The quick sizes (sizes's defaults are the full ones).
constexpr std::size_t kQuickGrid2 = 64, kQuickGrid3 = 16, kQuickPoints = 4096;
constexpr std::size_t kQuickFrameWidth = 192, kQuickFrameHeight = 108;

// Every registered noise's rows, in registry order (HUSH_NOISE_LIST).
using add_cases_fn = void (*)(std::vector<bench_case>&, const sizes&, bench_pass);
struct noise_rows {
  std::string_view noise;
  add_cases_fn add;
};
#define HUSH_BENCH_NOISE_ROWS(noise) noise_rows{#noise, &add_##noise##_cases},
constexpr noise_rows kNoiseRows[] = {HUSH_NOISE_LIST(HUSH_BENCH_NOISE_ROWS)};
#undef HUSH_BENCH_NOISE_ROWS

// The order of the noises' rows within a pass. A noise not named here follows these, in
// registry order, so a new noise needs no place in it.
constexpr std::string_view kRowOrder[] = {"perlin",   "fractal",     "gabor",    "wavelet",
                                          "coherent", "anisotropic", "npr_gabor"};

// Every noise's rows of `pass`, in kRowOrder's order.
void add_pass(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  std::vector<noise_rows> noises(std::begin(kNoiseRows), std::end(kNoiseRows));
  hush_tools::put_in_order(noises, kRowOrder, [](const noise_rows& n) { return n.noise; });
  for (const noise_rows& n : noises) n.add(cases, s, pass);
}

}  // namespace

sizes full_sizes() { return sizes{}; }
sizes quick_sizes() {
  sizes s{kQuickGrid2, kQuickGrid3, kQuickPoints, kQuickFrameWidth, kQuickFrameHeight};
  s.triangles = 16;
  s.npr_width = kQuickFrameWidth;
  s.npr_height = kQuickFrameHeight;
  s.npr_triangles = {5000};
  return s;
}

void error_stats::add(double measured, double reference) {
  const double e = measured - reference;
  max_abs = std::fmax(max_abs, std::fabs(e));
  sum_sq += e * e;
  ++count;
}

double error_stats::rms() const {
  return count ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
}

const char* describe(error_reference r) {
  switch (r) {
    case error_reference::hush_double:
      return "hush double";
    case error_reference::glm_double:
      return "glm double";
    case error_reference::none:
      return "n.a. (double only)";
    case error_reference::weights:
      return "n.a. (preprocessing)";
  }
  return "?";
}

std::string bench_case::id() const {
  std::string n = noise + "/" + backend + "/" + workload.substr(0, workload.find(' ')) + "/" +
                  (gradient ? "value+gradient" : "value");
  std::string id;
  for (const char ch : n)
    if (ch != ' ') id += ch == ':' ? '_' : ch;
  return id;
}

#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
// The SIMD rows again with dispatch pinned to one target (e.g. AVX2 on an AVX-512 machine),
// named "simd AVX2": the targets are stated per machine, and a program may run on either.
void add_pinned_simd_rows(std::vector<bench_case>& cases, std::int64_t target) {
  std::vector<bench_case> pinned;
  for (const bench_case& c : cases) {
    if (c.backend != hush::exec::simd_t::name && c.backend.rfind("memory-bound pass", 0) != 0)
      continue;
    bench_case p = c;
    p.backend = std::string(c.backend) + " " + hwy::TargetName(target);
    p.prepare = [prepare = c.prepare, target] {
      hwy::SetSupportedTargetsForTest(target);
      prepared_case r = prepare();
      hwy::SetSupportedTargetsForTest(0);
      r.run = [run = r.run, target] {
        hwy::SetSupportedTargetsForTest(target);
        run();
        hwy::SetSupportedTargetsForTest(0);
      };
      return r;
    };
    pinned.push_back(std::move(p));
  }
  cases.insert(cases.end(), pinned.begin(), pinned.end());
}
#endif

#if HUSH_BENCH_HAVE_GLSL
namespace {
hush::glsl::headless_device& bench_headless() {
  static hush::glsl::headless_device h;
  return h;
}
}  // namespace

hush::glsl::device& bench_glsl_device() { return bench_headless().device; }

hush::glsl::device& bench_resident_device() {
  return hush_glsl_test::wrapped_device(bench_headless().context.loader());
}
#endif

hush::thread_pool& bench_thread_pool() {
  static hush::thread_pool pool(kBenchThreads);  // outlives every case that captures it
  return pool;
}

std::vector<bench_case> all_cases(const sizes& s) {
  std::vector<bench_case> cases;
  for (const bench_pass pass :
       {bench_pass::scalar, bench_pass::simd, bench_pass::parallel, bench_pass::frames})
    add_pass(cases, s, pass);
#if HUSH_CONFIG_SIMD && !HUSH_CONFIG_SIMD_STATIC
  // AVX2 pinned when the machine would pick something better (AVX2 is the common baseline).
  const std::int64_t usable = hwy::SupportedTargets() & HWY_TARGETS;
  if ((usable & HWY_AVX2) && (usable & (HWY_AVX2 - 1))) add_pinned_simd_rows(cases, HWY_AVX2);
#endif
#if HUSH_BENCH_HAVE_GLSL
  add_pass(cases, s, bench_pass::glsl);
  add_kit_cases(cases, s);
#endif
  add_peer_cases(cases, s);
  // Rows made by copying a case (the backend and pinned-target variants) copied its quality
  // pointer too: give every row its own, so that no row reports a sibling's note.
  for (bench_case& c : cases) c.quality = std::make_shared<std::string>();
  return cases;
}

namespace {

// Runs one case under Google Benchmark, which calls it again per repetition and while it
// sizes the iteration count; `prepared` prepares the case on its first call.
void run_case(benchmark::State& state, const bench_case& c, prepared_cases& prepared,
              const loop_observer& after_loop) {
  prepared_case& p = prepared.get(c);
  for (auto _ : state)  // NOLINT(clang-analyzer-deadcode.DeadStores): Google Benchmark's idiom
    p.run();
  if (after_loop) after_loop(c, static_cast<std::int64_t>(state.iterations()));
  const double samples = static_cast<double>(p.samples);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(p.samples));
  // Samples per iteration as a rate, inverted: CPU seconds per sample (printed "25.8ns").
  state.counters[kSecondsPerSample] = benchmark::Counter(
      samples, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if (c.reference == error_reference::none || c.reference == error_reference::weights) return;
  state.counters[kMaxAbs] = p.value_error.max_abs;
  state.counters[kRms] = p.value_error.rms();
  if (p.gradient_error.count) {
    state.counters[kGradMaxAbs] = p.gradient_error.max_abs;
    state.counters[kGradRms] = p.gradient_error.rms();
  }
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos && colon + 2 <= line.size()) return line.substr(colon + 2);
    }
  return "unknown";
}

}  // namespace

prepared_case& prepared_cases::get(const bench_case& c) {
  const auto it = held_.find(&c);
  if (it != held_.end()) return it->second;
  // Free the held case before preparing the next, so that two are never held together.
  if (keep_ == keep_prepared::latest) held_.clear();
  prepared_case& p = held_.emplace(&c, c.prepare()).first->second;
  *c.quality = p.quality;
  return p;
}

void register_benchmarks(const std::vector<bench_case>& cases, double min_time, int repetitions,
                         prepared_cases& prepared, const loop_observer& after_loop) {
  for (const bench_case& c : cases) {
    // Google Benchmark's registry owns what RegisterBenchmark allocates; the analyzer cannot
    // see that (the registry is in the compiled library).
    // NOLINTNEXTLINE(clang-analyzer-cplusplus.NewDeleteLeaks)
    benchmark::internal::Benchmark* b = benchmark::RegisterBenchmark(
        c.id().c_str(), [&c, &prepared, after_loop](benchmark::State& state) {
          run_case(state, c, prepared, after_loop);
        });
    b->Unit(benchmark::kMillisecond);
    if (c.wall_clock) b->UseRealTime();
    if (repetitions > 0) b->Repetitions(repetitions);
    if (repetitions > 1) b->ReportAggregatesOnly(true);
    if (min_time > 0) b->MinTime(min_time);
  }
}

std::string simd_target() {
#if HUSH_CONFIG_SIMD
  return hush::simd::chosen_target() + " (" + hush::simd::dispatch_mode() + " dispatch)";
#else
  return "none (built without Highway: exec::simd runs the scalar loop)";
#endif
}

machine_info describe_machine() {
  machine_info m;
  m.cpu = cpu_model();
  const benchmark::CPUInfo& info = benchmark::CPUInfo::Get();
  m.cpus = info.num_cpus;
  m.mhz = info.cycles_per_second / 1e6;
  for (const double l : info.load_avg) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", l);
    m.load += (m.load.empty() ? "" : ", ") + std::string(buf);
  }
  if (m.load.empty()) m.load = "unknown";
#if defined(__clang__)
  m.compiler = "Clang " __clang_version__;
#elif defined(__GNUC__)
  m.compiler = "GCC " __VERSION__;
#else
  m.compiler = "unknown";
#endif
  m.build = HUSH_BENCH_BUILD;
#if defined(__AVX2__)
  m.build += ", compiled for AVX2";
#elif defined(__SSE4_2__)
  m.build += ", compiled for SSE4.2";
#else
  m.build += ", baseline x86-64 ISA (no -march)";
#endif
  m.simd_target = simd_target();
  m.peers = "";
#if HUSH_BENCH_HAVE_GLM
  m.peers += "glm " + std::to_string(GLM_VERSION_MAJOR) + "." + std::to_string(GLM_VERSION_MINOR) +
             "." + std::to_string(GLM_VERSION_PATCH) + "." + std::to_string(GLM_VERSION_REVISION);
#endif
#if HUSH_BENCH_HAVE_LIBNOISE
  m.peers += std::string(m.peers.empty() ? "" : ", ") + "libnoise (no version macro)";
#endif
  if (m.peers.empty()) m.peers = "none found at build time";
  return m;
}

}  // namespace hush_bench
