// Directional albedo a(V) = integral of f(L, V) (N.L) dw_L, by deterministic quadrature over L
// evaluated on the device: the energy figure that the demo prints and the furnace tests bound.
#pragma once
#include <vector>

#include "brdfcl/evaluator.hpp"

namespace brdfcl {

// For each material and each cosine in `viewCosines` (V in the XZ plane, N.V = mu), the RGB
// albedo of the evaluator's lobe. Result: materials x viewCosines x 3, material-major.
std::vector<float> directionalAlbedo(Evaluator& evaluator, const std::vector<MaterialParams>& materials,
                                     const std::vector<float>& viewCosines);

}  // namespace brdfcl
