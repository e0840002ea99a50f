// hush — the `hush` program: 8-bit grayscale and RGB images and PNG output.
//
// Images hold rows top to bottom: pixel (x, y) is pixels[y * width + x] and row 0 is the
// top of the PNG. Noise samples (i, j) become pixels (x, y) = (i, j), so j = 0 is at the top.
#ifndef HUSH_CLI_IMAGE_HPP
#define HUSH_CLI_IMAGE_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hush_cli {

struct gray_image {
  std::size_t width = 0;
  std::size_t height = 0;
  std::vector<std::uint8_t> pixels;  // width * height, row-major, row 0 at the top

  gray_image() = default;
  gray_image(std::size_t w, std::size_t h) : width(w), height(h), pixels(w * h) {}
  std::uint8_t& at(std::size_t x, std::size_t y) { return pixels[y * width + x]; }
  std::uint8_t at(std::size_t x, std::size_t y) const { return pixels[y * width + x]; }
};

// Three 8-bit channels per pixel (red, green, blue), the same layout as gray_image.
struct rgb_image {
  std::size_t width = 0;
  std::size_t height = 0;
  std::vector<std::uint8_t> pixels;  // 3 * width * height, row-major, row 0 at the top

  rgb_image() = default;
  rgb_image(std::size_t w, std::size_t h) : width(w), height(h), pixels(3 * w * h) {}
  std::uint8_t* at(std::size_t x, std::size_t y) { return &pixels[3 * (y * width + x)]; }
};

// Gray images of equal size as the red, green and blue channels of one image.
rgb_image compose_rgb(const gray_image& red, const gray_image& green, const gray_image& blue);

// The gray level of v shown over [lo, hi]: round(255 (v - lo) / (hi - lo)), clamped to
// 0 ... 255; NaN gives 0. Signed noise is shown over [-1, 1], i.e. 255 (v + 1) / 2.
std::uint8_t to_gray(double v, double lo, double hi);

// `values` (width * height, row-major) shown over [lo, hi].
gray_image to_gray_image(const std::vector<float>& values, std::size_t width, std::size_t height,
                         double lo, double hi);

// `left` and `right` next to each other; both must have the same height.
gray_image side_by_side(const gray_image& left, const gray_image& right);

// `tile` repeated `nx` times across and `ny` times down.
gray_image repeat(const gray_image& tile, std::size_t nx, std::size_t ny);

// Whether this build writes PNG files (stb_image_write was found at configure time).
bool png_supported();
// Why PNG output is unavailable, as a hint for error messages.
const char* png_unavailable_reason();

// The most pixels a PNG may have (stb_image_write computes sizes in int).
constexpr std::size_t kMaxPngPixels = std::size_t(1) << 28;

// Writes `image` as an 8-bit grayscale PNG. Throws run_error when the file cannot be
// written, or usage_error when this build has no PNG support or the image is too large.
void write_png(const std::string& path, const gray_image& image);
// The same for an 8-bit RGB PNG.
void write_png(const std::string& path, const rgb_image& image);

}  // namespace hush_cli

#endif  // HUSH_CLI_IMAGE_HPP
