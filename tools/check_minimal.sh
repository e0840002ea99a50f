#!/usr/bin/env bash
# A configuration without the optional packages (tinyobjloader, GLM, Eigen, Highway, Google
# Benchmark, OSMesa, stb): the program's translation units that switch parts off with
# HUSH_CLI_HAVE_* must stay clang-tidy clean there too (an unused helper of a missing part
# is an error under the check set of .clang-tidy). Cheap: configure, then clang-tidy on those
# files only; nothing is compiled.
# Usage: tools/check_minimal.sh [BUILD_DIR]   (default build/minimal)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/minimal}
rm -f "$build/CMakeCache.txt"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DHUSH_BUILD_TESTS=OFF -DHUSH_BUILD_BENCH=OFF \
  -DCMAKE_DISABLE_FIND_PACKAGE_tinyobjloader=ON -DCMAKE_DISABLE_FIND_PACKAGE_glm=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON -DCMAKE_DISABLE_FIND_PACKAGE_hwy=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON \
  -DHUSH_OSMESA_LIBRARY=HUSH_OSMESA_LIBRARY-NOTFOUND \
  -DHUSH_OSMESA_INCLUDE_DIR=HUSH_OSMESA_INCLUDE_DIR-NOTFOUND \
  -DHUSH_STB_INCLUDE_DIR=HUSH_STB_INCLUDE_DIR-NOTFOUND >"$build.log" 2>&1 ||
  { cat "$build.log"; exit 1; }
# The optional parts must really be off.
for part in "no test scenes" "Highway not found" "OSMesa not found" "Eigen3 not found" \
            "stb_image_write.h not found"; do
  grep -q "$part" "$build.log" || { echo "check_minimal: expected '$part' in $build.log"; exit 1; }
done
files=()
for f in examples/hush/*.cpp; do
  case "$f" in *stb_image_write_impl.cpp) continue ;; esac
  grep -q "HUSH_CLI_HAVE_" "$f" && grep -q "/$f\"" "$build/compile_commands.json" && files+=("$f")
done
# tools/tidy.sh's two passes (per file: analyzer and compiler warnings; unity units: the rest).
status=0
HUSH_TIDY_FILES="${files[*]}" bash tools/tidy.sh "$build" || status=1
echo "check_minimal: ${#files[@]} files checked without the optional packages"
[ "$status" -eq 0 ] && echo "check_minimal: clean"
exit "$status"
