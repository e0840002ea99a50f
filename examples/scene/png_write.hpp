// hush — test scenes: 8-bit PNG output for the G-buffer previews (stb_image_write).
#ifndef HUSH_SCENE_PNG_WRITE_HPP
#define HUSH_SCENE_PNG_WRITE_HPP

#include <cstdint>
#include <string>
#include <vector>

namespace hush_tools {
namespace scene {
namespace detail {

// Writes `pixels` (width * height * channels bytes, rows top to bottom) as a PNG;
// false when the file cannot be written or this build has no PNG support.
bool write_png(const std::string& path, int width, int height, int channels,
               const std::vector<std::uint8_t>& pixels);
bool png_available();

}  // namespace detail
}  // namespace scene
}  // namespace hush_tools

#endif  // HUSH_SCENE_PNG_WRITE_HPP
