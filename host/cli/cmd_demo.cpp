// `brdfcl demo`: the sphere sweep written as out/demo.glb and rendered to out/demo.png and
// out/demo.exr under the studio environment.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "host/src/gltf/demo_asset.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "render_options.hpp"

namespace brdfcl::cli {

void addDemoCommand(CLI::App& app) {
  struct Args {
    std::string size, device;
    float exposure = 0.0f;
    int spp = 4;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("demo", "Write the sphere sweep as out/demo.glb and render it to out/demo.png and out/demo.exr");
  cmd->add_option("--size", a->size, "WIDTHxHEIGHT (default 720x720, the camera's aspect at 720 rows)");
  cmd->add_option("--spp", a->spp, "stratified sub-pixel samples per pixel (default 4)");
  cmd->add_option("--exposure", a->exposure, "exposure in stops (default 0)");
  cmd->add_option("--device", a->device, "device index or name substring, or all, or a list such as 0,2 to shade row bands on several devices");
  cmd->callback([a] {
    checkSpp(a->spp);
    checkExposure(a->exposure);
    GltfArgs asset;
    asset.size = a->size;
    RenderJob job = asset.job();  // --size parsed before any file is written
    std::error_code ec;
    if (std::filesystem::exists("out", ec) && !std::filesystem::is_directory("out", ec))
      throw Error("cannot write the demo into 'out': it exists and is not a directory; move it or run elsewhere");
    std::filesystem::create_directories("out", ec);
    if (ec) throw Error(fmt::format("cannot create the demo directory 'out': {}", ec.message()));
    const std::string glb = "out/demo.glb", png = "out/demo.png", exr = "out/demo.exr";
    for (const auto& p : {glb, png, exr}) checkOutputPath("demo", p);
    gltf::writeDemoAsset(glb);
    job.gltf = glb;
    job.environment = "studio";
    job.environmentGiven = true;
    job.spp = a->spp;
    job.frameProgress = progressLine("brdfcl render", "sample");
    const PreparedRender prepared = prepareRender(job);
    DeviceSet devices(a->device);
    writeImages(renderPrepared(devices, prepared, job), exr, png, a->exposure);
    auto abs = [](const std::string& p) { return std::filesystem::absolute(p).string(); };
    fmt::print("brdfcl demo: wrote the sphere sweep as a glTF asset and rendered it on {}\n  {}\n  {}\n  {}\n"
               "Rows: white sheen and coloured sheen over a woven texture (sheen roughness 0.05 to 1), clearcoat over\n"
               "a flake normal map (roughness 0 to 1), brushed anisotropy strength 0 to 1, anisotropy rotation 0 to pi,\n"
               "gold metal/dielectric roughness 0 to 1. Studio environment, the file's key and fill lights.\n",
               deviceNames(devices), abs(glb), abs(png), abs(exr));
  });
}

}  // namespace brdfcl::cli
