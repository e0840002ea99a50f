// hush — animated GIF files of 8-bit grayscale or RGB frames: the gallery's animations
// (coherent noise, NPR Gabor noise and its styles). Written by hush itself (GIF89a, LZW), no
// library needed.
//
// Gray frames are width x height bytes, row 0 at the top, shown as gray levels 0 ... 255 (a
// 256-entry gray global colour table: exact, no dithering). RGB frames are 3 bytes (red,
// green, blue) per pixel, quantised to a fixed palette of 6 x 7 x 6 levels (252 colours; green
// gets the extra level, the eye is most sensitive to it) by ordered dithering with the 4 x 4
// Bayer matrix: deterministic, the same colour gives the same pattern in every frame (no
// temporal flicker of a static region), and the mean of a 4 x 4 block of one colour is that
// colour within a 32nd of a palette step per channel plus 1/2 (derived in gif.cpp). Frames
// after the first are shown `delay_cs` hundredths of a second each; the animation loops
// forever (the NETSCAPE2.0 extension). Readers: every browser, stb_image (tests/gif).
#ifndef HUSH_GIF_GIF_HPP
#define HUSH_GIF_GIF_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hush_tools {
namespace gif {

// The whole GIF file. Throws hush::invalid_argument when there are no frames, a size is 0 or
// above 65535 (the format's limit), a frame's size is not width * height, or delay_cs is
// outside 0 ... 65535.
std::vector<std::uint8_t> encode(const std::vector<std::vector<std::uint8_t>>& frames, int width,
                                 int height, int delay_cs);

// The same for RGB frames (3 * width * height bytes each, dithered to palette()): refuses
// as encode() does, a frame's size being 3 * width * height.
std::vector<std::uint8_t> encode_rgb(const std::vector<std::vector<std::uint8_t>>& frames,
                                     int width, int height, int delay_cs);

// The colour palette of encode_rgb: entry i = (red, green, blue) at bytes 3i ... 3i + 2, index
// r * 42 + g * 6 + b for levels r, b in 0 ... 5 and g in 0 ... 6 (value round(255 level / (L -
// 1))); entries 252 ... 255 are black and unused.
const std::vector<std::uint8_t>& palette();

// The palette index encode_rgb gives colour (r, g, b) at pixel (x, y): per channel of L
// levels, min(L - 1, floor(c (L - 1) / 255 + t)) with the threshold t = (B[y % 4][x % 4] +
// 1/2) / 16, B the 4 x 4 Bayer matrix.
std::uint8_t dither(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::size_t x, std::size_t y);

// encode() written to `path` (complete or absent, examples/npy/output_file.hpp); throws
// std::runtime_error naming the file when it cannot be written.
void save(const std::string& path, const std::vector<std::vector<std::uint8_t>>& frames, int width,
          int height, int delay_cs);

// encode_rgb() written to `path`, as save().
void save_rgb(const std::string& path, const std::vector<std::vector<std::uint8_t>>& frames,
              int width, int height, int delay_cs);

}  // namespace gif
}  // namespace hush_tools

#endif  // HUSH_GIF_GIF_HPP
