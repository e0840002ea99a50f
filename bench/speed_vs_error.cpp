// hush — the speed-vs-error benchmark as a Google Benchmark program: every case of
// bench/cases.hpp, each reporting ns/sample (CPU time, single thread) and its error against
// the double reference as counters (max_abs, rms, grad_max_abs, grad_rms).
//
//   build/rel/bench/hush_speed_vs_error --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true --benchmark_filter=perlin2D
//   build/rel/bench/hush_speed_vs_error --quick ...   (the small sizes of `hush bench --quick`)
//
// `hush bench` runs the same cases and prints the table as Markdown and JSON.
#include <benchmark/benchmark.h>

#include <cstring>
#include <vector>

#include "cases.hpp"

int main(int argc, char** argv) {
  // --quick is ours; everything else goes to Google Benchmark.
  bool quick = false;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (i > 0 && std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else
      args.push_back(argv[i]);
  }
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 1;
  // Repetitions and min time come from Google Benchmark's flags (1 and its default).
  const std::vector<hush_bench::bench_case> cases =
      hush_bench::all_cases(quick ? hush_bench::quick_sizes() : hush_bench::full_sizes());
  // One case's buffers at a time: Google Benchmark runs the cases one after another unless
  // given --benchmark_enable_random_interleaving=true, which then re-prepares a case (seconds)
  // whenever the next repetition is another case's; `hush bench --interleave` keeps them all.
  hush_bench::prepared_cases prepared(hush_bench::keep_prepared::latest);
  hush_bench::register_benchmarks(cases, 0.0, 0, prepared);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
