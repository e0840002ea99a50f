// hush — the speed-vs-error benchmark: the table of cases both the Google Benchmark program
// (bench/speed_vs_error.cpp) and `hush bench` run (DESIGN.md principle 4: throughput is
// reported next to the error against the double-precision reference).
//
// A case is one row of the table: a noise (one of the registry's, or a variant of one: "perlin
// 2D", "fbm 3D", "gabor 2D filtered", "coherent causal", ...), a backend (hush::exec::scalar,
// simd, parallel or glsl, or a peer library), a workload (a uniform grid, random points or
// samples, a frame) and an output (value, or value + gradient). Each noise's rows are in its
// own file, bench/<noise>_cases.cpp (rows.hpp). Preparing a case allocates its buffers,
// evaluates it once and measures its error against the reference; the timed loop then only
// re-runs the evaluation.
#ifndef HUSH_BENCH_CASES_HPP
#define HUSH_BENCH_CASES_HPP

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace hush_bench {

// Workload sizes. The full sizes: 2D grid 512x512, 3D grid 64x64x64, and as
// many random points as a grid has samples (2^18), so every row does the same work.
struct sizes {
  std::size_t grid2 = 512;      // 2D grid: grid2 x grid2
  std::size_t grid3 = 64;       // 3D grid: grid3^3
  std::size_t points = 262144;  // random points, per dimension
  // Scene-driven noises: one frame of frame_width x frame_height pixels (1080p).
  std::size_t frame_width = 1920, frame_height = 1080;
  // Anisotropic noise: the triangles whose least-squares compensation weights are timed
  // (its frame rows use frame_width x frame_height, a receding plane).
  std::size_t triangles = 1024;
  // NPR Gabor noise: frames of the `dense` scene with about these many triangles, at
  // npr_width x npr_height (1280x720 and 5k / 50k / 200k triangles).
  std::size_t npr_width = 1280, npr_height = 720;
  std::vector<long> npr_triangles = {5000, 50000, 200000};
};
sizes full_sizes();
sizes quick_sizes();  // for `hush bench --quick` and the smoke test: a few seconds in all

// Max abs and RMS of (measured - reference) over every sample (and every gradient component).
struct error_stats {
  double max_abs = 0;
  double sum_sq = 0;
  std::size_t count = 0;
  void add(double measured, double reference);
  double rms() const;
};

// What a row's error column compares against.
enum class error_reference {
  hush_double,  // hush's double-precision evaluation at the same positions
  glm_double,   // glm::perlin on glm::dvec at the same (float-rounded) positions: like for like
  none,         // the library computes in double only (libnoise): no float error to report
  weights,      // a preprocessing row (anisotropic compensation weights): no samples to compare
};
const char* describe(error_reference r);

// A case ready to time: run() evaluates the whole workload once, into buffers the case owns.
struct prepared_case {
  std::size_t samples = 0;
  std::function<void()> run;
  error_stats value_error;
  error_stats gradient_error;  // count 0 when the case computes no gradient
  // The noise's own quality metric, measured while preparing, as text ("" when none).
  std::string quality;
};

struct bench_case {
  std::string noise;      // "perlin 2D", "fbm 3D"
  std::string backend;    // "scalar", "simd", "glm::perlin", "libnoise"
  std::string workload;   // "grid 512x512", "points 262144"
  bool gradient = false;  // value + analytic gradient
  bool peer = false;      // another library, for comparison
  error_reference reference = error_reference::hush_double;
  std::string note;  // how a peer row was configured, when that matters
  // Time by the wall clock, not this thread's CPU time: for backends whose work runs on other
  // threads (GLSL on llvmpipe's worker threads, or a GPU).
  bool wall_clock = false;
  // Scene-driven noises: pixels per frame (the table adds ms/frame); 0 for point noises.
  std::size_t frame_pixels = 0;
  std::function<prepared_case()> prepare;
  // Where a run leaves prepared_case::quality for the report (shared by the case's copies).
  std::shared_ptr<std::string> quality = std::make_shared<std::string>();
  // "perlin2D/scalar/grid/value": the Google Benchmark name, unique in the table.
  std::string id() const;
};

// Every case: hush's noises on each backend (bench/<noise>_cases.cpp, one pass per backend
// over the registry's noises), then the peer libraries found at build time.
std::vector<bench_case> all_cases(const sizes& s);

// The Google Benchmark counters each case reports: CPU seconds per sample (single thread; wall
// seconds for wall_clock cases), and
// its error against the reference (none for error_reference::none; gradient ones only for
// gradient cases).
inline constexpr const char* kSecondsPerSample = "s/sample";
inline constexpr const char* kMaxAbs = "max_abs";
inline constexpr const char* kRms = "rms";
inline constexpr const char* kGradMaxAbs = "grad_max_abs";
inline constexpr const char* kGradRms = "grad_rms";

// Which prepared cases a run keeps in memory. Preparing a case can take seconds (it evaluates
// the double-precision reference), and the full table's buffers together are large.
enum class keep_prepared {
  latest,  // the case running now only: cases run one after another, so each is prepared once
  all,     // every case until the run ends: for interleaved repetitions, where cases alternate
};

// The prepared cases of one run: register_benchmarks' cases take their buffers from here.
// Destroying it (after the run) frees every buffer it holds.
class prepared_cases {
 public:
  explicit prepared_cases(keep_prepared keep) : keep_(keep) {}
  // `c` ready to time, prepared on its first use here (which also sets *c.quality). Under
  // keep_prepared::latest, preparing a case first frees the one held, so one case's memory is
  // held at a time; under keep_prepared::all every case stays until destruction.
  prepared_case& get(const bench_case& c);

 private:
  keep_prepared keep_;
  std::map<const bench_case*, prepared_case> held_;
};

// Called after each timed loop of a case with the loop's iteration count (e.g. for progress).
using loop_observer = std::function<void(const bench_case& c, std::int64_t iterations)>;

// Registers `cases` with Google Benchmark under their id(), reporting the counters above;
// each case takes its buffers from `prepared` (whose keep_prepared suits the run's order:
// keep_prepared::all when Google Benchmark interleaves the repetitions, else latest).
// `cases` and `prepared` must outlive the run.
// min_time: seconds per repetition; repetitions: > 1 reports only the aggregates (mean,
// median, ...). Either <= 0 leaves it to Google Benchmark's flags. after_loop: called after
// every timed loop, or nothing when empty.
void register_benchmarks(const std::vector<bench_case>& cases, double min_time, int repetitions,
                         prepared_cases& prepared, const loop_observer& after_loop = {});

// The machine a run measured, for the report.
struct machine_info {
  std::string cpu;       // "model name" from /proc/cpuinfo
  int cpus = 0;          // logical CPUs
  double mhz = 0;        // as Google Benchmark measures it
  std::string compiler;  // e.g. "GCC 12.2.0"
  std::string build;     // "Release -O2" etc.: what this program was compiled with
  std::string simd_target;
  std::string peers;  // the peer libraries compiled in
  std::string load;   // 1, 5 and 15 minute load averages when asked: timings on a busy machine
                      // are noisier
};
machine_info describe_machine();

// The SIMD target hush::exec::simd dispatches to on this machine, and the dispatch mode.
std::string simd_target();

}  // namespace hush_bench

#endif  // HUSH_BENCH_CASES_HPP
