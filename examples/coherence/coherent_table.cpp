// hush_coherent_table: the metrics table of docs/coherent.md. Renders the test scenes with the
// CPU rasterizer, runs coherent noise (include/hush/coherent.hpp) from frame 0 (causal and
// time-symmetric, the paper's filter and hush's stationary one, white and band-pass input),
// and prints one Markdown row per (scene, noise) for frames FIRST ... FIRST + FRAMES - 1,
// beside the three calibration baselines (docs/coherence.md), with alpha 0.98.
//
//   hush_coherent_table [WIDTH HEIGHT FIRST FRAMES [SCENE...]]
//   (default: 320 240 90 10 translate rotate zoom walkthrough)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "hush/coherent.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"

namespace {

namespace hc = hush::coherence;

int number(const char* text, const char* what) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (*end != '\0' || v < 0 || v > 1 << 20) {
    std::fprintf(stderr, "hush_coherent_table: %s '%s' is invalid; valid: 0 ... 1048576\n", what,
                 text);
    std::exit(2);
  }
  return static_cast<int>(v);
}

void row(const std::string& scene, const std::string& noise,
         const std::vector<hc::noise_frame>& frames, const std::vector<hush::scene::gbuffer>& g) {
  const hc::report r = hc::measure(frames, g);
  const auto& t = r.temporal;
  const auto& f = r.flatness;
  std::printf("| %s | %s | %.4f | %.3f | %.3f | %.3f | %.4f | %.3f | %.3f | %.3f | %.3f |\n",
              scene.c_str(), noise.c_str(), t.coherence_mean, t.following_mean, t.change_mean,
              t.change_p99, t.popping, f.frequency_cv, f.frequency_ratio, f.variance_cv,
              f.pooled_frequency_cv);
}

}  // namespace

int main(int argc, char** argv) {
  int width = 320, height = 240, first = 90, count = 10;
  std::vector<std::string> scenes = {"translate", "rotate", "zoom", "walkthrough"};
  if (argc > 1) {
    if (argc < 5) {
      std::fprintf(stderr, "usage: hush_coherent_table [WIDTH HEIGHT FIRST FRAMES [SCENE...]]\n");
      return 2;
    }
    width = number(argv[1], "WIDTH");
    height = number(argv[2], "HEIGHT");
    first = number(argv[3], "FIRST");
    count = number(argv[4], "FRAMES");
    if (argc > 5) scenes.assign(argv + 5, argv + argc);
  }
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  try {
    std::printf(
        "| scene | noise | coherence | following | mean abs change | p99 | popping | freq CV | "
        "freq max/min | var CV | pooled freq CV |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& name : scenes) {
      const hush::scene::scene s = hush::scene::make_scene(name);
      std::vector<hush::scene::gbuffer> all;
      for (int i = 0; i < first + count; ++i) {
        all.push_back(hush::scene::render_cpu(s, i, width, height));
        hush::scene::gbuffer& g = all.back();
        if (i < first) g.barycentric = g.uv = g.uv_jacobian = g.normal = g.position = {};
      }
      const std::vector<hush::scene::gbuffer> g(all.begin() + first, all.end());
      for (auto kind :
           {hc::baseline_kind::white, hc::baseline_kind::shower_door, hc::baseline_kind::texture})
        row(name, hc::baseline_name(kind), hc::make_baseline(kind, g), g);
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
            st.advance(hush::exec::simd, hush::scene::as_frame(all[static_cast<std::size_t>(i)]),
                       hush::image_view<float>(out.data(), static_cast<std::size_t>(width),
                                               static_cast<std::size_t>(height)));
            if (i >= first) causal.push_back(out);
          }
          row(name, "coherent causal, " + label, causal, g);
          hush::coherent_sequence<float> io;
          io.frames = all.size();
          io.frame_at = [&](std::size_t i) { return hush::scene::as_frame(all[i]); };
          std::vector<hc::noise_frame> symmetric(static_cast<std::size_t>(count));
          io.write = [&](std::size_t i, hush::span<const hush::image_view<float>> r) {
            if (i >= static_cast<std::size_t>(first))
              symmetric[i - static_cast<std::size_t>(first)].assign(r[0].data, r[0].data + pixels);
          };
          hush::coherent_symmetric(hush::exec::simd, prm, io);
          row(name, "coherent symmetric, " + label, symmetric, g);
        }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hush_coherent_table: %s\n", e.what());
    return 1;
  }
  return 0;
}
