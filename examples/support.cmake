# The program's support libraries (namespace hush_tools; not part of the installed library):
# included by the top-level CMakeLists.txt before bench/ and examples/, which link them. Each
# library links only hush and the libraries above it in this file; none adds itself to a
# consumer (examples/CMakeLists.txt states the dependency graph).

# ---- Optional dependencies, each announced. Without them `hush` still builds and says, when
# asked for PNG output or the gallery, what is missing.
find_package(Eigen3 3.3 CONFIG QUIET)
if(Eigen3_FOUND)
  message(STATUS "hush: Eigen ${Eigen3_VERSION} found: hush gallery draws power spectra (Eigen FFT)")
else()
  message(STATUS "hush: Eigen3 not found: hush gallery disabled (apt-get install libeigen3-dev)")
endif()
find_path(HUSH_STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb
          DOC "Directory holding stb_image_write.h (libstb-dev)")
if(HUSH_STB_INCLUDE_DIR)
  message(STATUS "hush: stb_image_write found in ${HUSH_STB_INCLUDE_DIR}: PNG output enabled")
else()
  message(STATUS
          "hush: stb_image_write.h not found: no PNG output, no gallery (apt-get install libstb-dev)")
endif()

# ---- NumPy .npy files (hush_npy: the program, the scenes and the coherence metrics).
add_subdirectory(examples/npy)

# ---- Animated GIF writer (hush_gif: the gallery's animations).
add_subdirectory(examples/gif)

# ---- Test scenes and G-buffer rasterizers (hush_scene: `hush scene`, the bench's NPR Gabor rows).
add_subdirectory(examples/scene)

# ---- Temporal-coherence metrics (hush_coherence: `hush coherence`; docs/coherence.md).
add_subdirectory(examples/coherence)

# ---- Anisotropic noise experiments (hush_aniso_figures and, with the scenes, hush_aniso_scene:
# the gallery, `hush render anisotropic`, the bench's anisotropic rows and tests/anisotropic).
add_subdirectory(examples/anisotropic)
