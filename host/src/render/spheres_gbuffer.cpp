// The built-in spheres scene (a 6x6 sweep of sheen, clearcoat, anisotropy and metal) and its
// G-buffer, ray-cast on the device by kernels/gbuffer_spheres.cl.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/render.hpp"
#include "kernels/common/shading_layout.h"
#include "render/camera.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

static_assert(sizeof(brdfcl_sphere) == 20 * 4 && offsetof(brdfcl_sphere, anisotropy_rotation) == 64);

using detail::cameraFor;
using detail::gbufferCamera;
using detail::normalized;

Scene spheresScene() {
  Scene s;
  s.hasCamera = true;
  s.cameraPosition = {0.0f, 0.0f, 13.0f};
  s.cameraTarget = {0.0f, 0.0f, 0.0f};
  s.fovDegrees = 30.0f;
  Light key;
  key.type = Light::Type::Directional;
  key.direction = detail::toArray(normalized({0.5f, -0.6f, -0.62f}));
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

namespace {
// The 6 x 6 spheres of the built-in scene: a row per material feature, varied along the row.
std::vector<brdfcl_sphere> sphereGrid() {
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
  return spheres;
}

// The G-buffer planes (GB_PLANES of width x height) of `spheres` ray-cast on the device, in bands
// of rows that fit its largest allocation.
std::vector<float> castSpheres(Runtime& rt, const Scene& scene, std::vector<brdfcl_sphere> spheres, int width,
                               int height) {
  const std::size_t np = std::size_t(width) * height;
  std::vector<float> planes(GB_PLANES * np);
  try {
    auto program = rt.opencl().program("gbuffer_spheres.cl");
    cl::Buffer bs(rt.opencl().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, spheres.size() * sizeof(brdfcl_sphere),
                  spheres.data());
    const int band = bandRows(rt.info(), width, GB_PLANES * sizeof(float));
    cl::Buffer out(rt.opencl().context(), CL_MEM_WRITE_ONLY, std::size_t(GB_PLANES) * width * std::min(band, height) * 4);
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
      rt.opencl().queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(std::size_t(width), std::size_t(rows)));
      for (int plane = 0; plane < GB_PLANES; ++plane)
        rt.opencl().queue().enqueueReadBuffer(out, CL_FALSE, plane * bandPixels * 4, bandPixels * 4,
                                     planes.data() + plane * np + std::size_t(y0) * width);
      rt.opencl().queue().finish();
    }
  } catch (const cl::Error&) {
    rethrowOpenCL("ray-casting the spheres scene");
  }
  return planes;
}

// The G-buffer held in `planes` (the kernel's plane order, layout shading_layout.h).
GBuffer gbufferFromPlanes(const std::vector<float>& planes, int width, int height) {
  const std::size_t np = std::size_t(width) * height;
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
  return g;
}
}  // namespace

GBuffer renderSpheresGBuffer(Runtime& rt, const Scene& scene, int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error(fmt::format("image size {}x{} is out of range; use 1 to 16384 per side", width, height));
  GBuffer g = gbufferFromPlanes(castSpheres(rt, scene, sphereGrid(), width, height), width, height);
  // Rays start 1e-4 along the ray (the kernel's hit threshold), a bound too small to record.
  g.camera = gbufferCamera(cameraFor(scene, width, height), scene.fovDegrees);
  return g;
}

}  // namespace brdfcl
