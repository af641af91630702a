// The statistics of `brdfcl diff`: per-pixel Rec. 709 luminance of both images, the relative
// difference d = (Y_A - Y_B) / max(Y_B, floor) and the absolute one, over the pixels finite in both.
#include "parity/image_diff.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "parity/diff.hpp"
#include "io/exr_header.hpp"
#include "io/input_limits.hpp"
#include "io/messages.hpp"

namespace brdfcl {

namespace detail {
double percentileOfSorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double rank = p / 100.0 * double(sorted.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double f = rank - double(lo);
  return sorted[lo] + f * (sorted[hi] - sorted[lo]);
}

std::string formatStat(double v) { return v == 0.0 ? "0" : fmt::format("{:.4g}", v); }
}  // namespace detail

namespace {
bool finitePixel(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// values: one per pixel, NaN where not compared.
DifferenceStats summarize(const std::vector<double>& values, int width) {
  DifferenceStats s;
  std::vector<double> magnitudes;
  magnitudes.reserve(values.size());
  double sumAbs = 0, sumSquares = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (std::isnan(v)) continue;
    const double m = std::fabs(v);
    // Strictly greater: the first pixel in row order keeps the maximum, so the location is stable.
    if (m > s.maxAbs || s.maxX < 0) {
      s.maxAbs = m;
      s.atMax = v;
      s.maxX = static_cast<int>(i % std::size_t(width));
      s.maxY = static_cast<int>(i / std::size_t(width));
    }
    sumAbs += m;
    sumSquares += v * v;
    magnitudes.push_back(m);
  }
  if (magnitudes.empty()) return s;
  const double n = double(magnitudes.size());
  s.meanAbs = sumAbs / n;
  s.rms = std::sqrt(sumSquares / n);
  std::sort(magnitudes.begin(), magnitudes.end());
  s.abs.p50 = detail::percentileOfSorted(magnitudes, 50);
  s.abs.p90 = detail::percentileOfSorted(magnitudes, 90);
  s.abs.p95 = detail::percentileOfSorted(magnitudes, 95);
  s.abs.p99 = detail::percentileOfSorted(magnitudes, 99);
  s.abs.p999 = detail::percentileOfSorted(magnitudes, 99.9);
  return s;
}
}  // namespace

ImageDiff diffImages(const std::vector<float>& a, const std::vector<float>& b, int width, int height,
                     const ImageDiffOptions& options) {
  const std::size_t n = width > 0 && height > 0 ? std::size_t(width) * std::size_t(height) : 0;
  if (n == 0 || a.size() != 3 * n || b.size() != 3 * n)
    throw std::invalid_argument("diffImages: a and b must hold 3 * width * height floats");
  if (!std::isfinite(options.floor) || options.floor < 0 || !std::isfinite(options.threshold) || options.threshold < 0)
    throw std::invalid_argument("diffImages: floor and threshold must be finite and not negative");

  ImageDiff out;
  ImageDiffStats& s = out.stats;
  s.width = width;
  s.height = height;
  s.pixels = n;
  s.threshold = options.threshold;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> ya(n, nan), yb(n, nan);
  double sumA = 0, sumB = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool okA = finitePixel(&a[3 * i]), okB = finitePixel(&b[3 * i]);
    s.nonFiniteA += !okA;
    s.nonFiniteB += !okB;
    if (!okA || !okB) continue;
    ya[i] = luminance709(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
    yb[i] = luminance709(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
    sumA += ya[i];
    sumB += yb[i];
    ++s.compared;
  }
  const double meanA = s.compared ? sumA / double(s.compared) : 0.0;
  s.meanLuminanceB = s.compared ? sumB / double(s.compared) : 0.0;
  s.floor = options.floor > 0                ? options.floor
            : s.meanLuminanceB > 0           ? kDefaultFloorFraction * s.meanLuminanceB
            : meanA > 0                      ? kDefaultFloorFraction * meanA
                                             : kDefaultFloorFraction;

  std::vector<double> relative(n, nan), absolute(n, nan);
  out.relative.assign(n, std::numeric_limits<float>::quiet_NaN());
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isnan(ya[i])) continue;
    absolute[i] = ya[i] - yb[i];
    relative[i] = absolute[i] / std::max(yb[i], s.floor);
    // Clamped to the float range: a compared pixel must not turn into an "infinite" one in the picture.
    const double fmax = std::numeric_limits<float>::max();
    out.relative[i] = static_cast<float>(std::clamp(relative[i], -fmax, fmax));
    s.aboveThreshold += std::fabs(relative[i]) > s.threshold;
  }
  s.fractionAbove = s.compared ? double(s.aboveThreshold) / double(s.compared) : 0.0;
  s.relative = summarize(relative, width);
  s.absolute = summarize(absolute, width);
  return out;
}

ImageDiff diffExrFiles(const std::string& pathA, const std::string& pathB, const ImageDiffOptions& options) {
  int wa = 0, ha = 0, wb = 0, hb = 0;
  // Each image's size from its header, before either is decoded: the diff keeps about 70 bytes
  // per pixel.
  for (const std::string* path : {&pathA, &pathB}) {
    const std::string shown = detail::printable(*path, 300, ' ');
    const detail::ExrLayout layout = detail::checkExrHeader(*path, shown);
    detail::checkImagePixels(detail::ImageKind::DiffImage, shown, layout.width, layout.height);
  }
  const std::vector<float> a = readExrRgb(pathA, wa, ha);
  const std::vector<float> b = readExrRgb(pathB, wb, hb);
  if (wa != wb || ha != hb)
    throw Error(fmt::format("the images differ in size: '{}' is {}x{}, '{}' is {}x{}; compare renders of the same size",
                            detail::printable(pathA), wa, ha, detail::printable(pathB), wb, hb));
  return diffImages(a, b, wa, ha, options);
}

double defaultDiffRange(const ImageDiffStats& stats) {
  return stats.relative.abs.p99 > 0 ? stats.relative.abs.p99 : stats.threshold > 0 ? stats.threshold : 0.01;
}

}  // namespace brdfcl
