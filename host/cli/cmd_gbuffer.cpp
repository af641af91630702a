// `brdfcl gbuffer`: a G-buffer EXR of the built-in spheres or of a glTF asset, ray-cast at pixel
// centres (docs/gbuffer.md).
#include <memory>
#include <optional>

#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "render_options.hpp"

namespace brdfcl::cli {

void addGbufferCommand(CLI::App& app) {
  struct Args {
    std::string scene = "spheres", out, device;
    GltfArgs gltf;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("gbuffer", "Ray-cast a glTF asset or a built-in scene into a G-buffer EXR (docs/gbuffer.md)");
  cmd->add_option("--scene", a->scene, "built-in scene (spheres)");
  a->gltf.add(cmd);
  cmd->add_option("--size", a->gltf.size, "WIDTHxHEIGHT (default 768x768 for spheres; 1280x720 or the camera's aspect at 720 rows)");
  cmd->add_option("--out", a->out, "output G-buffer .exr")->required();
  cmd->add_option("--device", a->device, "device index or name substring, or all, or a list such as 0,2 to shade row bands on several devices");
  cmd->callback([a, cmd] {
    checkOutput("--out", a->out, ".exr");
    checkDistinctFiles({{"--gltf", a->gltf.path, false}, {"--out", a->out, true}});
    if (!a->gltf.path.empty() && cmd->count("--scene")) throw Error("--scene and --gltf are alternatives; give one");
    RenderJob job = a->gltf.job();
    job.scene = a->scene;
    const PreparedRender prepared = prepareRender(job, FrameJob::GBuffer);
    std::optional<DeviceSet> devices;  // the built-in scene is ray-cast on a device
    writeGBuffer(a->out, tracePrepared(prepared, [&]() -> Runtime& { return devices.emplace(a->device).runtime(0); }));
  });
}

}  // namespace brdfcl::cli
