// hush_coherent_table: the metrics table of docs/coherent.md. Renders the test scenes with the
// CPU rasterizer, runs coherent noise (include/hush/coherent.hpp) from frame 0 (causal and
// time-symmetric, the paper's filter and hush's stationary one, white and band-pass input),
// and prints one Markdown row per (scene, noise) for frames FIRST ... FIRST + FRAMES - 1,
// beside the three calibration baselines (docs/coherence.md), with alpha 0.98.
//
//   hush_coherent_table [WIDTH HEIGHT FIRST FRAMES [SCENE...]]
//   (default: 320 240 90 10 translate rotate zoom walkthrough)
#include <cstdio>
#include <string>
#include <vector>

#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "coherence/table_cli.hpp"
#include "hush/coherent.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"

int main(int argc, char** argv) {
  namespace hc = hush_tools::coherence;
  const hc::table_args args = hc::parse_table_args(argc, argv, "hush_coherent_table");
  const int width = args.width, height = args.height, first = args.first, count = args.count;
  const std::vector<std::string>& scenes = args.scenes;
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  try {
    hc::print_metrics_header();
    for (const std::string& name : scenes) {
      const hush_tools::scene::scene s = hush_tools::scene::make_scene(name);
      std::vector<hush_tools::scene::gbuffer> all;
      for (int i = 0; i < first + count; ++i) {
        all.push_back(hush_tools::scene::render_cpu(s, i, width, height));
        hush_tools::scene::gbuffer& g = all.back();
        if (i < first) g.barycentric = g.uv = g.uv_jacobian = g.normal = g.position = {};
      }
      const std::vector<hush_tools::scene::gbuffer> g(all.begin() + first, all.end());
      for (auto kind :
           {hc::baseline_kind::white, hc::baseline_kind::shower_door, hc::baseline_kind::texture})
        hc::print_metrics_row(name, hc::baseline_name(kind), hc::make_baseline(kind, g), g);
      for (const bool bandpass : {true, false})
        for (auto filter : {hush::coherent_filter::stationary, hush::coherent_filter::paper}) {
          hush::coherent_params prm;
          prm.filter = filter;
          if (bandpass) prm.input = hush::coherent_input::bandpass;
          const std::string label =
              std::string(filter == hush::coherent_filter::stationary ? "stationary" : "paper") +
              (bandpass ? ", band-pass 4 px" : ", white");
          hush::coherent_stream st(prm);
          std::vector<hc::noise_frame> causal;
          std::vector<float> out(pixels);
          for (int i = 0; i < first + count; ++i) {
            st.advance(hush::exec::simd,
                       hush_tools::scene::as_frame(all[static_cast<std::size_t>(i)]),
                       hush::image_view<float>(out.data(), static_cast<std::size_t>(width),
                                               static_cast<std::size_t>(height)));
            if (i >= first) causal.push_back(out);
          }
          hc::print_metrics_row(name, "coherent causal, " + label, causal, g);
          hush::coherent_sequence<float> io;
          io.frames = all.size();
          io.frame_at = [&](std::size_t i) { return hush_tools::scene::as_frame(all[i]); };
          std::vector<hc::noise_frame> symmetric(static_cast<std::size_t>(count));
          io.write = [&](std::size_t i, hush::span<const hush::image_view<float>> r) {
            if (i >= static_cast<std::size_t>(first))
              symmetric[i - static_cast<std::size_t>(first)].assign(r[0].data, r[0].data + pixels);
          };
          hush::coherent_symmetric(hush::exec::simd, prm, io);
          hc::print_metrics_row(name, "coherent symmetric, " + label, symmetric, g);
        }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hush_coherent_table: %s\n", e.what());
    return 1;
  }
  return 0;
}
