// Engine facts the profiles reproduce, each checked on the kernels against a value derived by hand
// from the engine's formula at one input (docs/profiles.md): MaterialX's average-Fresnel energy
// compensation, three.js's sheen roughness clamp, Khronos's anisotropy on presence, its float D
// and sheen sin^2, Filament's caps, and the engines' own cosine clamps.
#include <gtest/gtest.h>

#include <cmath>

#include "brdfcl/io.hpp"
#include "profile_eval.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr double kPi = 3.14159265358979323846;

// One sample: unit L and V (normalized here) against one material under one profile and lobe.
std::array<double, 3> evalOne(const MaterialParams& m, Profile p, Lobe lobe, std::array<double, 3> L,
                              std::array<double, 3> V) {
  return evalPair(m, p, lobe, L, V);
}

MaterialParams dielectric(float roughness, float ior) {
  MaterialParams m;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  m.metallic = 0.0f;
  m.roughness = roughness;
  m.ior = ior;
  return m;
}

const std::array<double, 3> kN{0.0, 0.0, 1.0};

// MaterialX (since ce2398cde) tints the GGX energy compensation by the average Fresnel,
// Favg = F0 + (1 - F0)/21, not by F(V.H). At L = V = N the dielectric specular lobe is
// D V F0 comp with D = 1/(pi alpha^2), V = 1/4, comp = 1 + Favg (1 - E)/E. Two IORs at the same
// roughness share E, so (comp_a - 1)/(comp_b - 1) = Favg_a/Favg_b whatever the albedo fit gives:
// F0 = 0.04 (IOR 1.5) and 1/9 (IOR 2) give 0.0857143/0.1534392 = 0.558621; F(V.H) = F0 there would
// give 0.04/(1/9) = 0.36.
TEST(ProfileEngineFacts, MaterialxCompensatesWithTheAverageFresnel) {
  const double alpha = 0.25, dv = 0.25 / (kPi * alpha * alpha);
  const double f0a = 0.04, f0b = 1.0 / 9.0;
  const auto a = evalOne(dielectric(0.5f, 1.5f), Profile::Materialx, Lobe::Specular, kN, kN);
  const auto b = evalOne(dielectric(0.5f, 2.0f), Profile::Materialx, Lobe::Specular, kN, kN);
  const double compA = a[0] / (dv * f0a), compB = b[0] / (dv * f0b);
  ASSERT_GT(compA, 1.001) << "the fit leaves something to compensate at alpha 0.25";
  const double favgA = f0a + (1.0 - f0a) / 21.0, favgB = f0b + (1.0 - f0b) / 21.0;
  EXPECT_NEAR(favgA / favgB, 0.558621, 1e-6);
  EXPECT_NEAR((compA - 1.0) / (compB - 1.0), favgA / favgB, 2e-3 * favgA / favgB);

  // The coat's compensation uses F_diel's average, 0.04 + 0.96/21, the same as the IOR 1.5 base:
  // a white-coated black base at L = V = N gives coat = cc F_c(1) D_c V_c comp_c with F_c(1) = 0.04.
  MaterialParams coated = dielectric(0.5f, 1.5f);
  coated.baseColor = {0.0f, 0.0f, 0.0f};
  coated.clearcoat = 1.0f;
  coated.clearcoatRoughness = 0.5f;
  const auto c = evalOne(coated, Profile::Materialx, Lobe::Clearcoat, kN, kN);
  EXPECT_NEAR(c[0] / (dv * 0.04), compA, 1e-4 * compA);
}

// three.js's WebGPU path clamps sheen roughness to [0.07, 1] (MaterialNode, SHEEN_ROUGHNESS).
// L = V at N.L = N.V = 0.05 puts H = L: N.H = 0.05, sin^2 = 0.9975. The sheen lobe is
// c D_Charlie(alpha_s, sin^2) min(V_Neubelt, 1), V_Neubelt = 1/(4 (0.1 - 0.0025)) > 1, so the lobe is
// c (2 + 1/alpha_s) 0.9975^(1/(2 alpha_s)) / (2 pi) with alpha_s = 0.07^2, about 25.4 c; the
// unclamped r_s = 0.03 would give about 44.1 c.
TEST(ProfileEngineFacts, ThreejsClampsSheenRoughnessAt007) {
  MaterialParams m = dielectric(0.5f, 1.5f);
  m.sheenColor = {1.0f, 0.5f, 0.25f};
  m.sheenRoughness = 0.03f;
  const double c = 0.05, s = std::sqrt(1.0 - c * c);
  const auto got = evalOne(m, Profile::Threejs, Lobe::Sheen, {s, 0.0, c}, {s, 0.0, c});
  const double alphaS = 0.07 * 0.07, sin2 = 1.0 - c * c;
  const double want = (2.0 + 1.0 / alphaS) * std::pow(sin2, 0.5 / alphaS) / (2.0 * kPi);
  EXPECT_NEAR(want, 25.4, 0.1);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], m.sheenColor[i] * want, 1e-3 * want) << "channel " << i;
}

// The Sample Renderer defines MATERIAL_ANISOTROPY when KHR_materials_anisotropy is present, even
// at strength 0, and takes BRDF_specularGGXAnisotropy: alpha_b = clamp(alpha, 0.001, 1). A white
// metal (F = 1) of roughness 0.01 (alpha = 1e-4) with L = V = (sin 0.1, 0, cos 0.1) = H: H.B = 0,
// so both paths have V = 0.25 / (c sqrt(c^2 (1 - a^2) + a^2)), and D = a^2 / (pi (c^2 (a^2 - 1) + 1)^2)
// without the extension against 1 / (pi a 0.001 (s^2/a^2 + c^2)^2) with it, about 10x smaller.
// (Off N.H = 1: there the engine's float D is infinite at this roughness.)
TEST(ProfileEngineFacts, KhronosTakesTheAnisotropicPathWhenTheExtensionIsPresent) {
  const auto parsed = parseMaterials(
      R"({"materials": [
        {"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.01}},
        {"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.01},
         "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0}}}]})",
      "inline");
  ASSERT_EQ(parsed.size(), 2u);
  EXPECT_FALSE(parsed[0].anisotropyExtension);
  EXPECT_TRUE(parsed[1].anisotropyExtension);
  const std::array<double, 3> dir{std::sin(0.1), 0.0, std::cos(0.1)};
  const auto absent = evalOne(parsed[0], Profile::Khronos, Lobe::Specular, dir, dir);
  const auto present = evalOne(parsed[1], Profile::Khronos, Lobe::Specular, dir, dir);
  const double a = double(0.01f) * double(0.01f), c = double(float(std::cos(0.1))), s = std::sqrt(1.0 - c * c);
  const double V = 0.25 / (c * std::sqrt(c * c * (1.0 - a * a) + a * a));
  const double f = c * c * (a * a - 1.0) + 1.0;
  const double wantAbsent = a * a / (kPi * f * f) * V;
  const double q = s * s / (a * a) + c * c;
  const double wantPresent = 1.0 / (kPi * a * 0.001 * q * q) * V;
  EXPECT_NEAR(absent[0], wantAbsent, 1e-4 * wantAbsent);
  EXPECT_NEAR(present[0], wantPresent, 1e-4 * wantPresent);
  EXPECT_LT(wantPresent, 0.2 * wantAbsent) << "the input tells the paths apart";
  // Under spec, presence at strength 0 changes nothing.
  const auto specAbsent = evalOne(parsed[0], Profile::Spec, Lobe::Specular, dir, dir);
  const auto specPresent = evalOne(parsed[1], Profile::Spec, Lobe::Specular, dir, dir);
  EXPECT_EQ(specAbsent[0], specPresent[0]);
}

// The Sample Renderer's D_GGX denominator N.H^2 (a^2 - 1) + 1 is exactly 0 in float at N.H = 1
// once a^2 - 1 rounds to -1 (a^2 <= 2^-25, roughness below about 0.013): D is infinite, and
// mix(S F_d, S F_m, metallic) makes the specular NaN at any metallic (0 * inf); the coat, which is
// only scaled, is +inf. At roughness 0.2 the same input stays finite.
TEST(ProfileEngineFacts, KhronosDIsInfiniteWhereTheEnginesFloatDenominatorIsZero) {
  for (float metallic : {0.0f, 1.0f}) {
    MaterialParams m = dielectric(1e-4f, 1.5f);
    m.metallic = metallic;
    for (double v : evalOne(m, Profile::Khronos, Lobe::Specular, kN, kN))
      EXPECT_TRUE(std::isnan(v)) << "metallic " << metallic << ": " << v;
    m.roughness = 0.2f;
    for (double v : evalOne(m, Profile::Khronos, Lobe::Specular, kN, kN)) EXPECT_TRUE(std::isfinite(v));
  }
  MaterialParams coated = dielectric(0.5f, 1.5f);
  coated.clearcoat = 1.0f;
  coated.clearcoatRoughness = 1e-4f;
  for (double v : evalOne(coated, Profile::Khronos, Lobe::Clearcoat, kN, kN))
    EXPECT_TRUE(std::isinf(v) && v > 0.0) << v;
}

// With the extension present at roughness 0, alpha_t = mix(0, 1, 0) = 0 and the engine's
// D_GGX_anisotropic (a = at ab, w2 = a / |(ab H.T, at H.B, a N.H)|^2, D = a w2^2 / pi) is 0
// off N.H = 1: the specular lobe is 0 there, not NaN (dividing H.T by at first gives 0 * inf).
TEST(ProfileEngineFacts, KhronosAnisotropicRoughness0IsZeroOffTheMirror) {
  MaterialParams m = dielectric(0.0f, 1.5f);
  m.anisotropyExtension = true;
  const std::array<double, 3> L{0.6, 0.0, 0.8}, V{0.0, 0.8, 0.6};
  for (double v : evalOne(m, Profile::Khronos, Lobe::Specular, L, V)) EXPECT_EQ(v, 0.0);
  for (double v : evalOne(m, Profile::Khronos, Lobe::Specular, kN, kN)) EXPECT_TRUE(std::isnan(v)) << v;
}

// The Sample Renderer's D_Charlie takes sin^2 = 1 - N.H^2 in float, which is 1 for N.H below about
// 1.7e-4; at sheen roughness 0 (floored to 1e-6, alpha 1e-12) D is then (2 + 1e12)/(2 pi), not the
// exact (sin^2)^(5e11) = 0. L = (s, 0, c), V = (0, s, c) with c = 1e-4 give N.H = sqrt(2) c; V_Sheen is
// clamped to 1 there, so the sheen lobe is sheenColor (2 + 1/alpha)/(2 pi).
TEST(ProfileEngineFacts, KhronosSheenDUsesTheEnginesFloatSin2) {
  MaterialParams m = dielectric(0.5f, 1.5f);
  m.sheenColor = {1.0f, 0.8f, 0.6f};
  m.sheenRoughness = 0.0f;
  const double c = 1e-4, s = std::sqrt(1.0 - c * c);
  const auto got = evalOne(m, Profile::Khronos, Lobe::Sheen, {s, 0.0, c}, {0.0, s, c});
  const double alpha = double(1e-6f) * double(1e-6f);
  const double want = (2.0 + 1.0 / alpha) / (2.0 * kPi);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], m.sheenColor[i] * want, 1e-4 * want) << "channel " << i;
}

// 1 - F_Schlick(f0, 1, V.H) and the coat's 1 - cc F_Schlick(f0, 1, N.V) computed without
// cancellation: on the mirror pair L = (s, 0, c), V = (-s, 0, c), c = 1e-6, H = N and
// V.H = N.V = c, the diffuse lobe is (1 - f0)(1 - (1 - c)^5) b/pi, times (1 - f0)(1 - (1 - c)^5)
// more under a full coat (IOR 1.5: f0 = 0.04 for both). Written as 1 - F in float these lose
// several percent.
TEST(ProfileEngineFacts, KhronosOneMinusFresnelKeepsItsDigitsAtGrazingVdotH) {
  const double c = double(float(1e-6)), s = std::sqrt(1.0 - c * c);
  const double w = (1.0 - 0.04) * (1.0 - std::pow(1.0 - c, 5.0));
  MaterialParams m = dielectric(0.3f, 1.5f);
  const auto bare = evalOne(m, Profile::Khronos, Lobe::Diffuse, {s, 0.0, c}, {-s, 0.0, c});
  EXPECT_NEAR(bare[0], w * 0.5 / kPi, 1e-3 * w * 0.5 / kPi);
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 0.5f;
  const auto coated = evalOne(m, Profile::Khronos, Lobe::Diffuse, {s, 0.0, c}, {-s, 0.0, c});
  EXPECT_NEAR(coated[0], w * w * 0.5 / kPi, 1e-3 * w * w * 0.5 / kPi);
}

// Filament's D_GGX caps k = alpha / (1 - N.H^2 + (N.H alpha)^2) at 453.5, so D <= 453.5^2/pi
// (65464.9, below fp16's 65504); Kelemen's V = 0.25/(L.H)^2 has no cap on desktop. A coat of
// roughness 0 (floored to 0.045, alpha 0.002025: k = 1/alpha = 493.8 is capped) seen with
// L = (s, 0, c), V = (-s, 0, c), c = 1e-3: H = N, L.H = c, so
// coat = cc (0.04 + 0.96 (1 - c)^5) (453.5^2/pi) (0.25/c^2).
TEST(ProfileEngineFacts, FilamentCapsDAt4535SquaredOverPiAndNotV) {
  MaterialParams m = dielectric(0.5f, 1.5f);
  m.baseColor = {0.0f, 0.0f, 0.0f};
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 0.0f;
  const auto top = evalOne(m, Profile::Filament, Lobe::Clearcoat, kN, kN);
  const double dCap = 453.5 * 453.5 / kPi;
  EXPECT_NEAR(top[0], 0.04 * dCap * 0.25, 1e-5 * 0.04 * dCap * 0.25);

  const double c = 1e-3, s = std::sqrt(1.0 - c * c);
  const auto graze = evalOne(m, Profile::Filament, Lobe::Clearcoat, {s, 0.0, c}, {-s, 0.0, c});
  const double want = (0.04 + 0.96 * std::pow(1.0 - c, 5.0)) * dCap * (0.25 / (c * c));
  EXPECT_NEAR(graze[0], want, 1e-3 * want);
}

// Khronos clamps N.L to [0, 1] (clampedDot) with no floor. A white metal (F = 1) of roughness 0.1
// at V = N, N.L = 1e-5 has S = D V with V = 0.5 / (N.L + sqrt(N.L^2 (1 - a^2) + a^2)) = 49.95;
// a floor at 1e-4 would give 49.50.
TEST(ProfileEngineFacts, EngineCosinesAreNotFlooredAt1e4) {
  MaterialParams m;
  m.baseColor = {1.0f, 1.0f, 1.0f};
  m.metallic = 1.0f;
  m.roughness = 0.1f;
  const double nl = 1e-5, sl = std::sqrt(1.0 - nl * nl);
  const std::array<double, 3> L{sl, 0.0, nl};
  const auto got = evalOne(m, Profile::Khronos, Lobe::Specular, L, kN);
  // The light as the kernel sees it: components rounded to float, then normalized.
  const double lx = double(float(sl)), lz = double(float(nl));
  const double ln = std::sqrt(lx * lx + lz * lz), NdotL = lz / ln;
  const double r = double(0.1f), a = r * r;
  const double hx = lx / ln, hz = NdotL + 1.0, hn = std::sqrt(hx * hx + hz * hz), NdotH = hz / hn;
  const double d = NdotH * NdotH * (a * a - 1.0) + 1.0;
  const double D = a * a / (kPi * d * d);
  const double V = 0.5 / (NdotL * 1.0 + 1.0 * std::sqrt(NdotL * NdotL * (1.0 - a * a) + a * a));
  EXPECT_NEAR(got[0], D * V, 1e-4 * D * V);
  const double Vfloor = 0.5 / (1e-4 + std::sqrt(1e-8 * (1.0 - a * a) + a * a));
  EXPECT_GT(std::fabs(V / Vfloor - 1.0), 5e-3) << "the input tells the floor from none";
}

}  // namespace
