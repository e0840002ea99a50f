#!/usr/bin/env bash
# The GLSL backend on a real GPU through EGL: the GLSL test suites (CPU/GPU agreement, each
# against the double reference) and the GLSL rows of `hush bench`, on a machine with a GPU and
# its driver but none of hush's build dependencies.
#
# Prepare on the build machine (Debian 12), from the repository root:
#   cmake -S . -B build/device -DCMAKE_BUILD_TYPE=Release -DHUSH_WITH_OSMESA=OFF
#   cmake --build build/device --target hush_cli glsl_test glsl_fractal_test glsl_gabor_test \
#     glsl_wavelet_test glsl_anisotropic_test glsl_samples_test glsl_coherent_test glsl_timing
#   tools/gpu_rows.sh --stage
# which copies the binaries into .devbuild and the shared libraries they need into .devlib; put
# the glvnd loader packages into .gl (apt-get download libegl1 libglvnd0 libopengl0 libgl1
# libglx0 libgles2). Take .devbuild, .devlib and .gl to the GPU machine with the repository and
# run there, from the repository root (OUT: a folder for the results):
#   OUT=/some/dir tools/gpu_rows.sh
# Writes OUT/info.txt, OUT/tests.txt, OUT/bench.md and OUT/bench.json; exit status 1 if a suite
# failed.
set -u
cd "$(dirname "$0")/.."
build=build/device
suites="glsl_test glsl_fractal_test glsl_gabor_test glsl_wavelet_test glsl_anisotropic_test
        glsl_samples_test glsl_coherent_test"

if [ "${1:-}" = "--stage" ]; then
  rm -rf .devlib .devbuild && mkdir -p .devlib .devbuild/examples .devbuild/tests/glsl
  cp "$build/examples/hush" .devbuild/examples/
  # A noise's GLSL suite is built in tests/<noise>/ (glsl_<noise>_test), the backend-wide ones
  # in tests/glsl/; staged side by side.
  for t in $suites glsl_timing; do
    case "$t" in
      glsl_test | glsl_samples_test | glsl_timing) dir=glsl ;;
      *) dir=${t#glsl_} && dir=${dir%_test} ;;
    esac
    cp "$build/tests/$dir/$t" .devbuild/tests/glsl/
  done
  # Everything the binaries link beyond the C library, the loader and libEGL (the GPU
  # machine's glvnd provides libEGL; the C++ runtime goes along in case its is older).
  for exe in .devbuild/examples/hush .devbuild/tests/glsl/*; do
    ldd "$exe" | awk '/=>/ {print $3}'
  done | sort -u | grep -v -E '/(libc|libm|libdl|libpthread|librt|ld-linux[^/]*|libEGL[^/]*|libGLdispatch[^/]*)\.so' |
    while read -r lib; do cp -L "$lib" .devlib/; done
  ls .devlib .devbuild/*
  exit 0
fi
build=.devbuild

: "${OUT:?set OUT to the results folder}"
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
nvidia_vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$nvidia_vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$nvidia_vendor"
export LD_LIBRARY_PATH="$PWD/.devlib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export HUSH_GL_CONTEXT=egl

{
  nvidia-smi -L 2>&1
  "$build/examples/hush" info 2>&1
} | tee "$OUT/info.txt"

status=0
: > "$OUT/tests.txt"
for t in $suites; do
  # -s: each suite's MESSAGE lines carry the measured errors against the double reference.
  # The glsl-export case runs the program from the build machine's path: not here.
  timeout 300 "$build/tests/glsl/$t" -s -tce="*glsl-export*" >> "$OUT/tests.txt" 2>&1
  rc=$?
  echo "$t: exit $rc" | tee -a "$OUT/tests.txt"
  [ "$rc" -eq 0 ] || status=1
done
grep -E "^\[doctest\] (test cases|assertions)|: exit " "$OUT/tests.txt"

timeout 420 "$build/examples/hush" bench --filter "/glsl/|/glslresident/|/glslkit/" --repetitions 5 \
  --json "$OUT/bench.json" --markdown "$OUT/bench.md" > /dev/null 2>&1 || status=1
cat "$OUT/bench.md"
"$build/tests/glsl/glsl_timing" 3 2>&1 | tee -a "$OUT/info.txt"
exit "$status"
