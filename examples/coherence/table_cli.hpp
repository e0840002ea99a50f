// The command line and the Markdown row the metrics-table programs share
// (hush_coherence_table, hush_coherent_table, hush_npr_gabor_table):
//
//   PROGRAM [WIDTH HEIGHT FIRST FRAMES [SCENE...]]
//   (default: 320 240 90 10 translate rotate zoom walkthrough)
#ifndef HUSH_EXAMPLES_COHERENCE_TABLE_CLI_HPP
#define HUSH_EXAMPLES_COHERENCE_TABLE_CLI_HPP

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "coherence/report.hpp"
#include "scene.hpp"

namespace hush_tools::coherence {

struct table_args {
  int width = 320, height = 240, first = 90, count = 10;
  std::vector<std::string> scenes = {"translate", "rotate", "zoom", "walkthrough"};
};

// Parses argv; a bad argument exits 2 with one line naming it and the valid range.
inline table_args parse_table_args(int argc, char** argv, const char* program) {
  table_args a;
  if (argc == 1) return a;
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s [WIDTH HEIGHT FIRST FRAMES [SCENE...]]\n", program);
    std::exit(2);
  }
  const auto number = [program](const char* text, const char* what) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (*end != '\0' || v < 0 || v > 1 << 20) {
      std::fprintf(stderr, "%s: %s '%s' is invalid; valid: 0 ... 1048576\n", program, what, text);
      std::exit(2);
    }
    return static_cast<int>(v);
  };
  a.width = number(argv[1], "WIDTH");
  a.height = number(argv[2], "HEIGHT");
  a.first = number(argv[3], "FIRST");
  a.count = number(argv[4], "FRAMES");
  if (argc > 5) a.scenes.assign(argv + 5, argv + argc);
  return a;
}

// The metrics table of docs/coherent.md and docs/npr-gabor.md: its header, and one row per
// (scene, noise) measured over the frames `frames` with their G-buffers `g`.
inline void print_metrics_header() {
  std::printf(
      "| scene | noise | coherence | following | mean abs change | p99 | popping | freq CV | "
      "freq max/min | var CV | pooled freq CV |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
}
inline void print_metrics_row(const std::string& scene, const std::string& noise,
                              const std::vector<noise_frame>& frames,
                              const std::vector<hush_tools::scene::gbuffer>& g) {
  const report r = measure(frames, g);
  const auto& t = r.temporal;
  const auto& f = r.flatness;
  std::printf("| %s | %s | %.4f | %.3f | %.3f | %.3f | %.4f | %.3f | %.3f | %.3f | %.3f |\n",
              scene.c_str(), noise.c_str(), t.coherence_mean, t.following_mean, t.change_mean,
              t.change_p99, t.popping, f.frequency_cv, f.frequency_ratio, f.variance_cv,
              f.pooled_frequency_cv);
}

}  // namespace hush_tools::coherence

#endif  // HUSH_EXAMPLES_COHERENCE_TABLE_CLI_HPP
