// What `brdfcl render`, `gbuffer` and `demo` do between parsing their options and writing their
// files, as library calls: check a job, load and frame a glTF asset (or set up the built-in
// spheres), light it, ray-cast and shade it. The CLI and the Python module both render through
// these functions.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "brdfcl/frame_budget.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/gltf_render.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/runtime.hpp"
#include "brdfcl/scene.hpp"

namespace brdfcl {

// The built-in scene called `name` ("spheres"); else "unknown built-in scene 'x'; use spheres".
Scene builtinScene(const std::string& name);

// A glTF asset with the view and image size a render uses.
struct FramedAsset {
  gltf::Asset asset;  // its load warnings in asset.warnings
  gltf::View view;
  int width = 0, height = 0;
};

// Loads `path` (gltf::load with `options`) and frames it: size width x height, or, when width is
// 0, gltf::defaultSize for the camera; the view is gltf::chooseView(camera) ("" = the scene's
// first camera node, else auto; "auto"; a glTF camera index).
FramedAsset loadFramedAsset(const std::string& path, const gltf::LoadOptions& options, const std::string& camera,
                            int width = 0, int height = 0);

// Everything one render takes; the defaults are `brdfcl render`'s.
struct RenderJob {
  std::string gltf;                  // asset path; "" renders the built-in `scene`
  std::string scene = "spheres";     // built-in scene
  int width = 0, height = 0;         // 0 x 0: the default (768x768 spheres; glTF: defaultSize)
  std::string camera;                // glTF only: as loadFramedAsset
  int gltfScene = -1;                // glTF only: scene index, -1 = the file's default
  std::string variant;               // glTF only: KHR_materials_variants name
  bool strict = false;               // glTF only: material typos are errors
  bool allowOutsideUris = false;     // the asset's URIs and a --lights scene's environment may leave their folders
  int spp = 4;                       // glTF only: sub-pixel samples, 1..1024
  bool sppGiven = false;             // the user chose spp: refused for the built-in scene
  // Lighting: the environment given as `brdfcl render --environment/--env-intensity/--env-rotation`
  // (environmentGiven says whether the user chose it) and --lights.
  std::string environment = "builtin";
  float envIntensity = 1.0f, envRotation = 0.0f;
  bool environmentGiven = false;
  std::string lights = "gltf";
  EvalOptions model;                 // profile (lobe All)
  ShadeOptions shade;                // IBL mode; firstRow and rowCount shade a band of rows
  std::function<void(const std::string&)> warn;  // the asset's load warnings, one line each
  std::function<void(int, int)> frameProgress;   // glTF only: sub-pixel samples done of spp
  std::function<void(const ShadeStats&)> exactStats;  // after each --ibl exact shade: its error estimate
};

// A RenderJob checked, with its glTF asset loaded and framed and its light chosen, before any
// device opens: its size tells the CLI how to split the rows between ranks.
struct PreparedRender {
  std::optional<FramedAsset> framed;  // the glTF asset; empty for the built-in scene
  Scene scene;                        // the asset's lighting, or the built-in scene with the job's light
  int width = 0, height = 0;
};

// renderJob's checks, loading and lighting, in its order and with its messages. `kind`
// FrameJob::GBuffer prepares a G-buffer alone: no lighting, and the G-buffer's memory budget.
PreparedRender prepareRender(const RenderJob& job, FrameJob kind = FrameJob::Render);

// The devices a render runs on: one Runtime (the Python module) or a DeviceSet (`--device 0,2`).
class RenderDevices {
 public:
  RenderDevices(Runtime& rt) : runtime_(&rt) {}              // NOLINT: implicit, so callers pass either
  RenderDevices(DeviceSet& devices) : devices_(&devices) {}  // NOLINT
  Runtime& first();
  std::unique_ptr<Shader> shader(const Scene& scene, const EvalOptions& model) const;

 private:
  Runtime* runtime_ = nullptr;
  DeviceSet* devices_ = nullptr;
};

// Ray-casts and shades `prepared` under job.model and job.shade; `gbuffer`, when not null,
// receives the pixel-centre G-buffer.
Image renderPrepared(RenderDevices devices, const PreparedRender& prepared, const RenderJob& job,
                     GBuffer* gbuffer = nullptr);

// The pixel-centre G-buffer of `prepared`: a glTF asset is ray-cast on the host, the built-in
// scene on the device `device` opens (called only then).
GBuffer tracePrepared(const PreparedRender& prepared, const std::function<Runtime&()>& device);

// The linear radiance `brdfcl render --out x.exr` writes for the same options, after the same
// checks (spp and size ranges, options that apply to glTF assets only, --ibl exact with a
// profile, the frame's memory), with the CLI's messages.
Image renderJob(Runtime& rt, const RenderJob& job);

// The checks alone, before a device is opened (the CLI runs them first).
void checkRenderSpp(int spp);
void checkRenderSize(int width, int height);
// --ibl exact with an engine profile as `model` or as the --diff-against `against`.
void checkExactIbl(const ShadeOptions& shade, const EvalOptions& model, const EvalOptions& against = {});

}  // namespace brdfcl
