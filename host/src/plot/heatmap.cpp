// The heat-map figure: a scalar field drawn one pixel per value, a title and subtitle lines above
// it, ticked x and y axes with labels, and a colour bar with ticks on the right.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "plot/plot.hpp"

namespace brdfcl::plot {

namespace {
constexpr Colour kInk{32, 32, 32};
constexpr Colour kFrame{96, 96, 96};

struct Labelled {
  Ticks ticks;
  std::vector<std::string> labels;
  int widest = 0;
};

Labelled label(const Ticks& t, int scale) {
  Labelled l{t, {}, 0};
  for (const double v : t.values) {
    l.labels.push_back(tickLabel(v, t.step));
    l.widest = std::max(l.widest, textWidth(l.labels.back(), scale));
  }
  return l;
}

// x-axis ticks whose labels, centred under them, leave at least one glyph's room between
// neighbours: the densest such set.
Labelled xTicks(double a, double b, int pixels, int scale) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  for (int n = std::clamp(pixels / (10 * scale), 3, 40); n > 1; --n) {
    Labelled l = label(niceTicks(lo, hi, n), scale);
    if (l.ticks.values.size() < 2) return l;
    const double spacing = pixels * l.ticks.step / (hi - lo);
    if (spacing >= l.widest + kAdvance * scale) return l;
  }
  return label(niceTicks(lo, hi, 1), scale);
}

int position(double v, double from, double to, int pixels) {
  return static_cast<int>(std::lround((v - from) / (to - from) * pixels));
}
}  // namespace

Figure drawHeatMap(const HeatMap& s, int width, int height, const std::vector<float>& values) {
  if (width < 1 || height < 1 || values.size() != std::size_t(width) * std::size_t(height))
    throw std::invalid_argument("plot::drawHeatMap: values must hold width * height values");
  if (!std::isfinite(s.vMin) || !std::isfinite(s.vMax) || !(s.vMin < s.vMax))
    throw std::invalid_argument("plot::drawHeatMap: the colour range must be finite with vMin < vMax");
  if (s.axes && (!std::isfinite(s.xLeft) || !std::isfinite(s.xRight) || s.xLeft == s.xRight ||
                 !std::isfinite(s.yTop) || !std::isfinite(s.yBottom) || s.yTop == s.yBottom))
    throw std::invalid_argument("plot::drawHeatMap: the axis ranges must be finite and not empty");

  const int sc = s.textScale > 0 ? s.textScale : (height >= 600 ? 2 : 1);
  const int glyphH = kGlyphHeight * sc, line = kLineHeight * sc, pad = 8 * sc, tick = 4 * sc, gap = 3 * sc;

  // Measure everything first: the canvas is sized to hold it. A panel smaller than its labels
  // keeps its size; the labels then start at its top or left edge and the layout makes room.
  const int xLabelW = textWidth(s.xLabel, sc), yLabelW = textWidth(s.yLabel, sc), barLabelW = textWidth(s.barLabel, sc);
  const int barW = 14 * sc, barH = std::max({height, 100 * sc, barLabelW});
  const Labelled bar = label(niceTicks(s.vMin, s.vMax, std::max(2, barH / (2 * line))), sc);
  Labelled xs, ys;
  if (s.axes) {
    xs = xTicks(s.xLeft, s.xRight, width, sc);
    ys = label(niceTicks(std::min(s.yTop, s.yBottom), std::max(s.yTop, s.yBottom), std::max(2, height / (3 * line))), sc);
  }
  std::vector<std::string> heading;
  if (!s.title.empty()) heading.push_back(s.title);
  heading.insert(heading.end(), s.subtitle.begin(), s.subtitle.end());
  int headingW = 0;
  for (const auto& h : heading) headingW = std::max(headingW, textWidth(h, sc));

  const int left = pad + (s.yLabel.empty() ? 0 : line) + (s.axes ? ys.widest + tick + gap + 2 : 0);
  const int top = pad + static_cast<int>(heading.size()) * line + (heading.empty() ? 0 : pad);
  const int barX = left + std::max(width + std::max(2 * pad, (s.axes ? xs.widest / 2 : 0) + pad), xLabelW + 2 * pad);
  const int right = barX + barW + tick + gap + bar.widest + (s.barLabel.empty() ? 0 : gap + line) + pad;
  const int below = (s.axes ? tick + gap + glyphH : 0) + (s.xLabel.empty() ? 0 : 2 * gap + glyphH);
  const int canvasW = std::max(right, pad + headingW + pad);
  const int canvasH = top + std::max({height + below, barH + glyphH / 2 + 1, yLabelW}) + pad;

  Figure f{Canvas(canvasW, canvasH), {left, top, width, height}, {barX, top, barW, barH}};
  Canvas& c = f.canvas;

  for (std::size_t i = 0; i < heading.size(); ++i) c.text(pad, pad + static_cast<int>(i) * line, heading[i], kInk, sc);

  const double span = s.vMax - s.vMin;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const float v = values[std::size_t(j) * std::size_t(width) + std::size_t(i)];
      c.set(left + i, top + j, std::isfinite(v) ? mapColour(s.map, (double(v) - s.vMin) / span) : kNotFinite);
    }
  c.strokeRect({left - 1, top - 1, width + 2, height + 2}, kFrame);

  if (s.axes) {
    for (std::size_t k = 0; k < xs.ticks.values.size(); ++k) {
      const int px = left + std::clamp(position(xs.ticks.values[k], s.xLeft, s.xRight, width), 0, width);
      c.line(px, top + height + 1, px, top + height + tick, kFrame);
      c.text(px - textWidth(xs.labels[k], sc) / 2, top + height + tick + gap, xs.labels[k], kInk, sc);
    }
    for (std::size_t k = 0; k < ys.ticks.values.size(); ++k) {
      const int py = top + std::clamp(position(ys.ticks.values[k], s.yTop, s.yBottom, height), 0, height);
      c.line(left - 2 - tick, py, left - 2, py, kFrame);
      c.text(left - 2 - tick - gap - textWidth(ys.labels[k], sc), py - glyphH / 2, ys.labels[k], kInk, sc);
    }
  }
  if (!s.xLabel.empty())
    c.text(left + std::max(0, (width - xLabelW) / 2), top + height + below - glyphH, s.xLabel, kInk, sc);
  if (!s.yLabel.empty())
    c.text(pad, top + std::max(0, (height - yLabelW) / 2), s.yLabel, kInk, sc, true);

  // The bar's rows run from vMax (top row) to vMin (bottom row) exactly, so both ends are shown.
  for (int j = 0; j < barH; ++j) {
    const Colour col = mapColour(s.map, barH > 1 ? 1.0 - double(j) / (barH - 1) : 0.5);
    c.fillRect({barX, top + j, barW, 1}, col);
  }
  c.strokeRect({barX - 1, top - 1, barW + 2, barH + 2}, kFrame);
  for (std::size_t k = 0; k < bar.ticks.values.size(); ++k) {
    const int py = top + position(bar.ticks.values[k], s.vMax, s.vMin, barH - 1);
    c.line(barX + barW + 1, py, barX + barW + tick, py, kFrame);
    c.text(barX + barW + tick + gap, py - glyphH / 2, bar.labels[k], kInk, sc);
  }
  if (!s.barLabel.empty())
    c.text(barX + barW + tick + gap + bar.widest + gap, top + (barH - barLabelW) / 2, s.barLabel, kInk, sc, true);
  return f;
}

}  // namespace brdfcl::plot
