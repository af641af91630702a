// `brdfcl render`: a glTF asset or the built-in spheres ray-cast and shaded into linear EXR
// radiance and a tone-mapped PNG, or the difference of two profiles' renders (--diff-against).
// Under mpirun each rank shades a band of rows and rank 0 gathers them and writes the files.
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "host/src/parity/diff.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "host/src/io/output.hpp"
#include "render_options.hpp"

namespace brdfcl::cli {

namespace {
struct Args {
  std::string scene = "spheres", out, exr, gbuffer, device;
  float exposure = 0.0f;
  int spp = 4;
  GltfArgs gltf;
  LightingArgs lighting;
  IblArgs ibl;
  ProfileArgs profile;
  // Set by checkOutputs: the files --out stands for.
  std::string png, exrOut;
};

// Every output named, its extension and writability, and the options' ranges, before any work.
void checkOutputs(Args& a, bool diff) {
  a.png = a.out;
  a.exrOut = a.exr;
  if (diff && lowerExtension(a.out) != ".png" && !detail::isStreamTarget(a.out))
    throw Error(fmt::format("--out '{}': with --diff-against it is the difference picture, a .png; keep the render "
                            "with --exr FILE.exr",
                            a.out));
  if (diff) {
    // The picture is --out; --exr keeps the --profile render.
  } else if (lowerExtension(a.out) == ".exr" && !detail::isStreamTarget(a.out)) {
    if (!a.exrOut.empty()) throw Error("--out is already the EXR; drop --exr, or give --out FILE.png");
    a.exrOut = a.out;
    a.png.clear();
  } else if (lowerExtension(a.out) != ".png" && !detail::isStreamTarget(a.out)) {
    throw Error(fmt::format("--out '{}' must end in .png or .exr", a.out));
  }
  checkOneStdout({{"--out", &a.out}, {"--exr", &a.exr}, {"--gbuffer", &a.gbuffer}});
  checkOutput("--out", a.out, a.png.empty() ? ".exr" : ".png");
  checkOutput("--exr", a.exr, ".exr");
  checkOutput("--gbuffer", a.gbuffer, ".exr");
  checkDistinctFiles({{"--gltf", a.gltf.path, false},
                      {"--environment", a.lighting.environmentFile(), false},
                      {"--lights", a.lighting.lightsFile(), false},
                      {"--out", a.out, true},
                      {"--exr", a.exr, true},
                      {"--gbuffer", a.gbuffer, true}});
  checkExposure(a.exposure);
  checkSpp(a.spp);
}

// Under --diff-against: the --profile render to --exr, and the picture of the difference.
void writeOutputs(const Args& a, CLI::App* cmd, bool diff, const Image& img, const Image& other) {
  if (!diff) {
    writeImages(img, a.exrOut, a.png, a.exposure);
    a.profile.printEngines(cmd);
    return;
  }
  if (!a.exrOut.empty()) writeImages(img, a.exrOut, "", a.exposure);
  const std::string nameA = "--profile " + a.profile.profile, nameB = "--profile " + a.profile.against;
  const ImageDiff d = diffImages(img.rgb, other.rgb, img.width, img.height);
  writeImageDiffPng(a.out, d, defaultDiffRange(d.stats));
  std::fputs(formatImageDiff(d.stats, nameA, nameB).c_str(), detail::isStreamTarget(a.out) ? stderr : stdout);
  a.profile.printEngines(cmd);
}
}  // namespace

void addRenderCommand(CLI::App& app) {
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("render", "Render a glTF asset or a built-in scene (G-buffer + shading) to PNG (and EXR)");
  cmd->add_option("--scene", a->scene, "built-in scene (spheres)");
  a->gltf.add(cmd);
  cmd->add_option("--size", a->gltf.size, "WIDTHxHEIGHT (default 768x768 for spheres; 1280x720 or the camera's aspect at 720 rows)");
  cmd->add_option("--spp", a->spp, "stratified sub-pixel samples per pixel, glTF only (default 4)");
  a->lighting.add(cmd);
  a->ibl.add(cmd);
  a->profile.add(cmd, true);
  cmd->add_option("--exposure", a->exposure, "exposure in stops (default 0)");
  cmd->add_option("--out", a->out, "output tone-mapped .png, or linear radiance .exr (with --diff-against: the difference picture, .png)")->required();
  cmd->add_option("--exr", a->exr, "also the linear radiance as .exr");
  cmd->add_option("--gbuffer", a->gbuffer, "also the pixel-centre G-buffer as .exr");
  cmd->add_option("--device", a->device, "device index or name substring, or all, or a list such as 0,2 to shade row bands on several devices");
  cmd->callback([a, cmd] {
    mpi::Session& session = mpi::Session::get();
    const EvalOptions model = a->profile.options();
    const bool diff = cmd->count("--diff-against") > 0;
    const EvalOptions against = diff ? a->profile.againstOptions() : EvalOptions{};
    Image img, other;  // other: the --diff-against render
    std::vector<mpi::Share> shares;
    session.together([&] {
      checkOutputs(*a, diff);
      const ShadeOptions shade = a->ibl.check(cmd, "brdfcl render");
      checkExactIbl(shade, model, against);
      if (!a->gltf.path.empty() && cmd->count("--scene")) throw Error("--scene and --gltf are alternatives; give one");
      RenderJob job = a->gltf.job();
      job.model = model;
      job.shade = shade;
      job.scene = a->scene;
      job.spp = a->spp;
      job.sppGiven = cmd->count("--spp") > 0;
      a->lighting.apply(cmd, job);
      job.frameProgress = progressLine("brdfcl render", "sample");
      job.exactStats = printExactSummary;
      const PreparedRender prepared = prepareRender(job);
      shares = rowShares(prepared.height, job.shade.ibl);
      if (myShareIsEmpty(shares)) return;
      job.shade = forRank(job.shade, shares);
      DeviceSet devices(mpi::deviceSelector(a->device));
      // Rank 0 alone writes the G-buffer (every rank ray-casts the whole frame).
      const bool keepGBuffer = writesOutputs() && !a->gbuffer.empty();
      GBuffer g;
      img = renderPrepared(devices, prepared, job, keepGBuffer ? &g : nullptr);
      if (keepGBuffer) writeGBuffer(a->gbuffer, g);
      if (diff) {
        job.model = against;
        other = renderPrepared(devices, prepared, job);
      }
    });
    gatherRows(img, shares);
    if (diff) gatherRows(other, shares);
    session.together([&] {
      if (writesOutputs()) writeOutputs(*a, cmd, diff, img, other);
    });
  });
}

}  // namespace brdfcl::cli
