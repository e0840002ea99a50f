// hush — animated GIF files of 8-bit grayscale frames: the gallery's animations (coherent
// noise; NPR Gabor noise next). Written by hush itself (GIF89a, LZW), no library needed.
//
// Every frame is width x height bytes, row 0 at the top, shown as gray levels 0 ... 255
// (a 256-entry gray global colour table: exact, no dithering). Frames after the first are
// shown `delay_cs` hundredths of a second each; the animation loops forever (the NETSCAPE2.0
// extension). Readers: every browser, stb_image (tests/gif).
#ifndef HUSH_GIF_GIF_HPP
#define HUSH_GIF_GIF_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hush {
namespace gif {

// The whole GIF file. Throws hush::invalid_argument when there are no frames, a size is 0 or
// above 65535 (the format's limit), a frame's size is not width * height, or delay_cs is
// outside 0 ... 65535.
std::vector<std::uint8_t> encode(const std::vector<std::vector<std::uint8_t>>& frames, int width,
                                 int height, int delay_cs);

// encode() written to `path` (complete or absent, examples/npy/output_file.hpp); throws
// std::runtime_error naming the file when it cannot be written.
void save(const std::string& path, const std::vector<std::vector<std::uint8_t>>& frames, int width,
          int height, int delay_cs);

}  // namespace gif
}  // namespace hush

#endif  // HUSH_GIF_GIF_HPP
