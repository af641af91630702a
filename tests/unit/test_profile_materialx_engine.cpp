// MaterialX facts read from the engine's genglsl BSDFs (scripts/engine-check runs them): each BSDF
// returns at once (no response, throughput 1) when its weight is below M_FLOAT_EPS = 1e-8, and the
// image-based light compensates energy with the average Fresnel, as the direct light does.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "brdfcl/io.hpp"
#include "brdfcl/render.hpp"
#include "furnace.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

std::array<double, 3> evalMaterialx(const MaterialParams& m, Lobe lobe) {
  Samples s;
  s.material = {0};
  // L and V off the mirror, unit in float.
  const float l[3] = {0.3f, 0.1f, 0.948683298f}, v[3] = {-0.2f, 0.4f, 0.894427191f};
  s.L.assign(l, l + 3);
  s.V.assign(v, v + 3);
  EvalOptions o;
  o.profile = Profile::Materialx;
  o.lobe = lobe;
  const auto got = Evaluator(runtime(), o).evaluate({m}, s);
  return {got[0], got[1], got[2]};
}

MaterialParams grey() {
  MaterialParams m;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  return m;
}

// mx_sheen_bsdf: `if (weight < M_FLOAT_EPS) return;` with weight = max3(sheenColor) (gltf_pbr's
// sheen_intensity). 5e-9 is below it, 2e-8 above: the sheen lobe is 0, then c D V (about 1.2e-3 c).
TEST(ProfileMaterialxEngine, SheenWeightBelowFloatEpsHasNoSheen) {
  MaterialParams m = grey();
  m.sheenColor = {5e-9f, 0.0f, 0.0f};
  m.sheenRoughness = 0.5f;
  EXPECT_EQ(evalMaterialx(m, Lobe::Sheen)[0], 0.0);
  m.sheenColor = {2e-8f, 0.0f, 0.0f};
  const double above = evalMaterialx(m, Lobe::Sheen)[0];
  EXPECT_GT(above, 1e-12);
  EXPECT_LT(above, 1e-10);
}

// mx_dielectric_bsdf: the same early return, with weight = clearcoat.
TEST(ProfileMaterialxEngine, ClearcoatWeightBelowFloatEpsHasNoCoat) {
  MaterialParams m = grey();
  m.clearcoat = 5e-9f;
  m.clearcoatRoughness = 0.3f;
  EXPECT_EQ(evalMaterialx(m, Lobe::Clearcoat)[0], 0.0);
  // Below the coat, the base keeps throughput 1: the diffuse lobe is that of the uncoated material.
  const double coated = evalMaterialx(m, Lobe::Diffuse)[0];
  EXPECT_EQ(coated, evalMaterialx(grey(), Lobe::Diffuse)[0]);
  m.clearcoat = 2e-8f;
  EXPECT_GT(evalMaterialx(m, Lobe::Clearcoat)[0], 1e-12);
}

// MaterialX's Fit_MX(mu, alpha) (docs/profiles.md "Tables"): (A, B).
std::array<double, 2> fitMX(double x, double y) {
  const double k[9][4] = {{0.1003, 0.9345, 1.0, 1.0},      {-0.6303, -2.323, -1.765, 0.2281},
                          {9.748, 2.229, 8.263, 15.94},     {-2.038, -3.748, 11.53, -55.83},
                          {29.34, 1.424, 28.96, 13.08},     {-8.245, -0.7684, -7.507, 41.26},
                          {-26.44, 1.436, -36.11, 54.9},    {19.99, 0.2913, 15.86, 300.2},
                          {-5.448, 0.6286, 33.37, -285.1}};
  const double t[9] = {1, x, y, x * y, x * x, y * y, x * x * y, x * y * y, x * x * y * y};
  double r[4] = {0, 0, 0, 0};
  for (int i = 0; i < 9; ++i)
    for (int c = 0; c < 4; ++c) r[c] += k[i][c] * t[i];
  return {std::clamp(r[0] / r[2], 0.0, 1.0), std::clamp(r[1] / r[3], 0.0, 1.0)};
}

// The image-based light of mx_generalized_schlick_bsdf (CLOSURE_TYPE_INDIRECT) is the prefiltered
// radiance times (F0 A + B) times mx_ggx_energy_compensation, which since ce2398cde takes the
// average Fresnel F0 + (1 - F0)/21 in the indirect path too. A metal of base 0.5 at roughness 1 and
// N = V, under a uniform environment of radiance 1: (0.5 A + B)(1 + (0.5 + 0.5/21)(1 - E)/E), about
// 0.336; F(N.V) = 0.5 there would give 0.328.
TEST(ProfileMaterialxEngine, ImageBasedLightCompensatesWithTheAverageFresnel) {
  MaterialParams m;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  GBuffer g;
  g.width = 1;
  g.height = 1;
  addFurnacePixel(g, m, 0, 0, 1);
  EvalOptions o;
  o.profile = Profile::Materialx;
  const Image img = Shader(runtime(), builtinEnvironment(), o).shade(g);
  const auto ab = fitMX(1.0, 1.0);
  const double E = ab[0] + ab[1];
  const double want = (0.5 * ab[0] + ab[1]) * (1.0 + (0.5 + 0.5 / 21.0) * (1.0 - E) / E);
  const double old = (0.5 * ab[0] + ab[1]) * (1.0 + 0.5 * (1.0 - E) / E);
  ASSERT_GT(want / old, 1.02) << "the two compensations are told apart at this input";
  EXPECT_NEAR(img.rgb[0], want, 2e-3 * want);
}

}  // namespace
