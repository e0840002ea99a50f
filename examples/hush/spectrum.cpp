// hush — the `hush` program: power spectra of sampled noise, as images (see spectrum.hpp).
#include "spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include "args.hpp"
#include "features.hpp"

#if HUSH_CLI_HAVE_FFT
#include <unsupported/Eigen/FFT>
#endif

namespace hush_cli {
#if HUSH_CLI_HAVE_FFT
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace
#endif

bool spectrum_supported() { return HUSH_CLI_HAVE_FFT != 0; }

const char* spectrum_library() {
#if HUSH_CLI_HAVE_FFT
  return "Eigen " HUSH_CLI_EIGEN_VERSION " FFT";
#else
  return nullptr;
#endif
}

const char* spectrum_unavailable_reason() {
  return "spectra are not available in this build: Eigen3 was not found when hush was "
         "configured (apt-get install libeigen3-dev, then re-run cmake)";
}

#if HUSH_CLI_HAVE_FFT
std::vector<double> power_spectrum(const std::vector<float>& values, std::size_t width,
                                   std::size_t height) {
  using complex = std::complex<double>;
  double mean = 0;
  for (float v : values) mean += v;
  mean /= static_cast<double>(values.size());
  // The mean is removed (it would only be a spike at zero frequency), and the Hann window
  // fades every edge to 0 so that the tiling the FFT assumes has no jumps (spectrum.hpp).
  auto hann = [](std::size_t i, std::size_t n) {
    return 0.5 - 0.5 * std::cos(2 * kPi * (static_cast<double>(i) + 0.5) / static_cast<double>(n));
  };
  std::vector<complex> a(values.size());
  for (std::size_t y = 0; y < height; ++y)
    for (std::size_t x = 0; x < width; ++x)
      a[y * width + x] = (values[y * width + x] - mean) * hann(x, width) * hann(y, height);

  // 2D FFT = 1D FFTs along every row, then along every column.
  Eigen::FFT<double> fft;
  std::vector<complex> in, out;
  for (std::size_t y = 0; y < height; ++y) {
    in.assign(a.begin() + static_cast<std::ptrdiff_t>(y * width),
              a.begin() + static_cast<std::ptrdiff_t>((y + 1) * width));
    fft.fwd(out, in);
    std::copy(out.begin(), out.end(), a.begin() + static_cast<std::ptrdiff_t>(y * width));
  }
  in.resize(height);
  for (std::size_t x = 0; x < width; ++x) {
    for (std::size_t y = 0; y < height; ++y) in[y] = a[y * width + x];
    fft.fwd(out, in);
    for (std::size_t y = 0; y < height; ++y) a[y * width + x] = out[y];
  }

  std::vector<double> power(a.size());
  // fftshift (numpy's, also for odd sizes): frequency 0 moves to pixel (width/2, height/2).
  for (std::size_t y = 0; y < height; ++y) {
    const std::size_t fy = (y + height - height / 2) % height;
    for (std::size_t x = 0; x < width; ++x) {
      const std::size_t fx = (x + width - width / 2) % width;
      power[y * width + x] = std::norm(a[fy * width + fx]);
    }
  }
  return power;
}

gray_image log_power_spectrum(const std::vector<float>& values, std::size_t width,
                              std::size_t height, double decades) {
  std::vector<double> log_power = power_spectrum(values, width, height);
  double top = -std::numeric_limits<double>::infinity();
  for (double& p : log_power) {
    p = std::log10(p);  // -inf for an exactly zero bin: shown black
    top = std::max(top, p);
  }
  gray_image image(width, height);
  for (std::size_t n = 0; n < log_power.size(); ++n)
    image.pixels[n] = to_gray(log_power[n], top - decades, top);
  return image;
}
#else
std::vector<double> power_spectrum(const std::vector<float>&, std::size_t, std::size_t) {
  throw usage_error(spectrum_unavailable_reason());
}
gray_image log_power_spectrum(const std::vector<float>&, std::size_t, std::size_t, double) {
  throw usage_error(spectrum_unavailable_reason());
}
#endif

}  // namespace hush_cli
