// hush_npr_gabor_table: the metrics table of docs/npr-gabor.md. Renders the test scenes with
// the CPU rasterizer and prints one Markdown row per (scene, noise) for frames FIRST ...
// FIRST + FRAMES - 1: the three calibration baselines (docs/coherence.md: white noise,
// shower door, texture mapping), coherent noise (causal, stationary filter, band-pass 4 px,
// run from frame 0; docs/coherent.md) and NPR Gabor noise (include/hush/npr_gabor.hpp) with
// its defaults (F0 = 1/8 cycle per pixel, a = 0.08 per pixel, N' = 16, object and depth
// tests) in anisotropic and isotropic form, and the anisotropic form with the soft depth test
// (params::soft_depth, paper sec. 6.1) beside the binary one, and the anisotropic form with
// thinning of the N < 1 points (params::thinning), and the anisotropic form with a count per
// tree node (params::local_density: constant variance across foreshortened triangles). The
// last two rows per scene
// measure the binary and soft depth tests only in the silhouette band (silhouette_band.hpp:
// covered pixels within one kernel radius of a depth discontinuity), where occlusion changes;
// their flatness columns describe the band, not the whole image.
//
//   hush_npr_gabor_table [WIDTH HEIGHT FIRST FRAMES [SCENE...]]
//   (default: 320 240 90 10 translate rotate zoom walkthrough)
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "coherence/baselines.hpp"
#include "coherence/report.hpp"
#include "coherence/silhouette_band.hpp"
#include "coherence/table_cli.hpp"
#include "hush/coherent.hpp"
#include "hush/gabor/kernel.hpp"
#include "hush/npr_gabor.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"
#include "triangles.hpp"

int main(int argc, char** argv) {
  namespace hc = hush_tools::coherence;
  const hc::table_args args = hc::parse_table_args(argc, argv, "hush_npr_gabor_table");
  const int width = args.width, height = args.height, first = args.first, count = args.count;
  const std::vector<std::string>& scenes = args.scenes;
  const std::size_t w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  try {
    hc::print_metrics_header();
    for (const std::string& name : scenes) {
      const hush_tools::scene::scene s = hush_tools::scene::make_scene(name);
      hush::coherent_params cprm;
      cprm.input = hush::coherent_input::bandpass;
      hush::coherent_stream coherent(cprm);
      std::vector<hush_tools::scene::gbuffer> g;
      std::vector<hc::noise_frame> coh;
      std::vector<float> out(w * h);
      hush_tools::scene::gbuffer frame;
      for (int i = 0; i < first + count; ++i) {
        hush_tools::scene::render_cpu(s, i, width, height, hush_tools::scene::raster_options{},
                                      frame);
        coherent.advance(hush::exec::scalar, hush_tools::scene::as_frame(frame),
                         hush::image_view<float>(out.data(), w, h));
        if (i >= first) {
          g.push_back(frame);
          coh.push_back(out);
        }
      }
      for (auto kind :
           {hc::baseline_kind::white, hc::baseline_kind::shower_door, hc::baseline_kind::texture})
        hc::print_metrics_row(name, hc::baseline_name(kind), hc::make_baseline(kind, g), g);
      hc::print_metrics_row(name, "coherent causal, stationary, band-pass 4 px", coh, g);
      std::vector<std::vector<hc::noise_frame>> band_frames;  // binary, soft
      struct variant {
        bool isotropic, soft_depth, thinning, local_density;
        const char* label;
      };
      for (const variant v :
           {variant{false, false, false, false, "NPR Gabor, anisotropic"},
            variant{true, false, false, false, "NPR Gabor, isotropic"},
            variant{false, true, false, false, "NPR Gabor, anisotropic, soft depth test"},
            variant{false, false, true, false, "NPR Gabor, anisotropic, thinning"},
            variant{false, false, false, true, "NPR Gabor, anisotropic, local density"}}) {
        hush::npr_gabor::params p;
        p.isotropic = v.isotropic;
        p.soft_depth = v.soft_depth;
        p.thinning = v.thinning;
        p.local_density = v.local_density;
        const hush::npr_gabor noise{p};
        std::vector<hc::noise_frame> npr;
        for (int i = first; i < first + count; ++i) {
          const hush_tools::scene::triangle_frame t =
              hush_tools::scene::project_triangles(s, i, width, height);
          noise.render(hush_tools::scene::as_frame(g[static_cast<std::size_t>(i - first)]),
                       t.view(), hush::image_view<float>(out.data(), w, h));
          npr.push_back(out);
        }
        hc::print_metrics_row(name, v.label, npr, g);
        if (!v.isotropic && !v.thinning && !v.local_density) band_frames.push_back(npr);
      }
      // Band radius: the kernel's support radius, the reach of a kernel the depth test cuts.
      const hush::npr_gabor::params defaults;
      const int radius = static_cast<int>(
          std::ceil(hush::gabor_kernel<2>{defaults.bandwidth, defaults.truncation}.radius()));
      std::vector<hush_tools::scene::gbuffer> band;
      band.reserve(g.size());
      for (const hush_tools::scene::gbuffer& f : g)
        band.push_back(hc::silhouette_band(f, radius, defaults.depth_tolerance));
      const std::string suffix = ", silhouette band " + std::to_string(radius) + " px";
      hc::print_metrics_row(name, "NPR Gabor, anisotropic" + suffix, band_frames[0], band);
      hc::print_metrics_row(name, "NPR Gabor, anisotropic, soft depth test" + suffix,
                            band_frames[1], band);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hush_npr_gabor_table: %s\n", e.what());
    return 1;
  }
  return 0;
}
