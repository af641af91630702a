// Baking and caching of the anisotropic split-sum table. The t rule is graded towards t = 1,
// where the half vector turns grazing and the visibility cut moves fastest.
#include "render/aniso_dfg.hpp"

#include <fmt/format.h>

#include "common/shading_layout.h"
#include "eval/quadrature.hpp"
#include "io/disk_cache.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {
constexpr int kTexels = BRDFCL_ANISO_DFG_NV * BRDFCL_ANISO_DFG_R * BRDFCL_ANISO_DFG_S * BRDFCL_ANISO_DFG_PSI;
// Part of the cache key with the kernel source: bump when the rule below changes.
constexpr const char* kRuleVersion = "t-graded-9 GL5 phi48 v1";
}  // namespace

std::vector<float> bakeAnisotropicDfg(Runtime& rt, int tPerPanel, int phiCount) {
  const auto rule = compositeGaussLegendre({0.0, 0.5, 0.75, 0.9, 0.96, 0.99, 0.997, 0.9995, 0.99995, 1.0}, tPerPanel);
  const std::vector<float> nodes(rule.nodes.begin(), rule.nodes.end()), weights(rule.weights.begin(), rule.weights.end());
  std::vector<float> out(2 * std::size_t(kTexels));
  try {
    auto program = rt.opencl().program("aniso_dfg.cl");
    const auto& ctx = rt.opencl().context();
    const auto ro = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
    cl::Buffer bn(ctx, ro, nodes.size() * 4, const_cast<float*>(nodes.data()));
    cl::Buffer bw(ctx, ro, weights.size() * 4, const_cast<float*>(weights.data()));
    cl::Buffer bo(ctx, CL_MEM_WRITE_ONLY, out.size() * 4);
    cl::Kernel k(program, "bake_aniso_dfg");
    int a = 0;
    for (int v : {BRDFCL_ANISO_DFG_NV, BRDFCL_ANISO_DFG_R, BRDFCL_ANISO_DFG_S, BRDFCL_ANISO_DFG_PSI}) k.setArg(a++, v);
    k.setArg(a++, bn);
    k.setArg(a++, bw);
    k.setArg(a++, int(nodes.size()));
    k.setArg(a++, phiCount);
    k.setArg(a++, bo);
    rt.opencl().queue().enqueueNDRangeKernel(k, cl::NullRange,
                                    cl::NDRange(BRDFCL_ANISO_DFG_NV, BRDFCL_ANISO_DFG_R, BRDFCL_ANISO_DFG_S * BRDFCL_ANISO_DFG_PSI));
    rt.opencl().queue().enqueueReadBuffer(bo, CL_TRUE, 0, out.size() * 4, out.data());
  } catch (const cl::Error&) {
    rethrowOpenCL("baking the anisotropic DFG table");
  }
  return out;
}

std::vector<float> cachedAnisotropicDfg(Runtime& rt) {
  const std::string name = fmt::format(
      "aniso_dfg_{}x{}x{}x{}_{:016x}.f32", BRDFCL_ANISO_DFG_NV, BRDFCL_ANISO_DFG_R, BRDFCL_ANISO_DFG_S,
      BRDFCL_ANISO_DFG_PSI,
      detail::contentHash(kernelSource("aniso_dfg.cl") + kRuleVersion + rt.info().name + "|" + rt.info().platform));
  std::vector<float> table(2 * std::size_t(kTexels));
  if (detail::loadCachedFloats(name, table)) return table;
  table = bakeAnisotropicDfg(rt);
  detail::storeCachedFloats(name, table);
  return table;
}

}  // namespace brdfcl
