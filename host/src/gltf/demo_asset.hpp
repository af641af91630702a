// The demo scene as a self-contained binary glTF: the built-in 6x6 sphere sweep of spheresScene()
// and renderSpheresGBuffer() (same layout, camera, lights and material factors), as UV-sphere
// meshes with procedural textures in the sheen, clearcoat and anisotropy slots.
#pragma once
#include <string>

namespace brdfcl::gltf {

// Writes the demo asset to `path` (.glb), atomically: on failure no file (partial or temporary) is
// left and a one-line brdfcl::Error names the path. What it holds:
//  - 36 nodes at ((col - 2.5) * 1.05, (2.5 - row) * 1.05, 0), each with its own mesh (one
//    primitive, its own material) over shared accessors: a radius-0.46 UV sphere, 64 x 32
//    segments, u around +Y (u = 0.5 faces +Z, the seam at the back), v = 0 at the north pole
//    (glTF UVs: v grows downwards in the image); TANGENT = dP/du, w = +1 (bitangent towards -v).
//  - a perspective camera node at (0, 0, 13) looking down -Z (yfov 30 degrees, aspect 1) and
//    KHR_lights_punctual: the key (directional along normalize(0.5, -0.6, -0.62), 2.5, colour
//    (1, 0.96, 0.9)) and the fill (point at (-6, 2, 6), 30, colour (0.8, 0.85, 1)).
//  - textures (PNG, in the BIN chunk):
//    rows 0-1, "cloth" 128x128 RGBA, plain weave of 4 x 4 threads: RGB sRGB colour (warp and
//      weft tinted differently, dark gaps) as sheenColorTexture, A roughness (1 on threads, 0.5 in
//      gaps) as sheenRoughnessTexture, KHR_texture_transform scale (8, 4), repeat, trilinear;
//    row 2, "flakes" 256x256 RGB tangent-space normals, 8x8-texel cells tilted by up to 12
//      degrees, as clearcoatNormalTexture, scale (2, 1), repeat, nearest magnification;
//    rows 3-4, "brushed" 256x256 RGB anisotropyTexture: RG directions along circles around
//      UV (0.5, 0.5) (the point facing the camera; circles measured on the sphere, where u spans
//      twice the length of v), each ring one texel wide turned by up to +-4 degrees (streaks),
//      B strength 1; clamped, trilinear;
//    row 5 uses factors only.
void writeDemoAsset(const std::string& path);

}  // namespace brdfcl::gltf
