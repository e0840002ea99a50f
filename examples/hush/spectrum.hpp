// hush — the `hush` program: power spectra of sampled noise, as images.
//
// A noise's power spectrum shows what it is made of: band-limited noise is a ring or a
// blob around zero frequency, aliasing shows as energy folded back from the edges,
// periodicity as isolated peaks. The gallery puts one next to every noise image.
#ifndef HUSH_CLI_SPECTRUM_HPP
#define HUSH_CLI_SPECTRUM_HPP

#include <cstddef>
#include <vector>

#include "image.hpp"

namespace hush_cli {

// Whether this build computes spectra (Eigen's FFT was found at configure time).
bool spectrum_supported();
// "Eigen 3.4.0 FFT", or nullptr without FFT support.
const char* spectrum_library();
// Why spectra are unavailable, as a hint for error messages.
const char* spectrum_unavailable_reason();

// The power spectrum P of `values` (width * height, row-major), fftshifted, as described
// for log_power_spectrum below (window, mean removed), one value per pixel of its image.
// Throws usage_error when the build has no FFT.
std::vector<double> power_spectrum(const std::vector<float>& values, std::size_t width,
                                   std::size_t height);

// The log power spectrum of `values` (width * height, row-major) as an image of the same
// size: P = |FFT2(w * (values - mean))|^2, with w a separable Hann window (without it the
// jumps between opposite edges of the image, which the FFT sees as a tiling, draw a bright
// cross through zero frequency). P is fftshifted so that zero frequency sits at pixel
// (width / 2, height / 2), and shown as log10 P over the top kSpectrumDecades decades,
// white = the strongest frequency (`decades` > 0 of them instead where given). The 2D FFT is
// Eigen's, rows then columns. Throws usage_error when the build has no FFT.
constexpr double kSpectrumDecades = 8;  // dynamic range of the spectrum images, in decades
gray_image log_power_spectrum(const std::vector<float>& values, std::size_t width,
                              std::size_t height, double decades = kSpectrumDecades);

}  // namespace hush_cli

#endif  // HUSH_CLI_SPECTRUM_HPP
