// Batch BRDF evaluation on an OpenCL device: f(L, V) in 1/sr, no cosine, per sample or per
// material x direction grid. Owns the baked sheen albedo tables it needs.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "brdfcl/io.hpp"
#include "brdfcl/material.hpp"
#include "brdfcl/runtime.hpp"

namespace brdfcl {

// Directional albedo E(mu, r) of the white sheen lobe, looked up with mu = N.V (or N.L) and
// r = sheenRoughness, both in [0, 1]. Nodes sit at mu = s^2, r = t^2 for s, t uniform in [0, 1]
// (x fastest): E is steepest at grazing angles and low roughness, so the grid is densest there.
struct SheenAlbedoTable {
  static constexpr std::size_t kSize = 320;
  SheenDistribution distribution;
  SheenVisibility visibility;
  std::size_t width = kSize, height = kSize;
  std::vector<float> values;  // height rows of width
  float lookup(float mu, float sheenRoughness) const;  // bilinear, as the kernels do it
};

// Bakes E by numerical integration on the device (kernels/sheen_albedo.cl).
// nodesPerPanel sets the quadrature order (tests double it to prove convergence).
SheenAlbedoTable bakeSheenAlbedo(Runtime& rt, SheenDistribution d, SheenVisibility v,
                                 std::size_t size = SheenAlbedoTable::kSize, int nodesPerPanel = 12);

// The table for the default size from the on-disk cache ($XDG_CACHE_HOME or ~/.cache, then
// brdfcl/), baking and storing it on a miss. The key holds the device, the options and a hash of
// the kernel source, so a changed kernel never reads a stale table. An unwritable cache is skipped.
SheenAlbedoTable cachedSheenAlbedo(Runtime& rt, SheenDistribution d, SheenVisibility v);

class Evaluator {
 public:
  Evaluator(Runtime& rt, EvalOptions options);

  const EvalOptions& options() const { return options_; }

  // One result per sample; samples.material indexes `materials`. Returns rgb, 3 floats a sample.
  std::vector<float> evaluate(const std::vector<MaterialParams>& materials, const Samples& samples);

  // Every material x every direction pair, material-major. samples.material is ignored.
  std::vector<float> evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples);

  // The table this evaluator's sheen options use (baked on first use).
  const SheenAlbedoTable& sheenAlbedo();

 private:
  struct Batch;
  Batch prepare(const std::vector<MaterialParams>& materials);

  Runtime& rt_;
  EvalOptions options_;
  std::unique_ptr<SheenAlbedoTable> table_;
};

}  // namespace brdfcl
