// How each lane of a batch gets its own material (kernels/brdf/material.h, material_gather): a
// batch over 256 materials with random indices, through the planes kernel and the row kernel, gives
// bit for bit what each material gives alone: every lobe and profile at 16 lanes, the layered
// material at 8. Each material's own row of the sheen albedo table gives what the table gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <utility>
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

// Each material of a batch reads its own row of the sheen albedo table, blended once by the host
// (Evaluator::prepare, BRDFCL_E_ROW; materials of one sheenRoughness share a row); a batch of more
// than Evaluator::kMaxSheenRows materials blends the table's two rows at every lookup. Both give
// the albedo-scaled lobes to the rounding of E (a few ulps of values up to ~6, times
// max(sheenColor)), bounded here against the same lobe unscaled, at cosines from the clamp's 1e-4
// up, where E rises and falls fastest: through the gathering program and the one-material one.
TEST(MaterialLanes, RowsOfTheSheenTableGiveWhatTheTableGives) {
  std::mt19937_64 rng(seed() + 320);
  Domain d;
  d.minCos = 1e-4f;
  d.belowHorizon = 0;
  d.zeroLayerShare = 0;
  d.draftShare = 0;
  std::vector<MaterialParams> materials;
  for (int k = 0; k < 4; ++k) materials.push_back(randomMaterial(rng, d));
  materials.push_back(randomMaterial(rng, d));
  materials.back().sheenRoughness = materials[0].sheenRoughness;  // shares material 0's row
  const std::size_t n = 4096 + 5;
  const Samples s = randomSamples(rng, n, materials.size(), d);
  Samples first = s;  // every sample on material 0
  std::fill(first.material.begin(), first.material.end(), 0u);
  // The same materials, then copies of material 0 past the rows' limit: the table's program.
  std::vector<MaterialParams> padded = materials;
  padded.resize(Evaluator::kMaxSheenRows + 1, materials[0]);

  // Both scalings and both lobes that scale, in two pairings a width (each builds its own programs).
  const std::pair<SheenScaling, Lobe> cases[] = {{SheenScaling::Min, Lobe::All}, {SheenScaling::View, Lobe::Specular}};
  for (int lanes : {16, 1}) {
    ForcedLanes forced(lanes);
    for (const auto& c : cases) {
      const SheenScaling scaling = c.first;
      const Lobe lobe = c.second;
      EvalOptions o;
      o.lobe = lobe;
      o.sheenScaling = scaling;
      EvalOptions none = o;
      none.sheenScaling = SheenScaling::None;
      Evaluator ev(runtime(), o), unscaledEv(runtime(), none);
      const auto check = [&](const std::vector<float>& rows, const std::vector<float>& table,
                             const std::vector<float>& unscaled, const Samples& at, const std::string& what) {
        double worst = 0;
        std::size_t w = 0;
        for (std::size_t i = 0; i < 3 * n; ++i) {
          const double excess = std::abs(double(rows[i]) - double(table[i])) /
                                (4e-6 * std::abs(double(unscaled[i])) + 1e-6 * std::abs(double(table[i])) + 1e-30);
          if (excess > worst) worst = excess, w = i;
        }
        const std::size_t i = w / 3;
        EXPECT_LE(worst, 1.0) << what << ", " << lanes << " lanes, scaling " << toString(scaling) << ", lobe "
                              << toString(lobe) << ": sample " << i << " channel " << w % 3 << ", "
                              << brdfcl::test::describe(materials[at.material[i]]) << ", L (" << at.L[3 * i] << ", "
                              << at.L[3 * i + 1] << ", " << at.L[3 * i + 2] << "), V (" << at.V[3 * i] << ", "
                              << at.V[3 * i + 1] << ", " << at.V[3 * i + 2] << "): rows " << rows[w] << ", table "
                              << table[w] << ", unscaled " << unscaled[w];
      };
      check(ev.evaluate(materials, s), ev.evaluate(padded, s), unscaledEv.evaluate(materials, s), s,
            "five materials");
      check(ev.evaluate({materials[0]}, first), ev.evaluate(padded, first),
            unscaledEv.evaluate({materials[0]}, first), first, "one material");
    }
  }
}

}  // namespace
}  // namespace brdfcl::test
