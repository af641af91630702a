// The sampler's lane-level shortcuts write what the general paths write: a batch of one material
// (read once for all lanes) the rows of the same material gathered by index, and the whole groups'
// shuffled 7-column stores the rows of the partial group's lane-by-lane stores.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "host/src/eval/workload.hpp"
#include "support.hpp"

using namespace brdfcl;
using brdfcl::test::runtime;

namespace {

struct Rows {
  std::vector<float> view, u;
};

// n views from near-normal to grazing, at spread azimuths, and u from the counter-based generator.
Rows rowsOf(std::size_t n, std::uint64_t seed) {
  Rows r;
  r.view.resize(3 * n);
  r.u.resize(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const float z = 0.01f + 0.98f * float(i % 89) / 88.0f, phi = 0.93f * float(i), s = std::sqrt(1 - z * z);
    r.view[3 * i] = s * std::cos(phi), r.view[3 * i + 1] = s * std::sin(phi), r.view[3 * i + 2] = z;
  }
  Evaluator::drawUniforms(seed, 0, n, r.u.data());
  return r;
}

}  // namespace

TEST(SamplingLanes, OneMaterialBatchWritesTheRowsOfTheGatheringBatch) {
  for (const std::string lobe : {"specular", "all", "sheen", "clearcoat"}) {
    const bench::Workload w = bench::makeWorkload(lobe, 3, 1);
    const std::size_t n = 1000;
    const Rows r = rowsOf(n, 11);
    Evaluator ev(runtime(), w.options);
    // Two copies of the material make a gathering program; every index 0 reads the first.
    const std::vector<MaterialParams> two = {w.materials[0], w.materials[0]};
    const std::vector<float> one = ev.sample(w.materials, std::vector<std::uint32_t>(n, 0u), r.view, r.u);
    const std::vector<float> gathered = ev.sample(two, std::vector<std::uint32_t>(n, 0u), r.view, r.u);
    ASSERT_EQ(one.size(), 7 * n);
    EXPECT_EQ(one, gathered) << lobe;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < n; ++i) kept += one[7 * i + 3] > 0.0f;
    EXPECT_GT(kept, n / 10) << lobe;
  }
}

TEST(SamplingLanes, WholeGroupStoresMatchTheTailsStores) {
  // Row i sampled among n rows lands in a whole group or in the tail depending on n; its 7 floats
  // must not. 16 is the widest lane count (AVX-512), so n = 1..33 puts every row in both.
  const bench::Workload w = bench::makeWorkload("all", 5, 1);
  Evaluator ev(runtime(), w.options);
  const std::size_t n = 33;
  const Rows r = rowsOf(n, 12);
  const std::vector<float> whole = ev.sample(w.materials, {}, r.view, r.u);
  for (std::size_t m = 1; m < n; ++m) {
    const std::vector<float> view(r.view.begin(), r.view.begin() + 3 * m), u(r.u.begin(), r.u.begin() + 3 * m);
    const std::vector<float> part = ev.sample(w.materials, {}, view, u);
    ASSERT_EQ(part.size(), 7 * m);
    EXPECT_TRUE(std::equal(part.begin(), part.end(), whole.begin())) << m << " rows";
  }
}
