// Throwaway experiment (not built by CMake): where the GLSL NPR Gabor image's error against the
// double reference comes from on the bench's frame (bench/npr_gabor_cases.cpp: dense:N, frame
// 0, 1280 x 720, N' = 16, omega0 = 0.5, object and depth tests), and how tight the derived
// bound of tests/gabor/glsl_gabor_test.cpp is. Three images: GPU stage 1 + GPU splatting
// ("GPU points", render on exec::glsl), CPU stage 1 + GPU splatting ("CPU points"), the double
// reference. Per pixel the GPU-points error splits into stage 1's float records (GPU points
// - CPU points) and the splatting's float evaluation on llvmpipe (CPU points - double); the
// bound into its two parts (npr_compare::splat_bound, ::stage1_bound). Reuses the test's
// helpers by compiling the test file with doctest disabled. Build and run (after building
// glsl_gabor_test and hush_scene in build/release; a minute or two at 1280 x 720):
//
//   g++ -O2 -std=c++17 -DDOCTEST_CONFIG_DISABLE -DHUSH_GLSL_HAVE_OSMESA=1 \
//     -Itests/glsl -Itests -Iinclude \
//     -Ibackends/glsl/include -Iexamples/scene bench/experiments/npr_gabor_gpu_error.cpp \
//     build/release/examples/scene/libhush_scene.a -lOSMesa -o /tmp/npr_gpu_error
//   /tmp/npr_gpu_error 5000 [--local]
#include "glsl/glsl_gabor_test.cpp"  // NOLINT(bugprone-suspicious-include): the test's helpers

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gbuffer.hpp"
#include "raster_cpu.hpp"
#include "scene.hpp"
#include "triangles.hpp"

int main(int argc, char** argv) {
  namespace hs = hush_tools::scene;
  const long n = argc > 1 ? std::atol(argv[1]) : 5000;
  const bool local = argc > 2 && std::strcmp(argv[2], "--local") == 0;
  const int w = 1280, h = 720;
  const hs::scene s = hs::make_scene("dense:" + std::to_string(n));
  const hs::gbuffer g = hs::render_cpu(s, 0, w, h);
  const hs::triangle_frame t = hs::project_triangles(s, 0, w, h);
  const hush::frame f = hs::as_frame(g);
  hush::npr_gabor::params p;
  p.orientation = 0.5;
  p.local_density = local;
  const hush::npr_gabor noise{p};
  const npr_compare gp = npr_against_cpu(noise, f, t.view(), true);
  const npr_compare cp = npr_against_cpu(noise, f, t.view(), false);
  std::printf("dense:%ld%s: GPU points max %.3g RMS %.3g (worst error / bound %.3g, ties %zu); "
              "CPU points max %.3g RMS %.3g (worst / bound %.3g)\n",
              n, local ? " local" : "", gp.max_abs, gp.rms, gp.worst_ratio, gp.ties, cp.max_abs,
              cp.rms, cp.worst_ratio);
  // The worst pixels of GPU points (ties left out), each split into its parts.
  std::vector<std::size_t> order;
  for (std::size_t q = 0; q < gp.gpu.size(); ++q)
    if (!gp.tie[q]) order.push_back(q);
  const auto err = [&](std::size_t q) { return std::fabs(double(gp.gpu[q]) - gp.ref[q]); };
  std::partial_sort(order.begin(), order.begin() + 5, order.end(),
                    [&](std::size_t a, std::size_t b) { return err(a) > err(b); });
  double s1 = 0, sp = 0;  // largest part / its bound over all pixels
  for (std::size_t q : order) {
    s1 = std::max(s1, std::fabs(double(gp.gpu[q]) - cp.gpu[q]) / std::max(gp.stage1_bound[q], 1e-300));
    sp = std::max(sp, std::fabs(double(cp.gpu[q]) - gp.ref[q]) / std::max(gp.splat_bound[q], 1e-300));
  }
  for (std::size_t k = 0; k < 5; ++k) {
    const std::size_t q = order[k];
    std::printf("pixel (%zu, %zu): |GPU points - double| %.3g = stage 1 |GPU - CPU points| %.3g "
                "+ splatting |CPU points - double| %.3g; bound: stage 1 %.3g, splatting %.3g\n",
                q % std::size_t(w), q / std::size_t(w), err(q),
                std::fabs(double(gp.gpu[q]) - cp.gpu[q]),
                std::fabs(double(cp.gpu[q]) - gp.ref[q]), gp.stage1_bound[q], gp.splat_bound[q]);
  }
  std::printf("over all pixels: stage 1 part / its bound <= %.3g, splatting part / its bound <= "
              "%.3g\n", s1, sp);
  // At the worst pixel: the records whose disc holds it, CPU against GPU (matched by object,
  // triangle id, J): the weights' and the positions' differences (the position from the first
  // pixel's offset, both sides relative to the same pixel).
  {
    const std::size_t q = order[0];
    const double px = double(q % std::size_t(w)) + 0.5, py = double(q / std::size_t(w)) + 0.5;
    std::vector<hush::npr_gabor_splat> splats;
    noise.make_splats(f, t.view(), splats);
    std::vector<std::uint32_t> words, ids;
    std::size_t empty = 0;
    hush::glsl::npr_gabor_state(headless().device).records(noise, f, t.view(), {}, words, ids,
                                                            empty);
    std::size_t held = 0;
    double dw = 0, w_doff = 0, doff = 0, sum_w = 0;
    for (const hush::npr_gabor_splat& c : splats) {
      if (std::hypot(px - c.x, py - c.y) >= c.radius) continue;
      for (std::size_t k = 0; k < ids.size() / 4; ++k) {
        if (ids[4 * k] != c.object || ids[4 * k + 1] != c.triangle ||
            (ids[4 * k + 2] | (std::uint64_t(ids[4 * k + 3]) << 32)) != c.index)
          continue;
        hush::glsl::npr_gabor_gpu_record gr;
        std::memcpy(&gr, &words[16 * k], sizeof gr);
        // Position: first pixel centre - offset (the GPU's offset is relative to its box).
        const double gx = gr.box[0] + 0.5 - double(gr.kern[0]),
                     gy = gr.box[1] + 0.5 - double(gr.kern[1]);
        const double d = std::hypot(gx - c.x, gy - c.y);
        ++held;
        sum_w += std::fabs(c.weight);
        dw += std::fabs(double(gr.kern[3]) - c.weight);
        w_doff += std::fabs(c.weight) * d;
        doff = std::max(doff, d);
      }
    }
    std::printf("worst pixel's %zu records: sum |w| %.3g, sum |dw| %.3g, sum |w| |dposition| "
                "%.3g px, max |dposition| %.3g px\n",
                held, sum_w, dw, w_doff, doff);
  }
  const npr_records_compare r = npr_records_against_cpu(noise, f, t.view());
  std::printf("records: CPU %zu GPU %zu, worst field / its tolerance %.3g (offsets %.3g), box ties "
              "%zu, one-sided %zu + %zu, switched %zu\n",
              r.cpu, r.gpu, r.worst, r.worst_offset, r.box_ties, r.cpu_only, r.gpu_only,
              r.switched);
  return 0;
}
