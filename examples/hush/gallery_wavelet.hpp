// hush — the `hush` program: wavelet noise's gallery images (Cook & DeRose 2005,
// Fig. 8 and 9, and a receding plane at one sample per pixel against supersampled references).
#ifndef HUSH_CLI_GALLERY_WAVELET_HPP
#define HUSH_CLI_GALLERY_WAVELET_HPP

#include <string>
#include <vector>

#include "gallery_coherent.hpp"  // gallery_item

namespace hush_cli {

// Stills (one frame each): "wavelet_fig8.png", "wavelet_plane.png". The plane's RMS errors
// against its references go into the item's description when it is rendered.
std::vector<gallery_item> wavelet_gallery_items();

// Fig. 9 in colour, "wavelet_fig9.png" in `dir` (RGB, so not a gallery_item): the log power
// spectra of bands b, b + 1, b + 2 as red, green, blue, Perlin left, wavelet right. Prints
// each noise's band overlap (see gallery_wavelet.cpp) on stderr and appends the image's line,
// with the overlaps, to `written`. Throws run_error when the file cannot be written.
void write_wavelet_fig9(const std::string& dir, std::vector<std::string>& written);

}  // namespace hush_cli

#endif  // HUSH_CLI_GALLERY_WAVELET_HPP
