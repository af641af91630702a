// --profile babylon reads Babylon.js's own environment BRDF texture (docs/profiles.md "Tables"):
// the carried-over texels are its RGBD PNG decoded and held as half floats, sampled bilinearly at
// (N.V, roughness), and the multiscatter factors and the sheen albedo scaling come from them.
#include <gtest/gtest.h>

#include <cmath>

#include "brdfcl/io.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/scene.hpp"
#include "kernels/common/material_layout.h"
#include "model/engine_tables.hpp"
#include "reference/profiles.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr int kN = BRDFCL_BABYLON_BRDF_SIZE;

// Texel (i, j) = (N.V column, roughness row) of brdfTextureTools.ts's PNG, each channel
// pow(c / 255, 2.2) / (a / 255) rounded to half float: (.x, .y, .b).
struct Texel {
  int i, j;
  double x, y, b;
};
constexpr Texel kTexels[] = {
    {0, 0, 0.98193359375, 0.98193359375, 36.5},
    {255, 0, 0.0, 1.0, 5.692243576049805e-05},
    {255, 255, 2.3305416107177734e-05, 0.306640625, 0.1419677734375},
    {100, 128, 0.04144287109375, 0.84326171875, 0.30224609375},
    {40, 200, 0.035614013671875, 0.78173828125, 0.47607421875},
    {200, 60, 0.0008044242858886719, 0.9912109375, 0.0090179443359375},
    {25, 180, 0.061920166015625, 0.859375, 0.55419921875},
    {60, 128, 0.0823974609375, 0.84326171875, 0.44775390625},
    {61, 128, 0.0823974609375, 0.83544921875, 0.4423828125},
};

double centre(int i) { return (i + 0.5) / kN; }

// Babylon adds 1e-7 to |N.V| (absEps) before the look-up: the N.V that puts it at u.
float muFor(double u) { return float(u - 1e-7); }

Samples atLEqualsV(double mu, std::size_t materials) {
  Samples s;
  const float x = float(std::sqrt(1.0 - mu * mu)), z = float(mu);
  for (std::size_t k = 0; k < materials; ++k) {
    s.material.push_back(std::uint32_t(k));
    s.L.insert(s.L.end(), {x, 0.0f, z});
  }
  s.V = s.L;
  return s;
}

std::vector<float> eval(const std::vector<MaterialParams>& ms, const Samples& s, Lobe lobe) {
  EvalOptions o;
  o.profile = Profile::Babylon;
  o.lobe = lobe;
  return Evaluator(runtime(), o).evaluate(ms, s);
}

MaterialParams colouredMetal(float roughness) {
  MaterialParams m;
  m.baseColor = {1.0f, 0.5f, 0.25f};
  m.metallic = 1.0f;
  m.roughness = roughness;
  return m;
}

// At L = V, V.H = 1 and F = f0 = the base colour: the specular's red over green is
// (1 / E) / (0.5 (1 + 0.5 (1/E - 1))) = 4 / (E + 1), so E = 4 green / red - 1.
double specularE(double mu, float roughness) {
  const auto got = eval({colouredMetal(roughness)}, atLEqualsV(mu, 1), Lobe::Specular);
  return 4.0 * double(got[1]) / double(got[0]) - 1.0;
}

// The coat's multiscatter factor takes the base's F0: red over green is 2 / (E_c + 1).
double coatE(double mu, float coatRoughness) {
  MaterialParams m = colouredMetal(0.5f);
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = coatRoughness;
  const auto got = eval({m}, atLEqualsV(mu, 1), Lobe::Clearcoat);
  return 2.0 * double(got[1]) / double(got[0]) - 1.0;
}

// The diffuse lobe with sheen over without: 1 - max3(c) .b(N.V, r_s).
double sheenScaling(double mu, float sheenRoughness) {
  MaterialParams m;
  m.baseColor = {1.0f, 1.0f, 1.0f};
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  MaterialParams sheen = m;
  sheen.sheenColor = {1.0f, 0.5f, 0.25f};
  sheen.sheenRoughness = sheenRoughness;
  const auto got = eval({m, sheen}, atLEqualsV(mu, 2), Lobe::Diffuse);
  return double(got[3]) / double(got[0]);
}

}  // namespace

TEST(BabylonBrdfLut, TableHoldsTheDecodedHalfFloatTexels) {
  const auto& t = babylonBrdfTable();
  ASSERT_EQ(t.size(), std::size_t(3) * kN * kN);
  for (float v : t) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.0f);
  }
  for (const auto& k : kTexels) {
    const std::size_t at = (std::size_t(k.j) * kN + std::size_t(k.i)) * 3;
    EXPECT_EQ(double(t[at]), k.x) << k.i << "," << k.j;
    EXPECT_EQ(double(t[at + 1]), k.y) << k.i << "," << k.j;
    EXPECT_EQ(double(t[at + 2]), k.b) << k.i << "," << k.j;
  }
}

TEST(BabylonBrdfLut, ReferenceSamplesLikeAGpu) {
  for (const auto& k : kTexels) {
    const auto r = ref::babylonBrdf(centre(k.i), centre(k.j));
    EXPECT_DOUBLE_EQ(r[0], k.x);
    EXPECT_DOUBLE_EQ(r[1], k.y);
    EXPECT_DOUBLE_EQ(r[2], k.b);
  }
  // Halfway between two centres, their mean; beyond the outer centres, the edge texel.
  EXPECT_DOUBLE_EQ(ref::babylonBrdf(61.0 / kN, centre(128))[1], 0.5 * (0.84326171875 + 0.83544921875));
  EXPECT_DOUBLE_EQ(ref::babylonBrdf(0.0, 0.0)[2], 36.5);
  EXPECT_DOUBLE_EQ(ref::babylonBrdf(1.0, 1.0)[1], 0.306640625);
}

// The specular multiscatter factor 1 + f0 (1/E - 1) reads E from the texture's .y at
// (N.V, roughness).
TEST(BabylonBrdfLut, SpecularMultiscatterIsTheTexturesY) {
  for (const auto& k : {kTexels[3], kTexels[4], kTexels[6]})
    EXPECT_NEAR(specularE(muFor(centre(k.i)), float(centre(k.j))), k.y, 2e-5) << k.i << "," << k.j;
}

TEST(BabylonBrdfLut, SpecularMultiscatterIsBilinearBetweenTexels) {
  EXPECT_NEAR(specularE(muFor(61.0 / kN), float(centre(128))), 0.5 * (0.84326171875 + 0.83544921875), 2e-5);
}

// The coat's factor reads .y at (N.V, coat roughness).
TEST(BabylonBrdfLut, CoatMultiscatterIsTheTexturesY) {
  for (const auto& k : {kTexels[3], kTexels[4]})
    EXPECT_NEAR(coatE(muFor(centre(k.i)), float(centre(k.j))), k.y, 2e-5) << k.i << "," << k.j;
}

// SHEEN_ALBEDOSCALING: 1 - max3(c) times the texture's .b at (N.V, sheen roughness).
TEST(BabylonBrdfLut, SheenScalingIsTheTexturesB) {
  for (const auto& k : {kTexels[3], kTexels[4], kTexels[6]})
    EXPECT_NEAR(sheenScaling(muFor(centre(k.i)), float(centre(k.j))), 1.0 - k.b, 2e-5) << k.i << "," << k.j;
}

// Image-based light: the sheen scales the base by 1 - max3(c) .b(N.V, r_s) from the same texture.
// With c = (1, 0, 0) the green channel carries the scaling alone, under a uniform sky.
TEST(BabylonBrdfLut, ImageBasedSheenScalingIsTheTexturesB) {
  const Texel k = kTexels[3];
  const double mu = centre(k.i);
  GBuffer g;
  g.width = 2;
  g.height = 1;
  g.P = std::vector<float>(6, 0.0f);
  g.N = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f};
  const float vx = float(std::sqrt(1.0 - mu * mu)), vz = float(mu);
  g.V = {vx, 0.0f, vz, vx, 0.0f, vz};
  g.baseColor = std::vector<float>(6, 1.0f);
  g.metallic = {0.0f, 0.0f};
  g.roughness = {0.5f, 0.5f};
  g.mask = {1.0f, 1.0f};
  g.sheenColor = {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f};
  g.sheenRoughness = {0.0f, float(centre(k.j))};
  Scene scene;
  scene.environment.builtinKind = "uniform";
  EvalOptions o;
  o.profile = Profile::Babylon;
  const Image img = Shader(runtime(), scene, o).shade(g);
  const double plain = img.rgb[1], sheen = img.rgb[4];
  ASSERT_GT(plain, 1e-3) << "the uniform sky lights the base";
  EXPECT_NEAR(sheen / plain, 1.0 - k.b, 1e-4);
}

// Where max3(c) .b exceeds 1 (texel (0, 0): .b = 36.5) the sheen scaling is negative: Babylon clamps
// the final diffuse at 0 (pbrBlockFinalUnlitComponents) but not the specular scaled by it.
TEST(BabylonBrdfLut, NegativeSheenScalingLeavesNoNegativeDiffuse) {
  MaterialParams m;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  m.sheenColor = {1.0f, 0.5f, 0.25f};
  m.sheenRoughness = float(centre(0));
  const auto s = atLEqualsV(muFor(centre(0)), 1);
  for (float v : eval({m}, s, Lobe::Diffuse)) EXPECT_EQ(v, 0.0f);
  for (float v : eval({m}, s, Lobe::Specular)) EXPECT_LT(v, 0.0f);
}
