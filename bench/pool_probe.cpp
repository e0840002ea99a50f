// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// What a thread start per call costs (docs/performance.md "Two threads"):
// Perlin 2D grids of 128^2 ... 1024^2 samples (step 1/37 cell) on the SIMD
// backend, one thread, hush::exec::parallel(simd, 2) (threads started per
// call) and hush::exec::parallel(simd, pool) on a 2-thread hush::thread_pool.
// Wall time per call, median of 201 back-to-back calls (a program running
// many batches), and the speed-ups over one thread.
// Not built by default (no CI cost):
//   cmake --build build/release --target hush_pool_probe -j1
//   build/release/bench/hush_pool_probe
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <vector>

#include "hush/hush.hpp"

namespace {

template <class F>
double median_us(const F& f, int calls) {
  std::vector<double> t;
  t.reserve(static_cast<std::size_t>(calls));
  for (int r = 0; r < calls; ++r) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - a).count());
  }
  std::nth_element(t.begin(), t.begin() + calls / 2, t.end());
  return t[static_cast<std::size_t>(calls / 2)];
}

}  // namespace

int main() {
  const hush::perlin<2> noise{1};
  hush::thread_pool pool(2);
  std::printf("grid      one thread   2 threads per call      2-thread pool\n");
  for (std::size_t n : {128, 256, 512, 1024}) {
    hush::grid<2> g;
    g.origin = {0.1, 0.2};
    g.step = {1.0 / 37, 1.0 / 37};
    g.size = {n, n};
    std::vector<float> out(g.count());
    const int calls = 201;
    const double one =
        median_us([&] { hush::evaluate_grid(noise, hush::exec::simd, g, out); }, calls);
    const double per = median_us(
        [&] { hush::evaluate_grid(noise, hush::exec::parallel(hush::exec::simd, 2), g, out); },
        calls);
    const double pooled = median_us(
        [&] { hush::evaluate_grid(noise, hush::exec::parallel(hush::exec::simd, pool), g, out); },
        calls);
    std::printf("%4zu^2  %8.1f us   %8.1f us (x%.2f)   %8.1f us (x%.2f)\n", n, one, per, one / per,
                pooled, one / pooled);
  }
  return 0;
}
