#!/usr/bin/env bash
# hush's value + gradient against FastNoise2's value (which has no gradients), side by side in
# one process: the rows "with gradients". It reuses ../shared/peers (run.sh builds
# FastNoise2 into /tmp/peers; its harness peer_speed.cpp times every contender interleaved):
# this script adds hush contenders that also write analytic gradients (grids and random points,
# 2D and 3D, best target and pinned to AVX2; fBm 4 octaves on grids) to a copy of the harness,
# builds it like run.sh does and prints the harness's rows plus
#   summary gradients <workload> hush_value+gradient/fn2_value <ratio>
# Usage, from the repository root, on a quiet machine: bash tools/peers_gradients.sh
# Not a CI step: FastNoise2 is not a Debian package (its sources come from the search tool).
set -euo pipefail
proj=$(pwd)
[ -f "$proj/include/hush/hush.hpp" ] || { echo "run from the hush repository's root" >&2; exit 2; }
peers=$(cd "${HUSH_PEERS_DIR:-$proj/../shared/peers}" && pwd)  # HUSH_PEERS_DIR: elsewhere
p=/tmp/peers
[ -f $p/build-fn2/Release/lib/libFastNoise.a ] || { echo "run bash ../shared/peers/run.sh once first (it builds FastNoise2)" >&2; exit 2; }
python3 - "$peers/peer_speed.cpp" "$p/peer_gradients.cpp" <<'PY'
import sys
src, dst = sys.argv[1], sys.argv[2]
s = open(src).read()
rows = r'''
  // ---- hush value + analytic gradient (tools/peers_gradients.sh)
  std::vector<hush::vec2> gr2(kSamples);
  std::vector<hush::vec3> gr3(kSamples);
  cs.push_back({"hush_simd_perlin_grad", 2, [&](auto& o) { hush::evaluate_grid(hp2, hush::exec::simd, g2, o, gr2); }});
  cs.push_back({"hush_simd_perlin_grad", 3, [&](auto& o) { hush::evaluate_grid(hp3, hush::exec::simd, g3, o, gr3); }});
  cs.push_back({"hush_simd_fbm4_grad", 2, [&](auto& o) { hush::evaluate_grid(hf2, hush::exec::simd, g2, o, gr2); }});
  cs.push_back({"hush_simd_fbm4_grad", 3, [&](auto& o) { hush::evaluate_grid(hf3, hush::exec::simd, g3, o, gr3); }});
  cs.push_back({"hush_simd_perlin_points_grad", 2, [&](auto& o) { hush::evaluate(hp2, hush::exec::simd, pts2, o, gr2); }});
  cs.push_back({"hush_simd_perlin_points_grad", 3, [&](auto& o) { hush::evaluate(hp3, hush::exec::simd, pts3, o, gr3); }});
  if (can_pin) {
    cs.push_back({"hush_avx2_perlin_grad", 2, pinned([&](auto& o) { hush::evaluate_grid(hp2, hush::exec::simd, g2, o, gr2); })});
    cs.push_back({"hush_avx2_perlin_grad", 3, pinned([&](auto& o) { hush::evaluate_grid(hp3, hush::exec::simd, g3, o, gr3); })});
    cs.push_back({"hush_avx2_fbm4_grad", 2, pinned([&](auto& o) { hush::evaluate_grid(hf2, hush::exec::simd, g2, o, gr2); })});
    cs.push_back({"hush_avx2_fbm4_grad", 3, pinned([&](auto& o) { hush::evaluate_grid(hf3, hush::exec::simd, g3, o, gr3); })});
  }
'''
summary = r'''
  for (int d = 2; d <= 3; ++d) {
    std::printf("summary gradients %dD perlin grid hush_simd_value+gradient/fn2_best_value %.2f\n", d, ratio("hush_simd_perlin_grad", "fn2_best_perlin", d));
    std::printf("summary gradients %dD perlin grid hush_avx2_value+gradient/fn2_avx2_value %.2f\n", d, ratio("hush_avx2_perlin_grad", "fn2_avx2_perlin", d));
    std::printf("summary gradients %dD fbm4 grid hush_simd_value+gradient/fn2_best_value %.2f\n", d, ratio("hush_simd_fbm4_grad", "fn2_best_fbm4", d));
    std::printf("summary gradients %dD fbm4 grid hush_avx2_value+gradient/fn2_avx2_value %.2f\n", d, ratio("hush_avx2_fbm4_grad", "fn2_avx2_fbm4", d));
    std::printf("summary gradients %dD perlin points hush_simd_value+gradient/fn2_best_value %.2f\n", d, ratio("hush_simd_perlin_points_grad", "fn2_best_perlin_points", d));
  }
'''
anchor_rows = "  // ---- scalar peers, one call per sample"
anchor_sum = "  return low == 0 ? 0 : 3;\n}"
assert s.count(anchor_rows) == 1 and s.count(anchor_sum) == 1, "peer_speed.cpp changed: update tools/peers_gradients.sh"
s = s.replace(anchor_rows, rows + anchor_rows).replace(anchor_sum, summary + anchor_sum)
open(dst, "w").write(s)
PY
# Compiled as run.sh compiles its harness (CMake's Release flags, run-time dispatch).
fsinc=$(find $p/build-fn2 -path '*FastSIMD_FastNoise/include' -type d | head -1)
g++ -std=c++17 -O3 -DNDEBUG -DHUSH_SIMD_DYNAMIC -DFASTNOISE_STATIC_LIB -I"$proj/include" -I$p/fn2/include \
  -I$p/fastsimd/include -I"$fsinc" -I$p/fnl/Cpp $p/peer_gradients.cpp -o $p/peer_gradients \
  $p/build-fn2/Release/lib/libFastNoise.a -lhwy 2>$p/gradients_harness.log || { tail -20 $p/gradients_harness.log >&2; exit 1; }
busy=$(pgrep -c -f 'cc1plus|ctest' || true)
[ "${busy:-0}" -eq 0 ] || echo "warning: $busy compile/test process(es) running: timings are not clean" >&2
taskset -c 1 $p/peer_gradients
