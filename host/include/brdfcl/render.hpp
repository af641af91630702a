// Deferred shading of G-buffers under punctual and image-based light, and the built-in
// "spheres" scene ray-cast on the device. The shader evaluates the same BRDF layers as batch
// evaluation (kernels/brdf/material.h) and prepares its environment maps and tables once.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "brdfcl/gbuffer.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/runtime.hpp"
#include "brdfcl/scene.hpp"

namespace brdfcl {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear radiance, interleaved, rows from the top
};

// The built-in scene: a 6 x 6 grid of spheres sweeping sheen colour x sheen roughness, clearcoat
// roughness over a rough coloured base, anisotropy strength and rotation, metallic x roughness;
// its camera, a key and a fill light, and the built-in studio environment.
Scene spheresScene();
// The G-buffer carries the camera it was ray-cast with (GBuffer::camera).
GBuffer renderSpheresGBuffer(Runtime& rt, const Scene& scene, int width, int height);

// How a scene's camera differs from a G-buffer's, for a warning: "" when they agree within float
// rounding, else e.g. "position differs by 0.8 (0, 0, 13 vs 0, 0, 12.2), fov 40° vs 30°".
// The scene's (stand-in or given) camera comes first in every pair.
std::string cameraDifference(const Scene& scene, const GBufferCamera& gbufferCamera);

// `brdfcl shade`'s warning about the camera Shader::shade will use, without "brdfcl: warning: ",
// or "" when there is nothing to say: the scene's camera differs from the G-buffer's (naming the
// difference and which one is used), or neither file has a camera and the G-buffer no V.
std::string shadeCameraWarning(const std::string& sceneName, const Scene& scene, const std::string& gbufferName,
                               const GBuffer& g);

// Equirectangular RGB (3 planes) of a scene's environment, intensity applied; `builtin` kinds:
// "sky", "studio", "uniform" (radiance 1: the white furnace). A file (readEnvironmentRgb) has its
// negative texels taken as 0.
std::vector<float> environmentPlanes(const Environment& env, int& width, int& height);

// C(mu): the Lambert albedo weighted by Schlick's (1 - V.H)^5, integral of w (N.L) / pi over L.
// The IBL diffuse weight 1 - (0.04 + 0.96 C) then matches Appendix B's directional albedo.
double fresnelWeightedLambert(double mu);

// How image-based light is computed: the split sum (prefiltered chains and tables, the default)
// or the exact Monte Carlo integral of radiance x f x N.L (kernels/ibl_exact.cl), the ground truth.
enum class IblMode { SplitSum, Exact };
IblMode parseIblMode(const std::string& s);  // "split-sum" | "exact"; else a one-line Error
const char* toString(IblMode m);
constexpr int kMaxIblSamples = 65536;
void checkIblSamples(int samples);  // 1..kMaxIblSamples; else a one-line Error naming --ibl-samples
// A sample count given with the split sum, which takes none: an Error naming both options.
void checkIblSamplesApply(IblMode mode, bool samplesGiven);

struct ShadeOptions {
  IblMode ibl = IblMode::SplitSum;
  int iblSamples = 1024;  // exact: samples per pixel
  int chunkSamples = 0;   // exact: samples per launch (0: about 4M pixel-samples a launch); never changes the image
  // Exact: after each launch, samples done per pixel. Split sum: after each band of rows, bands
  // done (one band unless the frame's planes exceed the device's largest allocation, bandRows).
  std::function<void(int done, int total)> progress;
  unsigned seed = 0;  // exact: another seed rotates every pixel's sequence (independent estimates of one image)
  // Split sum: shade only rows [firstRow, firstRow + rowCount) (rowCount -1: to the bottom) and
  // leave the others 0; an mpirun rank's rows. A pixel's value never depends on which rows are
  // shaded with it. Exact mode shades every row.
  int firstRow = 0, rowCount = -1;
};

// What the exact integrator measured: the mean over covered pixels (with light) of each pixel's
// standard error of its image-based luminance (the spread of four independently rotated copies
// of its sample sequence) over that luminance.
struct ShadeStats {
  int iblSamples = 0;
  std::size_t coveredPixels = 0;
  double relativeStandardError = 0.0;
};
// "brdfcl: exact IBL, N samples per pixel: relative standard error of the image X % (mean over covered pixels)"
std::string exactIblSummary(const ShadeStats& stats);

class DeviceSet;

class Shader {
 public:
  Shader(Runtime& rt, const Scene& scene, EvalOptions options = {});
  // Every device of the set shades a band of rows (devices/device_set.hpp: byte-identical to one
  // device of the same kind); --ibl exact's integrator runs on the set's first device. The set
  // must outlive the Shader.
  Shader(DeviceSet& devices, const Scene& scene, EvalOptions options = {});
  ~Shader();
  // Not for concurrent calls on one Shader: it keeps its G-buffer planes between frames.
  // Pixels without V look from the scene's camera when it has one (Scene::hasCamera), else from
  // the G-buffer's (GBuffer::camera), else from the scene's stand-in defaults.
  Image shade(const GBuffer& g);
  // The same with a choice of image-based light; ShadeOptions{} gives shade(g)'s bytes. `stats`,
  // when given, receives the exact integrator's error estimate (left as is under the split sum).
  Image shade(const GBuffer& g, const ShadeOptions& options, ShadeStats* stats = nullptr);

 private:
  struct State;
  std::unique_ptr<State> s_;
  DeviceSet* devices_ = nullptr;
  std::vector<std::unique_ptr<Shader>> peers_;  // devices 1.. of devices_
};

}  // namespace brdfcl
