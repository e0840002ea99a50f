// hush — the `hush` program: `hush bench [--quick] [--interleave] [--json FILE]
// [--markdown FILE] [--plot FILE.svg] [--repetitions n] [--filter TEXT]`, the speed-vs-error
// table (DESIGN.md principle 4).
//
// It runs bench/'s cases (the ones the hush_speed_vs_error program runs) through Google
// Benchmark's library with a reporter that keeps, per case, the median over the repetitions
// of the CPU time per sample, and the case's error counters. The Markdown table goes to
// stdout (and --markdown FILE), the same rows with machine information to --json FILE, and a
// speed-vs-error scatter plot to --plot FILE.svg. Progress goes to stderr. --interleave runs
// the repetitions of all cases in random order (Google Benchmark's random interleaving), so
// that rows compared with each other are measured over the same stretch of time.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "hush/config.hpp"
#include "output_file.hpp"
#include "plot.hpp"
#include "progress.hpp"

#if HUSH_CLI_HAVE_BENCH
#include <benchmark/benchmark.h>

#include "cases.hpp"
#endif

namespace hush_cli {
namespace {

// Repetitions and minimum time per repetition: the full run (about a minute here) and
// --quick (a few seconds, for the smoke test).
constexpr int kRepetitions = 5;
constexpr int kMaxRepetitions = 100;
#if HUSH_CLI_HAVE_BENCH
constexpr double kMinTime = 0.1;
constexpr double kQuickMinTime = 0.002;
#endif

struct bench_request {
  bool quick = false;
  bool interleave = false;  // repetitions of all cases in random order
  int repetitions = kRepetitions;
  std::string filter;
  std::string json, markdown, plot;
  std::string command;  // as typed, for the report
};

bench_request parse_bench(const std::vector<std::string>& args) {
  bench_request r;
  r.command = "hush bench";
  std::vector<std::string> rest;
  for (const std::string& a : args) {
    r.command += " " + a;
    if (a == "--quick")
      r.quick = true;  // the flags, which take no value
    else if (a == "--interleave")
      r.interleave = true;
    else
      rest.push_back(a);
  }
  if (r.quick) r.repetitions = 1;
  arg_reader in(rest);
  while (!in.done()) {
    const std::string name = in.option(bench_options()).name;
    const std::string v = in.value();
    if (name == "--quick" || name == "--interleave") {
      std::string what = name + " is a flag and takes no value; got '";
      throw usage_error(what.append(v).append("'"));
    }
    if (name == "--json") r.json = v;
    if (name == "--markdown") r.markdown = v;
    if (name == "--filter") r.filter = v;
    if (name == "--repetitions")
      r.repetitions = static_cast<int>(parse_integer(name, v, 1, kMaxRepetitions));
    if (name == "--plot") {
      if (v.size() < 5 || v.compare(v.size() - 4, 4, ".svg") != 0)
        throw_bad_value("--plot", v, "a file name ending in .svg");
      r.plot = v;
    }
  }
  // Fail before a minute of measuring, not after, when an output cannot be created.
  for (const std::string* path : {&r.json, &r.markdown, &r.plot}) {
    if (path->empty()) continue;
    const std::filesystem::path dir = std::filesystem::path(*path).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
      throw run_error("cannot write '" + *path + "': directory '" + dir.string() +
                      "' does not exist");
  }
  return r;
}

#if HUSH_CLI_HAVE_BENCH

// One row of the report: a case and what its run measured.
struct bench_row {
  const hush_bench::bench_case* c = nullptr;
  double ns = NAN;                                                      // median ns/sample
  double max_abs = NAN, rms = NAN, grad_max_abs = NAN, grad_rms = NAN;  // NaN: not applicable
  int repetitions = 0;
};

// Keeps the median aggregate of each case (or its only run when there is one repetition).
// Google Benchmark 1.7 reports a case once, after its last repetition, also when it
// interleaves the repetitions of several cases (benchmark.cc, RunBenchmarks).
class row_reporter : public benchmark::BenchmarkReporter {
 public:
  explicit row_reporter(const std::vector<hush_bench::bench_case>& cases) {
    for (const hush_bench::bench_case& c : cases) {
      index_[c.id()] = rows_.size();
      rows_.push_back(bench_row{&c});
    }
  }
  bool ReportContext(const Context& /*context*/) override { return true; }
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      const auto it = index_.find(run.run_name.function_name);
      if (it == index_.end()) continue;
      if (run.error_occurred) {  // reported after the run: exceptions stay out of the library
        if (error_.empty()) error_ = "case " + it->first + " failed: " + run.error_message;
        continue;
      }
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      const bool single = run.run_type == Run::RT_Iteration && run.repetitions <= 1;
      if (!median && !single) continue;
      bench_row& row = rows_[it->second];
      row.repetitions = static_cast<int>(run.repetitions);
      auto counter = [&run](const char* name) {
        const auto c = run.counters.find(name);
        return c == run.counters.end() ? NAN : c->second.value;
      };
      row.ns = counter(hush_bench::kSecondsPerSample) * 1e9;
      row.max_abs = counter(hush_bench::kMaxAbs);
      row.rms = counter(hush_bench::kRms);
      row.grad_max_abs = counter(hush_bench::kGradMaxAbs);
      row.grad_rms = counter(hush_bench::kGradRms);
    }
  }
  const std::vector<bench_row>& rows() const { return rows_; }
  const std::string& error() const { return error_; }  // the first failed case, or ""

 private:
  std::map<std::string, std::size_t> index_;
  std::vector<bench_row> rows_;
  std::string error_;
};

// Progress in repetitions, counted from the timed loops: the reporter hears of a case only
// after its last repetition, which under --interleave comes near the end of the run for most
// cases. Google Benchmark 1.7 (benchmark_runner.cc, DoOneRepetition) sizes a case's first
// repetition by loops of growing iteration counts, back to back, and runs each later
// repetition as one loop of the final count; so a loop starts a repetition when it belongs to
// another case than the loop before, or its count did not grow.
class repetition_progress {
 public:
  repetition_progress(progress& bar, std::uint64_t total) : bar_(bar), total_(total) {}
  void loop_done(const hush_bench::bench_case& c, std::int64_t iterations) {
    if (last_ && (&c != last_ || iterations <= last_iterations_))
      bar_.update(std::min(++finished_, total_ - 1));  // 100% only when the run has ended
    last_ = &c;
    last_iterations_ = iterations;
  }
  void run_ended() { bar_.update(total_); }

 private:
  progress& bar_;
  std::uint64_t total_;
  std::uint64_t finished_ = 0;
  const hush_bench::bench_case* last_ = nullptr;
  std::int64_t last_iterations_ = 0;
};

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

std::string error_cell(double v) { return std::isfinite(v) ? format("%.2e", v) : "n.a."; }

std::string error_reference_cell(const hush_bench::bench_case& c) {
  return std::string(hush_bench::describe(c.reference)) + (c.note.empty() ? "" : "; " + c.note) +
         (c.quality->empty() ? "" : "; " + *c.quality);
}

// ns/sample, and ms per frame for scene-driven rows.
std::string time_cell(const bench_row& row) {
  std::string t = format("%.2f", row.ns);
  if (row.c->frame_pixels)
    t += format(" (%.2f ms/frame)", row.ns * static_cast<double>(row.c->frame_pixels) * 1e-6);
  return t;
}

std::string markdown(const std::vector<bench_row>& rows, const hush_bench::machine_info& m,
                     const bench_request& r, const std::string& date) {
  std::ostringstream os;
  os << "Measured " << date << " by `" << r.command << "` on " << m.cpu << " (" << m.cpus
     << " logical CPUs, load average " << m.load << "), " << m.compiler << ", " << m.build
     << "; SIMD target: " << m.simd_target << ". ns/sample: median of " << r.repetitions
     << " repetition(s)"
     << (r.interleave ? " (the repetitions of all rows interleaved in random order)" : "")
     << ", CPU time, one thread (GLSL rows: wall time; llvmpipe runs its own "
        "threads). Errors: against the double-precision reference"
        " named in the last column, at the same positions.\n\n"
     << "| noise | backend | workload | output | ns/sample | max abs error | RMS error | "
        "gradient max abs | gradient RMS | error against |\n"
     << "|---|---|---|---|--:|--:|--:|--:|--:|---|\n";
  for (const bench_row& row : rows) {
    const hush_bench::bench_case& c = *row.c;
    os << "| " << c.noise << " | " << c.backend << " | " << c.workload << " | "
       << (c.gradient ? "value + gradient" : "value") << " | " << time_cell(row) << " | "
       << error_cell(row.max_abs) << " | " << error_cell(row.rms) << " | "
       << (c.gradient ? error_cell(row.grad_max_abs) : "-") << " | "
       << (c.gradient ? error_cell(row.grad_rms) : "-") << " | " << error_reference_cell(c)
       << " |\n";
  }
  return os.str();
}

std::string json_string(const std::string& s) {
  std::string r = "\"";
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') {
      r += '\\';
      r += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(ch));
      r += buf;
    } else {
      r += ch;
    }
  }
  return r + "\"";
}

// A number, or null when it does not apply (JSON has no NaN).
std::string json_number(double v) { return std::isfinite(v) ? format("%.9g", v) : "null"; }

std::string json(const std::vector<bench_row>& rows, const hush_bench::machine_info& m,
                 const bench_request& r, const hush_bench::sizes& s, const std::string& date) {
  std::ostringstream os;
  os << "{\n  \"hush_version\": " << json_string(HUSH_VERSION_STRING) << ",\n"
     << "  \"command\": " << json_string(r.command) << ",\n"
     << "  \"date\": " << json_string(date) << ",\n"
     << "  \"machine\": {\"cpu\": " << json_string(m.cpu) << ", \"logical_cpus\": " << m.cpus
     << ", \"mhz\": " << json_number(m.mhz) << ", \"compiler\": " << json_string(m.compiler)
     << ", \"build\": " << json_string(m.build)
     << ", \"simd_target\": " << json_string(m.simd_target)
     << ", \"peers\": " << json_string(m.peers) << ", \"load_average\": " << json_string(m.load)
     << "},\n"
     << "  \"settings\": {\"quick\": " << (r.quick ? "true" : "false")
     << ", \"interleave\": " << (r.interleave ? "true" : "false")
     << ", \"repetitions\": " << r.repetitions
     << ", \"min_time_s\": " << json_number(r.quick ? kQuickMinTime : kMinTime)
     << ", \"statistic\": \"median\", \"timer\": \"CPU time, one thread; wall time for GLSL rows\""
     << ", \"filter\": " << json_string(r.filter) << ", \"grid2\": " << s.grid2
     << ", \"grid3\": " << s.grid3 << ", \"points\": " << s.points << "},\n"
     << "  \"rows\": [";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const bench_row& row = rows[i];
    const hush_bench::bench_case& c = *row.c;
    os << (i ? ",\n" : "\n") << "    {\"id\": " << json_string(c.id())
       << ", \"noise\": " << json_string(c.noise) << ", \"backend\": " << json_string(c.backend)
       << ", \"workload\": " << json_string(c.workload)
       << ", \"output\": " << json_string(c.gradient ? "value+gradient" : "value")
       << ", \"peer\": " << (c.peer ? "true" : "false") << ", \"repetitions\": " << row.repetitions
       << ", \"ns_per_sample\": " << json_number(row.ns)
       << ", \"max_abs_error\": " << json_number(row.max_abs)
       << ", \"rms_error\": " << json_number(row.rms)
       << ", \"gradient_max_abs_error\": " << json_number(row.grad_max_abs)
       << ", \"gradient_rms_error\": " << json_number(row.grad_rms)
       << ", \"error_reference\": " << json_string(hush_bench::describe(c.reference))
       << ", \"note\": " << json_string(c.note) << ", \"quality\": " << json_string(*c.quality)
       << ", \"frame_pixels\": " << c.frame_pixels << "}";
  }
  os << "\n  ]\n}\n";
  return os.str();
}

// Colour per backend (in order of first appearance); hush rows: circle = value, square =
// value + gradient; peers: hollow diamonds and triangles.
scatter_plot plot(const std::vector<bench_row>& rows, const hush_bench::machine_info& m,
                  const bench_request& r) {
  static const char* const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                        "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
  scatter_plot p;
  p.title = "hush: speed vs error (one thread, median ns/sample)";
  p.x_label = "ns/sample (log scale)";
  p.y_label = "max abs error against the double reference (log scale)";
  p.floor_note = "floor: error 0, or not applicable (libnoise computes in double only)";
  p.footer = m.cpu + ", " + m.compiler + "; " + r.command;
  std::map<std::string, std::size_t> series, colours;
  std::size_t peers = 0;
  for (const bench_row& row : rows) {
    const hush_bench::bench_case& c = *row.c;
    const std::string key =
        c.peer ? c.backend : c.backend + (c.gradient ? ", value + gradient" : ", value");
    if (!series.count(key)) {
      if (!colours.count(c.backend)) colours[c.backend] = colours.size();
      plot_series s;
      s.name = key;
      s.colour = palette[colours[c.backend] % (sizeof palette / sizeof palette[0])];
      s.shape = c.peer ? (peers++ % 2 ? marker::triangle : marker::diamond)
                       : (c.gradient ? marker::square : marker::circle);
      s.hollow = c.peer;
      series[key] = p.series.size();
      p.series.push_back(s);
    }
    plot_point pt;
    pt.x = row.ns;
    pt.y = row.max_abs;
    pt.label = c.noise + " " + c.workload.substr(0, c.workload.find(' '));
    pt.series = series[key];
    p.points.push_back(pt);
  }
  return p;
}

// Google Benchmark reads its flags once, from this argv: none from us (the cases set their
// own minimum time and repetitions) but the random interleaving of repetitions.
void initialize_benchmark(bool interleave) {
  char name[] = "hush";
  char interleave_flag[] = "--benchmark_enable_random_interleaving=true";
  std::vector<char*> argv = {name};
  if (interleave) argv.push_back(interleave_flag);
  int argc = static_cast<int>(argv.size());
  argv.push_back(nullptr);
  benchmark::Initialize(&argc, argv.data());
  // It removes the flags it knows; one left over means a library older than 1.6.
  if (argc != 1)
    throw run_error("--interleave needs Google Benchmark 1.6 or later (its " +
                    std::string(interleave_flag) + ")");
}

void write_file(const std::string& path, const std::string& text) {
  output_file f(path);
  f.write(text.data(), text.size());
  f.close();
  std::cerr << "hush bench: wrote " << path << '\n';
}

// --filter's texts: TEXT split at each '|' (several rows of different names in one run, e.g.
// for --interleave); an empty text would match every case, so it is refused.
std::vector<std::string> filter_texts(const std::string& filter) {
  std::vector<std::string> texts;
  for (std::size_t from = 0;;) {
    const std::size_t bar = filter.find('|', from);
    texts.push_back(filter.substr(from, bar == std::string::npos ? bar : bar - from));
    if (bar == std::string::npos) break;
    from = bar + 1;
  }
  if (texts.size() > 1 &&
      std::any_of(texts.begin(), texts.end(), [](const std::string& t) { return t.empty(); }))
    throw_bad_value("--filter", filter, "texts separated by '|', none of them empty");
  return texts;
}

#endif  // HUSH_CLI_HAVE_BENCH

}  // namespace

const std::vector<option_spec>& bench_options() {
  static const std::vector<option_spec> options = {
      {"--quick", "",
       "small workloads, 1 repetition: a few seconds in all (a flag: takes no value)"},
      {"--interleave", "",
       "run the repetitions of all matched cases in random order, so that every row's median "
       "spans the same stretch of time (rows compared with each other see the same machine "
       "load); holds every matched case's buffers at once, so it is meant for a --filter'ed "
       "set of rows (a flag: takes no value)"},
      {"--json", "FILE", "also write the rows and the machine as JSON to FILE"},
      {"--markdown", "FILE", "also write the Markdown table to FILE"},
      {"--plot", "FILE.svg", "write the speed-vs-error scatter plot (SVG) to FILE.svg"},
      {"--repetitions", "n",
       "repetitions per case, 1 ... 100; the table shows their median (default 5, --quick 1)"},
      {"--filter", "TEXT",
       "run only the cases whose name contains TEXT, or one of several texts separated by '|', "
       "e.g. perlin2D/simd or 'gabor2D/simd/points|gabor2Dfiltered/simd' (names: "
       "noise/backend/workload/output)"},
  };
  return options;
}

int run_bench(const std::vector<std::string>& args) {
  const bench_request r = parse_bench(args);
#if !HUSH_CLI_HAVE_BENCH
  (void)r;
  throw usage_error(
      "not available in this build (needs Google Benchmark: apt-get install libbenchmark-dev, "
      "and HUSH_BUILD_BENCH=ON)");
#else
  const hush_bench::sizes s = r.quick ? hush_bench::quick_sizes() : hush_bench::full_sizes();
  std::vector<hush_bench::bench_case> cases;
  const std::vector<std::string> texts = filter_texts(r.filter);
  for (hush_bench::bench_case& c : hush_bench::all_cases(s))
    if (std::any_of(texts.begin(), texts.end(),
                    [&c](const std::string& t) { return c.id().find(t) != std::string::npos; }))
      cases.push_back(std::move(c));
  if (cases.empty())
    throw_bad_value("--filter", r.filter,
                    "text that some case name contains, e.g. perlin2D, simd, grid, gradient");

  initialize_benchmark(r.interleave);
  std::cerr << "hush bench: " << cases.size() << " cases, " << r.repetitions
            << " repetition(s) each" << (r.interleave ? ", interleaved in random order" : "")
            << '\n';
  std::vector<bench_row> rows;
  {
    // Interleaved, the cases alternate: each stays prepared until the run ends.
    hush_bench::prepared_cases prepared(r.interleave ? hush_bench::keep_prepared::all
                                                     : hush_bench::keep_prepared::latest);
    const std::uint64_t total = cases.size() * static_cast<std::uint64_t>(r.repetitions);
    progress bar("hush bench", total);
    repetition_progress counter(bar, total);
    hush_bench::register_benchmarks(
        cases, r.quick ? kQuickMinTime : kMinTime, r.repetitions, prepared,
        [&counter](const hush_bench::bench_case& c, std::int64_t iterations) {
          counter.loop_done(c, iterations);
        });
    row_reporter reporter(cases);
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::ClearRegisteredBenchmarks();  // they refer to `prepared` and `counter`
    counter.run_ended();
    if (!reporter.error().empty()) throw run_error(reporter.error());
    rows = reporter.rows();
  }
  benchmark::Shutdown();
  for (const bench_row& row : rows)
    if (!(std::isfinite(row.ns) && row.ns > 0))
      throw run_error("case " + row.c->id() + " reported no time");

  const hush_bench::machine_info m = hush_bench::describe_machine();
  const std::string date = utc_now();
  const std::string table = markdown(rows, m, r, date);
  std::cout << table;
  if (!r.markdown.empty()) write_file(r.markdown, table);
  if (!r.json.empty()) write_file(r.json, json(rows, m, r, s, date));
  if (!r.plot.empty()) write_file(r.plot, to_svg(plot(rows, m, r)));
  return 0;
#endif
}

}  // namespace hush_cli
