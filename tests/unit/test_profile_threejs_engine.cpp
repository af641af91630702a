// threejs profile facts found by running three.js's own TSL (scripts/engine-check): at grazing
// mirrored pairs (V.H = N.V = 1e-6) the diffuse weight 1 - F(V.H) and the coat's 1 - cc F(N.V)
// keep their digits, as three.js's float64 run of its own code does.
#include <gtest/gtest.h>

#include <cmath>

#include "brdfcl/io.hpp"
#include "profile_eval.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::array<double, 3> evalThreejs(const MaterialParams& m, Lobe lobe, std::array<double, 3> L,
                                  std::array<double, 3> V) {
  return evalPair(m, Profile::Threejs, lobe, L, V);
}

// three.js's F_Schlick weight 1 - Fs, Fs = 2^(-(5.55473 x + 6.98316) x), without cancellation.
double oneMinusFs(double x) { return -std::expm1(-(5.55473 * x + 6.98316) * x * std::log(2.0)); }

// L = (a, b, c), V = (-a, -b, c): L + V = (0, 0, 2c) in float too, so H = N and V.H = N.V = c (the
// float c of the normalized V). Diffuse = (1 - m)(1 - f0)(1 - Fs(c)) b/pi with f0 = 1/9 at IOR 2;
// a coat multiplies it by 1 - cc F(c) = (1 - 0.04)(1 - Fs(c)) at cc = 1. Both weights are about
// 5e-6: a V.H taken as 1 - |V - H|^2/2 in float, or a 1 - F that cancels, is off by percents.
TEST(ProfileThreejsEngine, DiffuseKeepsItsDigitsAtGrazingMirroredPairs) {
  const double a = -0.421767056, b = 0.906704247, c = 1e-6;
  const std::array<double, 3> L{a, b, c}, V{-a, -b, c};
  const double n = std::sqrt(a * a + b * b + c * c);
  const double x = double(float(c / n));
  MaterialParams m;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  m.metallic = 0.0f;
  m.roughness = 0.3f;
  m.ior = 2.0f;
  const double wd = (1.0 - 1.0 / 9.0) * oneMinusFs(x);
  const auto bare = evalThreejs(m, Lobe::Diffuse, L, V);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(bare[i], wd * 0.5 / kPi, 1e-3 * wd * 0.5 / kPi) << "channel " << i;
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 0.2f;
  const double wc = (1.0 - 0.04) * oneMinusFs(x);
  const auto coated = evalThreejs(m, Lobe::Diffuse, L, V);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(coated[i], wd * wc * 0.5 / kPi, 1e-3 * wd * wc * 0.5 / kPi) << "channel " << i;
}

// Away from the horizon the weights are the plain 1 - F: at L = V = (sin 1, 0, cos 1) (V.H = 1,
// N.V = cos 1) the coated diffuse is (1 - f0)(1 - Fs(1)) (1 - cc F(cos 1)) b/pi.
TEST(ProfileThreejsEngine, DiffuseWeightsAwayFromTheHorizon) {
  const double c = std::cos(1.0), s = std::sin(1.0);
  MaterialParams m;
  m.baseColor = {0.5f, 0.25f, 1.0f};
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  m.ior = 1.5f;
  m.clearcoat = 0.6f;
  m.clearcoatRoughness = 0.3f;
  const auto got = evalThreejs(m, Lobe::Diffuse, {s, 0.0, c}, {s, 0.0, c});
  const double fs1 = 1.0 - oneMinusFs(1.0), fsc = 1.0 - oneMinusFs(c);
  const double k = 1.0 - 0.6 * (0.04 * (1.0 - fsc) + fsc);
  const double w = (1.0 - 0.04) * (1.0 - fs1) * k / kPi;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], w * m.baseColor[i], 1e-5 * w) << "channel " << i;
}

}  // namespace
