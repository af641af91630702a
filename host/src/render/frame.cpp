// Lighting choice and the multi-sample glTF render: stratified sub-pixel G-buffers, each shaded
// through the same deferred shader as `brdfcl shade`, averaged into the pixel.
#include "render/gltf_frame.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "io/option_style.hpp"
#include "io/vec3.hpp"

namespace brdfcl::gltf {

Light defaultKeyLight(const View& view) {
  Light key;
  key.type = Light::Type::Directional;
  key.intensity = 3.0f;
  using ::brdfcl::detail::toVec3;
  const Imath::V3d d = 0.5 * toVec3(view.right) - toVec3(view.up) + 0.6 * toVec3(view.forward);
  key.direction = ::brdfcl::detail::toArray(Imath::V3f(d / ::brdfcl::detail::norm(d)));
  return key;
}

void applyLightsOption(Scene& scene, const std::string& lights, bool environmentGiven, bool allowOutside) {
  if (lights == "gltf") return;
  if (lights == "none") {
    scene.lights.clear();
    return;
  }
  // A name that is no readable file is most often a mistyped choice: say which option it was.
  struct stat st {};
  const int err = ::stat(lights.c_str(), &st) != 0 ? errno
                  : S_ISDIR(st.st_mode)             ? EISDIR
                  : ::access(lights.c_str(), R_OK) != 0 ? errno
                                                        : 0;
  if (err != 0)
    throw Error(fmt::format("{}: cannot read: {}; give gltf, none, or a scene .json file",
                            optionWithValue("--lights", "'" + lights + "'"), std::strerror(err)));
  const Scene file = readScene(lights, allowOutside);
  scene.lights = file.lights;
  if (!environmentGiven) scene.environment = file.environment;
}

Scene frameLighting(const Asset& asset, const View& view, const std::string& lights, const Environment& environment,
                    bool environmentGiven, bool allowOutside) {
  Scene scene;
  scene.environment = environment;
  scene.lights = asset.lights;
  if (scene.lights.empty()) scene.lights.push_back(defaultKeyLight(view));
  applyLightsOption(scene, lights, environmentGiven, allowOutside);
  return scene;
}

std::vector<std::array<float, 2>> subpixelOffsets(int spp) {
  if (spp < 1) throw Error(fmt::format("{} must be at least 1", optionWithValue("--spp", std::to_string(spp))));
  if (spp == 1) return {{0.5f, 0.5f}};
  const int columns = int(std::ceil(std::sqrt(double(spp))));
  const int rows = (spp + columns - 1) / columns;
  // R2 sequence (Roberts 2018): the plastic constant's powers give well-spread points in a cell.
  const double g = 1.32471795724474602596, a1 = 1.0 / g, a2 = 1.0 / (g * g);
  std::vector<std::array<float, 2>> offsets;
  for (int i = 0; i < spp; ++i) {
    const double u = std::fmod(0.5 + a1 * (i + 1), 1.0), v = std::fmod(0.5 + a2 * (i + 1), 1.0);
    const int cx = i % columns, cy = i / columns;
    offsets.push_back({float((cx + u) / columns), float((cy + v) / rows)});
  }
  return offsets;
}

brdfcl::Image renderFrame(Shader& shader, const Raycaster& raycaster, const View& view, int width, int height, int spp,
                  const std::function<void(int, int)>& progress, const ShadeOptions& shadeOptions, ShadeStats* stats) {
  const auto offsets = subpixelOffsets(spp);
  brdfcl::Image sum;
  // Exact image-based light: the samples are shared out over the sub-pixel frames, each with its
  // own seed so that their errors are independent and average down.
  ShadeOptions perFrame = shadeOptions;
  perFrame.progress = {};
  perFrame.iblSamples = (shadeOptions.iblSamples + spp - 1) / spp;
  double relativeError = 0.0;
  std::size_t covered = 0;
  // One G-buffer for every sample: traced into again, its pages are not faulted in per sample.
  GBuffer g;
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    perFrame.seed = shadeOptions.seed + unsigned(k);
    ShadeStats frameStats;
    raycaster.trace(view, width, height, offsets[k][0], offsets[k][1], g);
    const brdfcl::Image one = shader.shade(g, perFrame, &frameStats);
    relativeError += frameStats.relativeStandardError;
    covered = std::max(covered, frameStats.coveredPixels);
    if (k == 0) {
      sum = one;
    } else {
      for (std::size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += one.rgb[i];
    }
    if (progress) progress(int(k + 1), spp);
  }
  if (offsets.size() > 1)
    for (auto& v : sum.rgb) v /= float(offsets.size());
  if (stats && shadeOptions.ibl == IblMode::Exact) {
    stats->iblSamples = perFrame.iblSamples * spp;
    stats->coveredPixels = covered;
    stats->relativeStandardError = relativeError / double(spp) / std::sqrt(double(spp));
  }
  return sum;
}

}  // namespace brdfcl::gltf
