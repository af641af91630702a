// The RGB8 canvas: its pixels, and its PNG output through the library's one PNG encoder and
// writeAtomically.
#include <cstring>
#include <stdexcept>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "plot/plot.hpp"
#include "io/files.hpp"
#include "io/messages.hpp"
#include "io/png.hpp"

namespace brdfcl::plot {

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
