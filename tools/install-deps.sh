#!/usr/bin/env bash
# Installs hush's build, test and example dependencies from Debian 12's archive.
# Safe to rerun: when every package is already present it changes nothing.
set -euo pipefail

packages=(
  cmake g++ make python3   # toolchain; the amalgamation script needs only python3
  doctest-dev              # tests
  libglm-dev               # optional glm::vec interop (tested)
  libeigen3-dev            # FFT for the gallery's power spectra
  libstb-dev               # stb_image_write for PNG output
  clang-tidy               # the lint test (.clang-tidy)
  libhwy-dev               # Highway: the SIMD backend (exec::simd)
  libosmesa6-dev           # headless GL 4.5 (llvmpipe) for the GLSL backend and GL G-buffers
  libegl-dev libegl-mesa0  # headless GL through EGL (a GPU's driver; Mesa's llvmpipe in CI)
  libbenchmark-dev         # Google Benchmark: bench/
  libnoise-dev             # peer row in the benchmark (libnoise Perlin)
  libtinyobjloader-dev     # Wavefront OBJ scenes (examples/scene)
  clang libclang-rt-14-dev # the fuzz targets (libFuzzer) and the clang half of the strict-flag builds
  python3-dev pybind11-dev python3-numpy python3-pytest  # import hush (backends/python) and its tests
  python3-dask python3-distributed python3-zarr          # hush.dask: chunked bakes past one machine
  glslang-tools            # compiles the GLSL for OpenGL, Vulkan (SPIR-V) and GLSL ES in tests
  doxygen                  # the API reference and its test (docs/Doxyfile, docs_doxygen)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install-deps: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
