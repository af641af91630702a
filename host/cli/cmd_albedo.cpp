// `brdfcl albedo`: the built-in gallery's directional albedo per lobe at a few view angles,
// evaluated on the device. Albedo <= 1 is energy conservation at a glance.
#include <cmath>

#include <fmt/format.h>

#include "brdfcl/albedo.hpp"
#include "brdfcl/gallery.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

void addAlbedoCommand(CLI::App& app) {
  auto device = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("albedo", "Print the directional albedo of the built-in material gallery");
  cmd->add_option("--device", *device, "device index or name substring (default $BRDFCL_DEVICE, then 0)");
  cmd->callback([device] {
    Runtime rt(*device);
    const auto materials = gallery();
    const std::vector<float> anglesDeg = {0, 30, 60, 75, 85};
    std::vector<float> mus;
    for (float a : anglesDeg) mus.push_back(float(std::cos(a * M_PI / 180.0)));
    const std::vector<Lobe> lobes = {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat, Lobe::All};
    std::vector<std::vector<float>> perLobe;
    for (Lobe l : lobes) {
      EvalOptions o;
      o.lobe = l;
      Evaluator ev(rt, o);
      perLobe.push_back(directionalAlbedo(ev, materials, mus));
    }
    fmt::print("brdfcl albedo on {} ({})\n", rt.info().name, rt.info().platform);
    fmt::print("Directional albedo: integral of f(L,V) N.L over the hemisphere of L, as luminance\n"
               "(Rec. 709 Y of the RGB albedo). Defaults: Charlie sheen, min albedo scaling.\n\n");
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
