// Engine profiles' image-based light under the white furnace (a uniform environment of radiance
// 1), as scripts/engine-check --ibl runs the engines' IBL code: every prefiltered level then reads
// 1, so the profile's colour is its combination of DFG, sheen albedo and coat alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/lut.hpp"
#include "brdfcl/render.hpp"
#include "furnace.hpp"
#include "reference/profiles.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

// One pixel per material: N = +Z, T = +X, V in the XZ plane at N.V = mu.
GBuffer furnacePixels(const std::vector<MaterialParams>& ms, float mu) {
  GBuffer g;
  g.width = int(ms.size());
  g.height = 1;
  const float s = std::sqrt(1.0f - mu * mu);
  for (const auto& m : ms) addFurnacePixel(g, m, s, 0, mu);
  return g;
}

// E(mu, r) as the kernels sample the table (kernels/brdf/sheen_albedo.h: texels at sqrt spacing).
double sheenE(const SheenAlbedoTable& t, double mu, double r) {
  const int n = int(t.width);
  const double x = std::sqrt(std::clamp(mu, 0.0, 1.0)) * (n - 1), y = std::sqrt(std::clamp(r, 0.0, 1.0)) * (n - 1);
  const int x0 = std::min(int(x), n - 2), y0 = std::min(int(y), n - 2);
  const double fx = x - x0, fy = y - y0;
  auto at = [&](int i, int j) { return double(t.values[std::size_t(j) * t.width + std::size_t(i)]); };
  return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) + (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}

}  // namespace

// Khronos's sheen reads the Charlie chain at lod r_s (levels - 1): col = Lc c E + col (1 - max3(c) E_K),
// E = E_CC and E_K the renderer's lut_sheen_E.png. With every level of the chain at 1, a white
// sheen over a sheen-less material A gives E + A (1 - E_K), at r_s = 0 (level 0, where Charlie's D
// underflows at every prefilter sample) as at r_s = 0.1 (a blend of levels 0 and 1).
TEST(ProfileIblEngine, KhronosCharlieChainOfAUniformEnvironmentIsOneAtEveryLevel) {
  EvalOptions o;
  o.profile = Profile::Khronos;
  Evaluator evaluator(runtime(), o);
  const SheenAlbedoTable& table = evaluator.sheenAlbedo();
  MaterialParams plain;
  plain.baseColor = {0.0f, 0.0f, 0.0f};
  plain.metallic = 0.0f;
  plain.roughness = 1.0f;
  std::vector<MaterialParams> ms{plain};
  const std::vector<float> rough{0.0f, 0.1f};
  for (float r : rough) {
    MaterialParams m = plain;
    m.sheenColor = {1.0f, 1.0f, 1.0f};
    m.sheenRoughness = r;
    ms.push_back(m);
  }
  const float mu = 0.1f;
  const Image img = Shader(runtime(), builtinEnvironment(), o).shade(furnacePixels(ms, mu));
  const double a = img.rgb[0];
  ASSERT_GT(a, 0.0);
  for (std::size_t k = 0; k < rough.size(); ++k) {
    const double e = sheenE(table, mu, rough[k]);
    ASSERT_GT(e, 0.01) << "r_s = " << rough[k];
    const double ek = ref::khronosSheenE(mu, rough[k]);
    const double want = e + a * (1.0 - ek);
    EXPECT_NEAR(img.rgb[3 * (k + 1)], want, 1e-4 * want) << "r_s = " << rough[k] << ", E = " << e << ", E_K = " << ek;
  }
}

// Khronos's getIBLGGXFresnel takes N.V through clampedDot (no floor): at N.V = 1e-6 a black
// dielectric shows F_ibl(0.04) = FssEss + Ems FssEss Favg / (1 - Favg Ems), kS = F0 + (max(1 - r, F0)
// - F0) (1 - N.V)^5, with (A, B) of brdfcl's 64x64 GGX table read at N.V itself (a floor at 1e-4
// moves it by 2e-4).
TEST(ProfileIblEngine, KhronosIblFresnelTakesNdotVWithoutAFloor) {
  EvalOptions o;
  o.profile = Profile::Khronos;
  MaterialParams m;
  m.baseColor = {0.0f, 0.0f, 0.0f};
  m.metallic = 0.0f;
  m.roughness = 0.3f;
  const float mu = 1e-6f;
  const Image img = Shader(runtime(), builtinEnvironment(), o).shade(furnacePixels({m}, mu));
  const Lut dfg = bakeLut(runtime(), LutKind::GgxDfg, 64);
  const int n = 64;
  const float s = std::sqrt(1.0f - mu * mu), len = std::sqrt(s * s + mu * mu);
  const double nv = double(mu / len), r = 0.3;
  const double x = nv * (n - 1), y = r * (n - 1);
  const int x0 = std::min(int(x), n - 2), y0 = std::min(int(y), n - 2);
  const double fx = x - x0, fy = y - y0;
  auto at = [&](int i, int j, int c) { return double(dfg.values[(std::size_t(j) * n + std::size_t(i)) * 2 + std::size_t(c)]); };
  auto lerp2 = [&](int c) {
    return (at(x0, y0, c) * (1 - fx) + at(x0 + 1, y0, c) * fx) * (1 - fy) +
           (at(x0, y0 + 1, c) * (1 - fx) + at(x0 + 1, y0 + 1, c) * fx) * fy;
  };
  const double A = lerp2(0), B = lerp2(1), f0 = 0.04;
  const double kS = f0 + (std::max(1.0 - r, f0) - f0) * std::pow(1.0 - nv, 5.0);
  const double fssEss = kS * A + B, ems = 1.0 - (A + B), favg = f0 + (1.0 - f0) / 21.0;
  const double want = fssEss + ems * fssEss * favg / (1.0 - favg * ems);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.rgb[std::size_t(c)], want, 2e-5 * want) << "channel " << c;
}
