#!/usr/bin/env bash
# The whole test suite, from a fresh Debian 12 machine: installs the
# dependencies, then builds and runs every test twice, in a Release build and
# in an AddressSanitizer + UndefinedBehaviorSanitizer build.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash tools/install-deps.sh

echo "== Release build and tests"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j"$jobs"
(cd build/release && ctest --output-on-failure -j"$jobs")

echo "== ASan + UBSan build and tests"
# -g1: line tables for the sanitizers' stack traces, without the variable tracking that
# makes the SIMD dispatch units slow to compile. -O1: ASan's documented level; -O2 cost
# ~45% more compile time (tests/hard_cases_test.cpp) for the same checks (docs/design.md "CI time").
cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHUSH_SANITIZE=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
cmake --build build/sanitize -j"$jobs"
# The packaging tests configure separate projects without sanitizers, and the
# long statistical sweeps (label `slow`, tests/CMakeLists.txt) cost the same
# time ten times over under the sanitizers: the Release run covers them. It
# also covers the two gallery tests (the program rendering every figure: 250 s
# and 85 s under ASan on 2026-11-25, the sanitizer run's long pole); the
# kernels they call are sanitized by their own tests.
(cd build/sanitize && ctest --output-on-failure -j"$jobs" -E "^package_|: ?gallery writes" -LE slow)

echo "== Fuzz targets (clang, libFuzzer + ASan + UBSan), each for 60 s from its corpus"
# tests/fuzz/CMakeLists.txt: every noise's params, the NPY reader, the OBJ loader, the program's
# command-line parsing.
CXX=clang++ cmake -S . -B build/fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHUSH_FUZZ=ON \
  -DHUSH_BUILD_TESTS=OFF -DHUSH_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
cmake --build build/fuzz -j"$jobs" --target fuzz_params fuzz_npy fuzz_obj fuzz_args
(cd build/fuzz && ctest --output-on-failure -j"$jobs" -L fuzz)
