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
  std::vector<float> reference(g.count()), fast(g.count());
  hush::evaluate_grid(noise, hush::exec::scalar, g, reference);  // plain C++ loop
  hush::evaluate_grid(noise, hush::exec::simd, g, fast);         // Highway, best target
  double worst = 0;
  for (std::size_t i = 0; i < fast.size(); ++i)
    worst = std::max(worst, std::fabs(double(fast[i]) - reference[i]));
  std::printf("simd (%s) vs scalar: max |difference| = %.2g\n",
              hush::simd::chosen_target().c_str(), worst);
}
