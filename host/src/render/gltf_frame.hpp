// A glTF frame: the lighting a render uses (the file's KHR_lights_punctual lights, none, a scene
// file's, or the default key light) and the multi-sample render that traces one G-buffer per
// stratified sub-pixel offset, shades each and box-filters them into the pixel.
#pragma once
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "brdfcl/gltf_render.hpp"
#include "brdfcl/render.hpp"

namespace brdfcl::gltf {

// The light used when a file has no KHR_lights_punctual light: white, 3 lux, directional,
// arriving from above the camera, a little to its left and from behind it: it travels along
// normalize(0.5 right - up + 0.6 forward) of the view.
Light defaultKeyLight(const View& view);

// `--lights` applied to a scene that has its own lights: "gltf" keeps them, "none" removes them,
// anything else is a scene JSON (docs/gbuffer.md) whose lights replace them and whose environment
// replaces the scene's unless the user gave --environment (`environmentGiven`). allowOutside is
// readScene's (--allow-outside-uris).
void applyLightsOption(Scene& scene, const std::string& lights, bool environmentGiven, bool allowOutside = false);

// The lighting of a glTF render: the file's KHR_lights_punctual lights (a file with none gets
// defaultKeyLight) and `environment`, then applyLightsOption.
Scene frameLighting(const Asset& asset, const View& view, const std::string& lights, const Environment& environment,
                    bool environmentGiven, bool allowOutside = false);

// The sub-pixel offsets of `spp` samples, in [0, 1)^2, the same for every pixel: one sample in
// each cell of a c x r grid (c = ceil(sqrt(spp)), r = ceil(spp / c)), placed in its cell by the
// R2 low-discrepancy sequence. spp = 1 is the pixel centre (0.5, 0.5).
std::vector<std::array<float, 2>> subpixelOffsets(int spp);

// Traces and shades spp G-buffers and averages them (box filter). progress(done, spp) is called
// after each sample when set. Under shadeOptions.ibl == Exact each sub-pixel sample integrates
// ceil(iblSamples / spp) samples with its own seed, and `stats` (when given) receives the
// image's estimate: the samples' total and the frames' mean relative error over sqrt(spp).
brdfcl::Image renderFrame(Shader& shader, const Raycaster& raycaster, const View& view, int width, int height, int spp,
                  const std::function<void(int, int)>& progress = {}, const ShadeOptions& shadeOptions = {},
                  ShadeStats* stats = nullptr);

}  // namespace brdfcl::gltf
