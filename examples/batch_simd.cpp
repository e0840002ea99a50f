#include <hush/hush.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  const hush::perlin<3> noise{/*seed=*/7};
  hush::grid<3> g;                                   // 128^3 samples, spacing 1/16
  g.origin = {0.0, 0.0, 0.0};
  g.step = {1.0 / 16, 1.0 / 16, 1.0 / 16};
  g.size = {128, 128, 128};
  std::vector<float> reference(g.count()), fast(g.count()), threaded(g.count()),
      pooled(g.count());
  hush::evaluate_grid(noise, hush::exec::scalar, g, reference);  // plain C++
  hush::evaluate_grid(noise, hush::exec::simd, g, fast);         // Highway, best target
  // The same SIMD work on every hardware thread (0 = std::thread::hardware_concurrency()):
  hush::evaluate_grid(noise, hush::exec::parallel(hush::exec::simd, 0), g, threaded);
  // For many batches, a pool starts its workers once instead of per call:
  hush::thread_pool pool;  // one thread per hardware thread, the caller included
  hush::evaluate_grid(noise, hush::exec::parallel(hush::exec::simd, pool), g, pooled);
  double worst = 0;
  for (std::size_t i = 0; i < fast.size(); ++i)
    worst = std::max(worst, std::fabs(double(fast[i]) - reference[i]));
  const bool same = threaded == fast && pooled == fast;  // bit for bit, whatever the thread count
  std::printf("simd (%s) vs scalar: max |difference| = %.2g; threads: %s\n",
              hush::simd::chosen_target().c_str(), worst, same ? "identical" : "DIFFERENT");
  return same ? 0 : 1;
}
