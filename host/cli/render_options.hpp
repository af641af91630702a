// The options and helpers that gbuffer, shade, render and demo share: output checks, the glTF
// asset's selection and framing, the image-based light, the lighting and profile choices, and
// the split of a frame's rows between the ranks under mpirun.
#pragma once
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "host/src/devices/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/gltf.hpp"
#include "host/src/model/profile_version.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/render_job.hpp"
#include "host/src/mpi/session.hpp"

namespace brdfcl::cli {

void parseSize(const std::string& s, int& w, int& h);
std::string lowerExtension(const std::string& path);
void checkExposure(float exposure);
// Every output named on the command line, checked before any work: extension and writability.
void checkOutput(const std::string& option, const std::string& path, const char* extension);
// stdout holds one file: two outputs there would interleave into neither.
void checkOneStdout(std::initializer_list<std::pair<const char*, const std::string*>> outputs);
void checkSpp(int spp);
void writeImages(const Image& img, const std::string& exr, const std::string& png, float exposure);

// Progress on stderr only when a person is watching it: "<what>: <unit> 3/12, 0:41 left".
std::function<void(int, int)> progressLine(const char* what, const char* unit);

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
  // A job with these choices and --size; the asset's warnings print as the CLI's. A glTF-only
  // option on the built-in scenes is refused by prepareRender.
  RenderJob job() const;
};

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
    checkIblSamplesApply(o.ibl, cmd->count("--ibl-samples") > 0);
    o.iblSamples = samples;
    o.progress = o.ibl == IblMode::Exact ? progressLine("brdfcl: exact IBL", "samples per pixel")
                                         : progressLine(what, "band");
    return o;
  }
};

// The options that choose light for render and demo.
struct LightingArgs {
  std::string environment = "builtin", lights = "gltf";
  float envIntensity = 1.0f, envRotation = 0.0f;

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
  // The job's environment and lights; the environment counts as given when any of its options is.
  void apply(CLI::App* cmd, RenderJob& job) const {
    job.environment = environment;
    job.envIntensity = envIntensity;
    job.envRotation = envRotation;
    job.environmentGiven = cmd->count("--environment") || cmd->count("--env-intensity") || cmd->count("--env-rotation");
    job.lights = lights;
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

// Shades under the chosen image-based light; exact mode reports its error estimate on stderr.
Image shadeWith(Shader& shader, const GBuffer& g, const ShadeOptions& o);
// The error estimate of an exact image-based light, one line on stderr.
void printExactSummary(const ShadeStats& stats);

// The rows of a frame `height` rows tall that each rank shades under mpirun, indexed by rank.
std::vector<mpi::Share> rowShares(int height, IblMode ibl);
// This rank's share of the shading.
ShadeOptions forRank(ShadeOptions o, const std::vector<mpi::Share>& shares);
bool myShareIsEmpty(const std::vector<mpi::Share>& shares);
// Rank 0 collects every rank's rows of `img` (a no-op in one process).
void gatherRows(Image& img, const std::vector<mpi::Share>& shares);
bool writesOutputs();
// "pthread-... CPU", or the devices of a list joined by " + ".
std::string deviceNames(DeviceSet& devices);

}  // namespace brdfcl::cli
