// The deferred shader's host side: environment prefiltering on the device (kernels/
// ibl_prefilter.cl), the tables it reads (GGX DFG, sheen albedo, Fresnel-weighted Lambert), the
// G-buffer planes, and the built-in spheres scene (kernels/gbuffer_spheres.cl).
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>
#include <type_traits>

#include <fmt/format.h>

#include "brdfcl/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/lut.hpp"
#include "io/disk_cache.hpp"
#include "render/aniso_dfg.hpp"
#include "brdfcl/render.hpp"
#include "kernels/common/shading_layout.h"
#include "model/pack.hpp"
#include "model/engine_tables.hpp"
#include "render/exact_ibl.hpp"

namespace brdfcl {

static_assert(sizeof(brdfcl_light) == 16 * 4 && std::is_trivially_copyable_v<brdfcl_light>);
static_assert(sizeof(brdfcl_camera) == 16 * 4 && offsetof(brdfcl_camera, orthographic) == 44 &&
              offsetof(brdfcl_camera, forward) == 48);
static_assert(sizeof(brdfcl_sphere) == 20 * 4 && offsetof(brdfcl_sphere, anisotropy_rotation) == 64);

namespace {
constexpr int kPrefilterLevels = 6;  // roughness 0, 0.2, ..., 1
constexpr int kIrradianceW = 64, kIrradianceH = 32;
constexpr int kDfgSize = 64, kFresnelLambertSize = 64;
// Part of the disk cache key of prefiltered environments: bump when the chain layout, the sample
// counts or the levels change (the kernel source is in the key already).
constexpr const char* kPrefilterVersion = "chains6 ggx1/128 cap512x256 charlie256 at128x64 irr512 v2";

using V3 = std::array<float, 3>;
V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(V3 a, V3 b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
V3 normalized(V3 a) {
  const float l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  return {a[0] / l, a[1] / l, a[2] / l};
}

brdfcl_camera cameraFor(const Scene& s, int w, int h) {
  brdfcl_camera c{};
  const V3 f = normalized(sub(s.cameraTarget, s.cameraPosition));
  const V3 worldUp = std::fabs(f[1]) > 0.999f ? V3{0, 0, -1} : V3{0, 1, 0};
  const V3 r = normalized(cross(f, worldUp)), u = cross(r, f);
  for (int i = 0; i < 3; ++i) {
    c.position[i] = s.cameraPosition[i];
    c.right[i] = r[i];
    c.up[i] = u[i];
    c.forward[i] = f[i];
  }
  c.tan_half_fov = std::tan(s.fovDegrees * float(M_PI) / 360.0f);
  c.aspect = float(w) / float(h);
  return c;
}

// A G-buffer's camera as it is; its fov goes through the same float expression as a scene's, so
// a spheres G-buffer shades exactly as with the scene that made it.
brdfcl_camera cameraFor(const GBufferCamera& g, int w, int h) {
  brdfcl_camera c{};
  for (int i = 0; i < 3; ++i) {
    c.position[i] = g.position[i];
    c.right[i] = g.right[i];
    c.up[i] = g.up[i];
    c.forward[i] = g.forward[i];
  }
  c.orthographic = g.orthographic ? 1.0f : 0.0f;
  c.tan_half_fov = g.orthographic ? 0.0f : std::tan(g.fovDegrees * float(M_PI) / 360.0f);
  c.aspect = float(w) / float(h);
  return c;
}

GBufferCamera gbufferCamera(const brdfcl_camera& c, float fovDegrees) {
  GBufferCamera g;
  for (int i = 0; i < 3; ++i) {
    g.position[i] = c.position[i];
    g.right[i] = c.right[i];
    g.up[i] = c.up[i];
    g.forward[i] = c.forward[i];
  }
  g.fovDegrees = fovDegrees;
  return g;
}

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

// kernels/common/environment.h's chain layout (env_level_w/h), which the kernels index by.
int levelW(int w0, int capW, int k) { return k == 0 ? std::max(w0, 8) : std::max(std::min(w0, capW) >> k, 8); }
int levelH(int h0, int capH, int k) { return k == 0 ? std::max(h0, 4) : std::max(std::min(h0, capH) >> k, 4); }

// The Charlie chain's level-0 size for a map of w x h (kernels/common/shading_layout.h).
int charlieW(int w) { return std::min(w, BRDFCL_CHARLIE_W); }
int charlieH(int h) { return std::min(h, BRDFCL_CHARLIE_H); }

// Floats of a prefiltered chain of kPrefilterLevels levels.
std::size_t chainFloatsOf(int w0, int h0, int capW, int capH) {
  std::size_t n = 0;
  for (int k = 0; k < kPrefilterLevels; ++k) n += 3 * std::size_t(levelW(w0, capW, k)) * levelH(h0, capH, k);
  return n;
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

cl::Buffer readOnly(const cl::Context& ctx, const std::vector<float>& v) {
  return cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, std::max<std::size_t>(v.size(), 1) * 4,
                    const_cast<float*>(v.data()));
}
}  // namespace

Scene spheresScene() {
  Scene s;
  s.hasCamera = true;
  s.cameraPosition = {0.0f, 0.0f, 13.0f};
  s.cameraTarget = {0.0f, 0.0f, 0.0f};
  s.fovDegrees = 30.0f;
  Light key;
  key.type = Light::Type::Directional;
  key.direction = normalized({0.5f, -0.6f, -0.62f});
  key.intensity = 2.5f;
  key.color = {1.0f, 0.96f, 0.9f};
  Light fill;
  fill.type = Light::Type::Point;
  fill.position = {-6.0f, 2.0f, 6.0f};
  fill.intensity = 30.0f;
  fill.color = {0.8f, 0.85f, 1.0f};
  s.lights = {key, fill};
  s.environment.builtin = true;
  s.environment.builtinKind = "studio";
  s.environment.intensity = 1.0f;
  return s;
}

GBuffer renderSpheresGBuffer(Runtime& rt, const Scene& scene, int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error(fmt::format("image size {}x{} is out of range; use 1 to 16384 per side", width, height));
  std::vector<brdfcl_sphere> spheres;
  for (int row = 0; row < 6; ++row)
    for (int col = 0; col < 6; ++col) {
      brdfcl_sphere s{};
      s.center[0] = (col - 2.5f) * 1.05f;
      s.center[1] = (2.5f - row) * 1.05f;
      s.radius = 0.46f;
      const float t = col / 5.0f;
      float base[3] = {0.5f, 0.5f, 0.5f};
      s.roughness = 0.5f;
      switch (row) {
        case 0:  // white sheen over dark blue cloth, sheen roughness 0 .. 1
        case 1:  // coloured sheen over dark red cloth
          base[0] = row ? 0.25f : 0.02f, base[1] = 0.02f, base[2] = row ? 0.03f : 0.12f;
          s.roughness = 0.8f;
          s.sheen_color[0] = 1.0f, s.sheen_color[1] = row ? 0.45f : 1.0f, s.sheen_color[2] = row ? 0.3f : 1.0f;
          s.sheen_roughness = 0.05f + 0.95f * t;
          break;
        case 2:  // clearcoat over a rough orange base, clearcoat roughness 0 .. 1
          base[0] = 0.8f, base[1] = 0.25f, base[2] = 0.05f;
          s.roughness = 0.7f;
          s.clearcoat = 1.0f;
          s.clearcoat_roughness = t;
          break;
        case 3:  // brushed metal, anisotropy strength 0 .. 1
          base[0] = 0.95f, base[1] = 0.93f, base[2] = 0.88f;
          s.metallic = 1.0f;
          s.roughness = 0.3f;
          s.anisotropy_strength = t;
          break;
        case 4:  // anisotropy 0.8, rotation 0 .. pi
          base[0] = 0.95f, base[1] = 0.64f, base[2] = 0.54f;
          s.metallic = 1.0f;
          s.roughness = 0.3f;
          s.anisotropy_strength = 0.8f;
          s.anisotropy_rotation = float(M_PI) * t;
          break;
        default:  // gold, metallic 1 on even columns, 0 on odd; roughness 0 .. 1
          base[0] = 1.0f, base[1] = 0.78f, base[2] = 0.34f;
          s.metallic = col % 2 == 0 ? 1.0f : 0.0f;
          s.roughness = t;
      }
      for (int c = 0; c < 3; ++c) s.base_color[c] = base[c];
      spheres.push_back(s);
    }
  const std::size_t np = std::size_t(width) * height;
  std::vector<float> planes(GB_PLANES * np);
  try {
    auto program = rt.program("gbuffer_spheres.cl");
    cl::Buffer bs(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, spheres.size() * sizeof(brdfcl_sphere),
                  spheres.data());
    const int band = bandRows(rt.info(), width, GB_PLANES * sizeof(float));
    cl::Buffer out(rt.context(), CL_MEM_WRITE_ONLY, std::size_t(GB_PLANES) * width * std::min(band, height) * 4);
    cl::Kernel k(program, "gbuffer_spheres");
    for (int y0 = 0; y0 < height; y0 += band) {
      const int rows = std::min(band, height - y0);
      const std::size_t bandPixels = std::size_t(width) * rows;
      k.setArg(0, bs);
      k.setArg(1, int(spheres.size()));
      k.setArg(2, width);
      k.setArg(3, height);
      k.setArg(4, y0);
      k.setArg(5, rows);
      k.setArg(6, cameraFor(scene, width, height));
      k.setArg(7, out);
      rt.queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(std::size_t(width), std::size_t(rows)));
      for (int plane = 0; plane < GB_PLANES; ++plane)
        rt.queue().enqueueReadBuffer(out, CL_FALSE, plane * bandPixels * 4, bandPixels * 4,
                                     planes.data() + plane * np + std::size_t(y0) * width);
      rt.queue().finish();
    }
  } catch (const cl::Error&) {
    rethrowOpenCL("ray-casting the spheres scene");
  }
  GBuffer g;
  g.width = width;
  g.height = height;
  auto get3 = [&](int first) {
    std::vector<float> v(3 * np);
    for (std::size_t i = 0; i < np; ++i)
      for (int c = 0; c < 3; ++c) v[3 * i + c] = planes[(first + c) * np + i];
    return v;
  };
  auto get1 = [&](int plane) { return std::vector<float>(planes.begin() + plane * np, planes.begin() + (plane + 1) * np); };
  g.P = get3(GB_PX);
  g.N = get3(GB_NX);
  g.T = get3(GB_TX);
  g.baseColor = get3(GB_BASE_R);
  g.metallic = get1(GB_METALLIC);
  g.roughness = get1(GB_ROUGHNESS);
  g.mask = get1(GB_MASK);
  g.sheenColor = get3(GB_SHEEN_R);
  g.sheenRoughness = get1(GB_SHEEN_ROUGHNESS);
  g.clearcoat = get1(GB_CLEARCOAT);
  g.clearcoatRoughness = get1(GB_CLEARCOAT_ROUGHNESS);
  g.clearcoatN = get3(GB_CCN_X);
  g.anisotropyStrength = get1(GB_ANISO_STRENGTH);
  g.anisotropyRotation = get1(GB_ANISO_ROTATION);
  // Rays start 1e-4 along the ray (the kernel's hit threshold), a bound too small to record.
  g.camera = gbufferCamera(cameraFor(scene, width, height), scene.fovDegrees);
  return g;
}

std::string cameraDifference(const Scene& scene, const GBufferCamera& g) {
  const brdfcl_camera c = cameraFor(scene, 1, 1);
  std::vector<std::string> parts;
  auto degrees = [](double cosine) { return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI; };
  auto dot3 = [](const float* a, const std::array<float, 3>& b) {
    return double(a[0]) * b[0] + double(a[1]) * b[1] + double(a[2]) * b[2];
  };
  double d2 = 0.0, scale2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    d2 += (double(c.position[i]) - g.position[i]) * (double(c.position[i]) - g.position[i]);
    scale2 += double(g.position[i]) * g.position[i];
  }
  // Tolerances well above float rounding of a written and re-read camera, well below what shows.
  if (std::sqrt(d2) > 1e-4 * std::max(1.0, std::sqrt(scale2)))
    parts.push_back(fmt::format("position differs by {:.3g} ({}, {}, {} vs {}, {}, {})", std::sqrt(d2), c.position[0],
                                c.position[1], c.position[2], g.position[0], g.position[1], g.position[2]));
  const double view = degrees(dot3(c.forward, g.forward)), roll = degrees(dot3(c.up, g.up));
  if (view > 0.01) parts.push_back(fmt::format("view direction differs by {:.3g}°", view));
  else if (roll > 0.01) parts.push_back(fmt::format("up direction differs by {:.3g}°", roll));
  if (g.orthographic)
    parts.push_back(fmt::format("projection perspective (fov {}°) vs orthographic (ymag {})", scene.fovDegrees, g.ymag));
  else if (std::fabs(scene.fovDegrees - g.fovDegrees) > 0.01)
    parts.push_back(fmt::format("fov {}° vs {}°", scene.fovDegrees, g.fovDegrees));
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : ", ") + p;
  return out;
}

std::string shadeCameraWarning(const std::string& sceneName, const Scene& scene, const std::string& gbufferName,
                               const GBuffer& g) {
  if (scene.hasCamera && g.camera) {
    const std::string difference = cameraDifference(scene, *g.camera);
    if (difference.empty()) return "";
    return fmt::format("the camera of {} differs from the one that made {} ({}); {}", sceneName, gbufferName, difference,
                       g.hasView() ? fmt::format("{}'s V channels give every pixel's view, so neither camera changes "
                                                 "the image",
                                                 gbufferName)
                                   : fmt::format("shading with the scene's camera, which {} gives explicitly (remove "
                                                 "its \"camera\" to use the G-buffer's)",
                                                 sceneName));
  }
  if (!scene.hasCamera && !g.camera && !g.hasView())
    return fmt::format("neither {} nor {} has a camera; shading with the default camera at ({}, {}, {}) looking at "
                       "({}, {}, {}) (add \"camera\" to {})",
                       sceneName, gbufferName, scene.cameraPosition[0], scene.cameraPosition[1],
                       scene.cameraPosition[2], scene.cameraTarget[0], scene.cameraTarget[1], scene.cameraTarget[2],
                       sceneName);
  return "";
}

// Everything the shader derives from the environment and the sheen options: prepared once per
// (runtime, environment, options) and shared by every Shader of the process.
struct PreparedLight {
  int envW = 0, envH = 0;
  cl::Buffer background, ggx, charlie, irradiance, dfg, sheenE, fresnelLambert;
  int sheenESize = 0;
};

namespace {
std::shared_ptr<const PreparedLight> prepareLight(Runtime& rt, const Environment& environment, const EvalOptions& options);
}

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
};

Shader::Shader(Runtime& rt, const Scene& scene, EvalOptions options)
    : s_(std::make_unique<State>(State{rt, scene, options, nullptr, {}, 0, {}, {}, {}, false, {}, {}, {}, {}, 0.0f})) {
  auto& s = *s_;
  checkProfileOptions(options);
  s.light = prepareLight(rt, scene.environment, options);
  try {
    const auto lights = packLights(scene);
    s.lightCount = int(scene.lights.size());
    s.lights = cl::Buffer(rt.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, lights.size() * sizeof(brdfcl_light),
                          const_cast<brdfcl_light*>(lights.data()));
    FeatureSet all;
    all.sheen = all.ratifiedSheen = all.clearcoat = all.anisotropy = true;
    EvalOptions o = options;
    o.lobe = Lobe::All;
    s.program = rt.program("shade.cl", materialDefines(o, all));
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing the shader");
  }
}

Shader::Shader(DeviceSet& devices, const Scene& scene, EvalOptions options) : Shader(devices.runtime(0), scene, options) {
  devices_ = &devices;
  for (std::size_t k = 1; k < devices.size(); ++k)
    peers_.push_back(std::make_unique<Shader>(devices.runtime(k), scene, options));
}

namespace {
// GGX and Charlie prefiltered chains (kPrefilterLevels levels each, roughness k / (levels - 1))
// and the irradiance map, concatenated in that order: the part of the light worth caching.
std::vector<float> prefilterEnvironment(Runtime& rt, const std::vector<float>& env, int envW, int envH) {
  const auto& ctx = rt.context();
  auto& q = rt.queue();
  // Source chain: the environment and its 2x2 box mips down to 8x4.
  std::vector<int> ws{envW}, hs{envH};
  while (ws.back() > 8 && hs.back() > 4) ws.push_back(std::max(ws.back() / 2, 8)), hs.push_back(std::max(hs.back() / 2, 4));
  std::size_t chainFloats = 0;
  for (std::size_t k = 0; k < ws.size(); ++k) chainFloats += 3 * std::size_t(ws[k]) * hs[k];
  cl::Buffer chain(ctx, CL_MEM_READ_WRITE, chainFloats * 4);
  q.enqueueWriteBuffer(chain, CL_TRUE, 0, env.size() * 4, env.data());
  auto prefilterProgram = rt.program("ibl_prefilter.cl");
  cl::Kernel down(prefilterProgram, "env_downsample");
  std::size_t offset = 0;
  for (std::size_t k = 0; k + 1 < ws.size(); ++k) {
    const std::size_t size = 3 * std::size_t(ws[k]) * hs[k], next = 3 * std::size_t(ws[k + 1]) * hs[k + 1];
    // Sub-buffer offsets need the device's base alignment; copy through temporaries instead.
    cl::Buffer a(ctx, CL_MEM_READ_WRITE, size * 4), b(ctx, CL_MEM_READ_WRITE, next * 4);
    q.enqueueCopyBuffer(chain, a, offset * 4, 0, size * 4);
    down.setArg(0, a);
    down.setArg(1, ws[k]);
    down.setArg(2, hs[k]);
    down.setArg(3, b);
    down.setArg(4, ws[k + 1]);
    down.setArg(5, hs[k + 1]);
    q.enqueueNDRangeKernel(down, cl::NullRange, cl::NDRange(std::size_t(ws[k + 1]), std::size_t(hs[k + 1])));
    q.enqueueCopyBuffer(b, chain, 0, (offset + size) * 4, next * 4);
    offset += size;
  }

  // Prefiltered chains: level k of kPrefilterLevels at roughness k / (levels - 1).
  cl::Kernel pre(prefilterProgram, "env_prefilter");
  // GGX level 0 is the mirror at the map's size; its blurred levels and the whole Charlie chain
  // are no larger than their lobes need, which keeps a 1k or 4k map's first use short.
  auto prefilterChain = [&](int kind) {
    std::vector<float> all;
    const int w0 = kind == 0 ? envW : charlieW(envW), h0 = kind == 0 ? envH : charlieH(envH);
    const int capW = kind == 0 ? BRDFCL_PREFILTER_CAP_W : w0, capH = kind == 0 ? BRDFCL_PREFILTER_CAP_H : h0;
    for (int k = 0; k < kPrefilterLevels; ++k) {
      const int w = levelW(w0, capW, k), h = levelH(h0, capH, k);
      cl::Buffer out(ctx, CL_MEM_WRITE_ONLY, 3 * std::size_t(w) * h * 4);
      pre.setArg(0, chain);
      pre.setArg(1, envW);
      pre.setArg(2, envH);
      pre.setArg(3, int(ws.size()));
      pre.setArg(4, kind);
      pre.setArg(5, float(k) / float(kPrefilterLevels - 1));
      pre.setArg(6, cl_uint(kind == 0 ? (k == 0 ? 1 : 128) : 256));
      pre.setArg(7, out);
      pre.setArg(8, w);
      pre.setArg(9, h);
      q.enqueueNDRangeKernel(pre, cl::NullRange, cl::NDRange(std::size_t(w), std::size_t(h)));
      std::vector<float> level(3 * std::size_t(w) * h);
      q.enqueueReadBuffer(out, CL_TRUE, 0, level.size() * 4, level.data());
      all.insert(all.end(), level.begin(), level.end());
    }
    return all;
  };
  std::vector<float> arrays = prefilterChain(0);
  const std::vector<float> charlie = prefilterChain(1);
  arrays.insert(arrays.end(), charlie.begin(), charlie.end());
  {
    cl::Buffer out(ctx, CL_MEM_WRITE_ONLY, 3 * kIrradianceW * kIrradianceH * 4);
    pre.setArg(0, chain);
    pre.setArg(1, envW);
    pre.setArg(2, envH);
    pre.setArg(3, int(ws.size()));
    pre.setArg(4, 2);
    pre.setArg(5, 1.0f);
    pre.setArg(6, cl_uint(512));
    pre.setArg(7, out);
    pre.setArg(8, kIrradianceW);
    pre.setArg(9, kIrradianceH);
    q.enqueueNDRangeKernel(pre, cl::NullRange, cl::NDRange(kIrradianceW, kIrradianceH));
    std::vector<float> irr(3 * kIrradianceW * kIrradianceH);
    q.enqueueReadBuffer(out, CL_TRUE, 0, irr.size() * 4, irr.data());
    arrays.insert(arrays.end(), irr.begin(), irr.end());
  }

  return arrays;
}

std::shared_ptr<const PreparedLight> prepareLight(Runtime& rt, const Environment& environment, const EvalOptions& options) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const PreparedLight>> cache;
  const EvalOptions table = sheenTableOptions(options);
  const std::string key = fmt::format("{}|{}|{}|{}|{}|{}|{}|{}", static_cast<const void*>(&rt), environment.builtin,
                                      environment.builtinKind, environment.path, environment.intensity,
                                      toString(table.sheenDistribution), toString(table.sheenVisibility),
                                      toString(options.profile));
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  auto prepared = std::make_shared<PreparedLight>();
  auto& s = *prepared;
  const auto env = environmentPlanes(environment, s.envW, s.envH);
  const auto& ctx = rt.context();
  try {
    s.background = readOnly(ctx, env);
    // The prefiltered chains and irradiance depend only on the environment's texels and the
    // prefilter kernel: keyed by both, they come from the disk cache on every run but the first.
    const std::string device = rt.info().name + "|" + rt.info().platform + "|" + rt.info().openclC;
    const std::uint64_t prefilterKey = detail::contentHash(
        env, detail::contentHash(fmt::format("{}|{}|{}x{}|{}|{}x{}", kernelSource("ibl_prefilter.cl"), kPrefilterVersion,
                                             s.envW, s.envH, device, kIrradianceW, kIrradianceH)));
    const std::size_t ggxFloats = chainFloatsOf(s.envW, s.envH, BRDFCL_PREFILTER_CAP_W, BRDFCL_PREFILTER_CAP_H);
    const std::size_t charlieFloats =
        chainFloatsOf(charlieW(s.envW), charlieH(s.envH), charlieW(s.envW), charlieH(s.envH));
    std::vector<float> arrays(ggxFloats + charlieFloats + 3 * kIrradianceW * kIrradianceH);
    const std::string prefilterName = fmt::format("env_{}x{}_{:016x}.f32", s.envW, s.envH, prefilterKey);
    if (!detail::loadCachedFloats(prefilterName, arrays)) {
      arrays = prefilterEnvironment(rt, env, s.envW, s.envH);
      detail::storeCachedFloats(prefilterName, arrays);
    }
    auto part = [&](std::size_t begin, std::size_t count) {
      return readOnly(ctx, std::vector<float>(arrays.begin() + std::ptrdiff_t(begin),
                                              arrays.begin() + std::ptrdiff_t(begin + count)));
    };
    s.ggx = part(0, ggxFloats);
    s.charlie = part(ggxFloats, charlieFloats);
    s.irradiance = part(ggxFloats + charlieFloats, 3 * kIrradianceW * kIrradianceH);

    std::vector<float> dfg(2 * kDfgSize * kDfgSize);
    const std::string dfgName =
        fmt::format("ggx_dfg_{}_{:016x}.f32", kDfgSize, detail::contentHash(kernelSource("lut.cl") + "|" + device));
    if (!detail::loadCachedFloats(dfgName, dfg)) {
      dfg = bakeLut(rt, LutKind::GgxDfg, kDfgSize).values;
      detail::storeCachedFloats(dfgName, dfg);
    }
    s.dfg = readOnly(ctx, dfg);
    const auto e = cachedSheenAlbedo(rt, table.sheenDistribution, table.sheenVisibility);
    std::vector<float> tables = e.values;
    // Engine profiles read three.js's DFG table right after the E table, and khronos the Sample
    // Renderer's sheen albedo texture after that (docs/profiles.md "Tables").
    if (options.profile != Profile::Spec) tables.insert(tables.end(), threejsDfgTable().begin(), threejsDfgTable().end());
    if (options.profile == Profile::Khronos)
      tables.insert(tables.end(), khronosSheenETable().begin(), khronosSheenETable().end());
    s.sheenE = readOnly(ctx, tables);
    s.sheenESize = int(e.width);
    std::vector<float> fl(kFresnelLambertSize);
    for (int i = 0; i < kFresnelLambertSize; ++i) fl[i] = float(fresnelWeightedLambert(double(i) / (kFresnelLambertSize - 1)));
    s.fresnelLambert = readOnly(ctx, fl);
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing image-based light");
  }
  cache.emplace(key, prepared);
  return prepared;
}
}  // namespace

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
  if (!needed) return readOnly(rt.context(), std::vector<float>(2, 0.0f));
  return tables.emplace(&rt, readOnly(rt.context(), cachedAnisotropicDfg(rt))).first->second;
}
}  // namespace

Image Shader::shade(const GBuffer& g) { return shade(g, ShadeOptions{}, nullptr); }

Image Shader::shade(const GBuffer& g, const ShadeOptions& options, ShadeStats* stats) {
  auto& s = *s_;
  const bool exact = options.ibl == IblMode::Exact;
  if (exact) checkIblSamples(options.iblSamples);
  if (exact && s.options.profile != Profile::Spec)
    throw Error(fmt::format("--ibl exact integrates the spec's BRDF only; --profile {} reproduces its engine's own "
                            "image-based light, so use --ibl split-sum with it",
                            toString(s.options.profile)));
  auto& planes = s.planes;
  gbufferPlanes(g, planes);
  Image img;
  img.width = g.width;
  img.height = g.height;
  const std::size_t np = std::size_t(g.width) * g.height;
  std::vector<float> out(3 * np);
  // Rows [rowBegin, rowEnd) on one device's state, in bands, into `out`. Each pixel's value
  // depends on the pixel alone, so any split of the rows gives the same bytes.
  auto shadeRows = [&](State& st, int rowBegin, int rowEnd, bool report) {
    const auto& ctx = st.rt.context();
    // Bands of rows keep every buffer below the device's largest allocation (any image size the
    // host can hold); the device copy of a band is kept between frames of one size.
    const int band = std::min(bandRows(st.rt.info(), g.width, GB_PLANES * sizeof(float)), rowEnd - rowBegin);
    const std::size_t bandFloats = std::size_t(GB_PLANES) * g.width * band;
    if (st.planesOnDevice.first != bandFloats) {
      st.planesOnDevice = {bandFloats, cl::Buffer(ctx, CL_MEM_READ_ONLY, bandFloats * 4)};
    }
    cl::Buffer& bg = st.planesOnDevice.second;
    cl::Buffer bo(ctx, CL_MEM_WRITE_ONLY, 3 * std::size_t(g.width) * band * 4);
    cl::Kernel k(st.program, "shade");
    // Held until the launch is done: a kernel argument does not keep its buffer alive.
    const cl::Buffer aniso = anisotropicDfgFor(st.rt, g);
    int a = 0;
    k.setArg(a++, bg);
    k.setArg(a++, g.width);
    k.setArg(a++, g.height);
    const int bandArg = a;  // y0, then the band's rows: set per band below
    a += 2;
    k.setArg(a++, st.scene.hasCamera || !g.camera ? cameraFor(st.scene, g.width, g.height)
                                                   : cameraFor(*g.camera, g.width, g.height));
    k.setArg(a++, st.lights);
    k.setArg(a++, st.lightCount);
    k.setArg(a++, st.light->background);
    k.setArg(a++, st.light->ggx);
    k.setArg(a++, st.light->charlie);
    k.setArg(a++, st.light->irradiance);
    k.setArg(a++, st.light->envW);
    k.setArg(a++, st.light->envH);
    k.setArg(a++, charlieW(st.light->envW));
    k.setArg(a++, charlieH(st.light->envH));
    k.setArg(a++, kPrefilterLevels);
    k.setArg(a++, kIrradianceW);
    k.setArg(a++, kIrradianceH);
    k.setArg(a++, st.scene.environment.rotation);
    k.setArg(a++, st.light->dfg);
    k.setArg(a++, kDfgSize);
    k.setArg(a++, aniso);
    k.setArg(a++, st.light->sheenE);
    k.setArg(a++, st.light->sheenESize);
    k.setArg(a++, st.light->fresnelLambert);
    k.setArg(a++, kFresnelLambertSize);
    k.setArg(a++, exact ? 0 : 1);
    k.setArg(a++, bo);
    auto& q = st.rt.queue();
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
      if (report && !exact && options.progress)
        options.progress((y0 - rowBegin) / band + 1, (rowEnd - rowBegin + band - 1) / band);
    }
  };
  try {
    const auto& ctx = s.rt.context();
    // Under mpirun, this rank's rows (ShadeOptions::firstRow, rowCount); the exact integrator's
    // split-sum pass always covers the whole frame.
    const int yBegin = exact ? 0 : std::clamp(options.firstRow, 0, g.height);
    const int yEnd = exact || options.rowCount < 0 ? g.height : std::min(g.height, yBegin + options.rowCount);
    if (peers_.empty()) {
      shadeRows(s, yBegin, yEnd, true);
    } else {
      // Row bands across the devices (DeviceSet); progress counts devices done.
      std::mutex progressMutex;
      int done = 0;
      devices_->run(std::size_t(yEnd - yBegin), 1, [&](std::size_t dev, std::size_t first, std::size_t count) {
        shadeRows(dev == 0 ? s : *peers_[dev - 1]->s_, yBegin + int(first), yBegin + int(first + count), false);
        std::lock_guard<std::mutex> lock(progressMutex);
        if (!exact && options.progress) options.progress(++done, int(devices_->size()));
      });
    }
    if (exact && !s.exactReady) {
      // The CDFs come from the full-resolution map the kernel reads, as it is on the device.
      std::vector<float> env(3 * std::size_t(s.light->envW) * s.light->envH);
      s.rt.queue().enqueueReadBuffer(s.light->background, CL_TRUE, 0, env.size() * 4, env.data());
      const auto cdf = detail::environmentCdf(env, s.light->envW, s.light->envH);
      s.envRows = readOnly(ctx, cdf.rows);
      s.envCols = readOnly(ctx, cdf.cols);
      s.envTexelP = readOnly(ctx, cdf.texelP);
      s.envShare = cdf.share;
      FeatureSet all;
      all.sheen = all.ratifiedSheen = all.clearcoat = all.anisotropy = true;
      EvalOptions o = s.options;
      o.lobe = Lobe::All;
      s.exactProgram = s.rt.program("ibl_exact.cl", materialDefines(o, all));
      s.exactReady = true;
    }
  } catch (const cl::Error&) {
    rethrowOpenCL("shading the G-buffer");
  }
  if (exact) {
    // The exact integrator reads the whole frame's planes: the split-sum pass's device copy when
    // it held the frame in one band, else a copy of its own, which must fit one allocation.
    cl::Buffer whole;
    if (s.planesOnDevice.first == planes.size()) {
      whole = s.planesOnDevice.second;
    } else {
      if (planes.size() * 4 > s.rt.info().maxAlloc)
        throw Error(fmt::format("--ibl exact: a {}x{} G-buffer needs a {:.1f} GiB device buffer, but '{}' allows {:.1f} GiB; "
                                "use a smaller --size or --ibl split-sum",
                                g.width, g.height, double(planes.size() * 4) / (1u << 30), s.rt.info().name,
                                double(s.rt.info().maxAlloc) / (1u << 30)));
      try {
        whole = readOnly(s.rt.context(), planes);
      } catch (const cl::Error&) {
        rethrowOpenCL("preparing the exact image-based light");
      }
    }
    detail::ExactIblInputs in;
    in.program = s.exactProgram;
    in.gbuffer = &whole;
    in.width = g.width;
    in.height = g.height;
    in.camera = s.scene.hasCamera || !g.camera ? cameraFor(s.scene, g.width, g.height) : cameraFor(*g.camera, g.width, g.height);
    in.environment = &s.light->background;
    in.rows = &s.envRows;
    in.cols = &s.envCols;
    in.texelP = &s.envTexelP;
    in.envW = s.light->envW;
    in.envH = s.light->envH;
    in.envShare = s.envShare;
    in.rotation = s.scene.environment.rotation;
    in.sheenE = &s.light->sheenE;
    in.sheenESize = s.light->sheenESize;
    detail::integrateExactIbl(s.rt, in, planes, options, out, stats);
  }
  img.rgb.resize(3 * np);
  for (std::size_t i = 0; i < np; ++i)
    for (int c = 0; c < 3; ++c) img.rgb[3 * i + c] = out[c * np + i];
  return img;
}

}  // namespace brdfcl
