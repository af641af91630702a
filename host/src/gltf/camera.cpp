// Primary-ray views of a glTF asset: its camera nodes (perspective or orthographic) or the
// automatic three-quarter view that frames the world bounding box, and the default image size.
// The automatic view is specified in docs/gltf.md, Rendering.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf_render.hpp"
#include "io/option_style.hpp"
#include "io/vec3.hpp"

namespace brdfcl::gltf {
namespace {

using Imath::V3d;
using ::brdfcl::detail::norm;
using ::brdfcl::detail::toArray;
using ::brdfcl::detail::toVec3;

// v / |v|, or v itself when it has no length.
V3d normalized(const V3d& v) {
  const double len = norm(v);
  return len > 0.0 ? v / len : v;
}

constexpr double kPi = 3.14159265358979323846;
constexpr double kAutoYFov = 40.0 * kPi / 180.0;
constexpr double kAutoMargin = 1.1;  // the bounding sphere fills 1/1.1 of the tighter image axis

// nullptr for "auto" (or "" without cameras); throws for anything else that names no camera.
const Camera* findCamera(const Asset& asset, const std::string& arg) {
  if (arg.empty()) return asset.cameras.empty() ? nullptr : &asset.cameras[0];
  if (arg == "auto") return nullptr;
  const bool digits = arg.size() <= 9 && std::all_of(arg.begin(), arg.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (!digits)
    throw Error(optionWithValue("--camera", "'" + arg + "'") + ": expected auto or a glTF camera index (a number such as 0)");
  const int index = std::stoi(arg);
  for (const Camera& c : asset.cameras)
    if (c.index == index) return &c;
  std::vector<int> used;
  for (const Camera& c : asset.cameras) used.push_back(c.index);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::string available;
  for (int i : used) available += (available.empty() ? " " : ", ") + std::to_string(i);
  throw Error(optionWithValue("--camera", arg, true) + ": no node of the scene uses cameras[" + arg + "]" +
              (available.empty() ? std::string("; the scene has no camera nodes, use auto")
                                 : "; cameras used by the scene:" + available));
}

View autoView(const Asset& asset, int width, int height) {
  View v;
  v.description = "auto";
  const V3d lo = toVec3(asset.boundsMin), hi = toVec3(asset.boundsMax);
  const V3d centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  double radius = norm(half);
  if (!(radius > 0.0) || !std::isfinite(radius)) radius = 1.0;
  v.aspect = static_cast<double>(width) / height;
  v.tanHalfFovY = std::tan(0.5 * kAutoYFov);
  // The sphere fits when its angular radius asin(r / d) is within the tighter half-angle.
  const double halfX = std::atan(v.tanHalfFovY * v.aspect);
  const double halfAngle = std::min(0.5 * kAutoYFov, halfX);
  const double distance = kAutoMargin * radius / std::sin(halfAngle);
  const V3d toEye = normalized(V3d(1.0, 0.6, 1.0));
  const V3d forward = -toEye, right = normalized(forward % V3d(0.0, 1.0, 0.0));
  v.position = toArray(centre + distance * toEye);
  v.forward = toArray(forward);
  v.right = toArray(right);
  v.up = toArray(right % forward);
  v.znear = 1e-3 * radius;
  v.zfar = 0.0;
  return v;
}

}  // namespace

View chooseView(const Asset& asset, const std::string& cameraArg, int width, int height) {
  if (width <= 0 || height <= 0)
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) + ": expected positive sizes");
  const Camera* cam = findCamera(asset, cameraArg);
  if (!cam) return autoView(asset, width, height);

  View v;
  const Mat4& m = cam->world;
  // The columns carry the node's scale, which a camera frame ignores; shear is removed too.
  const V3d x = normalized(V3d(m[0], m[1], m[2]));
  const V3d z = normalized(V3d(m[8], m[9], m[10]));
  const V3d right = normalized(x - (x ^ z) * z);
  v.forward = toArray(-z);
  v.right = toArray(right);
  v.up = toArray(z % right);
  if (!((right ^ right) > 0.5) || !((z ^ z) > 0.5))
    throw Error("cameras[" + std::to_string(cam->index) + "] (node " + std::to_string(cam->node) +
                "): the world matrix has a degenerate rotation; the camera has no view direction");
  v.position = {m[12], m[13], m[14]};
  v.orthographic = cam->orthographic;
  v.aspect = static_cast<double>(width) / height;
  const std::string name = "cameras[" + std::to_string(cam->index) + "]";
  if (cam->orthographic) {
    if (!(cam->ymag != 0.0) || !std::isfinite(cam->ymag))
      throw Error(name + ": orthographic ymag " + std::to_string(cam->ymag) + " must be a non-zero number");
    v.halfHeight = std::fabs(cam->ymag);
  } else {
    if (!(cam->yfov > 0.0 && cam->yfov < kPi))
      throw Error(name + ": perspective yfov " + std::to_string(cam->yfov) + " must lie in (0, pi) radians");
    v.tanHalfFovY = std::tan(0.5 * cam->yfov);
  }
  v.znear = cam->znear;
  v.zfar = cam->zfar;
  v.description = "cameras[" + std::to_string(cam->index) + "]" + (cam->name.empty() ? "" : " '" + cam->name + "'") +
                  " (node " + std::to_string(cam->node) + ")";
  return v;
}

void defaultSize(const Asset& asset, const std::string& cameraArg, int& width, int& height) {
  const Camera* cam = findCamera(asset, cameraArg);
  width = 1280;
  height = 720;
  double aspect = 0.0;
  if (cam) aspect = cam->orthographic ? (cam->ymag != 0.0 ? std::fabs(cam->xmag / cam->ymag) : 0.0) : cam->aspectRatio;
  if (aspect > 0.0 && std::isfinite(aspect)) width = std::max(1, static_cast<int>(std::lround(720.0 * aspect)));
}

}  // namespace brdfcl::gltf
