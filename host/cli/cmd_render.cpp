// `brdfcl gbuffer`, `brdfcl shade`, `brdfcl render` and `brdfcl demo`: the built-in spheres
// G-buffer, deferred shading of any G-buffer under a scene's lights and environment, and both
// chained into linear EXR radiance and a tone-mapped PNG.
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/render.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

namespace {
void parseSize(const std::string& s, int& w, int& h) {
  int n = 0;
  if (std::sscanf(s.c_str(), "%dx%d%n", &w, &h, &n) != 2 || n != int(s.size()) || w < 1 || h < 1 || w > 16384 ||
      h > 16384)
    throw Error(fmt::format("--size '{}' is not WIDTHxHEIGHT with sides 1 to 16384, e.g. 768x768", s));
}

Scene builtinScene(const std::string& name) {
  if (name != "spheres") throw Error(fmt::format("unknown built-in scene '{}'; use spheres", name));
  return spheresScene();
}

void renderAndWrite(Runtime& rt, const Scene& scene, const GBuffer& g, const std::string& exr, const std::string& png,
                    float exposure) {
  Shader shader(rt, scene);
  const Image img = shader.shade(g);
  if (!exr.empty()) writeExrRgb(exr, img.width, img.height, img.rgb);
  if (!png.empty()) writePng(png, img.width, img.height, img.rgb, exposure);
}

std::string lowerExtension(const std::string& path) {
  auto e = std::filesystem::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}
}  // namespace

void addRenderCommands(CLI::App& app) {
  {
    struct Args {
      std::string scene = "spheres", size = "768x768", out, device;
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("gbuffer", "Ray-cast a built-in scene into a G-buffer EXR (docs/gbuffer.md)");
    cmd->add_option("--scene", a->scene, "built-in scene (spheres)");
    cmd->add_option("--size", a->size, "WIDTHxHEIGHT (default 768x768)");
    cmd->add_option("--out", a->out, "output G-buffer .exr")->required();
    cmd->add_option("--device", a->device, "device index or name substring");
    cmd->callback([a] {
      int w, h;
      parseSize(a->size, w, h);
      if (lowerExtension(a->out) != ".exr") throw Error(fmt::format("--out '{}' must end in .exr", a->out));
      const Scene scene = builtinScene(a->scene);
      Runtime rt(a->device);
      writeGBuffer(a->out, renderSpheresGBuffer(rt, scene, w, h));
    });
  }
  {
    struct Args {
      std::string gbuffer, scene, out, png, device;
      float exposure = 0.0f;
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("shade", "Shade a G-buffer EXR under a scene's lights and environment");
    cmd->add_option("--gbuffer", a->gbuffer, "G-buffer .exr (docs/gbuffer.md)")->required();
    cmd->add_option("--scene", a->scene, "scene JSON (docs/gbuffer.md)")->required();
    cmd->add_option("--out", a->out, "linear radiance .exr")->required();
    cmd->add_option("--png", a->png, "also a tone-mapped sRGB PNG");
    cmd->add_option("--exposure", a->exposure, "exposure in stops for the PNG (default 0)");
    cmd->add_option("--device", a->device, "device index or name substring");
    cmd->callback([a] {
      if (lowerExtension(a->out) != ".exr") throw Error(fmt::format("--out '{}' must end in .exr", a->out));
      if (!a->png.empty() && lowerExtension(a->png) != ".png") throw Error(fmt::format("--png '{}' must end in .png", a->png));
      const GBuffer g = readGBuffer(a->gbuffer);
      const Scene scene = readScene(a->scene);
      Runtime rt(a->device);
      renderAndWrite(rt, scene, g, a->out, a->png, a->exposure);
    });
  }
  auto addRender = [&](const char* name, const char* help, bool demo) {
    struct Args {
      std::string scene = "spheres", size = "768x768", out, exr, device;
      float exposure = 0.0f;
    };
    auto a = std::make_shared<Args>();
    if (demo) a->out = "out/demo.png", a->exr = "out/demo.exr";
    auto* cmd = app.add_subcommand(name, help);
    if (!demo) {
      cmd->add_option("--scene", a->scene, "built-in scene (spheres)");
      cmd->add_option("--out", a->out, "output .png")->required();
      cmd->add_option("--exr", a->exr, "also the linear radiance as .exr");
    }
    cmd->add_option("--size", a->size, "WIDTHxHEIGHT (default 768x768)");
    cmd->add_option("--exposure", a->exposure, "exposure in stops (default 0)");
    cmd->add_option("--device", a->device, "device index or name substring");
    cmd->callback([a, demo] {
      int w, h;
      parseSize(a->size, w, h);
      if (lowerExtension(a->out) != ".png") throw Error(fmt::format("--out '{}' must end in .png", a->out));
      if (!a->exr.empty() && lowerExtension(a->exr) != ".exr") throw Error(fmt::format("--exr '{}' must end in .exr", a->exr));
      const Scene scene = builtinScene(a->scene);
      if (demo) std::filesystem::create_directories("out");
      Runtime rt(a->device);
      renderAndWrite(rt, scene, renderSpheresGBuffer(rt, scene, w, h), a->exr, a->out, a->exposure);
      if (demo)
        fmt::print("brdfcl demo: rendered the built-in spheres scene on {}\n  {}\n  {}\n"
                   "Rows: white sheen and coloured sheen (sheen roughness 0.05 to 1), clearcoat (roughness 0 to 1)\n"
                   "over a rough base, anisotropy strength 0 to 1, anisotropy rotation 0 to pi, gold metal/dielectric\n"
                   "roughness 0 to 1. Studio environment, a key and a fill light.\n",
                   rt.info().name, std::filesystem::absolute(a->out).string(), std::filesystem::absolute(a->exr).string());
    });
  };
  addRender("render", "Render a built-in scene (G-buffer + shading) to PNG (and EXR)", false);
  addRender("demo", "Render the built-in spheres scene to out/demo.png and out/demo.exr", true);
}

}  // namespace brdfcl::cli
