// Filament facts found by running its own shaders (scripts/engine-check): the anisotropic path
// follows the extension's presence (gltfio's MATERIAL_HAS_ANISOTROPY), strength 0 included, and a
// material without the extension keeps the capped isotropic D whatever else its batch holds.
#include <gtest/gtest.h>

#include <cmath>

#include "brdfcl/io.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A smooth white metal: F = 1, roughness floored at rho = 0.045 (alpha = 0.002025), so at
// L = V = N the isotropic D sits at its cap 453.5^2/pi while Burley's uncapped D is 1/(pi alpha^2).
MaterialParams smoothMetal() {
  MaterialParams m;
  m.baseColor = {1.0f, 1.0f, 1.0f};
  m.metallic = 1.0f;
  m.roughness = 0.01f;
  return m;
}

MaterialParams anisotropic(float strength) {
  MaterialParams m = smoothMetal();
  m.anisotropyExtension = true;
  m.anisotropyStrength = strength;
  return m;
}

// The specular lobe at L = V = N of each material, evaluated in one batch.
std::vector<float> specularAtNormal(const std::vector<MaterialParams>& ms) {
  Samples s;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    s.material.push_back(std::uint32_t(i));
    s.L.insert(s.L.end(), {0.0f, 0.0f, 1.0f});
    s.V.insert(s.V.end(), {0.0f, 0.0f, 1.0f});
  }
  EvalOptions o;
  o.profile = Profile::Filament;
  o.lobe = Lobe::Specular;
  return Evaluator(runtime(), o).evaluate(ms, s);
}

const double kAlpha = 0.045 * 0.045;
const double kCapped = 453.5 * 453.5 / kPi, kUncapped = 1.0 / (kPi * kAlpha * kAlpha);

}  // namespace

// Without the extension the capped D holds, alone or beside an anisotropic material.
TEST(ProfileFilamentEngine, IsotropicDKeepsItsCapInAnAnisotropicBatch) {
  const auto alone = specularAtNormal({smoothMetal()});
  const auto mixed = specularAtNormal({smoothMetal(), anisotropic(0.5f)});
  ASSERT_GT(alone[0], 0.0f);
  EXPECT_NEAR(mixed[0], alone[0], 1e-5 * alone[0]);
}

// With the extension at strength 0, Filament's anisotropic D (no cap) at at = ab = alpha:
// 1/(pi alpha^2) against 453.5^2/pi, a ratio of (1/(alpha 453.5))^2 = 1.18573, batch or not.
TEST(ProfileFilamentEngine, StrengthZeroWithTheExtensionTakesTheUncappedAnisotropicD) {
  const double ratio = kUncapped / kCapped;
  const auto alone = specularAtNormal({smoothMetal()});
  const auto ext = specularAtNormal({anisotropic(0.0f)});
  const auto both = specularAtNormal({smoothMetal(), anisotropic(0.0f)});
  ASSERT_GT(alone[0], 0.0f);
  EXPECT_NEAR(ext[0] / alone[0], ratio, 1e-4 * ratio);
  EXPECT_NEAR(both[3] / both[0], ratio, 1e-4 * ratio);
}
