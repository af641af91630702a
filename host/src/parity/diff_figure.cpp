// The picture of `brdfcl diff`: signed d in the diverging colour map over [-range, +range] at the
// image's own size, without text (`python -m brdfcl plot diff` draws the labelled figure).
#include <cmath>
#include <stdexcept>

#include "parity/diff.hpp"
#include "parity/image_diff.hpp"

namespace brdfcl {

plot::Figure drawImageDiff(const ImageDiff& diff, double range) {
  if (!std::isfinite(range) || !(range > 0)) throw std::invalid_argument("drawImageDiff: range must be finite and > 0");
  plot::HeatMap h;
  h.map = plot::ColourMap::Diverging;
  h.vMin = -range;
  h.vMax = range;
  return plot::drawHeatMap(h, diff.stats.width, diff.stats.height, diff.relative);
}

void writeImageDiffPng(const std::string& path, const ImageDiff& diff, double range) {
  plot::writePng(path, drawImageDiff(diff, range).canvas);
}

}  // namespace brdfcl
