// hush — the `hush` program: optional features of this build, always defined as 0 or 1.
//
// CMake defines HUSH_CLI_HAVE_PNG (stb_image_write found) and HUSH_CLI_HAVE_FFT (Eigen
// found) when the dependency is there; this header fills in 0 otherwise, so code tests
// them with #if and never with #ifdef.
#ifndef HUSH_CLI_FEATURES_HPP
#define HUSH_CLI_FEATURES_HPP

#ifndef HUSH_CLI_HAVE_PNG
#define HUSH_CLI_HAVE_PNG 0
#endif
#ifndef HUSH_CLI_HAVE_FFT
#define HUSH_CLI_HAVE_FFT 0
#endif

#endif  // HUSH_CLI_FEATURES_HPP
