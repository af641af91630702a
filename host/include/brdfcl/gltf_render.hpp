// Rendering a loaded glTF asset into G-buffers: camera choice (a glTF camera or the automatic
// three-quarter view), Embree ray casting of primary rays, and texture sampling with mip-maps
// and ray-cone footprints. Implemented in host/src/gltf/{camera,raycast,texture,surface}.cpp.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <string>

#include "brdfcl/gbuffer.hpp"
#include "brdfcl/gltf.hpp"

namespace brdfcl::gltf {

// The primary-ray camera in world space. A pixel position (px, py), from the top-left corner in
// pixels, maps to s = 2 px / width - 1, t = 1 - 2 py / height; perspective rays leave `position`
// along normalize(forward + s tanHalfFovY aspect right + t tanHalfFovY up); orthographic rays
// leave position + s halfHeight aspect right + t halfHeight up, along forward.
struct View {
  bool orthographic = false;
  std::array<double, 3> position{0, 0, 0}, right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, -1};
  double tanHalfFovY = 0.4142135623730951;  // perspective
  double halfHeight = 1.0;                   // orthographic: ymag
  double aspect = 16.0 / 9.0;                // width / height of the image plane
  double znear = 0.0, zfar = 0.0;            // rays start at znear (along the ray); zfar 0 = infinite
  std::string description;                   // "cameras[0] 'Camera' (node 3)" or "auto"
};

// cameraArg: "" = the first camera node of the scene, else "auto"; "auto" = the automatic
// view (docs/gltf.md); a number = that glTF camera index, wherever its node is. Throws a one-line
// brdfcl::Error for an index that no node of the scene uses, or an unparsable argument.
View chooseView(const Asset& asset, const std::string& cameraArg, int width, int height);

// The default image size for a camera: 1280x720, or the camera's aspect ratio (perspective
// aspectRatio, orthographic xmag/ymag) at 720 rows.
void defaultSize(const Asset& asset, const std::string& cameraArg, int& width, int& height);

// Builds the ray-tracing scene (Embree) and the textures' mip chains once; trace() is then
// const and may be called for many views and sub-pixel offsets.
class Raycaster {
 public:
  explicit Raycaster(const Asset& asset);
  ~Raycaster();
  Raycaster(const Raycaster&) = delete;
  Raycaster& operator=(const Raycaster&) = delete;

  // One primary ray per pixel through (x + jx, y + jy), jx, jy in [0, 1); (0.5, 0.5) is the
  // pixel centre. The G-buffer holds every channel of docs/gbuffer.md, V included; mask 0 where
  // the ray leaves the scene.
  GBuffer trace(const View& view, int width, int height, float jx = 0.5f, float jy = 0.5f) const;
  // The same into `out`, reusing its channels' memory when it already holds a G-buffer of this
  // size (a 1080p G-buffer is 270 MB: fresh pages cost the kernel page faults and zeroing).
  void trace(const View& view, int width, int height, float jx, float jy, GBuffer& out) const;

  // Memory held by the textures' mip chains (8 or 16 bits per channel, only the channels some
  // slot reads). The Raycaster keeps its own copies: the Asset may be destroyed after construction.
  std::size_t textureBytes() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace brdfcl::gltf
