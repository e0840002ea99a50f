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
status=0
# bench/ is built only with Google Benchmark; its files are checked when the build has them.
bench_files=$(grep -o '"file": *"[^"]*/bench/[^"]*\.cpp"' "$build/compile_commands.json" |
              sed 's/.*"\([^"]*\)"$/\1/' | sort -u || true)
for f in examples/basic_usage.cpp examples/hush/*.cpp examples/coherence/*.cpp $bench_files; do
  case "$f" in *stb_image_write_impl.cpp) continue ;; esac
  # GCC 12 defaults to C++17, so CMake passes no -std flag; clang-tidy needs it.
  clang-tidy -p "$build" --quiet --extra-arg=-std=c++17 \
    --header-filter='.*/(include/hush|examples|backends/glsl|bench)/.*' "$f" || status=1
done
# The test scenes (examples/scene), where this build compiles them (raster_gl.cpp needs OSMesa).
for f in examples/scene/*.cpp; do
  case "$f" in *png_write.cpp) continue ;; esac  # stb_image_write's implementation
  grep -q "/$f\"" "$build/compile_commands.json" || continue
  clang-tidy -p "$build" --quiet --extra-arg=-std=c++17 \
    --header-filter='.*/(include/hush|examples)/.*' "$f" || status=1
done
# The NPY library (examples/npy) that the program, the scenes and the coherence metrics use.
for f in examples/npy/*.cpp; do
  clang-tidy -p "$build" --quiet --extra-arg=-std=c++17 \
    --header-filter='.*/(include/hush|examples)/.*' "$f" || status=1
done
[ "$status" -eq 0 ] && echo "tidy: clean"
exit "$status"
