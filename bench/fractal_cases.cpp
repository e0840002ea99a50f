// hush — the speed-vs-error benchmark: fractal sums' rows (include/hush/fractal.hpp).
//
// fBm of kFbmOctaves improved Perlin octaves (lacunarity 2, gain 0.5, unit variance: fractal's
// defaults), seed 7, on the scalar, SIMD and GLSL backends: the 2D and 3D grids and random
// points of rows.hpp, value and value + gradient. libnoise's Perlin module with as many octaves
// times the same workloads (peer_cases.cpp).
#include <vector>

#include "cases.hpp"
#include "hush/fractal.hpp"
#include "hush/perlin.hpp"
#include "rows.hpp"

namespace hush_bench {
namespace {

template <int D>
hush::fractal<hush::perlin<D>> make_fbm() {
  typename hush::fractal<hush::perlin<D>>::params prm;
  prm.seed = kNoiseSeed;
  prm.octaves = kFbmOctaves;
  return hush::fractal<hush::perlin<D>>(prm);
}

}  // namespace

void add_fractal_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  on_backend(pass, [&](const auto& ex) {
    add_noise_rows(cases, s, "fbm 2D", make_fbm<2>(), ex);
    add_noise_rows(cases, s, "fbm 3D", make_fbm<3>(), ex);
  });
}

}  // namespace hush_bench
