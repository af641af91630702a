// MaterialX facts that scripts/engine-check found by running the engine's genglsl BSDFs: each BSDF
// returns at once (no response, throughput 1) when its weight is below M_FLOAT_EPS = 1e-8, so a
// sheen colour or clearcoat factor that small leaves no sheen or coat lobe under --profile materialx.
#include <gtest/gtest.h>

#include <cmath>

#include "brdfcl/io.hpp"
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

}  // namespace
