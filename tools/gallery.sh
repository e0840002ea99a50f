#!/usr/bin/env bash
# hush's main job, from a fresh Debian 12 machine: installs the dependencies,
# builds the `hush` program and renders the showcase images into ./gallery.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash tools/install-deps.sh
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release
cmake --build build/release -j"$jobs" --target hush_cli
build/release/examples/hush gallery --out gallery
