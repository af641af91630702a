// Cameras: the kernels' brdfcl_camera from a scene or a G-buffer, and the warnings shade gives
// when a scene's camera and the one that made a G-buffer differ, or when neither has one.
#include "render/camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/render.hpp"

namespace brdfcl {

static_assert(sizeof(brdfcl_camera) == 16 * 4 && offsetof(brdfcl_camera, orthographic) == 44 &&
              offsetof(brdfcl_camera, forward) == 48);

namespace detail {

Imath::V3f normalized(const Imath::V3f& a) { return a / norm(a); }

brdfcl_camera cameraFor(const Scene& s, int w, int h) {
  brdfcl_camera c{};
  const Imath::V3f f = normalized(toVec3(s.cameraTarget) - toVec3(s.cameraPosition));
  const Imath::V3f worldUp = std::fabs(f.y) > 0.999f ? Imath::V3f(0, 0, -1) : Imath::V3f(0, 1, 0);
  const Imath::V3f r = normalized(f % worldUp), u = r % f;
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
}  // namespace detail

using detail::cameraFor;

std::string cameraDifference(const Scene& scene, const GBufferCamera& g) {
  const brdfcl_camera c = cameraFor(scene, 1, 1);
  std::vector<std::string> parts;
  auto degrees = [](double cosine) { return std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI; };
  auto dot3 = [](const float* a, const std::array<float, 3>& b) {
    return Imath::V3d(a[0], a[1], a[2]) ^ Imath::V3d(detail::toVec3(b));
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

}  // namespace brdfcl
