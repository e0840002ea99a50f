// hush — the speed-vs-error benchmark: improved Perlin noise's rows (include/hush/perlin.hpp).
//
// Seed 7, not periodic, on every backend: the 2D and 3D grids and random points of rows.hpp,
// value and value + gradient; on exec::parallel too. glm::perlin and libnoise time the same
// workloads (peer_cases.cpp).
#include <vector>

#include "cases.hpp"
#include "hush/perlin.hpp"
#include "rows.hpp"

namespace hush_bench {

void add_perlin_cases(std::vector<bench_case>& cases, const sizes& s, bench_pass pass) {
  const auto add = [&](const auto& ex) {
    add_noise_rows(cases, s, "perlin 2D", hush::perlin<2>(kNoiseSeed), ex);
    add_noise_rows(cases, s, "perlin 3D", hush::perlin<3>(kNoiseSeed), ex);
  };
  if (pass == bench_pass::parallel)
    on_parallel_backend(cases, add);
  else
    on_backend(pass, add);
}

}  // namespace hush_bench
