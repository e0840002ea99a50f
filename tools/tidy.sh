#!/usr/bin/env bash
# clang-tidy over hush with the check set in .clang-tidy: every public header
# is checked through the translation units that instantiate it (the examples
# and the hush program). Third-party code (stb's implementation) is left out.
# Usage: tools/tidy.sh [BUILD_DIR [PASS [SHARD]]]   (BUILD_DIR default build/tidy; configured if missing)
#   PASS  all (default), files or units: the two passes below.
#   SHARD i/n: only every n-th item of the pass from the i-th (1-based); CTest runs the passes
#         as several tests so that ctest -j2 interleaves them with the other tests.
#   HUSH_TIDY_JOBS: clang-tidy processes at once (default: the number of cores).
#   HUSH_TIDY_FILES: the files to check instead of the list below (tools/check_minimal.sh).
# The two passes (docs/design.md "Testing"; together the whole check set on every file):
#   files  one clang-tidy per source file: the static analyzer (clang-analyzer-*, which
#          analyzes the functions of the main file only), the compiler's warnings
#          (clang-diagnostic-*: some, e.g. unused static functions, only in the main file; a
#          unit's renamed main() has no implicit return 0) and $main_file below: checks that
#          look at the main file only (misc-unused-using-decls) or would see the unit itself
#          (a .cpp #included; a function declared in one file and defined in another);
#   units  the other checks, on unity translation units (tools/tidy_units.py): one per compile
#          command, so the AST matchers walk the standard library and hush's headers once per
#          unit instead of once per file.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/tidy}
pass=${2:-all}
shard=${3:-1/1}
case "$pass" in all | files | units) ;; *) echo "tidy: PASS must be all, files or units, not '$pass'"; exit 2 ;; esac
[[ "$shard" =~ ^([1-9][0-9]*)/([1-9][0-9]*)$ ]] && [ "${BASH_REMATCH[1]}" -le "${BASH_REMATCH[2]}" ] ||
  { echo "tidy: SHARD must be i/n with 1 <= i <= n, not '$shard'"; exit 2; }
shard_i=${BASH_REMATCH[1]} shard_n=${BASH_REMATCH[2]}
if [ ! -f "$build/compile_commands.json" ]; then
  cmake -S . -B "$build" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DHUSH_BUILD_TESTS=OFF >/dev/null
fi
# The translation units to check: the examples, the program, the scene, coherence and
# anisotropic-figures libraries, and bench/ -- each where this build compiles it (bench needs Google Benchmark,
# raster_gl.cpp needs OSMesa). Third-party implementation files are left out.
# Not here: the SIMD kernels (include/hush/<noise>/*-inl.h), which the dispatch units
# src/simd/*.cpp compile; checking them costs more CPU than the CI's tidy tests can spare.
# After changing a kernel, check its unit by hand, e.g.:
#   clang-tidy -p build/release --quiet --extra-arg=-std=c++17 \
#     --header-filter='.*/include/hush/.*-inl\.h' src/simd/perlin.cpp
files=()
if [ -n "${HUSH_TIDY_FILES:-}" ]; then
  read -r -a files <<<"$HUSH_TIDY_FILES"
else
  for f in examples/*.cpp examples/hush/*.cpp examples/coherence/*.cpp examples/scene/*.cpp \
           examples/npy/*.cpp examples/gif/*.cpp examples/anisotropic/*.cpp bench/*.cpp; do
    case "$f" in *stb_image_write_impl.cpp | *png_write.cpp) continue ;; esac
    grep -q "/$f\"" "$build/compile_commands.json" || continue
    files+=("$f")
  done
fi
# The work items of this pass and shard: f:FILE or u:UNIT.
items=()
if [ "$pass" != units ]; then
  for f in "${files[@]}"; do items+=("f:$f"); done
fi
if [ "$pass" != files ]; then
  units_dir="$build/tidy_units"
  [ "$shard" = 1/1 ] || units_dir="$build/tidy_units_${shard_i}of${shard_n}"
  while IFS= read -r u; do items+=("u:$u"); done < <(python3 tools/tidy_units.py "$build" "$units_dir" "${files[@]}")
fi
# Shards of about equal size: the items by size, largest first, each to the shard with the
# fewest bytes so far (every n-th item had put 237 of 492 KB into one of three shards). Bytes
# are a rough proxy for clang-tidy's time (docs/design.md "Testing").
mine=()
while IFS= read -r item; do mine+=("$item"); done < <(
  for item in "${items[@]}"; do printf '%s %s\n' "$(wc -c <"${item#?:}")" "$item"; done |
    LC_ALL=C sort -k1,1nr -k2,2 |
    awk -v n="$shard_n" -v me="$shard_i" '{
      best = 1
      for (s = 2; s <= n; ++s) if (load[s] < load[best]) best = s
      load[best] += $1
      if (best == me) print $2
    }')
# Each pass's checks: .clang-tidy's set, less what the other pass runs (the check families
# listed in .clang-tidy). GCC 12 defaults to C++17, so CMake passes no -std flag; clang-tidy needs it.
filter='.*/(include/hush|examples|backends/glsl|bench)/.*'
main_file='misc-unused-using-decls,bugprone-suspicious-include,readability-redundant-declaration'
file_checks="-bugprone-*,-cert-*,-misc-*,-modernize-*,-performance-*,-portability-*,-readability-*,$main_file"
unit_checks="-clang-analyzer-*,-clang-diagnostic-*,-${main_file//,/,-}"
tidy_item() {
  local item=$1
  case "$item" in
    f:*) clang-tidy -p "$build" --quiet --extra-arg=-std=c++17 --header-filter="$filter" \
           --checks="$file_checks" "${item#f:}" ;;
    u:*) local unit=${item#u:} args=()
         mapfile -t args <"${unit%.cpp}.args"
         clang-tidy --quiet --config-file=.clang-tidy --header-filter="$filter" \
           --checks="$unit_checks" "$unit" -- -std=c++17 "${args[@]}" ;;
  esac
}
export -f tidy_item
export build filter file_checks unit_checks
status=0
if [ "${#mine[@]}" -gt 0 ]; then
  printf '%s\n' "${mine[@]}" |
    xargs -P "${HUSH_TIDY_JOBS:-$(nproc 2>/dev/null || echo 2)}" -I{} bash -c 'tidy_item "$1"' _ {} ||
    status=1
fi
echo "tidy: $pass pass, shard $shard: ${#mine[@]} of ${#items[@]} items (${#files[@]} files)"
[ "$status" -eq 0 ] && echo "tidy: clean"
exit "$status"
