// The babylon profile's image-based light as Babylon's PBR blocks combine it: the irradiance
// weighted by the legacy surface albedo, the base radiance mixed towards the irradiance by alpha_G
// (MIX_IBL_RADIANCE_WITH_IRRADIANCE), and the composed colour clamped at 0.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/render.hpp"
#include "furnace.hpp"
#include "reference/profiles.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

EvalOptions babylon() {
  EvalOptions o;
  o.profile = Profile::Babylon;
  return o;
}

// One pixel per material: N = +Z, T = +X, V in the XZ plane at N.V = mu.
Image shadeAt(const std::vector<MaterialParams>& ms, float mu, const std::string& env) {
  GBuffer g;
  g.width = int(ms.size());
  g.height = 1;
  const float s = std::sqrt(1.0f - mu * mu);
  for (const auto& m : ms) addFurnacePixel(g, m, s, 0, mu);
  return Shader(runtime(), builtinEnvironment(env), babylon()).shade(g);
}

MaterialParams plain(std::array<float, 3> b, float metallic, float roughness) {
  MaterialParams m;
  m.baseColor = b;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

// Babylon's multiscatter-weighted reflectance (f0 A + B)(1 + f0 (1/(A + B) - 1)) of its BRDF
// texture at (N.V, r): .x = B, .y = A + B.
double babylonReflectance(double f0, double nv, double r) {
  const auto t = ref::babylonBrdf(nv, r);
  const double A = t[1] - t[0], B = t[0];
  return (f0 * A + B) * (1.0 + f0 * (1.0 / (A + B) - 1.0));
}

}  // namespace

// Under the white furnace the irradiance is 1: the diffuse is b (1 - f0_ior)(1 - m)
// (pbrBlockReflectivity's legacy surfaceAlbedo, pbrBlockFinalLitComponents' finalIrradiance), not
// b (1 - m)(1 - (f0 A + B)), next to the specular (f0 A + B) ec.
TEST(ProfileBabylonIbl, IrradianceTakesTheLegacySurfaceAlbedo) {
  const std::array<float, 3> b{0.9f, 0.5f, 0.2f};
  const float metallic = 0.3f, r = 0.5f, mu = 0.5f;
  const Image img = shadeAt({plain(b, metallic, r)}, mu, "uniform");
  const double nv = double(mu) + 1e-7;
  for (int c = 0; c < 3; ++c) {
    const double f0 = 0.04 + (double(b[std::size_t(c)]) - 0.04) * metallic;
    const double want = b[std::size_t(c)] * (1.0 - 0.04) * (1.0 - metallic) + babylonReflectance(f0, nv, r);
    EXPECT_NEAR(img.rgb[std::size_t(c)], want, 2e-5 * want) << "channel " << c;
  }
}

// A white metal reflects mix(L, E, alpha_G) exactly (f0 = 1: (A + B) ec = 1), with L the
// radiance read at sqrt(alpha_G) and E the irradiance. Under the sky: at r = 1 (alpha_G = 1.0005)
// it is E up to 0.0005 (L - E), with E from a white dielectric at the same roughness
// (0.96 E + its reflectance times the same mix); at r = 0.5 a white sheen of roughness 0.5 reads
// L itself at the same level (sheenBlock samples the chain without the mix).
TEST(ProfileBabylonIbl, BaseRadianceIsMixedTowardsTheIrradianceByAlphaG) {
  const float mu = 1.0f;
  const double nv = 1.0 + 1e-7;
  MaterialParams sheened = plain({1, 1, 1}, 1.0f, 0.5f);
  sheened.sheenColor = {1.0f, 1.0f, 1.0f};
  sheened.sheenRoughness = 0.5f;
  const Image img = shadeAt({plain({1, 1, 1}, 1.0f, 1.0f), plain({1, 1, 1}, 0.0f, 1.0f), plain({1, 1, 1}, 1.0f, 0.5f), sheened},
                            mu, "sky");
  const double Es = ref::babylonBrdf(nv, 0.5)[2];
  ASSERT_GT(Es, 0.01);
  for (int c = 0; c < 3; ++c) {
    auto px = [&](int k) { return double(img.rgb[std::size_t(3 * k + c)]); };
    const double mixed1 = px(0);
    const double E = (px(1) - mixed1 * babylonReflectance(0.04, nv, 1.0)) / 0.96;
    const double mixed = px(2), L = (px(3) - mixed * (1.0 - Es)) / Es;
    ASSERT_GT(std::fabs(L - E), 0.02 * E) << "the sky's radiance at r = 0.5 should differ from its irradiance";
    EXPECT_NEAR(mixed1, E, 1e-3 * E + 0.0005 * std::fabs(L - E) * 2) << "channel " << c;
    const double ag = 0.5 * 0.5 + 0.0005;
    const double want = L + ag * (E - L);
    EXPECT_NEAR(mixed, want, 2e-4 * want) << "channel " << c << ": L = " << L << ", E = " << E;
  }
}

// pbrBlockFinalColorComposition clamps the colour at 0: at N.V = 1e-6 the sheen's albedo E of
// Babylon's texture exceeds 1, so 1 - max3(c) E scales the base negative where the sheen colour
// is weak, and the channel is 0, not below.
TEST(ProfileBabylonIbl, ComposedColourIsClampedAtZero) {
  MaterialParams m = plain({0.3f, 0.6f, 0.9f}, 0.0f, 0.5f);
  m.sheenColor = {1.0f, 0.8f, 0.05f};
  m.sheenRoughness = 0.0f;
  const Image img = shadeAt({m}, 1e-6f, "uniform");
  const double Es = ref::babylonBrdf(1e-6, 0.0)[2];
  ASSERT_GT(Es * 1.0, 1.2) << "the texture's sheen albedo at grazing N.V";
  EXPECT_GT(img.rgb[0], 0.0f);
  EXPECT_EQ(img.rgb[2], 0.0f);
}
