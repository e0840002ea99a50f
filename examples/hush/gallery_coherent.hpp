// hush — the `hush` program: the gallery's coherent-noise entries (docs/coherent.md): the
// animations (independent per-frame noise, constant "shower door" noise, causal and
// time-symmetric coherent noise on the rotate and walkthrough scenes) and Kass & Pesare's
// figures reproduced (Fig. 2: two frames and their difference; Fig. 6: a scanline through
// time; Fig. 3: a flat-shaded render stylised with dilate/erode and an image-plane warp, and
// object-ID boundary lines wiggled by the noise). Needs the scene library; without it the
// list is empty.
#ifndef HUSH_CLI_GALLERY_COHERENT_HPP
#define HUSH_CLI_GALLERY_COHERENT_HPP

#include <functional>
#include <vector>

#include "image.hpp"

#if HUSH_CLI_HAVE_SCENE
#include "gbuffer.hpp"
#endif

namespace hush_cli {

// One gallery entry: one frame is written as a PNG, more as an animated GIF
// (examples/gif) showing each frame delay_cs hundredths of a second. A colour entry sets
// render_rgb instead of render (its GIF uses gif::encode_rgb's dithered palette).
struct gallery_item {
  const char* file;
  const char* what;
  std::function<std::vector<gray_image>()> render;
  int delay_cs = 0;
  std::function<std::vector<rgb_image>()> render_rgb = nullptr;
};

std::vector<gallery_item> coherent_gallery_items();

#if HUSH_CLI_HAVE_SCENE
// Noise values `v` (one per pixel of g) on g's surfaces, shown over [-range, range];
// background black. Shared by the scene-driven noises' gallery entries.
gray_image noise_on_surfaces(const std::vector<float>& v, const hush_tools::scene::gbuffer& g,
                             double range);
#endif

}  // namespace hush_cli

#endif  // HUSH_CLI_GALLERY_COHERENT_HPP
