// The sheen D of the khronos, babylon and materialx profiles takes sin^2(theta_h) as the engines'
// shaders do, 1 - N.H^2 in float, so near N.H = 1 it carries the engines' cancellation and agrees
// with them on a GPU (scripts/engine-check's float32 run).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "brdfcl/io.hpp"
#include "brdfcl/render.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

// L = V, 1e-4 off the normal: H = L, the exact sin^2 is 1e-8, and the float N.H is 1 (or one
// ulp below it, where the normalization rounds the other way), so 1 - N.H^2 in float is 0 (or
// 1.19e-7), never 1e-8.
double sheenAtTinyOffset(Profile p) {
  Samples s;
  s.material = {0};
  const float d[3] = {1e-4f, 0.0f, 1.0f};
  s.L.assign(d, d + 3);
  s.V.assign(d, d + 3);
  MaterialParams m;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  m.sheenColor = {1.0f, 1.0f, 1.0f};
  m.sheenRoughness = 1.0f;
  EvalOptions o;
  o.profile = p;
  o.lobe = Lobe::Sheen;
  return Evaluator(runtime(), o).evaluate({m}, s)[0];
}

// (2 + 1/alpha) sin2^(1/(2 alpha)) / (2 pi) times Ashikhmin's V at N.L = N.V = 1 (1/4).
double charlieAshikhmin(double alpha, double sin2) {
  return (2.0 + 1.0 / alpha) * std::pow(sin2, 0.5 / alpha) / (2.0 * M_PI) * 0.25;
}

void expectEngineFloat(Profile p, double alpha) {
  const double got = sheenAtTinyOffset(p);
  const float below = std::nextafter(1.0f, 0.0f);
  const double oneUlp = charlieAshikhmin(alpha, static_cast<double>(1.0f - below * below));
  const double exact = charlieAshikhmin(alpha, 1e-8);  // what sin^2 from H's tangential part gives
  EXPECT_TRUE(got == 0.0 || std::abs(got - oneUlp) <= 1e-3 * oneUlp)
      << "sheen " << got << ": the engine's float 1 - N.H^2 gives 0 or " << oneUlp << ", the exact sin^2 "
      << exact;
}

}  // namespace

// mx_imageworks_sheen_NDF: float sin2 = 1.0 - NdotH * NdotH.
TEST(ProfileSheenFloat, MaterialxTakesOneMinusNdotHSquaredInFloat) { expectEngineFloat(Profile::Materialx, 1.0); }

// normalDistributionFunction_CharlieSheen: float sin2h = 1. - NdotH * NdotH, at alphaG = r_s^2 + 0.0005.
TEST(ProfileSheenFloat, BabylonTakesOneMinusNdotHSquaredInFloat) { expectEngineFloat(Profile::Babylon, 1.0005); }
