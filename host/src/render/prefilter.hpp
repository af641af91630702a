// The light a Shader reads from its environment, prepared once per (runtime, environment, sheen
// options): the prefiltered GGX and Charlie chains and the irradiance map, and the tables (GGX
// DFG, sheen albedo, Fresnel-weighted Lambert).
#pragma once
#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/render.hpp"
#include "runtime/opencl.hpp"
#include "kernels/common/shading_layout.h"

namespace brdfcl::detail {

inline constexpr int kPrefilterLevels = 6;  // roughness 0, 0.2, ..., 1
inline constexpr int kIrradianceW = 64, kIrradianceH = 32;
inline constexpr int kDfgSize = 64, kFresnelLambertSize = 64;

// The Charlie chain's level-0 size for a map of w x h (kernels/common/shading_layout.h).
inline int charlieW(int w) { return std::min(w, BRDFCL_CHARLIE_W); }
inline int charlieH(int h) { return std::min(h, BRDFCL_CHARLIE_H); }

// Everything the shader derives from the environment and the sheen options: prepared once per
// (runtime, environment, options) and shared by every Shader of the process.
struct PreparedLight {
  int envW = 0, envH = 0;
  cl::Buffer background, ggx, charlie, irradiance, dfg, sheenE, fresnelLambert;
  int sheenESize = 0;
};

std::shared_ptr<const PreparedLight> prepareLight(Runtime& rt, const Environment& environment, const EvalOptions& options);

inline cl::Buffer readOnly(const cl::Context& ctx, const std::vector<float>& v) {
  return cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, std::max<std::size_t>(v.size(), 1) * 4,
                    const_cast<float*>(v.data()));
}

}  // namespace brdfcl::detail
