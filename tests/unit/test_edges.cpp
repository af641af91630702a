// Edge sweep: no NaN or Inf anywhere in the domain, for every option combination: roughness 0,
// grazing and below-horizon directions, L = V = N, L = -V, anisotropy 1 at any rotation,
// denormal cosines. Below the horizon f is exactly 0; without albedo scaling f >= 0.
#include <gtest/gtest.h>

#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

std::vector<MaterialParams> edgeMaterials() {
  const float roughs[] = {0.0f, 1e-6f, 1e-3f, 0.05f, 0.5f, 1.0f};
  std::vector<MaterialParams> out;
  for (float r : roughs)
    for (float sr : roughs)
      for (float aniso : {0.0f, 1.0f})
        for (float rot : {0.0f, 1.5707964f, -5.0f}) {
          MaterialParams m;
          m.baseColor = {1.0f, 0.0f, 0.5f};
          m.metallic = aniso > 0 ? 1.0f : 0.0f;
          m.roughness = r;
          m.sheenColor = {1.0f, 1.0f, 1.0f};
          m.sheenRoughness = sr;
          m.clearcoat = 1.0f;
          m.clearcoatRoughness = sr;
          m.anisotropyStrength = aniso;
          m.anisotropyRotation = rot;
          out.push_back(m);
        }
  MaterialParams draft;
  draft.draftSheen = true;
  draft.roughness = 0.0f;
  out.push_back(draft);
  return out;
}

// Direction pairs that stress every term: exact normal, grazing from both sides, denormal
// and tiny cosines, mirror and retro configurations, and a spread of ordinary ones.
Samples edgeSamples() {
  std::vector<std::array<float, 3>> dirs = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, -1}};
  for (float z : {1e-38f, 1e-30f, 1e-7f, 1e-4f, 1e-2f, -1e-7f}) {
    const float s = std::sqrt(1.0f - z * z);
    dirs.push_back({s, 0, z});
    dirs.push_back({-s, 0, z});
    dirs.push_back({0.6f * s, 0.8f * s, z});
  }
  std::mt19937_64 rng(seed() ^ 0xed6e);
  for (int i = 0; i < 12; ++i) dirs.push_back(randomDirection(rng, 0.0f, false));
  Samples s;
  for (const auto& L : dirs)
    for (const auto& V : dirs) {
      s.L.insert(s.L.end(), L.begin(), L.end());
      s.V.insert(s.V.end(), V.begin(), V.end());
    }
  return s;
}

class EdgeSweep : public testing::TestWithParam<EvalOptions> {};

TEST_P(EdgeSweep, FiniteEverywhereAndZeroBelowTheHorizon) {
  const auto& o = GetParam();
  const auto materials = edgeMaterials();
  const auto s = edgeSamples();
  const auto f = Evaluator(runtime(), o).evaluateGrid(materials, s);
  const bool nonNegative = o.sheenScaling == SheenScaling::None;  // s < 0 is possible where E > 1
  std::size_t bad = 0;
  std::string first;
  for (std::size_t m = 0; m < materials.size(); ++m)
    for (std::size_t i = 0; i < s.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const float v = f[3 * (m * s.size() + i) + c];
        const bool below = s.L[3 * i + 2] <= 0.0f || s.V[3 * i + 2] <= 0.0f;
        const bool ok = std::isfinite(v) && (!below || v == 0.0f) && (!nonNegative || v >= 0.0f);
        if (!ok && bad++ == 0) {
          std::ostringstream d;
          d.precision(9);
          d << "f = " << v << " (channel " << c << ") for L(" << s.L[3 * i] << "," << s.L[3 * i + 1] << ","
            << s.L[3 * i + 2] << ") V(" << s.V[3 * i] << "," << s.V[3 * i + 1] << "," << s.V[3 * i + 2] << "), "
            << describe(materials[m]) << "; " << describeOptions(o);
          first = d.str();
        }
      }
  EXPECT_EQ(bad, 0u) << "first: " << first;
}

std::vector<EvalOptions> edgeModes() {
  std::vector<EvalOptions> modes;
  for (auto v : {SheenVisibility::Charlie, SheenVisibility::Ashikhmin})
    for (auto d : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin})
      for (auto sc : {SheenScaling::Min, SheenScaling::View, SheenScaling::None})
        for (auto l : {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat})
          modes.push_back({v, d, sc, l});
  return modes;
}

INSTANTIATE_TEST_SUITE_P(Modes, EdgeSweep, testing::ValuesIn(edgeModes()),
                         [](const testing::TestParamInfo<EvalOptions>& info) {
                           const auto& o = info.param;
                           return std::string(toString(o.sheenVisibility)) + "_" + toString(o.sheenDistribution) +
                                  "_" + toString(o.sheenScaling) + "_" + toString(o.lobe);
                         });

// Roughness 0 must stay finite at the mirror peak itself (the documented alpha clamp).
TEST(EdgeCases, MirrorPeakAtRoughnessZeroIsFinite) {
  MaterialParams m;
  m.roughness = 0.0f;
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 0.0f;
  Samples s;
  s.L = {0.6f, 0.0f, 0.8f};
  s.V = {-0.6f, 0.0f, 0.8f};
  const auto f = Evaluator(runtime(), EvalOptions{}).evaluateGrid({m}, s);
  for (float v : f) {
    EXPECT_TRUE(std::isfinite(v));
    EXPECT_GT(v, 1e4f);  // a sharp peak, not a collapse to 0
  }
}

}  // namespace
