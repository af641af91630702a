// The bitmap font's glyphs as bit rows, for Canvas::text. The glyphs were drawn for brdfcl: 5x7
// pixels, capitals and digits on the full height; g, p, q and y drop below the baseline.
#pragma once
#include <cstdint>

namespace brdfcl::plot::detail {

// Row `row` (0 = top, up to kGlyphHeight - 1) of the glyph for `c`: bit 4 is the leftmost pixel.
// Characters outside ASCII 32..126 get the glyph of '?'.
std::uint8_t glyphRow(char c, int row);

// Letters with descenders are drawn this many rows lower than the others: their 7 rows run from
// the x-height to below the baseline, into the space between lines (kLineHeight allows for it).
constexpr int kDescent = 2;
int glyphDrop(char c);

}  // namespace brdfcl::plot::detail
