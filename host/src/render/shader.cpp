// The deferred shader's host side: the scene's lights and the G-buffer's planes packed as
// kernels/common/shading_layout.h lays them out, and shade() in row bands across the devices,
// with split-sum or exact image-based light.
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>
#include <type_traits>

#include <fmt/format.h>

#include "devices/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/frame_budget.hpp"
#include "render/aniso_dfg.hpp"
#include "brdfcl/render.hpp"
#include "io/option_style.hpp"
#include "kernels/common/shading_layout.h"
#include "model/pack.hpp"
#include "render/camera.hpp"
#include "render/exact_ibl.hpp"
#include "render/prefilter.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

static_assert(sizeof(brdfcl_light) == 16 * 4 && std::is_trivially_copyable_v<brdfcl_light>);

using detail::cameraFor;
using detail::charlieH;
using detail::charlieW;
using detail::kDfgSize;
using detail::kFresnelLambertSize;
using detail::kIrradianceH;
using detail::kIrradianceW;
using detail::kPrefilterLevels;
using detail::PreparedLight;
using detail::prepareLight;
using detail::readOnly;

namespace {
std::vector<brdfcl_light> packLights(const Scene& s) {
  std::vector<brdfcl_light> out;
  for (const auto& l : s.lights) {
    brdfcl_light p{};
    p.type = l.type == Light::Type::Directional ? BRDFCL_LIGHT_DIRECTIONAL
             : l.type == Light::Type::Point     ? BRDFCL_LIGHT_POINT
                                                : BRDFCL_LIGHT_SPOT;
    for (int i = 0; i < 3; ++i) {
      p.color[i] = l.color[i] * l.intensity;
      p.position[i] = l.position[i];
      p.direction[i] = l.direction[i];
    }
    p.range = l.range;
    // KHR_lights_punctual's smooth cone falloff, as scale and offset of cos(angle).
    p.cone_scale = 1.0f / std::max(1e-3f, std::cos(l.innerCone) - std::cos(l.outerCone));
    p.cone_offset = -std::cos(l.outerCone) * p.cone_scale;
    out.push_back(p);
  }
  if (out.empty()) out.push_back(brdfcl_light{});  // OpenCL buffers cannot be empty; count stays 0
  return out;
}


// G-buffer channels -> the planes of kernels/common/shading_layout.h, defaults for absent ones.
// Fills `planes`, reusing its memory: at 512x512 the planes pass glibc's 32 MiB mmap threshold,
// so a fresh vector per frame would be mapped and page-faulted in again on every shade().
void gbufferPlanes(const GBuffer& g, std::vector<float>& planes) {
  const std::size_t n = std::size_t(g.width) * g.height;
  planes.assign(GB_PLANES * n, 0.0f);
  auto put3 = [&](const std::vector<float>& v, int first) {
    if (v.empty()) return;
    for (std::size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) planes[(first + c) * n + i] = v[3 * i + c];
  };
  auto put1 = [&](const std::vector<float>& v, int plane) {
    if (!v.empty()) std::copy(v.begin(), v.end(), planes.begin() + plane * n);
  };
  put3(g.P, GB_PX);
  put3(g.N, GB_NX);
  put3(g.T, GB_TX);
  put3(g.baseColor, GB_BASE_R);
  put1(g.metallic, GB_METALLIC);
  put1(g.roughness, GB_ROUGHNESS);
  put1(g.mask, GB_MASK);
  put3(g.emissive, GB_EMISSIVE_R);
  put3(g.sheenColor, GB_SHEEN_R);
  put1(g.sheenRoughness, GB_SHEEN_ROUGHNESS);
  put1(g.clearcoat, GB_CLEARCOAT);
  put1(g.clearcoatRoughness, GB_CLEARCOAT_ROUGHNESS);
  put3(g.clearcoatN, GB_CCN_X);
  put1(g.anisotropyStrength, GB_ANISO_STRENGTH);
  put1(g.anisotropyRotation, GB_ANISO_ROTATION);
  if (g.occlusion.empty())
    std::fill(planes.begin() + GB_OCCLUSION * n, planes.begin() + (GB_OCCLUSION + 1) * n, 1.0f);
  put1(g.occlusion, GB_OCCLUSION);
  put3(g.V, GB_VX);
  // The canonical EXR channel of each plane (docs/gbuffer.md), in the order of shading_layout.h:
  // what the user can look up in the file, rather than the plane's number.
  static const char* const kChannel[] = {
      "P.X",          "P.Y",          "P.Z",          "N.X",       "N.Y",        "N.Z",
      "T.X",          "T.Y",          "T.Z",          "baseColor.R", "baseColor.G", "baseColor.B",
      "metallic",     "roughness",    "mask",         "emissive.R", "emissive.G", "emissive.B",
      "sheenColor.R", "sheenColor.G", "sheenColor.B", "sheenRoughness", "clearcoat", "clearcoatRoughness",
      "clearcoatN.X", "clearcoatN.Y", "clearcoatN.Z", "anisotropyStrength", "anisotropyRotation",
      "occlusion",    "V.X",          "V.Y",          "V.Z"};
  static_assert(sizeof kChannel / sizeof kChannel[0] == GB_PLANES);
  for (std::size_t i = 0; i < planes.size(); ++i)
    if (!std::isfinite(planes[i]))
      throw Error(fmt::format("G-buffer pixel ({}, {}) has a non-finite value ({}) in channel '{}'; fix the renderer's output",
                              (i % n) % g.width, (i % n) / g.width, std::isnan(planes[i]) ? "nan" : planes[i] > 0 ? "inf" : "-inf",
                              kChannel[i / n]));
  // A zero V would make the kernel fall back to the camera (its "no V" flag), silently.
  for (std::size_t i = 0; i < g.V.size() / 3; ++i) {
    const double x = g.V[3 * i], y = g.V[3 * i + 1], z = g.V[3 * i + 2];
    if (x * x + y * y + z * z < 1e-12)
      throw Error(fmt::format("G-buffer pixel ({}, {}) has a zero-length view direction V; write the unit direction "
                              "towards the viewer, or leave V out to use the scene camera",
                              i % g.width, i / g.width));
  }
}
}  // namespace

struct Shader::State {
  Runtime& rt;
  Scene scene;
  EvalOptions options;
  std::shared_ptr<const PreparedLight> light;
  cl::Buffer lights;
  int lightCount = 0;
  cl::Program program;
  std::vector<float> planes;  // the G-buffer's planes, kept between frames (see gbufferPlanes)
  std::pair<std::size_t, cl::Buffer> planesOnDevice;  // their device copy, and its size in floats
  // --ibl exact, prepared on its first use: the integrator and the environment's CDFs.
  bool exactReady = false;
  cl::Program exactProgram;
  cl::Buffer envRows, envCols, envTexelP;
  float envShare = 0.0f;

  // The shade kernel with every argument set but the band's (y0 and rows, at bandArg and after).
  cl::Kernel shadeKernel(const GBuffer& g, const cl::Buffer& bg, const cl::Buffer& bo, const cl::Buffer& aniso,
                         bool exact, int& bandArg) const;
  // Rows [rowBegin, rowEnd) of the frame whose planes are `planes`, in bands, into `out` (3
  // planes of r, g, b). Each pixel's value depends on the pixel alone, so any split of the rows
  // gives the same bytes.
  void shadeRows(const GBuffer& g, const std::vector<float>& planes, int rowBegin, int rowEnd, bool exact,
                 const ShadeOptions& shadeOptions, bool report, std::vector<float>& out);
  // --ibl exact's program and environment CDFs, on its first use.
  void prepareExact();
  // --ibl exact over the whole frame of `planes`, into `out`.
  void integrateExact(const GBuffer& g, const ShadeOptions& shadeOptions, std::vector<float>& out, ShadeStats* stats);
};

Shader::Shader(Runtime& rt, const Scene& scene, EvalOptions options)
    : s_(std::make_unique<State>(State{rt, scene, options, nullptr, {}, 0, {}, {}, {}, false, {}, {}, {}, {}, 0.0f})) {
  auto& s = *s_;
  checkProfileOptions(options);
  s.light = prepareLight(rt, scene.environment, options);
  try {
    const auto lights = packLights(scene);
    s.lightCount = int(scene.lights.size());
    s.lights = cl::Buffer(rt.opencl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, lights.size() * sizeof(brdfcl_light),
                          const_cast<brdfcl_light*>(lights.data()));
    FeatureSet all;
    all.sheen = all.ratifiedSheen = all.clearcoat = all.anisotropy = true;
    EvalOptions o = options;
    o.lobe = Lobe::All;
    s.program = rt.opencl().program("shade.cl", materialDefines(o, all));
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing the shader");
  }
}

Shader::Shader(DeviceSet& devices, const Scene& scene, EvalOptions options) : Shader(devices.runtime(0), scene, options) {
  devices_ = &devices;
  for (std::size_t k = 1; k < devices.size(); ++k)
    peers_.push_back(std::make_unique<Shader>(devices.runtime(k), scene, options));
}

Shader::~Shader() = default;

namespace {
// The anisotropic split-sum table, only for G-buffers that have anisotropy: its first bake takes
// seconds, which nothing else should pay. Once per runtime; a one-float stand-in otherwise (the
// kernel reads the table only where the strength is > 0).
cl::Buffer anisotropicDfgFor(Runtime& rt, const GBuffer& g) {
  static std::mutex mutex;
  static std::map<const Runtime*, cl::Buffer> tables;
  const bool needed = std::any_of(g.anisotropyStrength.begin(), g.anisotropyStrength.end(), [](float v) { return v > 0.0f; });
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = tables.find(&rt); it != tables.end()) return it->second;
  if (!needed) return readOnly(rt.opencl().context(), std::vector<float>(2, 0.0f));
  return tables.emplace(&rt, readOnly(rt.opencl().context(), cachedAnisotropicDfg(rt))).first->second;
}
}  // namespace

Image Shader::shade(const GBuffer& g) { return shade(g, ShadeOptions{}, nullptr); }

cl::Kernel Shader::State::shadeKernel(const GBuffer& g, const cl::Buffer& bg, const cl::Buffer& bo,
                                     const cl::Buffer& aniso, bool exact, int& bandArg) const {
  cl::Kernel k(program, "shade");
  int a = 0;
  k.setArg(a++, bg);
  k.setArg(a++, g.width);
  k.setArg(a++, g.height);
  bandArg = a;  // y0, then the band's rows: set per band
  a += 2;
  k.setArg(a++, scene.hasCamera || !g.camera ? cameraFor(scene, g.width, g.height)
                                              : cameraFor(*g.camera, g.width, g.height));
  k.setArg(a++, lights);
  k.setArg(a++, lightCount);
  k.setArg(a++, light->background);
  k.setArg(a++, light->ggx);
  k.setArg(a++, light->charlie);
  k.setArg(a++, light->irradiance);
  k.setArg(a++, light->envW);
  k.setArg(a++, light->envH);
  k.setArg(a++, charlieW(light->envW));
  k.setArg(a++, charlieH(light->envH));
  k.setArg(a++, kPrefilterLevels);
  k.setArg(a++, kIrradianceW);
  k.setArg(a++, kIrradianceH);
  k.setArg(a++, scene.environment.rotation);
  k.setArg(a++, light->dfg);
  k.setArg(a++, kDfgSize);
  k.setArg(a++, aniso);
  k.setArg(a++, light->sheenE);
  k.setArg(a++, light->sheenESize);
  k.setArg(a++, light->fresnelLambert);
  k.setArg(a++, kFresnelLambertSize);
  k.setArg(a++, exact ? 0 : 1);
  k.setArg(a++, bo);
  return k;
}

void Shader::State::shadeRows(const GBuffer& g, const std::vector<float>& planes, int rowBegin, int rowEnd, bool exact,
                              const ShadeOptions& shadeOptions, bool report, std::vector<float>& out) {
  const std::size_t np = std::size_t(g.width) * g.height;
  const auto& ctx = rt.opencl().context();
  // Bands of rows keep every buffer below the device's largest allocation (any image size the
  // host can hold); the device copy of a band is kept between frames of one size.
  const int band = std::min(bandRows(rt.info(), g.width, GB_PLANES * sizeof(float)), rowEnd - rowBegin);
  const std::size_t bandFloats = std::size_t(GB_PLANES) * g.width * band;
  if (planesOnDevice.first != bandFloats) {
    planesOnDevice = {bandFloats, cl::Buffer(ctx, CL_MEM_READ_ONLY, bandFloats * 4)};
  }
  cl::Buffer& bg = planesOnDevice.second;
  cl::Buffer bo(ctx, CL_MEM_WRITE_ONLY, 3 * std::size_t(g.width) * band * 4);
  // Held until the launch is done: a kernel argument does not keep its buffer alive.
  const cl::Buffer aniso = anisotropicDfgFor(rt, g);
  int bandArg = 0;
  cl::Kernel k = shadeKernel(g, bg, bo, aniso, exact, bandArg);
  auto& q = rt.opencl().queue();
  for (int y0 = rowBegin; y0 < rowEnd; y0 += band) {
    const int rows = std::min(band, rowEnd - y0);
    const std::size_t bandPixels = std::size_t(g.width) * rows, first = std::size_t(y0) * g.width;
    for (int plane = 0; plane < GB_PLANES; ++plane)
      q.enqueueWriteBuffer(bg, CL_FALSE, plane * bandPixels * 4, bandPixels * 4, planes.data() + plane * np + first);
    k.setArg(bandArg, y0);
    k.setArg(bandArg + 1, rows);
    q.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(std::size_t(g.width), std::size_t(rows)));
    for (int c = 0; c < 3; ++c)
      q.enqueueReadBuffer(bo, CL_FALSE, c * bandPixels * 4, bandPixels * 4, out.data() + c * np + first);
    q.finish();
    if (report && !exact && shadeOptions.progress)
      shadeOptions.progress((y0 - rowBegin) / band + 1, (rowEnd - rowBegin + band - 1) / band);
  }
}

void Shader::State::prepareExact() {
  if (exactReady) return;
  const auto& ctx = rt.opencl().context();
  // The CDFs come from the full-resolution map the kernel reads, as it is on the device.
  std::vector<float> env(3 * std::size_t(light->envW) * light->envH);
  rt.opencl().queue().enqueueReadBuffer(light->background, CL_TRUE, 0, env.size() * 4, env.data());
  const auto cdf = detail::environmentCdf(env, light->envW, light->envH);
  envRows = readOnly(ctx, cdf.rows);
  envCols = readOnly(ctx, cdf.cols);
  envTexelP = readOnly(ctx, cdf.texelP);
  envShare = cdf.share;
  FeatureSet all;
  all.sheen = all.ratifiedSheen = all.clearcoat = all.anisotropy = true;
  EvalOptions o = options;
  o.lobe = Lobe::All;
  exactProgram = rt.opencl().program("ibl_exact.cl", materialDefines(o, all));
  exactReady = true;
}

void Shader::State::integrateExact(const GBuffer& g, const ShadeOptions& shadeOptions, std::vector<float>& out,
                                   ShadeStats* stats) {
  // The exact integrator reads the whole frame's planes: the split-sum pass's device copy when
  // it held the frame in one band, else a copy of its own, which must fit one allocation.
  cl::Buffer whole;
  if (planesOnDevice.first == planes.size()) {
    whole = planesOnDevice.second;
  } else {
    if (planes.size() * 4 > rt.info().maxAlloc)
      throw Error(fmt::format("{}: a {}x{} G-buffer needs a {:.1f} GiB device buffer, but '{}' allows {:.1f} GiB; "
                              "use a smaller {} or {}",
                              optionWithValue("--ibl", "exact", true), g.width, g.height,
                              double(planes.size() * 4) / (1u << 30), rt.info().name,
                              double(rt.info().maxAlloc) / (1u << 30), optionName("--size"),
                              optionWithValue("--ibl", "split-sum", true)));
    try {
      whole = readOnly(rt.opencl().context(), planes);
    } catch (const cl::Error&) {
      rethrowOpenCL("preparing the exact image-based light");
    }
  }
  detail::ExactIblInputs in;
  in.program = exactProgram;
  in.gbuffer = &whole;
  in.width = g.width;
  in.height = g.height;
  in.camera = scene.hasCamera || !g.camera ? cameraFor(scene, g.width, g.height) : cameraFor(*g.camera, g.width, g.height);
  in.environment = &light->background;
  in.rows = &envRows;
  in.cols = &envCols;
  in.texelP = &envTexelP;
  in.envW = light->envW;
  in.envH = light->envH;
  in.envShare = envShare;
  in.rotation = scene.environment.rotation;
  in.sheenE = &light->sheenE;
  in.sheenESize = light->sheenESize;
  detail::integrateExactIbl(rt, in, planes, shadeOptions, out, stats);
}

Image Shader::shade(const GBuffer& g, const ShadeOptions& options, ShadeStats* stats) {
  auto& s = *s_;
  const bool exact = options.ibl == IblMode::Exact;
  if (exact) checkIblSamples(options.iblSamples);
  if (exact && s.options.profile != Profile::Spec)
    throw Error(fmt::format("{} integrates the spec's BRDF only; {} reproduces its engine's own "
                            "image-based light, so use {} with it",
                            optionWithValue("--ibl", "exact", true),
                            optionWithValue("--profile", toString(s.options.profile), true),
                            optionWithValue("--ibl", "split-sum", true)));
  auto& planes = s.planes;
  gbufferPlanes(g, planes);
  Image img;
  img.width = g.width;
  img.height = g.height;
  const std::size_t np = std::size_t(g.width) * g.height;
  std::vector<float> out(3 * np);
  try {
    // Under mpirun, this rank's rows (ShadeOptions::firstRow, rowCount); the exact integrator's
    // split-sum pass always covers the whole frame.
    const int yBegin = exact ? 0 : std::clamp(options.firstRow, 0, g.height);
    const int yEnd = exact || options.rowCount < 0 ? g.height : std::min(g.height, yBegin + options.rowCount);
    if (peers_.empty()) {
      s.shadeRows(g, planes, yBegin, yEnd, exact, options, true, out);
    } else {
      // Row bands across the devices (DeviceSet); progress counts devices done.
      std::mutex progressMutex;
      int done = 0;
      devices_->run(std::size_t(yEnd - yBegin), 1, [&](std::size_t dev, std::size_t first, std::size_t count) {
        State& st = dev == 0 ? s : *peers_[dev - 1]->s_;
        st.shadeRows(g, planes, yBegin + int(first), yBegin + int(first + count), exact, options, false, out);
        std::lock_guard<std::mutex> lock(progressMutex);
        if (!exact && options.progress) options.progress(++done, int(devices_->size()));
      });
    }
    if (exact) s.prepareExact();
  } catch (const cl::Error&) {
    rethrowOpenCL("shading the G-buffer");
  }
  if (exact) s.integrateExact(g, options, out, stats);
  img.rgb.resize(3 * np);
  for (std::size_t i = 0; i < np; ++i)
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = out[c * np + i];
  return img;
}

}  // namespace brdfcl
