// hush — the `hush` program: the gallery's NPR Gabor noise entries (docs/npr-gabor.md):
// Benard et al.'s Figure 1 comparison as animations (2D Gabor noise in screen space = the
// shower door | Gabor noise of the object-space position = texture mapping | NPR Gabor
// noise) on the rotate and walkthrough scenes, and the grey styles (hatching, stippling,
// cross-hatching, graphite; npr_styles.hpp) in motion on the rotate scene. Needs the scene library; without it
// the list is empty.
#ifndef HUSH_CLI_GALLERY_NPR_HPP
#define HUSH_CLI_GALLERY_NPR_HPP

#include <vector>

#include "gallery_coherent.hpp"

namespace hush_cli {

std::vector<gallery_item> npr_gallery_items();

}  // namespace hush_cli

#endif  // HUSH_CLI_GALLERY_NPR_HPP
