// hush — the `hush` program: captions drawn into gallery images (a 5 x 7 pixel font), so that
// an image's figures (errors against a reference, say) travel with the image itself.
#ifndef HUSH_CLI_CAPTION_HPP
#define HUSH_CLI_CAPTION_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "image.hpp"

namespace hush_cli {

constexpr std::size_t kGlyphWidth = 5;   // pixels per glyph row, before scaling
constexpr std::size_t kGlyphHeight = 7;  // rows per glyph, before scaling

// The glyph of `c`: kGlyphHeight rows top to bottom, bit kGlyphWidth - 1 the leftmost pixel.
// Upper-case letters, digits, space and . , : - + = ( ) / have one; lower-case letters are
// drawn as upper-case ones. Throws std::invalid_argument naming any other character.
const std::array<std::uint8_t, kGlyphHeight>& glyph(char c);

// `image` with a white strip below it holding `captions` in black, one per column of equal
// width (captions.size() columns across the image), each centred in its column. The text is
// drawn at scale 2 (each font pixel 2 x 2) where every caption fits its column, else at
// scale 1; the strip is 15 scaled pixels high (the glyphs and 4 pixels above and below them).
// Throws std::invalid_argument when `captions` is empty, a caption does not fit its column
// at scale 1, or a character has no glyph.
gray_image with_captions(const gray_image& image, const std::vector<std::string>& captions);

}  // namespace hush_cli

#endif  // HUSH_CLI_CAPTION_HPP
