// hush_coherence_table: the calibration table of docs/coherence.md. Renders the test scenes
// with the CPU rasterizer, makes the three baselines, measures them, and prints one Markdown
// row per (scene, baseline), with the time measure() took on stderr.
//
//   hush_coherence_table [WIDTH HEIGHT FIRST_FRAME FRAMES [SCENE...]]
//   (default: 320 240 90 10 translate rotate zoom walkthrough)
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "coherence/table_cli.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"

int main(int argc, char** argv) {
  namespace hc = hush_tools::coherence;
  const hc::table_args args = hc::parse_table_args(argc, argv, "hush_coherence_table");
  const int width = args.width, height = args.height, first = args.first, count = args.count;
  const std::vector<std::string>& scenes = args.scenes;
  try {
    std::printf(
        "| scene | baseline | coherence mean | min | following | mean abs change | p99 | "
        "popping | freq CV | freq max/min | var CV | pooled freq CV |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& name : scenes) {
      const hush_tools::scene::scene s = hush_tools::scene::make_scene(name);
      std::vector<hush_tools::scene::gbuffer> g;
      for (int i = first; i < first + count; ++i)
        g.push_back(hush_tools::scene::render_cpu(s, i, width, height));
      for (auto kind :
           {hc::baseline_kind::white, hc::baseline_kind::shower_door, hc::baseline_kind::texture}) {
        const std::vector<hc::noise_frame> frames = hc::make_baseline(kind, g);
        const auto t0 = std::chrono::steady_clock::now();
        const hc::report r = hc::measure(frames, g);
        const auto t1 = std::chrono::steady_clock::now();
        std::fprintf(stderr, "%s %s: measure %.3f s\n", name.c_str(), hc::baseline_name(kind),
                     std::chrono::duration<double>(t1 - t0).count());
        const auto& t = r.temporal;
        const auto& f = r.flatness;
        std::printf(
            "| %s | %s | %.4f | %.4f | %.3f | %.3f | %.3f | %.4f | %.3f | %.3f | %.3f | %.3f |\n",
            name.c_str(), hc::baseline_name(kind), t.coherence_mean, t.coherence_min,
            t.following_mean, t.change_mean, t.change_p99, t.popping, f.frequency_cv,
            f.frequency_ratio, f.variance_cv, f.pooled_frequency_cv);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hush_coherence_table: %s\n", e.what());
    return 1;
  }
  return 0;
}
