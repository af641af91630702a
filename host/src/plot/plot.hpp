// A small raster plotting layer for figures brdfcl writes as PNG (image differences, heat maps):
// an RGB8 canvas with lines, rectangles and a built-in 5x7 bitmap font, two colour maps, and a
// heat-map figure with title, ticked axes and a colour bar. No dependency beyond the PNG encoder.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace brdfcl::plot {

struct Colour {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Colour& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const Colour& o) const { return !(*this == o); }
};

constexpr Colour kWhite{255, 255, 255};
constexpr Colour kBlack{0, 0, 0};
// Values that are NaN or infinite: a colour neither map contains.
constexpr Colour kNotFinite{255, 0, 255};

// The font: glyphs of 5x7 pixels for ASCII 32..126 (others draw as '?'), in a cell kAdvance
// wide and kLineHeight tall, scaled by whole numbers only so the pixels stay sharp. g, p, q and
// y are drawn 2 rows lower than the others, below the baseline, into the space between lines.
constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;
constexpr int kAdvance = 6;
constexpr int kLineHeight = 10;

// Every glyph takes one advance, so the width is text.size() * kAdvance * scale (the last
// column is the space after the last glyph).
int textWidth(const std::string& text, int scale = 1);

struct Rect {
  int x = 0, y = 0, width = 0, height = 0;
};

// Rows from the top, 3 bytes per pixel. Drawing outside the canvas is clipped, never an error.
class Canvas {
 public:
  Canvas(int width, int height, Colour background = kWhite);  // width, height >= 1
  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<std::uint8_t>& rgb() const { return rgb_; }

  Colour at(int x, int y) const;  // (x, y) inside the canvas, else std::out_of_range
  void set(int x, int y, Colour c);
  void fillRect(const Rect& r, Colour c);
  void strokeRect(const Rect& r, Colour c);  // the one-pixel outline just inside r
  void line(int x0, int y0, int x1, int y1, Colour c);
  // Text with the top-left of its bounding box at (x, y). Vertical text reads upwards (turned a
  // quarter anticlockwise), as a y-axis label does; its box is kGlyphHeight*scale wide.
  void text(int x, int y, const std::string& s, Colour c, int scale = 1, bool vertical = false);

 private:
  int width_, height_;
  std::vector<std::uint8_t> rgb_;
};

// The canvas as PNG bytes, and written as a PNG file through writeAtomically (no partial file).
std::string encodePng(const Canvas& canvas);
void writePng(const std::string& path, const Canvas& canvas);

// Colour maps, defined by control points chosen along paths of evenly rising (sequential) or
// falling-then-rising (diverging) CIELAB lightness, interpolated in linear RGB, sRGB-encoded.
// Diverging: blue (t = 0) - near-white (t = 0.5) - red (t = 1), for signed values.
// Sequential: dark violet - blue - teal - green - yellow, for magnitudes.
enum class ColourMap { Diverging, Sequential };
// t is clamped to [0, 1]; NaN gives kNotFinite.
Colour mapColour(ColourMap map, double t);

// Ticks at the multiples of a step of 1, 2 or 5 times a power of ten inside [lo, hi]: the
// smallest such step that gives at most maxTicks of them. lo <= hi, both finite, else
// std::invalid_argument; lo == hi gives the one tick lo.
struct Ticks {
  std::vector<double> values;
  double step = 1;
};
Ticks niceTicks(double lo, double hi, int maxTicks);
// A tick value written with as many decimals as the tick step needs ("0.05", "-10", "2e-05"); 0 is "0".
std::string tickLabel(double value, double step);

// A scalar field drawn one pixel per value with its colour bar.
struct HeatMap {
  std::string title;
  std::vector<std::string> subtitle;  // lines under the title (statistics, file names)
  std::string xLabel, yLabel, barLabel;
  bool axes = true;  // ticked axes round the panel
  // Data coordinates of the panel's edges: left/right for x, top/bottom for y (an image has
  // yTop = 0, yBottom = height; a plot of a function has yTop > yBottom).
  double xLeft = 0, xRight = 1, yTop = 1, yBottom = 0;
  ColourMap map = ColourMap::Sequential;
  double vMin = 0, vMax = 1;  // the colour bar's range; values beyond it take the end colours
  int textScale = 0;          // 0: 1, or 2 for panels at least 600 pixels tall
};

struct Figure {
  Canvas canvas;
  Rect panel;      // where value (i, j) is pixel (panel.x + i, panel.y + j)
  Rect colourBar;  // vMax at its top row, vMin at its bottom row
};

// values: width*height, rows from the top. Non-finite values are drawn in kNotFinite.
// width, height >= 1 and vMin < vMax (finite), else std::invalid_argument: a caller bug.
Figure drawHeatMap(const HeatMap& spec, int width, int height, const std::vector<float>& values);

}  // namespace brdfcl::plot
