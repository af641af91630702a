// What `brdfcl render` does between parsing its options and writing its files, as one library
// call: load and frame a glTF asset (or set up the built-in spheres), light it, ray-cast and
// shade it. The CLI and the Python module both render through these functions.
#pragma once
#include <functional>
#include <string>

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

// Ray-casts and shades a framed asset: spp stratified sub-pixel samples (gltf::renderFrame).
Image renderFramedAsset(Runtime& rt, const FramedAsset& framed, const Scene& lighting, int spp,
                        const ShadeOptions& shadeOptions = {}, const EvalOptions& model = {},
                        const std::function<void(int, int)>& progress = {}, ShadeStats* stats = nullptr);
// The same with the asset's Raycaster already built (the CLI traces a G-buffer with it too).
Image renderFramedAsset(Runtime& rt, const FramedAsset& framed, const gltf::Raycaster& raycaster, const Scene& lighting,
                        int spp, const ShadeOptions& shadeOptions = {}, const EvalOptions& model = {},
                        const std::function<void(int, int)>& progress = {}, ShadeStats* stats = nullptr);
// The same with the shading split across several devices (brdfcl/device_set.hpp).
Image renderFramedAsset(DeviceSet& devices, const FramedAsset& framed, const gltf::Raycaster& raycaster,
                        const Scene& lighting, int spp, const ShadeOptions& shadeOptions = {},
                        const EvalOptions& model = {}, const std::function<void(int, int)>& progress = {},
                        ShadeStats* stats = nullptr);

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
  ShadeOptions shade;                // IBL mode
  std::function<void(const std::string&)> warn;  // the asset's load warnings, one line each
};

// The linear radiance `brdfcl render --out x.exr` writes for the same options, after the same
// checks (spp and size ranges, options that apply to glTF assets only, --ibl exact with a
// profile, the frame's memory), with the CLI's messages.
Image renderJob(Runtime& rt, const RenderJob& job);

// The checks alone, before a device is opened (the CLI runs them first).
void checkRenderSpp(int spp);
void checkRenderSize(int width, int height);

}  // namespace brdfcl
