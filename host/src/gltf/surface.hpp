// Material evaluation at a ray hit: vertex attribute interpolation, the tangent frame, every
// texture slot of glTF 2.0 and KHR_materials_{sheen,clearcoat,anisotropy,emissive_strength},
// decoded into G-buffer values; and the any-hit test (back-face culling, alpha cut-outs).
#pragma once
#include <array>
#include <cstdint>

#include "brdfcl/gltf.hpp"
#include "gltf/texture.hpp"

namespace brdfcl::gltf {

// A candidate intersection: triangle `tri` of primitive `prim` at Embree's barycentrics
// (u, v = weights of vertices 1 and 2), seen along the unit direction `dir` by a ray cone of
// width `coneWidth` there.
struct Hit {
  int prim = 0;
  unsigned tri = 0;
  float u = 0.0f, v = 0.0f;
  std::array<float, 3> dir{0.0f, 0.0f, -1.0f};
  float coneWidth = 0.0f;
};

// One pixel's G-buffer values (docs/gbuffer.md), world space.
struct SurfacePoint {
  std::array<float, 3> P{}, N{}, T{}, baseColor{}, emissive{}, sheenColor{}, clearcoatN{};
  float metallic = 0, roughness = 0, sheenRoughness = 0, clearcoat = 0, clearcoatRoughness = 0;
  float anisotropyStrength = 0, anisotropyRotation = 0, occlusion = 1;
};

class Surfaces {
 public:
  // Keeps references to asset.primitives/materials and to textures: both must outlive this.
  Surfaces(const Asset& asset, const Textures& textures);

  // Whether a hit on this primitive may be rejected (single-sided or alpha-tested material),
  // i.e. whether its geometry needs an intersection filter.
  bool mayReject(int prim) const;
  // False for a back face of a single-sided material and for a texel below the alpha cutoff
  // (MASK: alphaCutoff, BLEND: 0.5): the ray goes on through.
  bool accepts(const Hit& hit) const;
  SurfacePoint evaluate(const Hit& hit) const;

 private:
  const Material& material(int prim) const;
  const Asset& asset_;
  const Textures& textures_;
  Material default_;
};

}  // namespace brdfcl::gltf
