// The picture of `brdfcl diff`: signed d in the diverging colour map at the image's own size, with
// pixel axes, a colour bar over [-range, +range], the two names and the headline statistics.
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "parity/diff.hpp"
#include "io/messages.hpp"
#include "parity/image_diff.hpp"

namespace brdfcl {

plot::Figure drawImageDiff(const ImageDiff& diff, const std::string& nameA, const std::string& nameB, double range) {
  if (!std::isfinite(range) || !(range > 0)) throw std::invalid_argument("drawImageDiff: range must be finite and > 0");
  const ImageDiffStats& s = diff.stats;
  using detail::formatStat;
  plot::HeatMap h;
  h.title = "Relative luminance difference of A and B";
  h.subtitle = {"A: " + detail::printable(nameA, 70), "B: " + detail::printable(nameB, 70),
                fmt::format("d = (Y_A - Y_B) / max(Y_B, {})", formatStat(s.floor))};
  if (s.compared > 0)
    h.subtitle.push_back(fmt::format("max |d| {} at ({}, {}), mean |d| {}, p99 {}", formatStat(s.relative.maxAbs),
                                     s.relative.maxX, s.relative.maxY, formatStat(s.relative.meanAbs),
                                     formatStat(s.relative.abs.p99)));
  if (s.compared < s.pixels)
    h.subtitle.push_back(fmt::format("magenta: {} pixels not finite in A or B", s.pixels - s.compared));
  h.xLabel = "x (pixels)";
  h.yLabel = "y (pixels)";
  h.barLabel = "d, clipped at |d| = " + formatStat(range);
  h.xLeft = 0;
  h.xRight = s.width;
  h.yTop = 0;
  h.yBottom = s.height;
  h.map = plot::ColourMap::Diverging;
  h.vMin = -range;
  h.vMax = range;
  return plot::drawHeatMap(h, s.width, s.height, diff.relative);
}

void writeImageDiffPng(const std::string& path, const ImageDiff& diff, const std::string& nameA,
                       const std::string& nameB, double range) {
  plot::writePng(path, drawImageDiff(diff, nameA, nameB, range).canvas);
}

}  // namespace brdfcl
