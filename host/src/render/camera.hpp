// The kernels' camera (brdfcl_camera) from a scene or a G-buffer, and back; shared by the spheres
// G-buffer, the shader and the camera warnings.
#pragma once
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/scene.hpp"
#include "io/vec3.hpp"
#include "kernels/common/shading_layout.h"

namespace brdfcl::detail {

// a / |a|, unchecked: the scene reader refuses a camera whose target is its position.
Imath::V3f normalized(const Imath::V3f& a);

brdfcl_camera cameraFor(const Scene& s, int w, int h);
// A G-buffer's camera as it is; its fov goes through the same float expression as a scene's, so
// a spheres G-buffer shades exactly as with the scene that made it.
brdfcl_camera cameraFor(const GBufferCamera& g, int w, int h);
GBufferCamera gbufferCamera(const brdfcl_camera& c, float fovDegrees);

}  // namespace brdfcl::detail
