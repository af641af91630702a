// `brdfcl gbuffer`, `brdfcl shade`, `brdfcl render` and `brdfcl demo`: G-buffers of the built-in
// spheres or of a glTF asset, deferred shading of any G-buffer under a scene's lights and
// environment, and both chained into linear EXR radiance and a tone-mapped PNG. Under mpirun,
// shade and render shade a band of rows per rank and rank 0 gathers them and writes the files.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "brdfcl/demo_asset.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/gltf_frame.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/image_diff.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/profile_version.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/render_job.hpp"
#include "commands.hpp"
#include "host/src/io/output.hpp"
#include "host/src/mpi/session.hpp"

namespace brdfcl::cli {

namespace {
void parseSize(const std::string& s, int& w, int& h) {
  int n = 0;
  if (std::sscanf(s.c_str(), "%dx%d%n", &w, &h, &n) != 2 || n != int(s.size()) || w < 1 || h < 1 || w > 16384 ||
      h > 16384)
    throw Error(fmt::format("--size '{}' is not WIDTHxHEIGHT with sides 1 to 16384, e.g. 768x768", s));
}

std::string lowerExtension(const std::string& path) {
  auto e = std::filesystem::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

void requireExtension(const std::string& option, const std::string& path, const char* extension) {
  if (!path.empty() && !detail::isStreamTarget(path) && lowerExtension(path) != extension)
    throw Error(fmt::format("{} '{}' must end in {}", option, path, extension));
}

void checkExposure(float exposure) {
  if (!std::isfinite(exposure)) throw Error(fmt::format("--exposure {} is not a finite number of stops; use e.g. 0 or -1.5", exposure));
}

// Every output named on the command line, checked before any work: extension and writability.
void checkOutput(const std::string& option, const std::string& path, const char* extension) {
  if (path.empty()) return;
  requireExtension(option, path, extension);
  checkOutputPath(option, path);
}

// stdout holds one file: two outputs there would interleave into neither.
void checkOneStdout(std::initializer_list<std::pair<const char*, const std::string*>> outputs) {
  std::vector<std::string> dashes;
  for (const auto& [option, path] : outputs)
    if (*path == "-") dashes.push_back(option);
  if (dashes.size() > 1)
    throw Error(fmt::format("{} all write to stdout ('-'); give at most one of them '-'", fmt::join(dashes, " and ")));
}

void checkSpp(int spp) { checkRenderSpp(spp); }

void writeImages(const Image& img, const std::string& exr, const std::string& png, float exposure) {
  if (!exr.empty()) writeExrRgb(exr, img.width, img.height, img.rgb);
  if (!png.empty()) writePng(png, img.width, img.height, img.rgb, exposure);
}

// What selects and frames a glTF asset; shared by gbuffer, render and demo.
struct GltfArgs {
  std::string path, camera, variant, size;
  int scene = -1;
  bool strict = false, allowOutsideUris = false;

  void add(CLI::App* cmd) {
    cmd->add_option("--gltf", path, "glTF asset (.gltf or .glb) instead of a built-in scene");
    cmd->add_flag("--allow-outside-uris", allowOutsideUris,
                  "let the asset's URIs (and a scene file's environment path) name files outside its folder: absolute "
                  "paths, '..' and links (docs/gltf.md)");
    cmd->add_flag("--strict", strict, "unknown keys and extensions in the glTF materials are errors, not warnings");
    cmd->add_option("--camera", camera, "glTF camera index, or auto (default: the scene's first camera node, else auto)");
    cmd->add_option("--gltf-scene", scene, "glTF scene index (default: the file's default scene)");
    cmd->add_option("--variant", variant, "KHR_materials_variants variant name");
  }
  // Options that only mean something for a glTF asset are refused for the built-in scenes.
  void checkBuiltin(CLI::App* cmd) const {
    for (const char* o : {"--camera", "--gltf-scene", "--variant", "--strict"})
      if (cmd->count(o)) throw Error(fmt::format("{} applies to glTF assets; add --gltf FILE", o));
  }
};

using LoadedAsset = FramedAsset;

// The asset framed as the library frames it for renderJob (brdfcl/render_job.hpp).
LoadedAsset loadAsset(const GltfArgs& a) {
  gltf::LoadOptions options;
  options.scene = a.scene;
  options.variant = a.variant;
  options.strict = a.strict;
  options.allowOutsideUris = a.allowOutsideUris;
  int w = 0, h = 0;
  if (!a.size.empty()) parseSize(a.size, w, h);
  LoadedAsset l = loadFramedAsset(a.path, options, a.camera, w, h);
  for (const auto& warning : l.asset.warnings) printWarning(warning);
  return l;
}

// Progress on stderr only when a person is watching it: "<what>: <unit> 3/12, 0:41 left". A
// single step has nothing to report.
std::function<void(int, int)> progressLine(const char* what, const char* unit) {
  if (!isatty(STDERR_FILENO)) return {};
  const auto start = std::chrono::steady_clock::now();
  return [what, unit, start](int done, int total) {
    if (total < 2) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const int left = int(std::lround(elapsed / done * (total - done)));
    std::fprintf(stderr, "\r%s: %s %d/%d, %d:%02d left ", what, unit, done, total, left / 60, left % 60);
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

// --ibl and --ibl-samples of shade and render, checked before any work.
struct IblArgs {
  std::string mode = "split-sum";
  int samples = 1024;

  void add(CLI::App* cmd) {
    cmd->add_option("--ibl", mode, "image-based light: split-sum (prefiltered, the default) or exact (Monte Carlo ground truth)");
    cmd->add_option("--ibl-samples", samples, "exact: samples per pixel, 1 to 65536 (default 1024)");
  }
  // `what` names the command in the progress line ("brdfcl shade").
  ShadeOptions check(CLI::App* cmd, const char* what) const {
    ShadeOptions o;
    o.ibl = parseIblMode(mode);
    checkIblSamples(samples);
    if (o.ibl != IblMode::Exact && cmd->count("--ibl-samples")) throw Error("--ibl-samples applies to --ibl exact; add --ibl exact");
    o.iblSamples = samples;
    o.progress = o.ibl == IblMode::Exact ? progressLine("brdfcl: exact IBL", "samples per pixel")
                                         : progressLine(what, "band");
    return o;
  }
};

// Shades under the chosen image-based light; exact mode reports its error estimate on stderr.
Image shadeWith(Shader& shader, const GBuffer& g, const ShadeOptions& o) {
  ShadeStats stats;
  Image img = shader.shade(g, o, &stats);
  if (o.ibl == IblMode::Exact) std::fprintf(stderr, "%s\n", exactIblSummary(stats).c_str());
  return img;
}

// The options that choose light for render and demo.
struct LightingArgs {
  std::string environment = "builtin", lights = "gltf";
  float envIntensity = 1.0f, envRotation = 0.0f;
  bool environmentGiven = false;

  void add(CLI::App* cmd) {
    cmd->add_option("--environment", environment, "builtin|sky|studio|uniform|FILE.hdr|FILE.exr (default: the sky with --gltf, studio for the spheres; builtin is the sky)");
    cmd->add_option("--env-intensity", envIntensity, "environment radiance scale (default 1)");
    cmd->add_option("--env-rotation", envRotation, "environment rotation about +Y in radians (default 0)");
    cmd->add_option("--lights", lights, "gltf (the scene's own lights: a file's KHR lights, else a default key light; the spheres' key and fill), none, or SCENE.json");
  }
  // The files among the choices ("" for the built-in ones), for checkDistinctFiles.
  std::string environmentFile() const {
    for (const char* builtin : {"builtin", "sky", "studio", "uniform"})
      if (environment == builtin) return "";
    return environment;
  }
  std::string lightsFile() const { return lights == "gltf" || lights == "none" ? "" : lights; }
  Environment environmentChoice(CLI::App* cmd) {
    environmentGiven = cmd->count("--environment") || cmd->count("--env-intensity") || cmd->count("--env-rotation");
    return parseEnvironmentSpec(environment, envIntensity, envRotation);
  }
};

// --profile and --diff-against of render (shade takes --profile only).
struct ProfileArgs {
  std::string profile = "spec", against;

  void add(CLI::App* cmd, bool diff) {
    cmd->add_option("--profile", profile,
                    "spec|khronos|threejs|filament|babylon|materialx: whose BRDF and image-based light (default spec; "
                    "docs/profiles.md)");
    if (diff)
      cmd->add_option("--diff-against", against,
                      "also render under this profile; --out is then the picture of the relative luminance difference "
                      "(profile - this) / this, and the statistics are printed");
  }
  EvalOptions options() const {
    EvalOptions o;
    o.profile = parseProfile(profile);
    return o;
  }
  EvalOptions againstOptions() const {
    EvalOptions o;
    o.profile = parseProfile(against, "--diff-against");
    return o;
  }
  // After the outputs are written (an error stays the only line of a failed run): the engine and
  // commits each named profile reproduces, since engines change their maths between commits.
  void printEngines(CLI::App* cmd) const {
    if (cmd->count("--profile"))
      std::fprintf(stderr, "brdfcl: profile %s\n", describeProfile(parseProfile(profile)).c_str());
    const CLI::Option* diff = cmd->get_option_no_throw("--diff-against");  // shade has none
    if (diff != nullptr && diff->count() > 0)
      std::fprintf(stderr, "brdfcl: profile %s\n", describeProfile(parseProfile(against, "--diff-against")).c_str());
  }
};

// The rows of a frame `height` rows tall that each rank shades under mpirun, indexed by rank:
// contiguous bands in rank order, or every row on rank 0 for the exact image-based light, which
// integrates the whole frame at once.
std::vector<mpi::Share> rowShares(int height, IblMode ibl) {
  const mpi::Session& s = mpi::Session::get();
  std::vector<mpi::Share> shares(static_cast<std::size_t>(s.size()));
  for (int r = 0; r < s.size(); ++r)
    shares[std::size_t(r)] = ibl == IblMode::Exact ? (r == 0 ? mpi::Share{0, std::uint64_t(height)} : mpi::Share{})
                                                   : mpi::shareOf(std::uint64_t(height), r, s.size());
  return shares;
}

// This rank's share of the shading.
ShadeOptions forRank(ShadeOptions o, const std::vector<mpi::Share>& shares) {
  const mpi::Session& s = mpi::Session::get();
  if (s.parallel() && o.ibl != IblMode::Exact) {
    o.firstRow = int(shares[std::size_t(s.rank())].begin);
    o.rowCount = int(shares[std::size_t(s.rank())].count());
  }
  return o;
}

bool myShareIsEmpty(const std::vector<mpi::Share>& shares) {
  return shares[std::size_t(mpi::Session::get().rank())].count() == 0;
}

// Rank 0 collects every rank's rows of `img` (a no-op in one process).
void gatherRows(Image& img, const std::vector<mpi::Share>& shares) {
  mpi::Session::get().gatherShares(img.rgb, shares, 3 * std::size_t(img.width));
}

bool writesOutputs() { return mpi::Session::get().rank() == 0; }

// "pthread-... CPU", or the devices of a list joined by " + ".
std::string deviceNames(DeviceSet& devices) {
  std::string names;
  for (std::size_t k = 0; k < devices.size(); ++k) names += (k ? " + " : "") + devices.runtime(k).info().name;
  return names;
}

Image renderGltf(DeviceSet& devices, const LoadedAsset& l, const Scene& lighting, int spp, const std::string& gbufferOut,
                 const ShadeOptions& shadeOptions = {}, const EvalOptions& model = {}) {
  const gltf::Raycaster raycaster(l.asset);
  ShadeStats stats;
  const Image img = renderFramedAsset(devices, l, raycaster, lighting, spp, shadeOptions, model, progressLine("brdfcl render", "sample"), &stats);
  if (shadeOptions.ibl == IblMode::Exact) std::fprintf(stderr, "%s\n", exactIblSummary(stats).c_str());
  if (!gbufferOut.empty()) writeGBuffer(gbufferOut, raycaster.trace(l.view, l.width, l.height));
  return img;
}
}  // namespace

void addRenderCommands(CLI::App& app) {
  {
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
      if (!a->gltf.path.empty()) {
        if (cmd->count("--scene")) throw Error("--scene and --gltf are alternatives; give one");
        const LoadedAsset l = loadAsset(a->gltf);
        checkFrameFits(FrameJob::GBuffer, l.width, l.height, usableHostMemory());
        gltf::Raycaster raycaster(l.asset);
        writeGBuffer(a->out, raycaster.trace(l.view, l.width, l.height));
        return;
      }
      a->gltf.checkBuiltin(cmd);
      int w = 768, h = 768;
      if (!a->gltf.size.empty()) parseSize(a->gltf.size, w, h);
      const Scene scene = builtinScene(a->scene);
      checkFrameFits(FrameJob::GBuffer, w, h, usableHostMemory());
      DeviceSet devices(a->device);
      writeGBuffer(a->out, renderSpheresGBuffer(devices.runtime(0), scene, w, h));
    });
  }
  {
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
  {
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
  {
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
      if (!a->size.empty()) {
        int w = 0, h = 0;
        parseSize(a->size, w, h);
      }
      std::error_code ec;
      if (std::filesystem::exists("out", ec) && !std::filesystem::is_directory("out", ec))
        throw Error("cannot write the demo into 'out': it exists and is not a directory; move it or run elsewhere");
      std::filesystem::create_directories("out", ec);
      if (ec) throw Error(fmt::format("cannot create the demo directory 'out': {}", ec.message()));
      const std::string glb = "out/demo.glb", png = "out/demo.png", exr = "out/demo.exr";
      for (const auto& p : {glb, png, exr}) checkOutputPath("demo", p);
      gltf::writeDemoAsset(glb);
      GltfArgs args;
      args.path = glb;
      args.size = a->size;
      const LoadedAsset l = loadAsset(args);
      Environment studio;
      studio.builtinKind = "studio";
      const Scene lighting = gltf::frameLighting(l.asset, l.view, "gltf", studio, true);
      checkFrameFits(FrameJob::Render, l.width, l.height, usableHostMemory());
      DeviceSet devices(a->device);
      writeImages(renderGltf(devices, l, lighting, a->spp, ""), exr, png, a->exposure);
      auto abs = [](const std::string& p) { return std::filesystem::absolute(p).string(); };
      fmt::print("brdfcl demo: wrote the sphere sweep as a glTF asset and rendered it on {}\n  {}\n  {}\n  {}\n"
                 "Rows: white sheen and coloured sheen over a woven texture (sheen roughness 0.05 to 1), clearcoat over\n"
                 "a flake normal map (roughness 0 to 1), brushed anisotropy strength 0 to 1, anisotropy rotation 0 to pi,\n"
                 "gold metal/dielectric roughness 0 to 1. Studio environment, the file's key and fill lights.\n",
                 deviceNames(devices), abs(glb), abs(png), abs(exr));
    });
  }
}

}  // namespace brdfcl::cli
