// How each lane of a batch gets its own material (kernels/brdf/material.h, material_gather): a
// batch over 256 materials with random indices, through the planes kernel and the row kernel, gives
// bit for bit what each material gives alone: every lobe and profile at 16 lanes, the layered
// material at 8.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "support.hpp"

namespace brdfcl::test {
namespace {

struct Case {
  Lobe lobe;
  Profile profile;
};

std::string describe(const Case& c, int lanes) {
  std::ostringstream o;
  o << "lobe " << toString(c.lobe) << ", profile " << toString(c.profile) << ", " << lanes << " lanes";
  return o.str();
}

// Counts the results of `got` that differ from material m's row of the grid (m = the sample's
// index) by more than `ulps`, and names the first.
std::size_t differences(const std::vector<float>& got, const std::vector<float>& grid, const Samples& s,
                        int ulps, std::string* first) {
  const std::size_t n = s.material.size();
  std::size_t differ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      const float a = got[3 * i + c], b = grid[3 * (s.material[i] * n + i) + c];
      std::int32_t x, y;
      std::memcpy(&x, &a, 4);
      std::memcpy(&y, &b, 4);
      const std::int64_t d = std::int64_t(x) - std::int64_t(y);
      if (d > ulps || d < -ulps) {
        if (!differ) {
          std::ostringstream o;
          o << "sample " << i << " (material " << s.material[i] << "), channel " << c << ": " << a << " against "
            << b;
          *first = o.str();
        }
        ++differ;
      }
    }
  }
  return differ;
}

TEST(MaterialLanes, ManyMaterialsGiveEachMaterialsOwnBitsOnEveryLobe) {
  std::mt19937_64 rng(seed() + 256);
  Domain d;
  d.draftShare = 0.15;  // draft lanes read the flags and the sheen weight
  std::vector<MaterialParams> materials;
  for (int m = 0; m < 256; ++m) materials.push_back(randomMaterial(rng, d));
  const std::size_t n = 4096 + 5;  // a partial group of lanes at the end
  const Samples s = randomSamples(rng, n, materials.size(), d);

  std::vector<Case> cases;
  for (Lobe l : {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat})
    cases.push_back({l, Profile::Spec});
  for (Profile p : kAllProfiles)
    if (p != Profile::Spec) cases.push_back({Lobe::All, p});

  // A GPU's compiler may contract the planes kernel differently from the grid's (as in
  // StreamStores); the CPU's gives the same bits.
  const int ulps = runtime().info().type == "CPU" ? 0 : 4;
  for (int lanes : {16, 8}) {
    ForcedLanes forced(lanes);
    for (const Case& c : cases) {
      if (lanes != 16 && (c.lobe != Lobe::All || c.profile != Profile::Spec)) continue;
      SCOPED_TRACE(describe(c, lanes));
      EvalOptions o;
      o.lobe = c.lobe;
      o.profile = c.profile;
      Evaluator ev(runtime(), o);
      // Each material alone: the grid splats one material over all lanes, with the batch's layers.
      const std::vector<float> grid = ev.evaluateGrid(materials, s);

      SoaBatch batch(ev, materials, n);
      for (int k = 0; k < 3; ++k) {
        for (std::size_t i = 0; i < n; ++i) {
          batch.direction(k)[i] = s.L[3 * i + std::size_t(k)];
          batch.direction(3 + k)[i] = s.V[3 * i + std::size_t(k)];
        }
      }
      std::copy(s.material.begin(), s.material.end(), batch.materialIndex());
      batch.setCount(n);
      batch.run();
      std::vector<float> planes(3 * n);
      for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) planes[3 * i + std::size_t(k)] = batch.result(k)[i];

      std::string first;
      EXPECT_EQ(differences(planes, grid, s, ulps, &first), 0u) << "planes kernel, first at " << first;
      EXPECT_EQ(differences(ev.evaluate(materials, s), grid, s, ulps, &first), 0u) << "row kernel, first at " << first;
    }
  }
}

}  // namespace
}  // namespace brdfcl::test
