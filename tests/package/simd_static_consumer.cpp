// A program on the SIMD backend's static route (HUSH_SIMD_STATIC: the compiler's baseline
// target, kernels inline), compiled by the consumer_simd_baseline_avx3_dl_static test under flags
// whose baseline is Highway's AVX3_DL target (-march=sapphirerapids; -march=native on Sapphire
// Rapids or Zen 5), and compiled only: the machine running the tests may lack those instructions.
// Run on such a CPU, it exits 0 when exec::simd agrees with exec::scalar within 2^-15.
#include <hush/hush.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  const hush::perlin<3> noise{/*seed=*/3};
  hush::grid<3> g;
  g.origin = {0.5, -1.25, 2.0};
  g.step = {0.1, 0.2, 0.3};
  g.size = {16, 8, 4};
  std::vector<float> simd(g.count()), scalar(g.count());
  hush::evaluate_grid(noise, hush::exec::simd, g, simd);
  hush::evaluate_grid(noise, hush::exec::scalar, g, scalar);
  double worst = 0;
  for (std::size_t i = 0; i < simd.size(); ++i)
    worst = std::fmax(worst, std::fabs(double(simd[i]) - double(scalar[i])));
  std::printf("exec::simd on %s: max |simd - scalar| %.3g\n", hush::simd::chosen_target().c_str(),
              worst);
  return worst <= std::ldexp(1.0, -15) ? 0 : 1;
}
