// Comparison of two linear RGB renders (`brdfcl diff`): per-pixel relative and absolute Rec. 709
// luminance differences, their statistics, the report (text or JSON) and the false-colour PNG.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "io/luminance.hpp"
#include "plot/plot.hpp"

namespace brdfcl {

// The default floor of the relative difference's denominator, as a fraction of B's mean luminance.
constexpr double kDefaultFloorFraction = 1e-3;

struct ImageDiffOptions {
  // Denominator floor of d = (Y_A - Y_B) / max(Y_B, floor), in luminance units. 0 (the default):
  // kDefaultFloorFraction times the mean luminance of B over the compared pixels (of A when B's is
  // 0; 1e-3 when both are), so black pixels do not turn noise into huge relative differences.
  double floor = 0;
  double threshold = 0.01;  // the report counts the pixels with |d| > threshold
};

// Percentiles interpolate linearly between the two nearest ranks of the sorted values (rank
// p/100 * (n - 1), as numpy's default does).
struct Percentiles {
  double p50 = 0, p90 = 0, p95 = 0, p99 = 0, p999 = 0;
};

// Statistics over the compared pixels: those whose R, G and B are finite in both images.
// With no compared pixel every statistic is 0 and the locations are -1.
struct DifferenceStats {
  double maxAbs = 0;
  int maxX = -1, maxY = -1;  // the first pixel (in row order) where |difference| is largest
  double atMax = 0;          // the signed difference there
  double meanAbs = 0, rms = 0;
  Percentiles abs;  // of |difference|
};

struct ImageDiffStats {
  int width = 0, height = 0;
  std::size_t pixels = 0, compared = 0;
  std::size_t nonFiniteA = 0, nonFiniteB = 0;  // pixels with a NaN or infinite component (one pixel may count in both)
  double floor = 0;                            // the floor used
  double meanLuminanceB = 0;                   // over the compared pixels
  double threshold = 0;
  std::size_t aboveThreshold = 0;  // compared pixels with |d| > threshold
  double fractionAbove = 0;        // aboveThreshold / compared (0 when nothing was compared)
  DifferenceStats relative;        // of d
  DifferenceStats absolute;        // of Y_A - Y_B
};

struct ImageDiff {
  ImageDiffStats stats;
  std::vector<float> relative;  // signed d per pixel, rows from the top; NaN where not compared
};

// a, b: interleaved linear RGB of width x height pixels. Sizes that do not match, or a floor or
// threshold that is negative or not finite: std::invalid_argument (the CLI checks them first).
ImageDiff diffImages(const std::vector<float>& a, const std::vector<float>& b, int width, int height,
                     const ImageDiffOptions& options = {});

// Reads both files with readExrRgb and compares them. Different sizes: brdfcl::Error
// "the images differ in size: a.exr is 256x256, b.exr is 128x128; ...".
ImageDiff diffExrFiles(const std::string& pathA, const std::string& pathB, const ImageDiffOptions& options = {});

// The colour range of the picture when none is given: the 99th percentile of |d|, or the
// threshold when that is 0 (identical images, or differences in fewer than 1% of the pixels),
// or 0.01 when the threshold is 0 too.
double defaultDiffRange(const ImageDiffStats& stats);

// The text report (several lines, each ending in '\n') and the JSON object (one line) that
// `brdfcl diff` prints. nameA and nameB label the images; range is the picture's colour range
// and out its path ("" when no picture is written).
std::string formatImageDiff(const ImageDiffStats& stats, const std::string& nameA, const std::string& nameB);
std::string imageDiffJson(const ImageDiffStats& stats, const std::string& nameA, const std::string& nameB,
                          double range, const std::string& out);

// The false-colour picture of d: the image at its own size in the diverging map over
// [-range, +range] (beyond: the end colours; not compared: plot::kNotFinite), without text.
// range > 0 and finite, else std::invalid_argument.
plot::Figure drawImageDiff(const ImageDiff& diff, double range);
// drawImageDiff written as a PNG through writeAtomically.
void writeImageDiffPng(const std::string& path, const ImageDiff& diff, double range);

}  // namespace brdfcl
