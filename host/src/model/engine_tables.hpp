// Tables the engine profiles read besides the sheen E table: three.js's published DFG table,
// decoded once from the half floats it ships as, and the glTF Sample Renderer's sheen albedo
// texture as the 8-bit texels a GPU holds, Babylon's BRDF texture as the half floats its RGBD
// expansion writes (docs/profiles.md "Tables").
#pragma once
#include <vector>

namespace brdfcl {

// BRDFCL_DFG_SIZE^2 texels of (A, B), rows = N.V, columns = perceptual roughness.
const std::vector<float>& threejsDfgTable();

// BRDFCL_KHRONOS_SHEEN_E_SIZE^2 texels of lut_sheen_E.png's red channel, each unorm8 / 255 as a
// GPU converts it; rows = sheen roughness, columns = N.V, the PNG's first row first.
const std::vector<float>& khronosSheenETable();

// BRDFCL_BABYLON_BRDF_SIZE^2 texels of Babylon's environment BRDF texture, 3 floats each (.x, .y,
// .b) as its RGBD expansion holds them in half float; rows = perceptual roughness, columns = N.V.
const std::vector<float>& babylonBrdfTable();

}  // namespace brdfcl
