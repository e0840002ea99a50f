// Throughput and per-call overhead of the GLSL backend on this machine's GL
// (OSMesa: llvmpipe here). Prints ns/sample for Perlin 2D (1024x1024 grid) and
// 3D (128^3 grid), values and values + gradients, and the fixed cost of a
// 1-sample call (median of many). Timings are reported, never asserted.
//   glsl_timing [repeats]   (default 5; the best of the repeats is reported)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "hush/exec.hpp"
#include "hush/glsl/device.hpp"
#include "hush/glsl/headless.hpp"
#include "hush/hush.hpp"

namespace {

using clock_type = std::chrono::steady_clock;

template <class F>
double best_seconds(int repeats, F&& f) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = clock_type::now();
    f();
    best = std::min(best, std::chrono::duration<double>(clock_type::now() - t0).count());
  }
  return best;
}

template <int D>
void grid_row(hush::glsl::device& dev, const hush::grid<D>& g, int repeats, const char* label) {
  const hush::perlin<D> p(7);
  std::vector<float> out(g.count());
  std::vector<hush::vec<float, D>> grad(g.count());
  const hush::exec::glsl<hush::glsl::device> ex{dev};
  hush::evaluate_grid(p, ex, g, out);  // compile and warm up
  hush::evaluate_grid(p, ex, g, out, grad);
  const double tv = best_seconds(repeats, [&] { hush::evaluate_grid(p, ex, g, out); });
  const double tg = best_seconds(repeats, [&] { hush::evaluate_grid(p, ex, g, out, grad); });
  const double ts = best_seconds(1, [&] { hush::evaluate_grid(p, hush::exec::scalar, g, out); });
  const double n = static_cast<double>(g.count());
  std::printf(
      "%-24s %10zu samples  glsl values %7.2f ns/sample  glsl +gradient %7.2f ns/sample"
      "  (cpu scalar values %6.2f ns/sample)\n",
      label, g.count(), tv / n * 1e9, tg / n * 1e9, ts / n * 1e9);
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  hush::glsl::headless_context context;  // HUSH_GL_CONTEXT=egl: the machine's GPU
  hush::glsl::device dev{context.loader()};
  std::printf("renderer: %s\n", dev.renderer().c_str());
  grid_row(dev, hush::grid<2>{{0.5, 0.5}, {1.0 / 64, 1.0 / 64}, {1024, 1024}}, repeats,
           "perlin 2D 1024x1024");
  grid_row(dev, hush::grid<3>{{0.5, 0.5, 0.5}, {1.0 / 16, 1.0 / 16, 1.0 / 16}, {128, 128, 128}},
           repeats, "perlin 3D 128^3");

  // Per-call overhead: one sample, values only, median of many calls.
  const hush::perlin<3> p(7);
  const hush::exec::glsl<hush::glsl::device> ex{dev};
  std::vector<hush::vec3> one = {{0.5f, 0.25f, 0.75f}};
  std::vector<float> out(1);
  const hush::grid<3> cell{{0.5, 0.25, 0.75}, {1, 1, 1}, {1, 1, 1}};
  auto median_us = [&](auto&& call) {
    call();  // compile
    std::vector<double> t;
    for (int i = 0; i < 1000; ++i) {
      const auto t0 = clock_type::now();
      call();
      t.push_back(std::chrono::duration<double>(clock_type::now() - t0).count());
    }
    std::sort(t.begin(), t.end());
    std::printf("median %.1f us (p10 %.1f, p90 %.1f) over %zu calls\n", t[t.size() / 2] * 1e6,
                t[t.size() / 10] * 1e6, t[t.size() * 9 / 10] * 1e6, t.size());
  };
  std::printf("per-call overhead, perlin 3D, 1 point, values: ");
  median_us([&] { hush::evaluate(p, ex, one, out); });
  std::printf("per-call overhead, perlin 3D, 1x1x1 grid, values: ");
  median_us([&] { hush::evaluate_grid(p, ex, cell, out); });
  return 0;
}
