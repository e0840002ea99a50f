// hush — the `hush` program: the gallery's anisotropic-noise images (the paper's figures,
// examples/anisotropic/figures.hpp), with the errors the figures report in their captions.
#ifndef HUSH_CLI_GALLERY_ANISOTROPIC_HPP
#define HUSH_CLI_GALLERY_ANISOTROPIC_HPP

#include <string>
#include <vector>

namespace hush_cli {

// Renders the images into `dir` and appends "file (WxH): caption" to `written`;
// progress on stderr.
void write_anisotropic_gallery(const std::string& dir, std::vector<std::string>& written);

}  // namespace hush_cli

#endif  // HUSH_CLI_GALLERY_ANISOTROPIC_HPP
