// Baking of the sheen albedo table E(mu, r) on the device (kernels/sheen_albedo.cl), the
// host-side bilinear lookup that mirrors the kernels' one (kernels/brdf/sheen_albedo.h), and the
// row of one sheenRoughness that the materials of a batch read (Evaluator::prepare).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "eval/quadrature.hpp"
#include "eval/sheen_albedo_bake.hpp"
#include "io/disk_cache.hpp"
#include "model/pack.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {
// Panels graded towards the grazing corner N.L -> 0, where a small-alpha Charlie lobe puts its
// mass, and towards phi = pi (L opposite V).
const std::vector<double> kCosBreaks = {0.0, 1e-3, 1e-2, 0.05, 0.2, 0.5, 1.0};
const std::vector<double> kPhiBreaks = {0.0, M_PI / 2, 3 * M_PI / 4, 7 * M_PI / 8, 15 * M_PI / 16, 31 * M_PI / 32, M_PI};
// Part of the cache key: bump when the quadrature above or the table layout changes.
constexpr const char* kBakeVersion = "graded-GL12 sqrt-warp v2";

// Where sheenRoughness r falls between rows y0 and y0 + 1 of a table of `height` rows, as the
// kernels' E_SheenAlbedoRow places it.
struct RowPosition {
  int y0;
  float fy;
};
RowPosition rowPosition(float r, std::size_t height) {
  const float y = std::sqrt(std::clamp(r, 0.0f, 1.0f)) * float(height - 1);
  const int y0 = std::min(int(y), int(height) - 2);
  return {y0, y - float(y0)};
}
}  // namespace

float SheenAlbedoTable::lookup(float mu, float sheenRoughness) const {
  const float x = std::sqrt(std::clamp(mu, 0.0f, 1.0f)) * float(width - 1);
  const int x0 = std::min(int(x), int(width) - 2);
  const float fx = x - float(x0);
  const auto [y0, fy] = rowPosition(sheenRoughness, height);
  const float* row0 = values.data() + std::size_t(y0) * width + x0;
  const float* row1 = row0 + width;
  const float top = row0[0] + (row0[1] - row0[0]) * fx;
  const float bottom = row1[0] + (row1[1] - row1[0]) * fx;
  return top + (bottom - top) * fy;
}

std::vector<float> SheenAlbedoTable::rowAt(float sheenRoughness) const {
  const auto [y0, fy] = rowPosition(sheenRoughness, height);
  const float* row0 = values.data() + std::size_t(y0) * width;
  const float* row1 = row0 + width;
  std::vector<float> row(width);
  for (std::size_t x = 0; x < width; ++x) row[x] = row0[x] + (row1[x] - row0[x]) * fy;
  return row;
}

SheenAlbedoTable bakeSheenAlbedo(Runtime& rt, SheenDistribution d, SheenVisibility v, std::size_t size,
                                 int nodesPerPanel) {
  return bakeSheenAlbedoFrom(rt, "sheen_albedo.cl", d, v, size, nodesPerPanel);
}

SheenAlbedoTable bakeSheenAlbedoFrom(Runtime& rt, const std::string& kernelFile, SheenDistribution d,
                                     SheenVisibility v, std::size_t size, int nodesPerPanel) {
  if (size < 2) throw Error(fmt::format("sheen albedo table size {} is too small; use at least 2", size));
  SheenAlbedoTable table;
  table.distribution = d;
  table.visibility = v;
  table.width = table.height = size;
  table.values.assign(size * size, 0.0f);

  // phi over [0, pi] with weight x2 (the lobe is symmetric about the plane of V and N).
  auto cosRule = compositeGaussLegendre(kCosBreaks, nodesPerPanel);
  auto phiRule = compositeGaussLegendre(kPhiBreaks, nodesPerPanel);
  std::vector<float> u(cosRule.nodes.begin(), cosRule.nodes.end()), uw(cosRule.weights.begin(), cosRule.weights.end());
  std::vector<float> pc, ps, pw;
  for (std::size_t i = 0; i < phiRule.nodes.size(); ++i) {
    pc.push_back(float(std::cos(phiRule.nodes[i])));
    ps.push_back(float(std::sin(phiRule.nodes[i])));
    pw.push_back(float(2.0 * phiRule.weights[i]));
  }
  // The kernel reads phi nodes 16 lanes at a time: pad with harmless zero-weight nodes.
  while (pc.size() % 16 != 0) {
    pc.push_back(1.0f);
    ps.push_back(0.0f);
    pw.push_back(0.0f);
  }

  EvalOptions o;
  o.sheenDistribution = d;
  o.sheenVisibility = v;
  FeatureSet f;
  f.sheen = true;
  try {
    // 16 lanes on every device, whatever laneShape() says: the lanes sum the phi nodes, so the
    // width sets the order of the sum and with it the last bits of the table (and its cache key).
    auto program = rt.opencl().program(kernelFile, materialDefines(o, f) + " -DBRDFCL_W=16");
    const auto& ctx = rt.opencl().context();
    auto ro = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
    cl::Buffer bu(ctx, ro, u.size() * 4, u.data()), buw(ctx, ro, uw.size() * 4, uw.data());
    cl::Buffer bpc(ctx, ro, pc.size() * 4, pc.data()), bps(ctx, ro, ps.size() * 4, ps.data());
    cl::Buffer bpw(ctx, ro, pw.size() * 4, pw.data());
    cl::Buffer out(ctx, CL_MEM_WRITE_ONLY, table.values.size() * 4);
    cl::KernelFunctor<int, cl::Buffer, cl::Buffer, int, cl::Buffer, cl::Buffer, cl::Buffer, int, cl::Buffer> bake(
        program, "bake_sheen_albedo");
    bake(cl::EnqueueArgs(rt.opencl().queue(), cl::NDRange(size, size)), int(size), bu, buw, int(u.size()), bpc, bps, bpw,
         int(pc.size()), out);
    rt.opencl().queue().enqueueReadBuffer(out, CL_TRUE, 0, table.values.size() * 4, table.values.data());
  } catch (const cl::Error&) {
    rethrowOpenCL("baking the sheen albedo table");
  }
  return table;
}

SheenAlbedoTable cachedSheenAlbedo(Runtime& rt, SheenDistribution d, SheenVisibility v) {
  const std::size_t n = SheenAlbedoTable::kSize;
  const std::uint64_t key = detail::contentHash(kernelSource("sheen_albedo.cl") + kBakeVersion + rt.info().name +
                                                rt.info().platform + rt.info().openclC);
  const std::string name = fmt::format("sheen_e_{}_{}_{}_{:016x}.f32", toString(d), toString(v), n, key);
  SheenAlbedoTable t{d, v, n, n, std::vector<float>(n * n)};
  if (detail::loadCachedFloats(name, t.values)) return t;
  auto table = bakeSheenAlbedo(rt, d, v, n);
  detail::storeCachedFloats(name, table.values);
  return table;
}

}  // namespace brdfcl
