// renderJob and its pieces (brdfcl/render_job.hpp): the asset framing, lighting and frame render
// that `brdfcl render` and the Python module's render() share, so both give the same bits.
#include "brdfcl/render_job.hpp"

#include <fmt/format.h>

#include "brdfcl/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/gltf_frame.hpp"
#include "io/input_limits.hpp"

namespace brdfcl {

Scene builtinScene(const std::string& name) {
  if (name != "spheres") throw Error(fmt::format("unknown built-in scene '{}'; use spheres", name));
  return spheresScene();
}

void checkRenderSpp(int spp) {
  if (spp < 1 || spp > 1024) throw Error(fmt::format("--spp {} is out of range; use 1 to 1024", spp));
}

void checkRenderSize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error(fmt::format("--size '{}x{}' is not WIDTHxHEIGHT with sides 1 to 16384, e.g. 768x768", width, height));
}

FramedAsset loadFramedAsset(const std::string& path, const gltf::LoadOptions& options, const std::string& camera,
                            int width, int height) {
  detail::imagePixelOverride();  // a bad BRDFCL_MAX_IMAGE_PIXELS is refused before the file is read
  FramedAsset f{gltf::load(path, options), {}, width, height};
  if (width == 0) gltf::defaultSize(f.asset, camera, f.width, f.height);
  f.view = gltf::chooseView(f.asset, camera, f.width, f.height);
  return f;
}

Image renderFramedAsset(Runtime& rt, const FramedAsset& framed, const Scene& lighting, int spp,
                        const ShadeOptions& shadeOptions, const EvalOptions& model,
                        const std::function<void(int, int)>& progress, ShadeStats* stats) {
  const gltf::Raycaster raycaster(framed.asset);
  return renderFramedAsset(rt, framed, raycaster, lighting, spp, shadeOptions, model, progress, stats);
}

Image renderFramedAsset(Runtime& rt, const FramedAsset& framed, const gltf::Raycaster& raycaster, const Scene& lighting,
                        int spp, const ShadeOptions& shadeOptions, const EvalOptions& model,
                        const std::function<void(int, int)>& progress, ShadeStats* stats) {
  Shader shader(rt, lighting, model);
  return gltf::renderFrame(shader, raycaster, framed.view, framed.width, framed.height, spp, progress, shadeOptions,
                           stats);
}

Image renderFramedAsset(DeviceSet& devices, const FramedAsset& framed, const gltf::Raycaster& raycaster,
                        const Scene& lighting, int spp, const ShadeOptions& shadeOptions, const EvalOptions& model,
                        const std::function<void(int, int)>& progress, ShadeStats* stats) {
  Shader shader(devices, lighting, model);
  return gltf::renderFrame(shader, raycaster, framed.view, framed.width, framed.height, spp, progress, shadeOptions,
                           stats);
}

Image renderJob(Runtime& rt, const RenderJob& job) {
  const bool sizeGiven = job.width != 0 || job.height != 0;
  if (sizeGiven) checkRenderSize(job.width, job.height);
  checkRenderSpp(job.spp);
  checkIblSamples(job.shade.iblSamples);
  if (job.shade.ibl == IblMode::Exact && job.model.profile != Profile::Spec)
    throw Error("--ibl exact integrates the spec's BRDF only; an engine profile reproduces its engine's own "
                "image-based light, so use --ibl split-sum with --profile and --diff-against");
  const Environment environment = parseEnvironmentSpec(job.environment, job.envIntensity, job.envRotation);
  if (!job.gltf.empty()) {
    gltf::LoadOptions options;
    options.scene = job.gltfScene;
    options.variant = job.variant;
    options.strict = job.strict;
    options.allowOutsideUris = job.allowOutsideUris;
    const FramedAsset framed = loadFramedAsset(job.gltf, options, job.camera, job.width, job.height);
    if (job.warn)
      for (const auto& w : framed.asset.warnings) job.warn(w);
    const Scene lighting =
        gltf::frameLighting(framed.asset, framed.view, job.lights, environment, job.environmentGiven, job.allowOutsideUris);
    checkFrameFits(FrameJob::Render, framed.width, framed.height, usableHostMemory());
    return renderFramedAsset(rt, framed, lighting, job.spp, job.shade, job.model);
  }
  if (!job.camera.empty()) throw Error("--camera applies to glTF assets; add --gltf FILE");
  if (job.gltfScene != -1) throw Error("--gltf-scene applies to glTF assets; add --gltf FILE");
  if (!job.variant.empty()) throw Error("--variant applies to glTF assets; add --gltf FILE");
  if (job.strict) throw Error("--strict applies to glTF assets; add --gltf FILE");
  if (job.sppGiven)
    throw Error("--spp applies to glTF assets (the spheres are shaded at pixel centres); add --gltf FILE");
  const int w = sizeGiven ? job.width : 768, h = sizeGiven ? job.height : 768;
  Scene scene = builtinScene(job.scene);
  if (job.environmentGiven) scene.environment = environment;
  gltf::applyLightsOption(scene, job.lights, job.environmentGiven, job.allowOutsideUris);
  checkFrameFits(FrameJob::Render, w, h, usableHostMemory());
  const GBuffer g = renderSpheresGBuffer(rt, scene, w, h);
  Shader shader(rt, scene, job.model);
  return shader.shade(g, job.shade);
}

}  // namespace brdfcl
