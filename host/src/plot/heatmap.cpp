// The heat map: a scalar field drawn one pixel per value in a colour map, nothing else (the
// labelled figure is `python -m brdfcl plot`).
#include <cmath>
#include <stdexcept>

#include "plot/plot.hpp"

namespace brdfcl::plot {

Figure drawHeatMap(const HeatMap& s, int width, int height, const std::vector<float>& values) {
  if (width < 1 || height < 1 || values.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument("plot::drawHeatMap: values must hold width * height values");
  if (!std::isfinite(s.vMin) || !std::isfinite(s.vMax) || !(s.vMin < s.vMax))
    throw std::invalid_argument("plot::drawHeatMap: the colour range must be finite with vMin < vMax");
  Figure f{Canvas(width, height), {0, 0, width, height}};
  const double span = s.vMax - s.vMin;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float v = values[std::size_t(j) * std::size_t(width) + std::size_t(i)];
      f.canvas.set(i, j, std::isfinite(v) ? mapColour(s.map, (double(v) - s.vMin) / span) : kNotFinite);
    }
  return f;
}

}  // namespace brdfcl::plot
