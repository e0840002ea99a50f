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
cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHUSH_SANITIZE=ON
cmake --build build/sanitize -j"$jobs"
# The packaging tests configure separate projects without sanitizers, and test
# cases marked [slow] (long statistical sweeps, tests/CMakeLists.txt) check
# numbers, not memory safety: the Release run covers both.
(cd build/sanitize && ctest --output-on-failure -j"$jobs" -E "^package_|\[slow\]")
