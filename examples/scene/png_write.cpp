// hush — test scenes: the translation unit compiling stb_image_write (third-party code)
// with internal linkage, so it never clashes with another copy in the same program.
#include "png_write.hpp"

#if HUSH_SCENE_HAVE_PNG
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include "stb_image_write.h"
#endif

namespace hush_tools {
namespace scene {
namespace detail {

bool write_png(const std::string& path, int width, int height, int channels,
               const std::vector<std::uint8_t>& pixels) {
#if HUSH_SCENE_HAVE_PNG
  return stbi_write_png(path.c_str(), width, height, channels, pixels.data(), width * channels) !=
         0;
#else
  (void)path, (void)width, (void)height, (void)channels, (void)pixels;
  return false;
#endif
}

bool png_available() { return HUSH_SCENE_HAVE_PNG != 0; }

}  // namespace detail
}  // namespace scene
}  // namespace hush_tools
