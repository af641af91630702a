// Environment images: the built-in procedural sky, studio and uniform (furnace) environments, or
// an equirectangular EXR or Radiance HDR file, in the layout of kernels/common/environment.h
// (3 planes, v = 0 at +Y).
#include <algorithm>
#include <cmath>
#include <mutex>
#include <set>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/render.hpp"
#include "eval/quadrature.hpp"
#include "io/disk_cache.hpp"

namespace brdfcl {

namespace {
struct Dir {
  double x, y, z;
};

// The inverse of env_uv (kernels/common/environment.h) at a texel centre.
Dir texelDirection(int x, int y, int w, int h) {
  const double u = (x + 0.5) / w, v = (y + 0.5) / h;
  const double phi = (u - 0.5) * 2 * M_PI, theta = v * M_PI;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

constexpr double kSoftEdge = 0.03;

// How far inside an edge a point is, from 0 (kSoftEdge / 2 outside) to 1 (kSoftEdge / 2 inside):
// smoothstep of the signed distance `t`, positive inside.
double inside(double t) {
  const double x = std::clamp(t / kSoftEdge + 0.5, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

void builtinRadiance(const std::string& kind, Dir d, float rgb[3]) {
  if (kind == "uniform") {
    rgb[0] = rgb[1] = rgb[2] = 1.0f;
    return;
  }
  if (kind == "sky") {
    // Horizon-to-zenith gradient, a warm ground, and a small bright sun.
    const double t = std::max(0.0, d.y);
    const double sky[3] = {0.9 - 0.65 * t, 0.95 - 0.5 * t, 1.0 - 0.15 * t};
    const double ground[3] = {0.18, 0.16, 0.14};
    const Dir sun = {0.4 / 0.883, 0.6 / 0.883, 0.5 / 0.883};
    const double cosSun = d.x * sun.x + d.y * sun.y + d.z * sun.z;
    for (int c = 0; c < 3; ++c) rgb[c] = float(d.y >= 0 ? sky[c] : ground[c]);
    if (cosSun > std::cos(0.035)) rgb[0] += 400.0f, rgb[1] += 380.0f, rgb[2] += 340.0f;
    return;
  }
  // Studio: dim walls, a large overhead softbox in front, two vertical strips, a darker floor.
  // Each light's edges ramp over kSoftEdge in direction components (about 2.5 texels of the
  // 512x256 map): a hard edge steps from texel to texel, and mirror-like surfaces show the steps.
  double v = d.y >= 0 ? 0.06 : 0.03;
  const double softbox = inside(d.y - 0.55) * inside(d.z - 0.1) * inside(0.45 - std::fabs(d.x));
  v += (6.0 - v) * softbox;
  const double strip =
      inside(0.5 - std::fabs(d.y)) * inside(0.08 - std::fabs(std::fabs(d.x) - 0.85)) * inside(0.2 - d.z);
  v += (3.0 - v) * strip;
  for (int c = 0; c < 3; ++c) rgb[c] = float(v);
}
}  // namespace

std::vector<float> environmentPlanes(const Environment& env, int& width, int& height) {
  std::vector<float> planes;
  if (env.builtin) {
    if (env.builtinKind != "sky" && env.builtinKind != "studio" && env.builtinKind != "uniform")
      throw Error(fmt::format("unknown built-in environment '{}'; use sky, studio or uniform", env.builtinKind));
    width = 512;
    height = 256;
    const std::size_t n = std::size_t(width) * height;
    planes.assign(3 * n, 0.0f);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        float rgb[3];
        builtinRadiance(env.builtinKind, texelDirection(x, y, width, height), rgb);
        for (int c = 0; c < 3; ++c) planes[c * n + std::size_t(y) * width + x] = rgb[c] * env.intensity;
      }
    return planes;
  }
  const auto rgb = readEnvironmentRgb(env.path, width, height);
  if (width < 8 || height < 4)
    throw Error(fmt::format("{}: environment of {}x{} texels is too small; use at least 8x4", env.path, width, height));
  // Any size maps onto the sphere, so another shape is no error; but a picture that is not 2:1
  // (a render, a photo) is stretched over it, which is seldom what was meant.
  // Once per file and process: a render under two profiles reads the environment twice.
  static std::mutex warnedMutex;
  static std::set<std::string> warned;
  std::unique_lock<std::mutex> lock(warnedMutex);
  if (width != 2 * height && warned.insert(env.path).second)
    detail::cacheWarning(fmt::format("{}: environment of {}x{} texels is not 2:1; it is read as an equirectangular "
                                     "map (longitude across, latitude down) and stretched to fit",
                                     env.path, width, height));
  lock.unlock();
  const std::size_t n = std::size_t(width) * height;
  planes.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    // Lossy EXR compression (DWAA/DWAB) rings slightly below zero (to -0.004 in Blender's studio
    // lights); negative radiance has no meaning and would make dark pixels negative.
    for (int c = 0; c < 3; ++c) planes[c * n + i] = std::max(rgb[3 * i + c], 0.0f) * env.intensity;
  return planes;
}

double fresnelWeightedLambert(double mu) {
  mu = std::max(mu, 1e-4);
  const double V[3] = {std::sqrt(1 - mu * mu), 0.0, mu};
  static const auto cosRule = compositeGaussLegendre({0.0, 0.1, 0.4, 0.7, 1.0}, 16);
  static const auto phiRule = compositeGaussLegendre({0.0, M_PI / 2, M_PI}, 24);
  double acc = 0;
  for (std::size_t i = 0; i < cosRule.nodes.size(); ++i) {
    const double u = cosRule.nodes[i], s = std::sqrt(1 - u * u);
    for (std::size_t j = 0; j < phiRule.nodes.size(); ++j) {
      const double L[3] = {s * std::cos(phiRule.nodes[j]), s * std::sin(phiRule.nodes[j]), u};
      double H[3], len = 0;
      for (int c = 0; c < 3; ++c) H[c] = L[c] + V[c], len += H[c] * H[c];
      len = std::sqrt(len);
      const double vh = (V[0] * H[0] + V[1] * H[1] + V[2] * H[2]) / len;
      acc += 2 * cosRule.weights[i] * phiRule.weights[j] * std::pow(1 - vh, 5) * u / M_PI;
    }
  }
  return acc;
}

}  // namespace brdfcl
