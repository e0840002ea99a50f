#!/bin/bash
# hush — builds tools/anisotropic_kernel/driver.cpp against this checkout's headers
# ("base") and against copies with each patch applied, for AVX-512 (-march=skylake-avx512)
# and AVX2 (-march=haswell), plus ceilings.patch's two timing ceilings (CEIL_EXP2,
# CEIL_SPLIT: wrong values, timing only), and runs every binary alternating, K = 4 and 8,
# two rounds. Usage: tools/anisotropic_kernel/run.sh [WORKDIR] (default /tmp/aniso_kernel).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
work=${1:-/tmp/aniso_kernel}
rm -rf "$work" && mkdir -p "$work"
cxx="g++ -std=c++17 -O3 -DNDEBUG"
$cxx -I"$repo/include" -c "$repo/examples/anisotropic/figures.cpp" -o "$work/figures.o"
build() {  # name include-dir extra-flags...
  local name=$1 inc=$2; shift 2
  local common=(-I"$inc" -I"$repo/examples/anisotropic" "$@" "$here/driver.cpp" "$work/figures.o")
  $cxx -march=skylake-avx512 "${common[@]}" -o "$work/${name}_avx3"
  $cxx -march=haswell -maes -mpclmul "${common[@]}" -o "$work/${name}_avx2"
}
variants=(base)
build base "$repo/include"
for p in channel_tree lanes_samples_accumulate gather ceilings; do
  mkdir -p "$work/$p"
  cp -r "$repo/include" "$work/$p/"
  (cd "$work/$p" && patch -s -p1 < "$here/$p.patch")
  if [ "$p" = ceilings ]; then
    build ceil_exp2 "$work/$p/include" -DCEIL_EXP2
    build ceil_split "$work/$p/include" -DCEIL_SPLIT
    build ceil_both "$work/$p/include" -DCEIL_EXP2 -DCEIL_SPLIT
    variants+=(ceil_exp2 ceil_split ceil_both)
  else
    build "$p" "$work/$p/include"
    variants+=("$p")
  fi
done
date -u; uptime
for round in 1 2; do
  for k in 4 8; do
    for t in avx3 avx2; do
      for v in "${variants[@]}"; do
        echo -n "round $round $v "
        "$work/${v}_$t" "$k" 5
      done
    done
  done
done
uptime; date -u
