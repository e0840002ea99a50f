// The `hush` program's caption strips (examples/hush/caption.hpp): the font is complete and
// unambiguous, captions land centred in their columns at the documented scale, and what
// cannot be drawn is refused before anything is drawn.
#include <doctest/doctest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "caption.hpp"

using hush_cli::glyph;
using hush_cli::gray_image;
using hush_cli::kGlyphHeight;
using hush_cli::kGlyphWidth;
using hush_cli::with_captions;

namespace {

const std::string kDrawable = " .,:-+=()/0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ";

// The ink's bounding box in rows [y0, y1) of `im`: {x min, x max, y min, y max}, or all -1.
std::vector<long> ink_box(const gray_image& im, std::size_t x0, std::size_t x1, std::size_t y0,
                          std::size_t y1) {
  long xmin = -1, xmax = -1, ymin = -1, ymax = -1;
  for (std::size_t y = y0; y < y1; ++y)
    for (std::size_t x = x0; x < x1; ++x)
      if (im.at(x, y) == 0) {
        const auto xl = static_cast<long>(x), yl = static_cast<long>(y);
        if (xmin < 0 || xl < xmin) xmin = xl;
        if (xl > xmax) xmax = xl;
        if (ymin < 0 || yl < ymin) ymin = yl;
        if (yl > ymax) ymax = yl;
      }
  return {xmin, xmax, ymin, ymax};
}

}  // namespace

TEST_CASE("every drawable character has its own glyph, within 5 x 7, ink on all but space") {
  std::set<std::array<std::uint8_t, kGlyphHeight>> seen;
  for (char c : kDrawable) {
    CAPTURE(c);
    const auto& rows = glyph(c);
    unsigned ink = 0;
    for (std::uint8_t r : rows) {
      CHECK(r < (1u << kGlyphWidth));  // nothing beyond the 5 columns
      ink |= r;
    }
    CHECK((ink != 0) == (c != ' '));
    CHECK(seen.insert(rows).second);  // no two characters look the same
  }
  // Spot checks of the bit order: '1' has its stem in the middle column, 'L' its stem on the
  // left and a full bottom row, '7' a full top row.
  CHECK(glyph('1')[3] == 0b00100);
  CHECK(glyph('L')[0] == 0b10000);
  CHECK(glyph('L')[kGlyphHeight - 1] == 0b11111);
  CHECK(glyph('7')[0] == 0b11111);
}

TEST_CASE("lower-case letters are drawn as upper-case ones; others are refused by name") {
  for (char c = 'a'; c <= 'z'; ++c) CHECK(glyph(c) == glyph(static_cast<char>(c - 'a' + 'A')));
  for (char c : std::string("#%&_~\t\n!?")) {
    CAPTURE(c);
    CHECK_THROWS_AS(glyph(c), std::invalid_argument);
  }
  try {
    glyph('#');
    FAIL("no exception");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("'#'") != std::string::npos);
  }
}

TEST_CASE("with_captions keeps the image, adds a white strip, and centres each caption") {
  gray_image im(120, 10);
  for (std::size_t k = 0; k < im.pixels.size(); ++k)
    im.pixels[k] = static_cast<std::uint8_t>(1 + k % 250);  // no 0 and no 255
  // Columns of 40 pixels: "1" (5 pixels wide) fits at scale 2; "AB" is 11 pixels, 22 at scale
  // 2: fits too, so the scale is 2 and the strip 2 * (7 + 8) = 30 rows.
  const gray_image out = with_captions(im, {"1", "ab", ""});
  REQUIRE(out.width == 120);
  REQUIRE(out.height == 10 + 30);
  for (std::size_t y = 0; y < 10; ++y)
    for (std::size_t x = 0; x < 120; ++x) REQUIRE(out.at(x, y) == im.at(x, y));
  for (std::size_t y = 10; y < out.height; ++y)
    for (std::size_t x = 0; x < 120; ++x) REQUIRE((out.at(x, y) == 0 || out.at(x, y) == 255));
  // "1" at scale 2: 10 x 14 pixels from x = (40 - 10) / 2 = 15, y = 10 + 8; its ink spans the
  // glyph's columns 1 ... 3 (the foot) and all 7 rows.
  CHECK(ink_box(out, 0, 40, 10, 40) == std::vector<long>{15 + 2, 15 + 7, 18, 18 + 13});
  // "AB": 22 pixels from x = 40 + 9; A's ink starts in its first column, B's ends in its last.
  CHECK(ink_box(out, 40, 80, 10, 40) == std::vector<long>{49, 49 + 2 * 6 + 2 * 4 + 1, 18, 31});
  CHECK(ink_box(out, 80, 120, 10, 40) == std::vector<long>{-1, -1, -1, -1});  // empty caption
}

TEST_CASE("with_captions falls back to scale 1, and refuses what does not fit or draw") {
  const gray_image im(60, 4);
  // 4 characters: 23 pixels, 46 at scale 2 > 30: scale 1, a strip of 15 rows.
  const gray_image out = with_captions(im, {"0123", "4"});
  CHECK(out.height == 4 + 15);
  CHECK(ink_box(out, 0, 30, 4, out.height) == std::vector<long>{3, 3 + 22, 8, 14});
  CHECK_THROWS_AS(with_captions(im, {"0123456", "1"}), std::invalid_argument);  // 41 > 30
  CHECK_THROWS_AS(with_captions(im, {}), std::invalid_argument);
  CHECK_THROWS_AS(with_captions(im, {"ok", "n_o"}), std::invalid_argument);
}
