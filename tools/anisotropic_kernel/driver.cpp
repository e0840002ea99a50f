// hush — timing driver for experiments on the anisotropic SIMD kernel (docs/anisotropic.md,
// "Performance": the kernel shapes measured). Not built by CMake: run.sh builds it against
// the current headers and against copies with each *.patch here applied, one static
// Highway target per binary (-march), and runs them alternating.
//
// The bench's frame (1920 x 1080 receding plane, K orientations, 3 scales, 3 octaves,
// frequency 2, seed 7, centre heuristic weights per pixel from the exact Jacobian) through
// hush::HWY_NAMESPACE::anisotropic_samples; prints the median and minimum thread CPU time
// of `reps` frames, max and RMS |float - double| and the count of values that differ from
// the scalar float path in their bits (every 37th pixel), and a checksum.
// Usage: driver K REPS [SCALES] (default 3; octaves = min(3, SCALES)).
#include <hwy/highway.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>
#include "figures.hpp"  // examples/anisotropic: the receding plane
#include "hush/hush.hpp"
#include "hush/anisotropic/simd-inl.h"
static double cpu_s() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
int main(int argc, char** argv) {
  const int k = argc > 1 ? std::atoi(argv[1]) : 4;
  const int reps = argc > 2 ? std::atoi(argv[2]) : 7;
  const int scales = argc > 3 ? std::atoi(argv[3]) : 3;
  // The bench's frame (bench/anisotropic_cases.cpp).
  const hush_tools::aniso::receding_plane plane =
      hush_tools::aniso::make_receding_plane(1920, 1080);
  const std::size_t n = plane.positions.size();
  static_assert(sizeof(hush::vec2) == 8 && sizeof(hush::footprint<2>) == 12, "packed floats");
  const auto* xy = reinterpret_cast<const float*>(plane.positions.data());
  const auto* fp = reinterpret_cast<const float*>(plane.footprints.data());
  hush::anisotropic::params p;
  p.seed = 7;
  p.orientations = k;
  p.scales = scales;
  p.octaves = std::min(3, scales);
  p.frequency = 2.0;
  const hush::anisotropic a(p);
  std::vector<float> out(n);
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    const double t0 = cpu_s();
    hush::HWY_NAMESPACE::anisotropic_samples(a, xy, fp, nullptr, n, out.data(), nullptr);
    t.push_back(cpu_s() - t0);
  }
  std::sort(t.begin(), t.end());
  double emax = 0, e2 = 0;
  std::size_t mism = 0;
  std::size_t m = 0;
  for (std::size_t q = 0; q < n; q += 37, ++m) {
    const hush::footprint<2>& F = plane.footprints[q];
    const double d = a.sample(hush::dvec2{xy[2 * q], xy[2 * q + 1]}, F);
    const double e = std::fabs(out[q] - d);
    emax = std::max(emax, e);
    e2 += e * e;
    hush::sample_input<2> in;
    in.position = {xy[2 * q], xy[2 * q + 1]};
    in.fp = F;
    const float s = a.sample_value<float>(in);
    std::uint32_t bs = 0, bo = 0;  // bit patterns: NaN compares unequal to itself
    std::memcpy(&bs, &s, 4);
    std::memcpy(&bo, &out[q], 4);
    if (bs != bo) ++mism;
  }
  double cs = 0;
  for (float v : out) cs += v;
  std::printf(
      "%s K=%d S=%d median %.2f ms (min %.2f) max|e| %.3g rms %.3g scalar-mismatch %zu/%zu "
      "checksum "
      "%.9g\n",
      hwy::TargetName(HWY_TARGET), k, scales, 1e3 * t[t.size() / 2], 1e3 * t[0], emax,
      std::sqrt(e2 / static_cast<double>(m)), mism, m, cs);
}
