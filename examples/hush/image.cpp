// hush — the `hush` program: 8-bit grayscale and RGB images and PNG output (see image.hpp).
#include "image.hpp"

#include <cmath>
#include <exception>

#include "args.hpp"
#include "features.hpp"
#include "output_file.hpp"

#if HUSH_CLI_HAVE_PNG
#include "stb_image_write.h"  // declarations; stb_image_write_impl.cpp compiles the code
#endif

namespace hush_cli {

std::uint8_t to_gray(double v, double lo, double hi) {
  const double t = (v - lo) / (hi - lo);
  if (!(t > 0)) return 0;  // also NaN
  if (t >= 1) return 255;
  return static_cast<std::uint8_t>(std::lround(255 * t));
}

gray_image to_gray_image(const std::vector<float>& values, std::size_t width, std::size_t height,
                         double lo, double hi) {
  gray_image image(width, height);
  for (std::size_t n = 0; n < image.pixels.size(); ++n)
    image.pixels[n] = to_gray(values[n], lo, hi);
  return image;
}

gray_image side_by_side(const gray_image& left, const gray_image& right) {
  gray_image image(left.width + right.width, left.height);
  for (std::size_t y = 0; y < image.height; ++y) {
    for (std::size_t x = 0; x < left.width; ++x) image.at(x, y) = left.at(x, y);
    for (std::size_t x = 0; x < right.width; ++x) image.at(left.width + x, y) = right.at(x, y);
  }
  return image;
}

gray_image repeat(const gray_image& tile, std::size_t nx, std::size_t ny) {
  gray_image image(tile.width * nx, tile.height * ny);
  for (std::size_t y = 0; y < image.height; ++y)
    for (std::size_t x = 0; x < image.width; ++x)
      image.at(x, y) = tile.at(x % tile.width, y % tile.height);
  return image;
}

rgb_image compose_rgb(const gray_image& red, const gray_image& green, const gray_image& blue) {
  rgb_image image(red.width, red.height);
  for (std::size_t n = 0; n < red.pixels.size(); ++n) {
    image.pixels[3 * n] = red.pixels[n];
    image.pixels[3 * n + 1] = green.pixels[n];
    image.pixels[3 * n + 2] = blue.pixels[n];
  }
  return image;
}

bool png_supported() { return HUSH_CLI_HAVE_PNG != 0; }

const char* png_unavailable_reason() {
  return "PNG output is not available in this build: stb_image_write.h was not found when hush "
         "was configured (apt-get install libstb-dev, then re-run cmake)";
}

#if HUSH_CLI_HAVE_PNG
namespace {

// The one PNG writer: `channels` interleaved 8-bit samples per pixel (1 gray, 3 RGB).
void write_png_pixels(const std::string& path, std::size_t width, std::size_t height, int channels,
                      const std::uint8_t* pixels) {
  if (width * height > kMaxPngPixels)
    throw usage_error("a PNG holds at most " + std::to_string(kMaxPngPixels) +
                      " pixels; write .npy");
  // stb hands the encoded bytes to a C callback. An exception must not unwind through
  // stb (it would leak stb's buffers), so the callback keeps it for after the call.
  struct sink_state {
    output_file file;
    std::exception_ptr error;
  } state{output_file(path), nullptr};
  auto sink = [](void* context, void* data, int size) {
    auto& s = *static_cast<sink_state*>(context);
    if (s.error) return;
    try {
      s.file.write(data, static_cast<std::size_t>(size));
    } catch (...) {
      s.error = std::current_exception();
    }
  };
  const int w = static_cast<int>(width), h = static_cast<int>(height);
  const int ok = stbi_write_png_to_func(sink, &state, w, h, channels, pixels, w * channels);
  if (state.error) std::rethrow_exception(state.error);
  if (!ok) throw run_error("cannot encode '" + path + "' as PNG (out of memory?)");
  state.file.close();
}
}  // namespace

void write_png(const std::string& path, const gray_image& image) {
  write_png_pixels(path, image.width, image.height, 1, image.pixels.data());
}
void write_png(const std::string& path, const rgb_image& image) {
  write_png_pixels(path, image.width, image.height, 3, image.pixels.data());
}
#else
void write_png(const std::string&, const gray_image&) {
  throw usage_error(png_unavailable_reason());
}
void write_png(const std::string&, const rgb_image&) {
  throw usage_error(png_unavailable_reason());
}
#endif

}  // namespace hush_cli
