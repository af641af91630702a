// `brdfcl render`: a glTF asset or the built-in spheres ray-cast and shaded into linear EXR
// radiance and a tone-mapped PNG, or the difference of two profiles' renders (--diff-against).
// Under mpirun each rank shades a band of rows and rank 0 gathers them and writes the files.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "brdfcl/demo_asset.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/gltf_frame.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/image_diff.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "host/src/io/output.hpp"
#include "render_options.hpp"

namespace brdfcl::cli {

void addRenderCommand(CLI::App& app) {
  struct Args {
    std::string scene = "spheres", out, exr, gbuffer, device;
    float exposure = 0.0f;
    int spp = 4;
    GltfArgs gltf;
    LightingArgs lighting;
    IblArgs ibl;
    ProfileArgs profile;
  };
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
    std::string png = a->out, exr = a->exr;
    Image img, other;  // other: the --diff-against render
    std::vector<mpi::Share> shares;
    session.together([&] {
      if (diff && lowerExtension(a->out) != ".png" && !detail::isStreamTarget(a->out))
        throw Error(fmt::format("--out '{}': with --diff-against it is the difference picture, a .png; keep the render "
                                "with --exr FILE.exr",
                                a->out));
      if (diff) {
        // The picture is --out; --exr keeps the --profile render.
      } else if (lowerExtension(a->out) == ".exr" && !detail::isStreamTarget(a->out)) {
        if (!exr.empty()) throw Error("--out is already the EXR; drop --exr, or give --out FILE.png");
        exr = a->out;
        png.clear();
      } else if (lowerExtension(a->out) != ".png" && !detail::isStreamTarget(a->out)) {
        throw Error(fmt::format("--out '{}' must end in .png or .exr", a->out));
      }
      checkOneStdout({{"--out", &a->out}, {"--exr", &a->exr}, {"--gbuffer", &a->gbuffer}});
      checkOutput("--out", a->out, png.empty() ? ".exr" : ".png");
      checkOutput("--exr", a->exr, ".exr");
      checkOutput("--gbuffer", a->gbuffer, ".exr");
      checkDistinctFiles({{"--gltf", a->gltf.path, false},
                          {"--environment", a->lighting.environmentFile(), false},
                          {"--lights", a->lighting.lightsFile(), false},
                          {"--out", a->out, true},
                          {"--exr", a->exr, true},
                          {"--gbuffer", a->gbuffer, true}});
      checkExposure(a->exposure);
      checkSpp(a->spp);
      const ShadeOptions shadeOptions = a->ibl.check(cmd, "brdfcl render");
      if (shadeOptions.ibl == IblMode::Exact && (model.profile != Profile::Spec || against.profile != Profile::Spec))
        throw Error("--ibl exact integrates the spec's BRDF only; an engine profile reproduces its engine's own "
                    "image-based light, so use --ibl split-sum with --profile and --diff-against");
      const Environment environment = a->lighting.environmentChoice(cmd);
      // Rank 0 alone writes the G-buffer (every rank ray-casts the whole frame).
      const std::string gbufferOut = writesOutputs() ? a->gbuffer : "";
      if (!a->gltf.path.empty()) {
        if (cmd->count("--scene")) throw Error("--scene and --gltf are alternatives; give one");
        const LoadedAsset l = loadAsset(a->gltf);
        const Scene lighting =
            gltf::frameLighting(l.asset, l.view, a->lighting.lights, environment, a->lighting.environmentGiven,
                                a->gltf.allowOutsideUris);
        checkFrameFits(FrameJob::Render, l.width, l.height, usableHostMemory());
        shares = rowShares(l.height, shadeOptions.ibl);
        if (myShareIsEmpty(shares)) return;
        const ShadeOptions mine = forRank(shadeOptions, shares);
        DeviceSet devices(mpi::deviceSelector(a->device));
        img = renderGltf(devices, l, lighting, a->spp, gbufferOut, mine, model);
        if (diff) other = renderGltf(devices, l, lighting, a->spp, "", mine, against);
        return;
      }
      a->gltf.checkBuiltin(cmd);
      if (cmd->count("--spp")) throw Error("--spp applies to glTF assets (the spheres are shaded at pixel centres); add --gltf FILE");
      int w = 768, h = 768;
      if (!a->gltf.size.empty()) parseSize(a->gltf.size, w, h);
      Scene scene = builtinScene(a->scene);
      if (a->lighting.environmentGiven) scene.environment = environment;
      gltf::applyLightsOption(scene, a->lighting.lights, a->lighting.environmentGiven, a->gltf.allowOutsideUris);
      checkFrameFits(FrameJob::Render, w, h, usableHostMemory());
      shares = rowShares(h, shadeOptions.ibl);
      if (myShareIsEmpty(shares)) return;
      const ShadeOptions mine = forRank(shadeOptions, shares);
      DeviceSet devices(mpi::deviceSelector(a->device));
      const GBuffer g = renderSpheresGBuffer(devices.runtime(0), scene, w, h);
      if (!gbufferOut.empty()) writeGBuffer(gbufferOut, g);
      Shader shader(devices, scene, model);
      img = shadeWith(shader, g, mine);
      if (diff) {
        Shader againstShader(devices, scene, against);
        other = shadeWith(againstShader, g, mine);
      }
    });
    gatherRows(img, shares);
    if (diff) gatherRows(other, shares);
    // Under --diff-against: the --profile render to --exr, and the picture of the difference.
    session.together([&] {
      if (!writesOutputs()) return;
      if (!diff) {
        writeImages(img, exr, png, a->exposure);
        a->profile.printEngines(cmd);
        return;
      }
      if (!exr.empty()) writeImages(img, exr, "", a->exposure);
      const std::string nameA = "--profile " + a->profile.profile, nameB = "--profile " + a->profile.against;
      const ImageDiff d = diffImages(img.rgb, other.rgb, img.width, img.height);
      writeImageDiffPng(a->out, d, nameA, nameB, defaultDiffRange(d.stats));
      std::fputs(formatImageDiff(d.stats, nameA, nameB).c_str(), detail::isStreamTarget(a->out) ? stderr : stdout);
      a->profile.printEngines(cmd);
    });
  });
}

}  // namespace brdfcl::cli
