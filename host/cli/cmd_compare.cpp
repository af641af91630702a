// `brdfcl compare --materials M.json --profile A [--against B]`: how far one parity profile's f is
// from another's, per material and lobe, with directional albedos and optional log2-ratio heat maps.
// The work is compareProfiles (parity/compare.hpp); this file checks options and prints.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "host/src/parity/compare.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

namespace {
struct CompareArgs {
  std::string device, materials, profile, against = "spec", out;
  long long material = -1, pairs = 100000;
  bool strict = false, json = false;
};

// The directory is created now, before any input is read, so a bad --out fails before the work.
void prepareOutDir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw Error(fmt::format("--out '{}': it exists and is not a directory; name a directory (created if missing)", dir));
  fs::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("--out '{}': cannot create the directory: {}", dir, ec.message()));
}
}  // namespace

void addCompareCommand(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  auto* cmd = app.add_subcommand("compare", "Compare the BRDF of two parity profiles: relative differences per lobe, albedos, heat maps");
  cmd->add_option("--materials", args->materials, "glTF 2.0 JSON (or .glb) whose materials to compare")->required();
  cmd->add_option("--material", args->material, "only this material index of --materials (default: all)");
  cmd->add_option("--profile", args->profile, "profile A: spec|khronos|threejs|filament|babylon|materialx")->required();
  cmd->add_option("--against", args->against, "profile B, the reference of d = |A - B| / max(|B|, floor) (default spec)");
  cmd->add_option("--out", args->out, "write log2(A/B) heat maps (PNG) into this directory, created if missing");
  cmd->add_option("--pairs", args->pairs, "random out-of-plane direction pairs (default 100000, 0 to 100000000)");
  cmd->add_flag("--strict", args->strict, "unknown keys and extensions in the materials file are errors, not warnings");
  cmd->add_option("--device", args->device, "device index or name substring (default $BRDFCL_DEVICE, then 0)");
  cmd->add_flag("--json", args->json, "print one JSON object instead of the table");
  cmd->callback([args, cmd] {
    CompareOptions o;
    o.a = parseProfile(args->profile);
    o.b = parseProfile(args->against, "--against");
    if (args->pairs < 0 || args->pairs > 100000000)
      throw Error(fmt::format("--pairs {} is out of range; use 0 to 100000000", args->pairs));
    o.randomPairs = std::size_t(args->pairs);
    o.heatMaps = !args->out.empty();
    if (cmd->count("--out") && args->out.empty()) throw Error("--out needs a directory name; drop it or give e.g. --out maps");
    if (o.heatMaps) prepareOutDir(args->out);

    std::vector<MaterialParams> materials = readUserMaterials(args->materials, args->strict);
    if (materials.empty()) throw Error(fmt::format("{}: the file has no materials", args->materials));
    std::vector<std::size_t> indices;
    for (std::size_t m = 0; m < materials.size(); ++m) {
      if (materials[m].name.empty()) materials[m].name = fmt::format("materials[{}]", m);
      indices.push_back(m);
    }
    if (cmd->count("--material")) {
      if (args->material < 0 || args->material >= static_cast<long long>(materials.size()))
        throw Error(fmt::format("--material {} is out of range: {} has {} material(s), 0 to {}", args->material,
                                args->materials, materials.size(), materials.size() - 1));
      materials = {materials[std::size_t(args->material)]};
      indices = {std::size_t(args->material)};
    }

    Runtime rt(args->device);
    Comparison c = compareProfiles(rt, materials, o);
    for (std::size_t m = 0; m < c.materials.size(); ++m) c.materials[m].index = indices[m];
    std::vector<std::vector<std::string>> paths;
    if (o.heatMaps)
      for (const MaterialComparison& m : c.materials) paths.push_back(writeRatioMaps(args->out, c, m));
    if (args->json) {
      std::fputs(comparisonJson(c, paths).c_str(), stdout);
    } else {
      std::fputs(formatComparison(c).c_str(), stdout);
      if (!paths.empty()) {
        fmt::print("\nheat maps (log2 of the luminance ratio A/B, lobe all):\n");
        for (const auto& ps : paths)
          for (const auto& p : ps) fmt::print("  {}\n", p);
      }
    }
    std::fflush(stdout);
  });
}

}  // namespace brdfcl::cli
