// `brdfcl lut`: bakes an engine LUT (sheen-e, ggx-dfg, charlie-dfg) on the device and writes it
// as .exr, .csv, .h or .npy. Arguments are checked before the bake, so a typo fails at once.
#include <chrono>
#include <cstdio>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/lut.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

namespace {
struct LutArgs {
  std::string kind, out, device;
  std::string visibility = "charlie", distribution = "charlie";
  long long size = 128;
};
}  // namespace

void addLutCommand(CLI::App& app) {
  auto args = std::make_shared<LutArgs>();
  auto* cmd = app.add_subcommand("lut", "Bake a look-up table (x = N.V, y = roughness) for engines");
  cmd->add_option("--kind", args->kind, "sheen-e|ggx-dfg|charlie-dfg")->required();
  cmd->add_option("--size", args->size, "texels per side, 2..4096 (default 128)");
  cmd->add_option("--sheen-visibility", args->visibility, "sheen-e only: charlie|ashikhmin (default charlie)");
  cmd->add_option("--sheen-distribution", args->distribution, "sheen-e only: charlie|ashikhmin (default charlie)");
  cmd->add_option("--out", args->out, "output .exr (FLOAT R[,G]), .csv, .h or .npy (float32); - writes CSV to stdout")->required();
  cmd->add_option("--device", args->device, "device index or name substring (default $BRDFCL_DEVICE, then 0)");
  cmd->callback([args, cmd] {
    const LutKind kind = parseLutKind(args->kind);
    // The DFG tables have no sheen choices: accepting them would change nothing silently.
    if (kind != LutKind::SheenE)
      for (const char* o : {"--sheen-visibility", "--sheen-distribution"})
        if (cmd->count(o))
          throw Error(std::string(o) + " applies to --kind sheen-e only; drop it for --kind " + args->kind);
    if (args->size < static_cast<long long>(kMinLutSize) || args->size > static_cast<long long>(kMaxLutSize))
      throw Error("--size " + std::to_string(args->size) + " is out of range; use 2 to 4096");
    EvalOptions o;
    o.sheenVisibility = parseSheenVisibility(args->visibility);
    o.sheenDistribution = parseSheenDistribution(args->distribution);
    checkOutputPath("--out", args->out);  // first: a directory is named as --out, not as a bad extension
    checkLutPath(args->out);
    Runtime rt(args->device);
    const auto lut = bakeLut(rt, kind, std::size_t(args->size), o);
    writeLut(lut, args->out);
  });
}

}  // namespace brdfcl::cli
