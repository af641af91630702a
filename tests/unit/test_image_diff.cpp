// Image comparison (`brdfcl diff`) and the plotting layer under its picture: statistics checked
// against numbers computed here from the inputs, the picture's size and colours (nothing but the
// field: no text), the colour maps' lightness, a heat map of an analytic field, and the command's
// exit codes.
#include <gtest/gtest.h>
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "host/src/parity/diff.hpp"
#include "host/src/plot/plot.hpp"
#include "process.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using namespace brdfcl;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

double lum(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

// Percentile as numpy's default computes it, written out again here rather than shared.
double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const double rank = p / 100.0 * double(v.size() - 1);
  const auto lo = static_cast<std::size_t>(rank);
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (rank - double(lo)) * (v[hi] - v[lo]);
}

// A grey-ish image whose luminance varies, never black.
std::vector<float> baseImage(int w, int h) {
  std::vector<float> rgb(std::size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = &rgb[(std::size_t(y) * w + x) * 3];
      p[0] = 0.2f + 0.05f * x;
      p[1] = 0.3f + 0.02f * y;
      p[2] = 0.5f;
    }
  return rgb;
}

std::uint32_t be32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

// CIELAB L* of an sRGB-encoded colour (D65): how light the colour looks.
double lightness(plot::Colour c) {
  auto lin = [](std::uint8_t v) {
    const double e = v / 255.0;
    return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
  };
  const double y = lum(lin(c.r), lin(c.g), lin(c.b));
  return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : y * 24389.0 / 27.0;
}

RunResult cli(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), BRDFCL_CLI_PATH);
  return brdfcl::test::runProcess(std::move(args), dir.dir(), dir.dir());
}

void expectOneLineError(const RunResult& r, const std::string& text) {
  EXPECT_EQ(r.status, 2) << r.describe();
  ASSERT_EQ(r.errorLines().size(), 1u) << r.describe();
  EXPECT_NE(r.errorLines()[0].find(text), std::string::npos) << "expected '" << text << "' in\n" << r.describe();
}

// The scratch directory's entries other than the captured stdout and stderr.
std::set<std::string> files(const ScratchDir& dir) {
  std::set<std::string> names;
  for (const auto& n : dir.list())
    if (n != "stdout" && n != "stderr") names.insert(n);
  return names;
}

// The picture is the field and nothing else: every pixel is the colour of its value, so no
// text, tick or frame is drawn.
void expectFieldOnly(const plot::Figure& f, plot::ColourMap map, const std::vector<float>& values, double vMin,
                     double vMax) {
  const plot::Rect& p = f.panel;
  ASSERT_EQ(p.x, 0);
  ASSERT_EQ(p.y, 0);
  ASSERT_EQ(f.canvas.width(), p.width);
  ASSERT_EQ(f.canvas.height(), p.height);
  for (int j = 0; j < p.height; ++j)
    for (int i = 0; i < p.width; ++i) {
      const float v = values[std::size_t(j) * p.width + i];
      const plot::Colour want = std::isfinite(v) ? plot::mapColour(map, (v - vMin) / (vMax - vMin)) : plot::kNotFinite;
      ASSERT_EQ(f.canvas.at(i, j), want) << "pixel " << i << "," << j;
    }
}

}  // namespace

TEST(ImageDiff, StatisticsMatchDirectComputation) {
  ScratchDir dir("imgdiff");
  const int w = 16, h = 8;
  const std::vector<float> b = baseImage(w, h);
  std::vector<float> a = b;
  // A = B scaled per pixel by 1 + e, e spread over [-0.05, 0.05]; one pixel 30% too bright.
  for (int i = 0; i < w * h; ++i) {
    const float e = 0.05f * std::sin(0.7f * float(i));
    for (int c = 0; c < 3; ++c) a[3 * i + c] *= 1.0f + e;
  }
  const int wx = 11, wy = 5;
  for (int c = 0; c < 3; ++c) a[3 * (wy * w + wx) + c] = b[3 * (wy * w + wx) + c] * 1.3f;
  writeExrRgb(dir.path("a.exr"), w, h, a);
  writeExrRgb(dir.path("b.exr"), w, h, b);

  const ImageDiff diff = diffExrFiles(dir.path("a.exr"), dir.path("b.exr"));
  const ImageDiffStats& s = diff.stats;

  std::vector<double> d, absd, absy;
  double sumB = 0;
  for (int i = 0; i < w * h; ++i) sumB += lum(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
  const double floor = 1e-3 * sumB / (w * h);
  for (int i = 0; i < w * h; ++i) {
    const double ya = lum(a[3 * i], a[3 * i + 1], a[3 * i + 2]), yb = lum(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
    d.push_back((ya - yb) / std::max(yb, floor));
    absd.push_back(std::fabs(d.back()));
    absy.push_back(std::fabs(ya - yb));
  }
  double sumAbs = 0, sumSq = 0, above = 0;
  for (double v : d) {
    sumAbs += std::fabs(v);
    sumSq += v * v;
    above += std::fabs(v) > 0.01;
  }
  EXPECT_EQ(s.width, w);
  EXPECT_EQ(s.height, h);
  EXPECT_EQ(s.pixels, std::size_t(w * h));
  EXPECT_EQ(s.compared, std::size_t(w * h));
  EXPECT_EQ(s.nonFiniteA, 0u);
  EXPECT_EQ(s.nonFiniteB, 0u);
  EXPECT_NEAR(s.floor, floor, 1e-9);
  // float images: the relative difference of 30% is exact to about 1e-7.
  EXPECT_NEAR(s.relative.maxAbs, 0.3, 1e-6);
  EXPECT_NEAR(s.relative.atMax, 0.3, 1e-6);
  EXPECT_EQ(s.relative.maxX, wx);
  EXPECT_EQ(s.relative.maxY, wy);
  EXPECT_NEAR(s.relative.meanAbs, sumAbs / (w * h), 1e-9);
  EXPECT_NEAR(s.relative.rms, std::sqrt(sumSq / (w * h)), 1e-9);
  EXPECT_NEAR(s.relative.abs.p50, percentile(absd, 50), 1e-9);
  EXPECT_NEAR(s.relative.abs.p90, percentile(absd, 90), 1e-9);
  EXPECT_NEAR(s.relative.abs.p95, percentile(absd, 95), 1e-9);
  EXPECT_NEAR(s.relative.abs.p99, percentile(absd, 99), 1e-9);
  EXPECT_NEAR(s.relative.abs.p999, percentile(absd, 99.9), 1e-9);
  EXPECT_EQ(double(s.aboveThreshold), above);
  EXPECT_NEAR(s.fractionAbove, above / (w * h), 1e-12);
  EXPECT_NEAR(s.absolute.maxAbs, *std::max_element(absy.begin(), absy.end()), 1e-9);
  EXPECT_NEAR(s.absolute.abs.p99, percentile(absy, 99), 1e-9);
  EXPECT_NEAR(diff.relative[wy * w + wx], 0.3f, 1e-6f);
}

TEST(ImageDiff, PercentilesOfAKnownDistribution) {
  // d = i / 1000 for i = 0..999 (B = 1, A = 1 + d): percentile p is p/100 * 0.999 exactly.
  const int w = 1000, h = 1;
  std::vector<float> a(3 * w), b(3 * w, 1.0f);
  for (int i = 0; i < w; ++i) a[3 * i] = a[3 * i + 1] = a[3 * i + 2] = 1.0f + float(i) / 1000.0f;
  ImageDiffOptions o;
  o.threshold = 0.0105;  // between two of the values, clear of their rounding
  const ImageDiffStats s = diffImages(a, b, w, h, o).stats;
  EXPECT_NEAR(s.relative.abs.p50, 0.4995, 1e-6);
  EXPECT_NEAR(s.relative.abs.p90, 0.8991, 1e-6);
  EXPECT_NEAR(s.relative.abs.p99, 0.98901, 1e-6);
  EXPECT_NEAR(s.relative.abs.p999, 0.998001, 1e-6);
  EXPECT_EQ(s.relative.maxX, 999);
  EXPECT_EQ(s.aboveThreshold, 989u);  // i = 11..999
  EXPECT_NEAR(s.fractionAbove, 0.989, 1e-12);
}

TEST(ImageDiff, IdenticalImagesGiveZeros) {
  const std::vector<float> a = baseImage(9, 7);
  const ImageDiff diff = diffImages(a, a, 9, 7);
  const ImageDiffStats& s = diff.stats;
  EXPECT_EQ(s.compared, 63u);
  for (const DifferenceStats* d : {&s.relative, &s.absolute}) {
    EXPECT_EQ(d->maxAbs, 0.0);
    EXPECT_EQ(d->meanAbs, 0.0);
    EXPECT_EQ(d->rms, 0.0);
    EXPECT_EQ(d->abs.p50, 0.0);
    EXPECT_EQ(d->abs.p999, 0.0);
    EXPECT_EQ(d->maxX, 0);  // the first pixel holds the (zero) maximum
  }
  EXPECT_EQ(s.aboveThreshold, 0u);
  for (float v : diff.relative) EXPECT_EQ(v, 0.0f);
  // Nothing to scale the picture by: the threshold is the range.
  EXPECT_EQ(defaultDiffRange(s), 0.01);
}

TEST(ImageDiff, HugeDifferencesStayFiniteInThePicture) {
  // d = 3e38 / floor is beyond float: the pixel was compared, so it is drawn at the red end.
  std::vector<float> a(12, 0.5f), b(12, 0.5f);
  a[0] = a[1] = a[2] = 3e38f;
  ImageDiffOptions o;
  o.floor = 1e-6;
  const ImageDiff diff = diffImages(a, b, 4, 1, o);
  EXPECT_EQ(diff.stats.compared, 4u);
  EXPECT_TRUE(std::isfinite(diff.relative[0]));
  const plot::Figure f = drawImageDiff(diff, 1.0);
  EXPECT_EQ(f.canvas.at(f.panel.x, f.panel.y), plot::mapColour(plot::ColourMap::Diverging, 1.0));
}

TEST(ImageDiff, NonFinitePixelsAreCountedAndExcluded) {
  const int w = 6, h = 5;
  const std::vector<float> b0 = baseImage(w, h);
  std::vector<float> a0 = b0;
  for (int i = 0; i < w * h; ++i) a0[3 * i + 1] *= 1.0f + 0.01f * float(i % 7);
  std::vector<float> a = a0, b = b0;
  a[3 * 2 + 0] = kNaN;   // pixel 2: A
  a[3 * 9 + 2] = -kInf;  // pixel 9: A
  b[3 * 9 + 1] = kNaN;   // pixel 9: B too
  b[3 * 20 + 0] = kInf;  // pixel 20: B
  const ImageDiff diff = diffImages(a, b, w, h);
  EXPECT_EQ(diff.stats.nonFiniteA, 2u);
  EXPECT_EQ(diff.stats.nonFiniteB, 2u);
  EXPECT_EQ(diff.stats.compared, std::size_t(w * h - 3));
  for (int i : {2, 9, 20}) EXPECT_TRUE(std::isnan(diff.relative[i])) << i;

  // The statistics are those of the other pixels alone: compare with the images without them.
  std::vector<double> absd;
  for (int i = 0; i < w * h; ++i) {
    if (i == 2 || i == 9 || i == 20) continue;
    absd.push_back(std::fabs(double(diff.relative[i])));
  }
  EXPECT_FLOAT_EQ(float(diff.stats.relative.abs.p50), float(percentile(absd, 50)));
  EXPECT_FLOAT_EQ(float(diff.stats.relative.maxAbs), float(*std::max_element(absd.begin(), absd.end())));
  for (double v : {diff.stats.relative.meanAbs, diff.stats.relative.rms, diff.stats.absolute.maxAbs})
    EXPECT_TRUE(std::isfinite(v));

  const std::string report = formatImageDiff(diff.stats, "a.exr", "b.exr");
  EXPECT_NE(report.find("2 pixels are not finite in A"), std::string::npos) << report;
  EXPECT_NE(report.find("2 pixels are not finite in B"), std::string::npos) << report;

  // Nothing finite in both: zeros, no location, and the report says so.
  std::vector<float> nan(3 * w * h, kNaN);
  const ImageDiffStats none = diffImages(nan, b0, w, h).stats;
  EXPECT_EQ(none.compared, 0u);
  EXPECT_EQ(none.relative.maxX, -1);
  EXPECT_NE(formatImageDiff(none, "a", "b").find("nothing to compare"), std::string::npos);
}

TEST(ImageDiff, FloorKeepsBlackReferencePixelsBounded) {
  const int w = 4, h = 1;
  std::vector<float> b = {0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  std::vector<float> a = {0.01f, 0.01f, 0.01f, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  // Mean Y_B = 0.75: the default floor is 7.5e-4, so d at the black pixel is 0.01 / 7.5e-4.
  const ImageDiffStats s = diffImages(a, b, w, h).stats;
  EXPECT_NEAR(s.floor, 7.5e-4, 1e-9);
  EXPECT_NEAR(s.relative.maxAbs, 0.01 / 7.5e-4, 1e-3);
  ImageDiffOptions o;
  o.floor = 0.1;
  EXPECT_NEAR(diffImages(a, b, w, h, o).stats.relative.maxAbs, 0.1, 1e-6);
  // An all-black B takes the floor from A; both black, 1e-3: never a division by zero.
  std::vector<float> black(12, 0.0f);
  EXPECT_NEAR(diffImages(a, black, w, h).stats.floor, 1e-3 * lum(0.01, 0.01, 0.01) / 4 + 1e-3 * 0.75, 1e-9);
  EXPECT_EQ(diffImages(black, black, w, h).stats.floor, 1e-3);
}

TEST(ImageDiff, SizeMismatchNamesBothSizes) {
  ScratchDir dir("imgdiff");
  writeExrRgb(dir.path("a.exr"), 4, 3, std::vector<float>(36, 0.5f));
  writeExrRgb(dir.path("b.exr"), 3, 4, std::vector<float>(36, 0.5f));
  try {
    diffExrFiles(dir.path("a.exr"), dir.path("b.exr"));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("the images differ in size"), std::string::npos) << m;
    EXPECT_NE(m.find("a.exr' is 4x3"), std::string::npos) << m;
    EXPECT_NE(m.find("b.exr' is 3x4"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(ImageDiff, PictureIsTheImageInTheDivergingMapWithoutText) {
  ScratchDir dir("imgdiff");
  const int w = 40, h = 30;
  std::vector<float> b(3 * w * h, 1.0f), a = b;
  const double range = 0.2;
  auto setD = [&](int x, int y, float d) {
    for (int c = 0; c < 3; ++c) a[3 * (y * w + x) + c] = 1.0f + d;
  };
  setD(5, 7, 0.2f);    // +range: the red end
  setD(6, 7, -0.5f);   // beyond -range: the blue end
  setD(7, 7, 0.1f);    // half way to red
  a[3 * (8 * w + 9)] = kNaN;
  const ImageDiff diff = diffImages(a, b, w, h);
  const plot::Figure f = drawImageDiff(diff, range);
  EXPECT_EQ(f.panel.width, w);
  EXPECT_EQ(f.panel.height, h);
  auto at = [&](int x, int y) { return f.canvas.at(f.panel.x + x, f.panel.y + y); };
  const plot::Colour centre = plot::mapColour(plot::ColourMap::Diverging, 0.5);
  const plot::Colour red = plot::mapColour(plot::ColourMap::Diverging, 1.0);
  const plot::Colour blue = plot::mapColour(plot::ColourMap::Diverging, 0.0);
  EXPECT_EQ(at(0, 0), centre);
  EXPECT_EQ(at(w - 1, h - 1), centre);
  EXPECT_EQ(at(5, 7), red);
  EXPECT_EQ(at(6, 7), blue);
  EXPECT_EQ(at(7, 7), plot::mapColour(plot::ColourMap::Diverging, 0.75));
  EXPECT_EQ(at(9, 8), plot::kNotFinite);
  EXPECT_GT(red.r, red.b + 80);
  EXPECT_GT(blue.b, blue.r + 80);
  EXPECT_GT(std::min({centre.r, centre.g, centre.b}), 230);
  expectFieldOnly(f, plot::ColourMap::Diverging, diff.relative, -range, range);

  // The file is this picture, PNG-encoded, at the image's size.
  writeImageDiffPng(dir.path("d.png"), diff, range);
  const std::string png = brdfcl::test::slurp(dir.path("d.png"));
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(be32(png, 16), std::uint32_t(f.canvas.width()));
  EXPECT_EQ(be32(png, 20), std::uint32_t(f.canvas.height()));
  EXPECT_EQ(png, plot::encodePng(f.canvas));
}

TEST(ImageDiff, JsonReportHoldsTheStatistics) {
  const std::vector<float> b = baseImage(8, 8);
  std::vector<float> a = b;
  a[3 * 10] *= 2.0f;
  const ImageDiffStats s = diffImages(a, b, 8, 8).stats;
  const auto j = nlohmann::json::parse(imageDiffJson(s, "a.exr", "b.exr", 0.5, ""));
  EXPECT_EQ(j["pixels"], 64);
  EXPECT_EQ(j["compared"], 64);
  EXPECT_EQ(j["relative"]["max_x"], 2);
  EXPECT_EQ(j["relative"]["max_y"], 1);
  EXPECT_DOUBLE_EQ(j["relative"]["p99"].get<double>(), s.relative.abs.p99);
  EXPECT_DOUBLE_EQ(j["absolute"]["max_abs"].get<double>(), s.absolute.maxAbs);
  EXPECT_EQ(j["above_threshold"], 1);
  EXPECT_TRUE(j["out"].is_null());
  EXPECT_EQ(j["range"], 0.5);
}

// ---- the plotting layer ----

TEST(Plot, CanvasPixelsAreClippedToTheCanvas) {
  plot::Canvas c(10, 10);
  c.set(-1, 5, plot::kBlack);
  c.set(10, 5, plot::kBlack);
  c.set(3, 4, plot::kBlack);
  EXPECT_EQ(c.at(3, 4), plot::kBlack);
  EXPECT_EQ(c.at(0, 5), plot::kWhite);
  EXPECT_THROW(c.at(10, 0), std::out_of_range);
}

TEST(Plot, ColourMapsChangeLightnessMonotonically) {
  using plot::ColourMap;
  EXPECT_EQ(plot::mapColour(ColourMap::Diverging, 0.5), (plot::Colour{0xf3, 0xf3, 0xf3}));
  EXPECT_EQ(plot::mapColour(ColourMap::Diverging, -3.0), plot::mapColour(ColourMap::Diverging, 0.0));
  EXPECT_EQ(plot::mapColour(ColourMap::Sequential, 7.0), plot::mapColour(ColourMap::Sequential, 1.0));
  EXPECT_EQ(plot::mapColour(ColourMap::Sequential, std::nan("")), plot::kNotFinite);
  // Lightness falls from the white centre to both ends of the diverging map and rises along the
  // sequential one; the 8-bit rounding allows a step back of a fraction of a unit of L*.
  const int n = 512;
  double prevD = lightness(plot::mapColour(ColourMap::Diverging, 0.0));
  double prevS = lightness(plot::mapColour(ColourMap::Sequential, 0.0));
  double maxStep = 0, minStep = 1e9;
  for (int i = 1; i <= n; ++i) {
    const double t = double(i) / n;
    const double ld = lightness(plot::mapColour(ColourMap::Diverging, t));
    const double ls = lightness(plot::mapColour(ColourMap::Sequential, t));
    if (t <= 0.5)
      EXPECT_GE(ld, prevD - 0.3) << t;
    else
      EXPECT_LE(ld, prevD + 0.3) << t;
    EXPECT_GE(ls, prevS - 0.3) << t;
    if (i % 64 == 0) {
      const double step = ls - lightness(plot::mapColour(ColourMap::Sequential, t - 64.0 / n));
      maxStep = std::max(maxStep, step);
      minStep = std::min(minStep, step);
    }
    prevD = ld;
    prevS = ls;
  }
  // Even steps of t give roughly even steps of lightness along the sequential map.
  EXPECT_LT(maxStep, 1.6 * minStep) << minStep << " .. " << maxStep;
  EXPECT_LT(lightness(plot::mapColour(ColourMap::Sequential, 0.0)), 25.0);
  EXPECT_GT(lightness(plot::mapColour(ColourMap::Sequential, 1.0)), 85.0);
}

TEST(Plot, HeatMapOfAnAnalyticField) {
  // f(x, y) = sin x cos y on x in [0, 2 pi], y in [-pi, pi] (y up), sampled at pixel centres.
  const int w = 240, h = 160;
  const double pi = std::acos(-1.0);
  std::vector<float> v(std::size_t(w) * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const double x = (i + 0.5) / w * 2 * pi, y = pi - (j + 0.5) / h * 2 * pi;
      v[std::size_t(j) * w + i] = float(std::sin(x) * std::cos(y));
    }
  plot::HeatMap spec;
  spec.map = plot::ColourMap::Sequential;
  spec.vMin = -1;
  spec.vMax = 1;
  const plot::Figure f = plot::drawHeatMap(spec, w, h, v);
  for (int j = 0; j < h; j += 7)
    for (int i = 0; i < w; i += 11)
      ASSERT_EQ(f.canvas.at(f.panel.x + i, f.panel.y + j),
                plot::mapColour(spec.map, (v[std::size_t(j) * w + i] + 1.0) / 2.0))
          << i << "," << j;
  expectFieldOnly(f, spec.map, v, -1, 1);
  EXPECT_THROW(plot::drawHeatMap(spec, w, h, std::vector<float>(10)), std::invalid_argument);

  ScratchDir dir("plot");
  plot::writePng(dir.path("field.png"), f.canvas);
  EXPECT_EQ(brdfcl::test::slurp(dir.path("field.png")), plot::encodePng(f.canvas));
  // BRDFCL_TEST_FIGURES=DIR keeps the picture for a person to look at.
  if (const char* keep = std::getenv("BRDFCL_TEST_FIGURES")) plot::writePng(std::string(keep) + "/heatmap.png", f.canvas);
}

// The encoder's allocation failing, as ErrorsDeathTest.PngEncoderOutOfMemory provokes it for the
// renders' PNG (test_errors.cpp explains the method): a fresh copy of this binary makes a canvas
// larger than the heap's free space, then caps its address space just above what it holds.
TEST(PlotDeathTest, PngEncoderOutOfMemory) {
  if (brdfcl::test::kAddressSanitizer) GTEST_SKIP() << brdfcl::test::kNoAddressSpaceLimitUnderAsan;
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  ScratchDir dir("plotoom");
  const std::string out = dir.path("big.png");
  EXPECT_EXIT(
      {
        const std::size_t freeHeap = mallinfo2().fordblks;
        int side = 2048;
        while (3ull * side * side <= freeHeap + (16u << 20)) side *= 2;
        const plot::Canvas canvas(side, side, plot::Colour{10, 20, 30});
        std::size_t vm = 0;
        std::ifstream status("/proc/self/status");
        for (std::string line; std::getline(status, line);)
          if (line.rfind("VmSize:", 0) == 0) vm = std::stoull(line.substr(7)) << 10;
        struct rlimit limit {};
        limit.rlim_cur = limit.rlim_max = vm + (8u << 20);
        ::setrlimit(RLIMIT_AS, &limit);
        int code = 1;
        try {
          plot::writePng(out, canvas);
        } catch (const Error& e) {
          std::fprintf(stderr, "%s\n", e.what());
          code = fs::exists(out) || !fs::is_empty(dir.dir()) ? 2 : 0;
        }
        std::error_code ec;
        fs::remove_all(dir.dir(), ec);  // this copy's own directory: its destructor never runs
        std::fflush(stderr);
        ::_exit(code);
      },
      ::testing::ExitedWithCode(0), "cannot write '.*/big.png': the PNG encoder failed \\(out of memory\\?\\)");
}

// ---- the command ----

TEST(ImageDiffCli, PrintsStatisticsAndWritesThePicture) {
  ScratchDir dir("diffcli");
  const int w = 32, h = 24;
  const std::vector<float> b = baseImage(w, h);
  std::vector<float> a = b;
  for (int c = 0; c < 3; ++c) a[3 * (10 * w + 20) + c] *= 1.5f;
  a[3 * 3] = kNaN;
  writeExrRgb(dir.path("a.exr"), w, h, a);
  writeExrRgb(dir.path("b.exr"), w, h, b);

  const RunResult r = cli(dir, {"diff", "a.exr", "b.exr", "--out", "d.png"});
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.err.empty()) << r.err;
  for (const char* text : {"768 pixels, 767 compared", "1 pixels are not finite in A", "0 pixels are not finite in B",
                           "max |d|   0.5 at (20, 10)", "p99.9", "|d| > 0.01: 1 of 767 pixels", "picture: d.png"})
    EXPECT_NE(r.out.find(text), std::string::npos) << "expected '" << text << "' in\n" << r.out;
  const ImageDiff diff = diffExrFiles(dir.path("a.exr"), dir.path("b.exr"));
  const plot::Figure f = drawImageDiff(diff, defaultDiffRange(diff.stats));
  const std::string png = brdfcl::test::slurp(dir.path("d.png"));
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(be32(png, 16), std::uint32_t(f.canvas.width()));
  EXPECT_EQ(be32(png, 20), std::uint32_t(f.canvas.height()));
  EXPECT_EQ(png, plot::encodePng(f.canvas));
  EXPECT_EQ(files(dir), (std::set<std::string>{"a.exr", "b.exr", "d.png"}));

  const RunResult j = cli(dir, {"diff", "a.exr", "b.exr", "--json", "--threshold", "0.2", "--floor", "0.5"});
  ASSERT_EQ(j.status, 0) << j.describe();
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["not_finite_a"], 1);
  EXPECT_EQ(doc["compared"], 767);
  EXPECT_EQ(doc["threshold"], 0.2);
  EXPECT_EQ(doc["floor"], 0.5);
  EXPECT_EQ(doc["relative"]["max_x"], 20);
  EXPECT_EQ(doc["relative"]["max_y"], 10);
  EXPECT_EQ(doc["above_threshold"], 1);
}

TEST(ImageDiffCli, FailAboveExitsOneAfterTheReport) {
  ScratchDir dir("diffcli");
  const std::vector<float> b = baseImage(10, 10);
  std::vector<float> a = b;
  for (int i = 0; i < 5; ++i) a[3 * i + 1] *= 1.2f;  // 5% of the pixels differ by more than 1%
  writeExrRgb(dir.path("a.exr"), 10, 10, a);
  writeExrRgb(dir.path("b.exr"), 10, 10, b);
  const RunResult fail = cli(dir, {"diff", "a.exr", "b.exr", "--fail-above", "0.01"});
  EXPECT_EQ(fail.status, 1) << fail.describe();
  EXPECT_NE(fail.out.find("max |d|"), std::string::npos) << fail.out;
  ASSERT_EQ(fail.errorLines().size(), 1u) << fail.describe();
  EXPECT_NE(fail.err.find("5 of 100 compared pixels (a fraction 0.05) have |d| > 0.01, more than --fail-above 0.01"),
            std::string::npos)
      << fail.err;
  EXPECT_EQ(cli(dir, {"diff", "a.exr", "b.exr", "--fail-above", "0.05"}).status, 0);
  EXPECT_EQ(cli(dir, {"diff", "a.exr", "b.exr", "--fail-above", "0", "--threshold", "0.2"}).status, 0);
  // Nothing comparable is a failure for CI, not a pass; without --fail-above it is only reported.
  writeExrRgb(dir.path("nan.exr"), 10, 10, std::vector<float>(300, kNaN));
  const RunResult none = cli(dir, {"diff", "nan.exr", "b.exr", "--fail-above", "1"});
  EXPECT_EQ(none.status, 1) << none.describe();
  EXPECT_NE(none.out.find("100 pixels are not finite in A"), std::string::npos) << none.out;
  EXPECT_NE(none.err.find("no pixel is finite in both images (--fail-above)"), std::string::npos) << none.err;
  const RunResult reported = cli(dir, {"diff", "nan.exr", "b.exr", "--out", "n.png"});
  EXPECT_EQ(reported.status, 0) << reported.describe();
  EXPECT_NE(reported.out.find("nothing to compare"), std::string::npos) << reported.out;
  EXPECT_TRUE(fs::exists(dir.path("n.png")));
}

TEST(ImageDiffCli, BadInputIsOneLineAndWritesNothing) {
  ScratchDir dir("diffcli");
  writeExrRgb(dir.path("a.exr"), 4, 3, std::vector<float>(36, 0.5f));
  writeExrRgb(dir.path("b.exr"), 3, 4, std::vector<float>(36, 0.5f));
  writeExrRgb(dir.path("c.exr"), 4, 3, std::vector<float>(36, 0.25f));
  const std::set<std::string> inputs{"a.exr", "b.exr", "c.exr"};

  expectOneLineError(cli(dir, {"diff", "a.exr", "b.exr", "--out", "d.png"}),
                     "the images differ in size: 'a.exr' is 4x3, 'b.exr' is 3x4; compare renders of the same size");
  expectOneLineError(cli(dir, {"diff", "a.exr", "missing.exr", "--out", "d.png"}), "missing.exr");
  expectOneLineError(cli(dir, {"diff", "a.exr"}), "B is required");
  // Options and the output are checked before the inputs are read (the inputs here do not exist).
  expectOneLineError(cli(dir, {"diff", "x.exr", "y.exr", "--out", "d.jpg"}),
                     "--out 'd.jpg': the picture is written as PNG; name it .png");
  expectOneLineError(cli(dir, {"diff", "x.exr", "y.exr", "--out", "no/such/dir/d.png"}), "--out 'no/such/dir/d.png'");
  expectOneLineError(cli(dir, {"diff", "x.exr", "y.exr", "--threshold", "-1"}), "--threshold -1 must be a finite number >= 0");
  expectOneLineError(cli(dir, {"diff", "x.exr", "y.exr", "--floor", "0"}), "--floor 0 must be a finite number > 0");
  expectOneLineError(cli(dir, {"diff", "x.exr", "y.exr", "--range", "nan"}), "--range nan must be a finite number > 0");
  expectOneLineError(cli(dir, {"diff", "x.exr", "y.exr", "--fail-above", "2"}), "--fail-above 2 must be a fraction from 0 to 1");
  EXPECT_EQ(files(dir), inputs);

  // A comparison that runs exits 0 whatever the difference.
  const RunResult ok = cli(dir, {"diff", "a.exr", "c.exr", "--range", "0.5", "--out", "D.PNG"});
  EXPECT_EQ(ok.status, 0) << ok.describe();
  EXPECT_TRUE(fs::exists(dir.path("D.PNG")));
}
