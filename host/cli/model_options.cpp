// --profile and the sheen variants, parsed into EvalOptions (docs/profiles.md for the profiles).
#include "model_options.hpp"

#include "host/src/model/pack.hpp"

namespace brdfcl::cli {

void addModelOptions(CLI::App* cmd, ModelArgs& args) {
  cmd->add_option("--profile", args.profile,
                  "spec|khronos|threejs|filament|babylon|materialx: whose BRDF (default spec; docs/profiles.md)");
  cmd->add_option("--sheen-visibility", args.visibility, "charlie|ashikhmin (default charlie; spec profile only)");
  cmd->add_option("--sheen-distribution", args.distribution, "charlie|ashikhmin (default charlie; spec profile only)");
  cmd->add_option("--sheen-scaling", args.scaling, "min|view|none (default min; spec profile only)");
}

EvalOptions modelOptions(const ModelArgs& args) {
  EvalOptions o;
  o.profile = parseProfile(args.profile);
  o.sheenVisibility = parseSheenVisibility(args.visibility);
  o.sheenDistribution = parseSheenDistribution(args.distribution);
  o.sheenScaling = parseSheenScaling(args.scaling);
  checkProfileOptions(o);  // before any file is read
  return o;
}

}  // namespace brdfcl::cli
