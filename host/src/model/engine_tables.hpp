// Tables the engine profiles read besides the sheen E table: three.js's published DFG table,
// decoded once from the half floats it ships as, and the glTF Sample Renderer's sheen albedo
// texture as the 8-bit texels a GPU holds (docs/profiles.md "Tables").
#pragma once
#include <vector>

namespace brdfcl {

// BRDFCL_DFG_SIZE^2 texels of (A, B), rows = N.V, columns = perceptual roughness.
const std::vector<float>& threejsDfgTable();

// BRDFCL_KHRONOS_SHEEN_E_SIZE^2 texels of lut_sheen_E.png's red channel, each unorm8 / 255 as a
// GPU converts it; rows = sheen roughness, columns = N.V, the PNG's first row first.
const std::vector<float>& khronosSheenETable();

}  // namespace brdfcl
