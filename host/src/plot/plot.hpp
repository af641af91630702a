// The false-colour pictures brdfcl writes as PNG (image differences, profile ratios): an RGB8
// canvas, two colour maps and a scalar field drawn one pixel per value. They hold no text: the
// labelled figures are `python -m brdfcl plot` (matplotlib), from the same numbers.
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

// A scalar field in a colour map, one pixel per value: the picture is the field's size.
struct HeatMap {
  ColourMap map = ColourMap::Sequential;
  double vMin = 0, vMax = 1;  // the colour range; values beyond it take the end colours
};

struct Figure {
  Canvas canvas;
  Rect panel;  // where value (i, j) is pixel (panel.x + i, panel.y + j)
};

// values: width*height, rows from the top. Non-finite values are drawn in kNotFinite.
// width, height >= 1 and vMin < vMax (finite), else std::invalid_argument: a caller bug.
Figure drawHeatMap(const HeatMap& spec, int width, int height, const std::vector<float>& values);

}  // namespace brdfcl::plot
