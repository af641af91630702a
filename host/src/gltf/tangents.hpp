// Per-vertex tangent generation for primitives whose file has no TANGENT but whose material needs
// a tangent frame: brdfcl's own implementation of the MikkTSpace approach (see tangents.cpp).
#pragma once
#include "brdfcl/gltf.hpp"

namespace brdfcl::gltf::detail {

// Fills p.tangents (4 per vertex, w = +-1) from p.positions, p.normals (face normals when empty) and
// the UV set `uvSet` (0 or 1, which must be present), and sets p.generatedTangents. A vertex shared
// by triangles of opposite UV handedness (mirrored UVs) is split in two: the copy is appended to
// every per-vertex array and the mirrored triangles' indices point to it. Works in any space; the
// loader calls it before the world transform.
void generateTangents(Primitive& p, int uvSet);

}  // namespace brdfcl::gltf::detail
