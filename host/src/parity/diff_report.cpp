// What `brdfcl diff` prints: the statistics as aligned text lines, or as one JSON object whose
// keys scripts can rely on (docs/cli.md lists them).
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "parity/diff.hpp"
#include "io/messages.hpp"
#include "parity/image_diff.hpp"

namespace brdfcl {

namespace {
using detail::formatStat;

std::string percentiles(const Percentiles& p) {
  return fmt::format("p50 {}  p90 {}  p95 {}  p99 {}  p99.9 {}", formatStat(p.p50), formatStat(p.p90),
                     formatStat(p.p95), formatStat(p.p99), formatStat(p.p999));
}

nlohmann::json statsJson(const DifferenceStats& d) {
  return {{"max_abs", d.maxAbs}, {"max_x", d.maxX},   {"max_y", d.maxY},     {"at_max", d.atMax},
          {"mean_abs", d.meanAbs}, {"rms", d.rms},     {"p50", d.abs.p50},    {"p90", d.abs.p90},
          {"p95", d.abs.p95},     {"p99", d.abs.p99}, {"p99_9", d.abs.p999}};
}
}  // namespace

std::string formatImageDiff(const ImageDiffStats& s, const std::string& nameA, const std::string& nameB) {
  std::string r;
  r += fmt::format("A: {}\nB: {}\n", detail::printable(nameA, 200), detail::printable(nameB, 200));
  r += fmt::format("size: {}x{}, {} pixels, {} compared (finite in both)\n", s.width, s.height, s.pixels, s.compared);
  r += fmt::format("{} pixels are not finite in A\n{} pixels are not finite in B\n", s.nonFiniteA, s.nonFiniteB);
  if (s.compared == 0) return r + "no pixel is finite in both images: nothing to compare\n";
  r += fmt::format("relative luminance difference d = (Y_A - Y_B) / max(Y_B, {}), mean Y_B {}:\n", formatStat(s.floor),
                   formatStat(s.meanLuminanceB));
  const DifferenceStats& d = s.relative;
  r += fmt::format("  max |d|   {} at ({}, {}), d = {}\n", formatStat(d.maxAbs), d.maxX, d.maxY, formatStat(d.atMax));
  r += fmt::format("  mean |d|  {}\n  RMS d     {}\n", formatStat(d.meanAbs), formatStat(d.rms));
  r += "  |d|       " + percentiles(d.abs) + "\n";
  r += fmt::format("  |d| > {}: {} of {} pixels ({}%)\n", formatStat(s.threshold), s.aboveThreshold, s.compared,
                   formatStat(100.0 * s.fractionAbove));
  const DifferenceStats& a = s.absolute;
  r += "absolute luminance difference Y_A - Y_B:\n";
  r += fmt::format("  max |Y_A - Y_B|   {} at ({}, {}), Y_A - Y_B = {}\n", formatStat(a.maxAbs), a.maxX, a.maxY,
                   formatStat(a.atMax));
  r += fmt::format("  mean |Y_A - Y_B|  {}\n  RMS               {}\n", formatStat(a.meanAbs), formatStat(a.rms));
  r += "  |Y_A - Y_B|       " + percentiles(a.abs) + "\n";
  return r;
}

std::string imageDiffJson(const ImageDiffStats& s, const std::string& nameA, const std::string& nameB, double range,
                          const std::string& out) {
  nlohmann::json j = {{"a", nameA},
                      {"b", nameB},
                      {"width", s.width},
                      {"height", s.height},
                      {"pixels", s.pixels},
                      {"compared", s.compared},
                      {"not_finite_a", s.nonFiniteA},
                      {"not_finite_b", s.nonFiniteB},
                      {"floor", s.floor},
                      {"mean_luminance_b", s.meanLuminanceB},
                      {"threshold", s.threshold},
                      {"above_threshold", s.aboveThreshold},
                      {"fraction_above_threshold", s.fractionAbove},
                      {"relative", statsJson(s.relative)},
                      {"absolute", statsJson(s.absolute)},
                      {"range", range},
                      {"out", out.empty() ? nlohmann::json(nullptr) : nlohmann::json(out)}};
  // Names are the user's bytes: replace what is not UTF-8 rather than fail to print the report.
  return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace brdfcl
