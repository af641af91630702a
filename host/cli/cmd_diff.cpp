// `brdfcl diff A.exr B.exr`: compares two linear renders (any engine's, saved as EXR) by their
// luminance, prints the statistics (text or --json) and optionally writes a false-colour PNG.
// Options and the output path are checked before either image is read.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "host/src/parity/diff.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

namespace {
struct DiffArgs {
  std::string a, b, out;
  double threshold = 0.01, floor = 0, range = 0, failAbove = 0;
  bool json = false;
};

bool endsWithPng(const std::string& path) {
  if (path.size() < 4) return false;
  std::string ext = path.substr(path.size() - 4);
  for (auto& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return ext == ".png";
}

void requireNumber(const char* option, double v, bool positive) {
  if (!std::isfinite(v) || v < 0 || (positive && v == 0))
    throw Error(fmt::format("{} {} must be a finite number {}", option, v, positive ? "> 0" : ">= 0"));
}
}  // namespace

void addDiffCommand(CLI::App& app) {
  auto args = std::make_shared<DiffArgs>();
  auto* cmd = app.add_subcommand("diff", "Compare two EXR renders: luminance difference statistics, false-colour PNG");
  cmd->add_option("A", args->a, "first image (.exr)")->required();
  cmd->add_option("B", args->b, "second image (.exr), the reference: d = (Y_A - Y_B) / max(Y_B, floor)")->required();
  cmd->add_option("--out", args->out, "write the picture of d here (.png)");
  cmd->add_option("--threshold", args->threshold, "count the pixels with |d| above this (default 0.01)");
  cmd->add_option("--floor", args->floor, "luminance floor of the denominator (default 1e-3 x mean luminance of B)");
  cmd->add_option("--range", args->range, "the picture's colour range +-R (default: p99 of |d|)");
  cmd->add_option("--fail-above", args->failAbove,
                  "exit 1 when the fraction of pixels with |d| > threshold exceeds this (0..1)");
  cmd->add_flag("--json", args->json, "print one JSON object instead of text");
  cmd->callback([args, cmd] {
    requireNumber("--threshold", args->threshold, false);
    if (cmd->count("--floor")) requireNumber("--floor", args->floor, true);
    if (cmd->count("--range")) requireNumber("--range", args->range, true);
    const bool failCheck = cmd->count("--fail-above") > 0;
    if (failCheck && !(args->failAbove >= 0 && args->failAbove <= 1))
      throw Error(fmt::format("--fail-above {} must be a fraction from 0 to 1", args->failAbove));
    if (!args->out.empty()) {
      if (!endsWithPng(args->out))
        throw Error("--out '" + args->out + "': the picture is written as PNG; name it .png");
      checkOutputPath("--out", args->out);
      checkDistinctFiles({{"A", args->a, false}, {"B", args->b, false}, {"--out", args->out, true}});
    }

    ImageDiffOptions o;
    o.threshold = args->threshold;
    o.floor = args->floor;
    const ImageDiff diff = diffExrFiles(args->a, args->b, o);
    const ImageDiffStats& s = diff.stats;
    const double range = cmd->count("--range") ? args->range : defaultDiffRange(s);
    if (!args->out.empty()) writeImageDiffPng(args->out, diff, range);
    if (args->json) {
      std::fputs(imageDiffJson(s, args->a, args->b, range, args->out).c_str(), stdout);
    } else {
      std::fputs(formatImageDiff(s, args->a, args->b).c_str(), stdout);
      if (!args->out.empty()) fmt::print("picture: {} (colour range +-{:.4g})\n", args->out, range);
    }
    std::fflush(stdout);
    // For CI: the report is out first, then the verdict, with its own exit status.
    if (failCheck && (s.compared == 0 || s.fractionAbove > args->failAbove))
      throw Error(s.compared == 0 ? std::string("no pixel is finite in both images (--fail-above)")
                                  : fmt::format("{} of {} compared pixels (a fraction {:.4g}) have |d| > {:.4g}, more than --fail-above {:.4g}",
                                                s.aboveThreshold, s.compared, s.fractionAbove, s.threshold,
                                                args->failAbove),
                  1);
  });
}

}  // namespace brdfcl::cli
