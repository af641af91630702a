// --profile babylon as Babylon.js's glTF loader leaves PBRMaterial's defines: legacy specular
// energy conservation (albedo b (1 - f0_ior)(1 - m), no N.H weight), the coat's multiscatter
// factor on the base's F0, and saturateEps / absEps on the cosines. Kernel and reference both.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/profiles.hpp"
#include "profile_eval.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<float> kernel(const MaterialParams& m, Lobe lobe, const Samples& s) {
  return evalProfile(m, Profile::Babylon, lobe, s);
}

double rel(double a, double b) { return std::fabs(a - b) / std::max(std::fabs(b), 1e-30); }

}  // namespace

// LEGACY_SPECULAR_ENERGY_CONSERVATION: the diffuse is b (1 - f0_ior)(1 - m)/pi at every pair,
// with no Fresnel on N.H (a half-metal at L = V = N loses 0.04 of its albedo, not 0.52).
TEST(BabylonEngine, LegacyDiffuseLosesDielectricF0WithNoAngle) {
  MaterialParams m;
  m.baseColor = {0.9f, 0.5f, 0.2f};
  m.metallic = 0.5f;
  m.roughness = 0.4f;
  m.ior = 1.5f;
  const Samples s = pairsOf({{0, 0, 1, 0, 0, 1}, {0.8f, 0, 0.6f, -0.1f, 0.3f, 0.9486833f}, {0.99f, 0, 0.1410674f, 0, 0.99f, 0.1410674f}});
  const auto k = kernel(m, Lobe::Diffuse, s);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const ref::Vec3 L{s.L[3 * i], s.L[3 * i + 1], s.L[3 * i + 2]}, V{s.V[3 * i], s.V[3 * i + 1], s.V[3 * i + 2]};
    const auto r = ref::profileBrdf(m, Profile::Babylon, Lobe::Diffuse, L, V);
    for (int c = 0; c < 3; ++c) {
      const double want = double(m.baseColor[c]) * (1.0 - 0.04) * 0.5 / kPi;
      EXPECT_LE(rel(r[c], want), 1e-12) << "pair " << i << " channel " << c;
      EXPECT_LE(rel(k[3 * i + c], want), 1e-5) << "pair " << i << " channel " << c;
    }
  }
}

// The coat's MS_BRDF_ENERGY_CONSERVATION factor 1 + f0 (1/E_ss(r_c, N.V) - 1) takes the base's
// F0 per channel, so over a red metal the coat is redder than over its blue.
TEST(BabylonEngine, CoatMultiscatterFactorTakesBaseF0PerChannel) {
  MaterialParams m;
  m.baseColor = {1.0f, 0.1f, 0.1f};
  m.metallic = 1.0f;
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 0.6f;
  const Samples s = pairsOf({{0, 0, 1, 0, 0, 1}});
  const auto k = kernel(m, Lobe::Clearcoat, s);
  const double rc = m.clearcoatRoughness;
  const double E = ref::babylonBrdf(1.0 + 1e-7, rc)[1];  // Babylon's own BRDF texture, .y
  const double aG = rc * rc + 0.0005;
  const double white = 0.04 / (kPi * aG * aG) * 0.25;
  for (int c = 0; c < 3; ++c) {
    const double want = white * (1.0 + m.baseColor[c] * (1.0 / E - 1.0));
    EXPECT_LE(rel(ref::profileBrdf(m, Profile::Babylon, Lobe::Clearcoat, {0, 0, 1}, {0, 0, 1})[c], want), 1e-12) << c;
    EXPECT_LE(rel(k[c], want), 1e-5) << c;
  }
  EXPECT_GT(k[0], k[2] * (1.0 + 1e-3));
}

// helperFunctions.fx: N.L = clamp(N.L, 1e-7, 1) and N.V = |N.V| + 1e-7, not brdfcl's 1e-4
// floor: at cosines of 1e-6 the Ashikhmin sheen V is 1/(4 (N.L + N.V - N.L N.V)) at 1e-6 and
// 1.1e-6, some 90 times what a 1e-4 floor gives.
TEST(BabylonEngine, CosinesFollowSaturateEpsAndAbsEps) {
  MaterialParams m;
  m.metallic = 0.0f;
  m.sheenColor = {1.0f, 1.0f, 1.0f};
  m.sheenRoughness = 0.5f;
  const float z = 1e-6f, t = std::sqrt(1.0f - z * z);
  const Samples s = pairsOf({{t, 0, z, 0, t, z}});
  const auto k = kernel(m, Lobe::Sheen, s);
  const auto r = ref::profileBrdf(m, Profile::Babylon, Lobe::Sheen, {t, 0, z}, {0, t, z});
  // Charlie D at N.H = 2z / |(t, t, 2z)| (sin^2 = 1 - N.H^2) times the Ashikhmin V at the engine's cosines.
  const double nh = 2.0 * z / std::sqrt(2.0 * double(t) * t + 4.0 * double(z) * z);
  const double aG = 0.25 + 0.0005;
  const double D = (2.0 + 1.0 / aG) * std::pow(1.0 - nh * nh, 0.5 / aG) / (2.0 * kPi);
  const double nl = z, nv = double(z) + 1e-7;
  const double want = D / (4.0 * (nl + nv - nl * nv));
  EXPECT_LE(rel(r[0], want), 1e-9);
  EXPECT_LE(rel(k[0], want), 1e-3);
  const double floored = D / (4.0 * (2e-4 - 1e-8));
  EXPECT_GT(k[0] / floored, 80.0);
}
