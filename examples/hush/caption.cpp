// hush — the `hush` program: captions drawn into gallery images.
#include "caption.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>

namespace hush_cli {
namespace {

// The font, one row of 5 pixels per string ('#' ink, '.' paper), top row first.
struct glyph_rows {
  char c;
  const char* rows[kGlyphHeight];
};

constexpr glyph_rows kFont[] = {
    {' ', {".....", ".....", ".....", ".....", ".....", ".....", "....."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {',', {".....", ".....", ".....", ".....", ".##..", "..#..", ".#..."}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'+', {".....", "..#..", "..#..", "#####", "..#..", "..#..", "....."}},
    {'=', {".....", ".....", "#####", ".....", "#####", ".....", "....."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {'A', {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'B', {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
    {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'D', {"####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."}},
    {'E', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {'F', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {'G', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
    {'H', {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'I', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'J', {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {'K', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {'L', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {'M', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {'N', {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
    {'O', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'P', {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
    {'Q', {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
    {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'S', {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
    {'T', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'U', {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'V', {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'W', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
    {'X', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {'Y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
    {'Z', {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
};
constexpr std::size_t kGlyphs = sizeof kFont / sizeof kFont[0];

// The font as bit rows, indexed like kFont.
const std::array<std::array<std::uint8_t, kGlyphHeight>, kGlyphs>& bit_rows() {
  static const auto rows = [] {
    std::array<std::array<std::uint8_t, kGlyphHeight>, kGlyphs> r{};
    for (std::size_t g = 0; g < kGlyphs; ++g)
      for (std::size_t y = 0; y < kGlyphHeight; ++y)
        for (std::size_t x = 0; x < kGlyphWidth; ++x)
          if (kFont[g].rows[y][x] == '#')
            r[g][y] = static_cast<std::uint8_t>(r[g][y] | (1u << (kGlyphWidth - 1 - x)));
    return r;
  }();
  return rows;
}

constexpr std::size_t kAdvance = kGlyphWidth + 1;  // one blank column between glyphs
constexpr std::size_t kPad = 4;                    // blank rows above and below the text

std::size_t text_width(const std::string& s) { return s.empty() ? 0 : kAdvance * s.size() - 1; }

}  // namespace

const std::array<std::uint8_t, kGlyphHeight>& glyph(char c) {
  const char u = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
  for (std::size_t g = 0; g < kGlyphs; ++g)
    if (kFont[g].c == u) return bit_rows()[g];
  throw std::invalid_argument("caption: no glyph for the character '" + std::string(1, c) +
                              "' (code " + std::to_string(static_cast<unsigned char>(c)) + ")");
}

gray_image with_captions(const gray_image& image, const std::vector<std::string>& captions) {
  if (captions.empty()) throw std::invalid_argument("with_captions: no captions");
  const std::size_t column = image.width / captions.size();
  std::size_t widest = 0;
  for (const std::string& s : captions) {
    for (char c : s) glyph(c);  // every character drawable, before any drawing
    widest = std::max(widest, text_width(s));
  }
  if (widest > column)
    throw std::invalid_argument("with_captions: a caption of " + std::to_string(widest) +
                                " pixels does not fit a column of " + std::to_string(column));
  const std::size_t scale = 2 * widest <= column ? 2 : 1;
  const std::size_t strip = scale * (kGlyphHeight + 2 * kPad);
  gray_image out(image.width, image.height + strip);
  std::copy(image.pixels.begin(), image.pixels.end(), out.pixels.begin());
  std::fill(out.pixels.begin() + static_cast<std::ptrdiff_t>(image.pixels.size()), out.pixels.end(),
            std::uint8_t{255});
  for (std::size_t k = 0; k < captions.size(); ++k) {
    const std::string& s = captions[k];
    const std::size_t x0 = k * column + (column - scale * text_width(s)) / 2;
    const std::size_t y0 = image.height + scale * kPad;
    for (std::size_t n = 0; n < s.size(); ++n) {
      const auto& rows = glyph(s[n]);
      for (std::size_t y = 0; y < scale * kGlyphHeight; ++y)
        for (std::size_t x = 0; x < scale * kGlyphWidth; ++x)
          if ((rows[y / scale] >> (kGlyphWidth - 1 - x / scale)) & 1u)
            out.at(x0 + scale * kAdvance * n + x, y0 + y) = 0;
    }
  }
  return out;
}

}  // namespace hush_cli
