// hush — the `hush` program: the one translation unit that compiles stb_image_write's
// implementation (third-party code: tools/tidy.sh leaves this file out).
#include "features.hpp"

#if HUSH_CLI_HAVE_PNG
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include "stb_image_write.h"
#endif
