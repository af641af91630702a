// The anisotropic GGX split-sum table the shader's image-based light reads for anisotropic
// pixels: baked once on the device (kernels/aniso_dfg.cl) and kept in the disk cache.
#pragma once
#include <vector>

#include "brdfcl/runtime.hpp"

namespace brdfcl {

// A, B interleaved over the grid of kernels/common/shading_layout.h (BRDFCL_ANISO_DFG_*):
// F0 A + B is the directional albedo of the anisotropic specular lobe with Schlick's Fresnel.
// tPerPanel and phiCount set the quadrature (the tests raise them to show convergence).
std::vector<float> bakeAnisotropicDfg(Runtime& rt, int tPerPanel = 5, int phiCount = 48);

// The table from the disk cache, baked and stored on first use.
std::vector<float> cachedAnisotropicDfg(Runtime& rt);

}  // namespace brdfcl
