// `brdfcl shade`: deferred shading of any G-buffer under a scene's lights and environment. Under
// mpirun each rank shades a band of rows and rank 0 gathers them and writes the files.
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "host/src/io/output.hpp"
#include "render_options.hpp"

namespace brdfcl::cli {

void addShadeCommand(CLI::App& app) {
  struct Args {
    std::string gbuffer, scene, out, png, exr, device;
    float exposure = 0.0f;
    bool noCheck = false, allowOutsideUris = false;
    IblArgs ibl;
    ProfileArgs profile;
  };
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("shade", "Shade a G-buffer EXR under a scene's lights and environment");
  cmd->add_option("--gbuffer", a->gbuffer, "G-buffer .exr (docs/gbuffer.md)")->required();
  cmd->add_option("--scene", a->scene, "scene JSON (docs/gbuffer.md); without \"camera\", the G-buffer's camera")->required();
  cmd->add_option("--out", a->out, "linear radiance .exr, or a tone-mapped sRGB .png")->required();
  cmd->add_option("--png", a->png, "also a tone-mapped sRGB PNG");
  cmd->add_option("--exr", a->exr, "also the linear radiance as .exr");
  cmd->add_option("--exposure", a->exposure, "exposure in stops for the PNG (default 0)");
  cmd->add_option("--device", a->device, "device index or name substring, or all, or a list such as 0,2 to shade row bands on several devices");
  cmd->add_flag("--no-check", a->noCheck, "skip the G-buffer's range checks (factors in [0, 1], unit normals)");
  cmd->add_flag("--allow-outside-uris", a->allowOutsideUris,
                "let the scene's environment path name a file outside the scene file's folder (docs/gltf.md)");
  a->ibl.add(cmd);
  a->profile.add(cmd, false);
  cmd->callback([a, cmd] {
    mpi::Session& session = mpi::Session::get();
    std::string exr = a->exr, png = a->png;
    Image img;
    std::vector<mpi::Share> shares;
    session.together([&] {
      if (lowerExtension(a->out) == ".png" && !detail::isStreamTarget(a->out)) {
        if (!png.empty()) throw Error("--out is already the PNG; drop --png, or give --out FILE.exr");
        png = a->out;
      } else {
        if (lowerExtension(a->out) != ".exr" && !detail::isStreamTarget(a->out))
          throw Error(fmt::format("--out '{}' must end in .exr or .png", a->out));
        if (!exr.empty()) throw Error("--out is already the EXR; drop --exr, or give --out FILE.png");
        exr = a->out;
      }
      checkOneStdout({{"--out", &a->out}, {"--png", &a->png}, {"--exr", &a->exr}});
      checkOutput("--out", a->out, png == a->out ? ".png" : ".exr");
      checkOutput("--png", a->png, ".png");
      checkOutput("--exr", a->exr, ".exr");
      checkDistinctFiles({{"--gbuffer", a->gbuffer, false},
                          {"--scene", a->scene, false},
                          {"--out", a->out, true},
                          {"--png", a->png, true},
                          {"--exr", a->exr, true}});
      checkExposure(a->exposure);
      const ShadeOptions shadeOptions = a->ibl.check(cmd, "brdfcl shade");
      const EvalOptions model = a->profile.options();
      if (shadeOptions.ibl == IblMode::Exact && model.profile != Profile::Spec)
        throw Error("--ibl exact integrates the spec's BRDF only; --profile " + a->profile.profile +
                    " reproduces its engine's own image-based light, so use --ibl split-sum with it");
      GBufferReadOptions readOptions;
      readOptions.check = !a->noCheck;
      // readGBuffer checks the frame budget from the EXR header, before decoding.
      const GBuffer g = readGBuffer(a->gbuffer, readOptions);
      const Scene scene = readScene(a->scene, a->allowOutsideUris);
      if (const std::string w = shadeCameraWarning(a->scene, scene, a->gbuffer, g); !w.empty())
        printWarning(w);
      shares = rowShares(g.height, shadeOptions.ibl);
      if (myShareIsEmpty(shares)) return;
      DeviceSet devices(mpi::deviceSelector(a->device));
      Shader shader(devices, scene, model);
      img = shadeWith(shader, g, forRank(shadeOptions, shares));
    });
    gatherRows(img, shares);
    session.together([&] {
      if (!writesOutputs()) return;
      writeImages(img, exr, png, a->exposure);
      a->profile.printEngines(cmd);
    });
  });
}

}  // namespace brdfcl::cli
