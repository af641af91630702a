// `brdfcl albedo`: the directional albedo per lobe at a few view angles, evaluated on the device,
// of the built-in gallery or of the user's own materials. Albedo <= 1 is energy conservation at a glance.
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "brdfcl/albedo.hpp"
#include "brdfcl/error.hpp"
#include "host/src/model/gallery.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "model_options.hpp"

namespace brdfcl::cli {

namespace {
struct AlbedoArgs {
  std::string device, materials;
  long long material = -1;
  bool strict = false;
  ModelArgs model;
};
}  // namespace

void addAlbedoCommand(CLI::App& app) {
  auto args = std::make_shared<AlbedoArgs>();
  auto* cmd = app.add_subcommand("albedo", "Print the directional albedo per lobe of the built-in gallery or of your materials");
  cmd->add_option("--materials", args->materials, "glTF 2.0 JSON (or .glb) whose materials to integrate (default: the built-in gallery)");
  cmd->add_option("--material", args->material, "only this material index of --materials (default: all)");
  cmd->add_flag("--strict", args->strict, "unknown keys and extensions in the materials file are errors, not warnings");
  addModelOptions(cmd, args->model);
  cmd->add_option("--device", args->device, "device index or name substring (default $BRDFCL_DEVICE, then 0)");
  cmd->callback([args, cmd] {
    const EvalOptions base = modelOptions(args->model);
    std::vector<MaterialParams> materials;
    if (args->materials.empty()) {
      for (const char* o : {"--material", "--strict"})
        if (cmd->count(o)) throw Error(fmt::format("{} applies to --materials FILE; add --materials", o));
      materials = gallery();
    } else {
      // The reader's warnings wait until --material is known to be in range: a run that fails
      // prints its error line alone.
      std::vector<std::string> warnings;
      materials = readUserMaterials(args->materials, args->strict,
                                    [&warnings](const std::string& w) { warnings.push_back(w); });
      if (materials.empty()) throw Error(fmt::format("{}: the file has no materials", args->materials));
      for (std::size_t m = 0; m < materials.size(); ++m)
        if (materials[m].name.empty()) materials[m].name = fmt::format("materials[{}]", m);
      if (cmd->count("--material")) {
        if (args->material < 0 || args->material >= static_cast<long long>(materials.size()))
          throw Error(fmt::format("--material {} is out of range: {} has {} material(s), 0 to {}", args->material,
                                  args->materials, materials.size(), materials.size() - 1));
        materials = {materials[std::size_t(args->material)]};
      }
      for (const auto& w : warnings) printWarning(w);
    }
    Runtime rt(args->device);
    const std::vector<float> anglesDeg = {0, 30, 60, 75, 85};
    std::vector<float> mus;
    for (float a : anglesDeg) mus.push_back(float(std::cos(a * M_PI / 180.0)));
    const std::vector<Lobe> lobes = {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat, Lobe::All};
    std::vector<std::vector<float>> perLobe;
    for (Lobe l : lobes) {
      EvalOptions o = base;
      o.lobe = l;
      Evaluator ev(rt, o);
      perLobe.push_back(directionalAlbedo(ev, materials, mus));
    }
    fmt::print("brdfcl albedo on {} ({})\n", rt.info().name, rt.info().platform);
    fmt::print("Directional albedo: integral of f(L,V) N.L over the hemisphere of L, as luminance\n");
    if (base.profile == Profile::Spec)
      fmt::print("(Rec. 709 Y of the RGB albedo). Sheen: {} distribution, {} visibility, {} albedo scaling.\n\n",
                 args->model.distribution, args->model.visibility, args->model.scaling);
    else
      fmt::print("(Rec. 709 Y of the RGB albedo). Profile {}: {}'s BRDF as docs/profiles.md defines it.\n\n",
                 toString(base.profile), toString(base.profile));
    for (std::size_t m = 0; m < materials.size(); ++m) {
      fmt::print("{}\n  {:<10}", materials[m].name, "view");
      for (float a : anglesDeg) fmt::print("{:>9}", fmt::format("{:.0f} deg", a));
      fmt::print("\n");
      for (std::size_t l = 0; l < lobes.size(); ++l) {
        fmt::print("  {:<10}", toString(lobes[l]));
        for (std::size_t v = 0; v < mus.size(); ++v) {
          const float* c = &perLobe[l][3 * (m * mus.size() + v)];
          fmt::print("{:>9.4f}", 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]);
        }
        fmt::print("\n");
      }
      fmt::print("\n");
    }
  });
}

}  // namespace brdfcl::cli
