// renderJob and its pieces (brdfcl/render_job.hpp): the checks, asset framing, lighting and frame
// render that `brdfcl render`, `gbuffer`, `demo` and the Python module's render() share, so all
// give the same bits.
#include "brdfcl/render_job.hpp"

#include <fmt/format.h>

#include "devices/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "render/gltf_frame.hpp"
#include "io/input_limits.hpp"
#include "io/option_style.hpp"

namespace brdfcl {

Scene builtinScene(const std::string& name) {
  if (name != "spheres") throw Error(fmt::format("unknown built-in scene '{}'; use spheres", name));
  return spheresScene();
}

void checkRenderSpp(int spp) {
  if (spp < 1 || spp > 1024)
    throw Error(fmt::format("{} is out of range; use 1 to 1024", optionWithValue("--spp", std::to_string(spp))));
}

void checkRenderSize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error(fmt::format("{} is not WIDTHxHEIGHT with sides 1 to 16384, e.g. 768x768",
                            optionWithValue("--size", fmt::format("'{}x{}'", width, height))));
}

FramedAsset loadFramedAsset(const std::string& path, const gltf::LoadOptions& options, const std::string& camera,
                            int width, int height) {
  detail::imagePixelOverride();  // a bad BRDFCL_MAX_IMAGE_PIXELS is refused before the file is read
  FramedAsset f{gltf::load(path, options), {}, width, height};
  if (width == 0) gltf::defaultSize(f.asset, camera, f.width, f.height);
  f.view = gltf::chooseView(f.asset, camera, f.width, f.height);
  return f;
}

void checkExactIbl(const ShadeOptions& shade, const EvalOptions& model, const EvalOptions& against) {
  if (shade.ibl == IblMode::Exact && (model.profile != Profile::Spec || against.profile != Profile::Spec))
    throw Error(fmt::format("{} integrates the spec's BRDF only; an engine profile reproduces its engine's own "
                            "image-based light, so use {} with {}",
                            optionWithValue("--ibl", "exact", true), optionWithValue("--ibl", "split-sum", true),
                            optionStyle() == OptionStyle::Cli ? "--profile and --diff-against" : "profile="));
}

PreparedRender prepareRender(const RenderJob& job, FrameJob kind) {
  const bool sizeGiven = job.width != 0 || job.height != 0;
  if (sizeGiven) checkRenderSize(job.width, job.height);
  checkRenderSpp(job.spp);
  checkIblSamples(job.shade.iblSamples);
  checkExactIbl(job.shade, job.model);
  const Environment environment = parseEnvironmentSpec(job.environment, job.envIntensity, job.envRotation);
  const bool lit = kind != FrameJob::GBuffer;
  PreparedRender p;
  if (!job.gltf.empty()) {
    gltf::LoadOptions options;
    options.scene = job.gltfScene;
    options.variant = job.variant;
    options.strict = job.strict;
    options.allowOutsideUris = job.allowOutsideUris;
    p.framed = loadFramedAsset(job.gltf, options, job.camera, job.width, job.height);
    if (job.warn)
      for (const auto& w : p.framed->asset.warnings) job.warn(w);
    if (lit)
      p.scene = gltf::frameLighting(p.framed->asset, p.framed->view, job.lights, environment, job.environmentGiven,
                                    job.allowOutsideUris);
    p.width = p.framed->width;
    p.height = p.framed->height;
  } else {
    const auto gltfOnly = [](const char* option) {
      return Error(optionName(option) + " applies to glTF assets; add " + optionWithValue("--gltf", "FILE"));
    };
    if (!job.camera.empty()) throw gltfOnly("--camera");
    if (job.gltfScene != -1) throw gltfOnly("--gltf-scene");
    if (!job.variant.empty()) throw gltfOnly("--variant");
    if (job.strict) throw gltfOnly("--strict");
    if (job.sppGiven)
      throw Error(optionName("--spp") + " applies to glTF assets (the spheres are shaded at pixel centres); add " +
                  optionWithValue("--gltf", "FILE"));
    p.width = sizeGiven ? job.width : 768;
    p.height = sizeGiven ? job.height : 768;
    p.scene = builtinScene(job.scene);
    if (lit) {
      if (job.environmentGiven) p.scene.environment = environment;
      gltf::applyLightsOption(p.scene, job.lights, job.environmentGiven, job.allowOutsideUris);
    }
  }
  checkFrameFits(kind, p.width, p.height, usableHostMemory());
  return p;
}

Runtime& RenderDevices::first() { return devices_ != nullptr ? devices_->runtime(0) : *runtime_; }

std::unique_ptr<Shader> RenderDevices::shader(const Scene& scene, const EvalOptions& model) const {
  return devices_ != nullptr ? std::make_unique<Shader>(*devices_, scene, model)
                             : std::make_unique<Shader>(*runtime_, scene, model);
}

Image renderPrepared(RenderDevices devices, const PreparedRender& p, const RenderJob& job, GBuffer* gbuffer) {
  ShadeStats stats;
  ShadeStats* const wanted = job.exactStats ? &stats : nullptr;
  Image img;
  if (p.framed) {
    const gltf::Raycaster raycaster(p.framed->asset);
    const auto shader = devices.shader(p.scene, job.model);
    img = gltf::renderFrame(*shader, raycaster, p.framed->view, p.width, p.height, job.spp, job.frameProgress, job.shade,
                            wanted);
    if (gbuffer != nullptr) *gbuffer = raycaster.trace(p.framed->view, p.width, p.height);
  } else {
    GBuffer g = renderSpheresGBuffer(devices.first(), p.scene, p.width, p.height);
    img = devices.shader(p.scene, job.model)->shade(g, job.shade, wanted);
    if (gbuffer != nullptr) *gbuffer = std::move(g);
  }
  if (wanted != nullptr && job.shade.ibl == IblMode::Exact) job.exactStats(stats);
  return img;
}

GBuffer tracePrepared(const PreparedRender& p, const std::function<Runtime&()>& device) {
  if (p.framed) return gltf::Raycaster(p.framed->asset).trace(p.framed->view, p.width, p.height);
  return renderSpheresGBuffer(device(), p.scene, p.width, p.height);
}

Image renderJob(Runtime& rt, const RenderJob& job) { return renderPrepared(rt, prepareRender(job), job); }

}  // namespace brdfcl
