// hush — the `hush` program: wavelet noise's gallery images (issue 8; Cook & DeRose 2005,
// Fig. 8, and a receding plane at one sample per pixel against supersampled references).
#ifndef HUSH_CLI_GALLERY_WAVELET_HPP
#define HUSH_CLI_GALLERY_WAVELET_HPP

#include <vector>

#include "gallery_coherent.hpp"  // gallery_item

namespace hush_cli {

// Stills (one frame each): "wavelet_fig8.png", "wavelet_plane.png". The plane's RMS errors
// against its references go into the item's description when it is rendered.
std::vector<gallery_item> wavelet_gallery_items();

}  // namespace hush_cli

#endif  // HUSH_CLI_GALLERY_WAVELET_HPP
