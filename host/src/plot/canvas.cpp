// The RGB8 canvas: pixels, rectangles, lines and bitmap text, and its PNG output through the
// library's one PNG encoder and writeAtomically.
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "plot/plot.hpp"
#include "io/files.hpp"
#include "io/messages.hpp"
#include "io/png.hpp"
#include "plot/font.hpp"

namespace brdfcl::plot {

int textWidth(const std::string& text, int scale) { return static_cast<int>(text.size()) * kAdvance * scale; }

Canvas::Canvas(int width, int height, Colour background) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("plot::Canvas: width and height must be at least 1");
  rgb_.resize(std::size_t(width) * std::size_t(height) * 3);
  for (std::size_t i = 0; i < rgb_.size(); i += 3) {
    rgb_[i] = background.r;
    rgb_[i + 1] = background.g;
    rgb_[i + 2] = background.b;
  }
}

Colour Canvas::at(int x, int y) const {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) throw std::out_of_range("plot::Canvas::at: outside the canvas");
  const std::size_t i = (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3;
  return {rgb_[i], rgb_[i + 1], rgb_[i + 2]};
}

void Canvas::set(int x, int y, Colour c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const std::size_t i = (std::size_t(y) * std::size_t(width_) + std::size_t(x)) * 3;
  rgb_[i] = c.r;
  rgb_[i + 1] = c.g;
  rgb_[i + 2] = c.b;
}

void Canvas::fillRect(const Rect& r, Colour c) {
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) set(x, y, c);
}

void Canvas::strokeRect(const Rect& r, Colour c) {
  if (r.width < 1 || r.height < 1) return;
  line(r.x, r.y, r.x + r.width - 1, r.y, c);
  line(r.x, r.y + r.height - 1, r.x + r.width - 1, r.y + r.height - 1, c);
  line(r.x, r.y, r.x, r.y + r.height - 1, c);
  line(r.x + r.width - 1, r.y, r.x + r.width - 1, r.y + r.height - 1, c);
}

void Canvas::line(int x0, int y0, int x1, int y1, Colour c) {
  // Bresenham: integer steps, so axis lines and ticks are exactly one pixel wide.
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    set(x0, y0, c);
    if (x0 == x1 && y0 == y1) return;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

void Canvas::text(int x, int y, const std::string& s, Colour c, int scale, bool vertical) {
  if (scale < 1) scale = 1;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const int offset = static_cast<int>(k) * kAdvance * scale;
    for (int row = 0; row < kGlyphHeight; ++row) {
      const std::uint8_t bits = detail::glyphRow(s[k], row);
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (!(bits & (1u << (kGlyphWidth - 1 - col)))) continue;
        // Upright: glyph (col, row) at (offset + col, row). Vertical: the upright text turned a
        // quarter anticlockwise inside a box of textWidth tall, so it starts at the bottom.
        const int u = offset + col * scale, v = (row + detail::glyphDrop(s[k])) * scale;
        const int px = vertical ? x + v : x + u;
        const int py = vertical ? y + textWidth(s, scale) - 1 - u - (scale - 1) : y + v;
        fillRect({px, py, scale, scale}, c);
      }
    }
  }
}

std::string encodePng(const Canvas& canvas) {
  return brdfcl::detail::encodePng(canvas.rgb().data(), canvas.width(), canvas.height(), 3);
}

void writePng(const std::string& path, const Canvas& canvas) {
  const std::string shown = brdfcl::detail::printable(path);
  const std::string png = encodePng(canvas);
  if (png.empty()) throw Error("cannot write '" + shown + "': the PNG encoder failed (out of memory?)");
  writeAtomically(path, [&](const std::string& tmp) {
    if (const int err = brdfcl::detail::writeWholeFile(tmp, png.data(), png.size()))
      throw Error("cannot write '" + shown + "': " + std::strerror(err));
  });
}

}  // namespace brdfcl::plot
