// Tables the engine profiles read besides the sheen E table: three.js's published DFG table,
// decoded once from the half floats it ships as (docs/profiles.md "Tables").
#pragma once
#include <vector>

namespace brdfcl {

// BRDFCL_DFG_SIZE^2 texels of (A, B), rows = N.V, columns = perceptual roughness.
const std::vector<float>& threejsDfgTable();

}  // namespace brdfcl
