#!/usr/bin/env bash
# clang-tidy over hush with the check set in .clang-tidy: every public header
# is checked through the translation units that instantiate it (the examples
# and the hush program). Third-party code (stb's implementation) is left out.
# Usage: tools/tidy.sh [BUILD_DIR]   (default build/tidy; configured if missing)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/tidy}
if [ ! -f "$build/compile_commands.json" ]; then
  cmake -S . -B "$build" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DHUSH_BUILD_TESTS=OFF >/dev/null
fi
# The translation units to check: the examples, the program, the scene, coherence and
# anisotropic-figures libraries, and bench/ -- each where this build compiles it (bench needs Google Benchmark,
# raster_gl.cpp needs OSMesa). Third-party implementation files are left out.
# Not here: the SIMD kernels (include/hush/simd/*-inl.h), which only src/simd_dispatch.cpp
# compiles; checking it costs about 21 s of CPU (32 s wall here), which the CI's tidy test
# (~590 s of one core) cannot spare.
# After changing a kernel, check it by hand:
#   clang-tidy -p build/release --quiet --extra-arg=-std=c++17 \
#     --header-filter='.*/include/hush/simd/.*-inl\.h' src/simd_dispatch.cpp
files=()
for f in examples/*.cpp examples/hush/*.cpp examples/coherence/*.cpp examples/scene/*.cpp \
         examples/npy/*.cpp examples/gif/*.cpp examples/anisotropic/*.cpp bench/*.cpp; do
  case "$f" in *stb_image_write_impl.cpp | *png_write.cpp) continue ;; esac
  grep -q "/$f\"" "$build/compile_commands.json" || continue
  files+=("$f")
done
# One clang-tidy per file, as many at once as there are cores. GCC 12 defaults to C++17, so
# CMake passes no -std flag; clang-tidy needs it.
status=0
printf '%s\n' "${files[@]}" |
  xargs -P "$(nproc 2>/dev/null || echo 2)" -n 1 clang-tidy -p "$build" --quiet \
    --extra-arg=-std=c++17 \
    --header-filter='.*/(include/hush|examples|backends/glsl|bench)/.*' || status=1
echo "tidy: ${#files[@]} files checked"
[ "$status" -eq 0 ] && echo "tidy: clean"
exit "$status"
