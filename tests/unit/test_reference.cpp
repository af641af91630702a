// Tests of the double-precision reference itself (tests/reference), not of the kernels: closed
// forms, normalisation, reciprocity, the layering formulas and the lobe split (the sheen albedo
// and energy bounds: test_reference_albedo.cpp).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>
#include <vector>

#include "reference/reference.hpp"
#include "reference_checks.hpp"

// ---------------------------------------------------------------------------------------------
// Quadrature and closed forms
// ---------------------------------------------------------------------------------------------

TEST(Reference, GaussKronrodIsExactUpToDegree31) {
  for (int n = 0; n <= 31; ++n) {
    // One interval only: the 21-point Kronrod rule must integrate x^n exactly.
    const double v = ref::integrate([&](double x) { return std::pow(x, n); }, -1.0, 1.0, 1e300, 1);
    const double exact = n % 2 ? 0.0 : 2.0 / (n + 1);
    EXPECT_NEAR(v, exact, 1e-14) << "x^" << n;
  }
  EXPECT_NEAR(ref::integrate([](double x) { return std::sqrt(x); }, 0.0, 1.0, 1e-13), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(ref::integrate([](double x) { return 1.0 / (1e-4 + x * x); }, -1.0, 1.0, 1e-10),
              2.0 * std::atan(100.0) * 100.0, 1e-8);
}

TEST(Reference, GgxClosedForms) {
  for (double alpha : {0.0025, 0.04, 0.3, 1.0}) {
    // (N.H)^2 (alpha^2 - 1) + 1 cancels to alpha^2 at N.H = 1: ~1e-16 / alpha^2 relative error.
    const double atNormal = 1.0 / (kPi * alpha * alpha);
    EXPECT_NEAR(ref::D_GGX(1.0, alpha), atNormal, 1e-10 * atNormal);
    EXPECT_NEAR(ref::D_GGX(1e-9, alpha), alpha * alpha / kPi, 1e-15);
    EXPECT_EQ(ref::D_GGX(0.0, alpha), 0.0);  // chi+(0) = 0
    EXPECT_EQ(ref::D_GGX(-0.3, alpha), 0.0);
    EXPECT_NEAR(ref::V_SmithGGXCorrelated(1.0, 1.0, alpha), 0.25, 1e-15);
  }
  // alpha = 1: both square roots are 1.
  EXPECT_NEAR(ref::V_SmithGGXCorrelated(0.3, 0.8, 1.0), 0.5 / 1.1, 1e-15);
  // Against the separable product at alpha -> 0 (both G1 -> 1): V -> 1 / (4 N.L N.V).
  EXPECT_NEAR(ref::V_SmithGGXCorrelated(0.3, 0.8, 1e-9), 1.0 / (4.0 * 0.3 * 0.8), 1e-9);
}

TEST(Reference, SheenTermsMatchAnIndependentTranscription) {
  // Values from a separate transcription of 000's l(x)/lambda_sheen/Charlie D and 003's
  // AshikhminD into Python (same double arithmetic).
  EXPECT_NEAR(ref::V_Charlie(0.3, 0.8, 0.25), 0.24449487606781367, 1e-13);
  EXPECT_NEAR(ref::V_Charlie(0.7, 0.2, 0.0625), 0.20408087793275032, 1e-13);
  EXPECT_NEAR(ref::V_Charlie(0.45, 0.55, 1.0), 0.41348345521959445, 1e-13);
  EXPECT_NEAR(ref::V_Charlie(0.05, 0.9, 0.5), 0.33797897797755744, 1e-13);
  EXPECT_NEAR(ref::D_Charlie(0.3, 0.25), 0.7907772502463912, 1e-13);
  EXPECT_NEAR(ref::D_Charlie(0.7, 0.0625), 0.013111550304363347, 1e-15);
  EXPECT_NEAR(ref::D_Charlie(0.1, 1.0), 0.4750715067895647, 1e-13);
  EXPECT_NEAR(ref::D_Ashikhmin(0.3, 0.25), 0.507392631977102, 1e-13);
  EXPECT_NEAR(ref::D_Ashikhmin(0.05, 0.0625), 0.976706470952876, 1e-13);
  EXPECT_NEAR(ref::D_Ashikhmin(0.7, 1.0), 0.43823494880301683, 1e-13);
  for (double a : {0.0025, 0.1, 0.5, 1.0}) {
    EXPECT_NEAR(ref::D_Charlie(0.0, a), (2.0 + 1.0 / a) / (2.0 * kPi), 1e-12);
    EXPECT_EQ(ref::D_Charlie(1.0, a), 0.0);
    EXPECT_NEAR(ref::D_Ashikhmin(0.0, a), 5.0 / (kPi * (1.0 + 4.0 * a * a)), 1e-14);
    // H = N: the article's 0/0, defined by its limit.
    EXPECT_NEAR(ref::D_Ashikhmin(1.0, a), 1.0 / (kPi * (1.0 + 4.0 * a * a)), 1e-14);
    EXPECT_NEAR(ref::D_Ashikhmin(1.0 - 1e-9, a), 1.0 / (kPi * (1.0 + 4.0 * a * a)), 1e-12);
  }
  EXPECT_NEAR(ref::V_Ashikhmin(1.0, 1.0), 0.25, 1e-15);
  EXPECT_NEAR(ref::V_Ashikhmin(0.5, 0.5), 1.0 / 3.0, 1e-15);
}

TEST(Reference, CharlieLambdaIsContinuousAtOneHalf) {
  // The two branches of lambda_sheen meet at cos = 0.5 (value and slope).
  for (double a : {0.0025, 0.1, 0.5, 1.0}) {
    const double lo = ref::V_Charlie(0.5 - 1e-9, 0.7, a), hi = ref::V_Charlie(0.5 + 1e-9, 0.7, a);
    EXPECT_NEAR(lo, hi, 1e-8 * lo) << a;
    const double h = 1e-4;
    const double slopeLo = (ref::V_Charlie(0.5, 0.7, a) - ref::V_Charlie(0.5 - h, 0.7, a)) / h;
    const double slopeHi = (ref::V_Charlie(0.5 + h, 0.7, a) - ref::V_Charlie(0.5, 0.7, a)) / h;
    EXPECT_NEAR(slopeLo, slopeHi, 1e-2 * std::abs(slopeLo)) << a;
  }
}

TEST(Reference, FresnelSchlick) {
  EXPECT_NEAR(ref::F_Schlick(0.04, 1.0), 0.04, 1e-15);
  EXPECT_NEAR(ref::F_Schlick(0.04, 0.0), 1.0, 1e-15);
  EXPECT_NEAR(ref::F_Schlick(0.04, 0.5), 0.04 + 0.96 / 32.0, 1e-15);
  EXPECT_NEAR(ref::F_Schlick(0.7, -0.5), ref::F_Schlick(0.7, 0.5), 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Normalisation of the distributions: int D (N.H) dw_H = 1
// ---------------------------------------------------------------------------------------------

TEST(Reference, DistributionsAreNormalized) {
  for (double a : {0.0025, 0.01, 0.09, 0.36, 1.0}) {
    EXPECT_NEAR(projectedArea([&](double t) { return ref::D_GGX(t, a); }, 0.9), 1.0, 1e-8) << "GGX " << a;
    EXPECT_NEAR(projectedArea([&](double t) { return ref::D_Charlie(t, a); }, 0.1), 1.0, 1e-8) << "Charlie " << a;
  }
  // 1/(1+4m^2) from the constant part, 4m^2/(1+4m^2) from the spike at N.H ~ m: both must be there.
  for (double a : {0.0025, 0.05, 0.3, 1.0}) {
    EXPECT_NEAR(projectedArea([&](double t) { return ref::D_Ashikhmin(t, a); }, std::min(0.5, 10.0 * a)),
                1.0, 1e-8)
        << "Ashikhmin " << a;
  }
}

TEST(Reference, AnisotropicDistributionIsNormalized) {
  for (const auto& ta : {std::pair{0.3, 0.05}, std::pair{1.0, 0.2}, std::pair{0.5, 0.5}}) {
    const double at = ta.first, ab = ta.second;  // not structured bindings: C++17 lambdas cannot capture those
    auto overPhi = [&](double t) {
      const double s = std::sqrt(1.0 - t * t);
      auto f = [&](double phi) {
        return ref::D_GGX_Anisotropic(t, s * std::cos(phi), s * std::sin(phi), at, ab);
      };
      return 4.0 * ref::integrate(f, 0.0, kPi / 2.0, 1e-12) * t;  // four symmetric quadrants
    };
    const double v = ref::integrate(overPhi, 0.0, 0.9, 1e-11) + ref::integrate(overPhi, 0.9, 1.0, 1e-11);
    EXPECT_NEAR(v, 1.0, 1e-7) << at << " " << ab;
  }
}

// ---------------------------------------------------------------------------------------------
// Anisotropy
// ---------------------------------------------------------------------------------------------

TEST(Reference, AnisotropicTermsReduceToIsotropic) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 L = randomDir(rng), V = randomDir(rng);
    const Vec3 H = normalized({L.x + V.x, L.y + V.y, L.z + V.z});
    const double a = 0.0025 + u(rng), rot = 2.0 * kPi * u(rng);
    const Vec3 T{std::cos(rot), std::sin(rot), 0.0}, B{-std::sin(rot), std::cos(rot), 0.0};
    const double dIso = ref::D_GGX(H.z, a);
    EXPECT_NEAR(ref::D_GGX_Anisotropic(H.z, dot(T, H), dot(B, H), a, a), dIso, 1e-12 * dIso);
    const double vIso = ref::V_SmithGGXCorrelated(L.z, V.z, a);
    EXPECT_NEAR(ref::V_GGX_Anisotropic(L.z, V.z, dot(T, V), dot(B, V), dot(T, L), dot(B, L), a, a), vIso,
                1e-12 * vIso);
  }
  // Through brdf(): a vanishing strength (anisotropic code path) matches strength 0 (isotropic).
  MaterialParams m;
  m.roughness = 0.4f;
  m.anisotropyRotation = 1.1f;
  MaterialParams mTiny = m;
  mTiny.anisotropyStrength = 1e-6f;
  for (int i = 0; i < 50; ++i) {
    const Vec3 L = randomDir(rng), V = randomDir(rng);
    expectRgbNear(ref::brdf(mTiny, {}, L, V), ref::brdf(m, {}, L, V), 1e-9, 0.0, "strength 1e-6");
  }
}

TEST(Reference, AnisotropyStretchesAlongTheRotatedTangent) {
  // 002: roughness grows along T' (rotated CCW from T = +X); the highlight is elongated along T'.
  MaterialParams m;  // white metal: Specular = D V exactly
  m.roughness = 0.3f;
  m.anisotropyStrength = 0.8f;
  EvalOptions o;
  o.lobe = Lobe::Specular;
  const Vec3 V{0.0, 0.0, 1.0};
  auto reflectAbout = [&](Vec3 H) {
    const double d = 2.0 * dot(V, H);
    return Vec3{d * H.x - V.x, d * H.y - V.y, d * H.z - V.z};
  };
  const double tilt = 0.3;
  for (double rotD : {0.0, kPi / 2.0, 0.7}) {
    m.anisotropyRotation = static_cast<float>(rotD);
    const double rot = m.anisotropyRotation;  // the float the reference reads
    const Vec3 alongT = dir(std::cos(tilt), rot), alongB = dir(std::cos(tilt), rot + kPi / 2.0);
    const double fT = ref::brdf(m, o, reflectAbout(alongT), V)[0];
    const double fB = ref::brdf(m, o, reflectAbout(alongB), V)[0];
    EXPECT_GT(fT, 2.0 * fB) << "rotation " << rot;
    // Exact value along T': alpha_t governs the tilt, alpha_b = alpha.
    const double a = double(m.roughness) * m.roughness, s2 = double(m.anisotropyStrength) * m.anisotropyStrength;
    const double at = a * (1.0 - s2) + s2;
    const double expectedD = 1.0 / (kPi * at * a *
                                    std::pow(std::sin(tilt) * std::sin(tilt) / (at * at) + std::cos(tilt) * std::cos(tilt), 2.0));
    const Vec3 L = reflectAbout(alongT);
    const double tL = std::cos(rot) * L.x + std::sin(rot) * L.y, bL = -std::sin(rot) * L.x + std::cos(rot) * L.y;
    const double expectedV = 0.5 / (L.z * 1.0 + 1.0 * std::sqrt(at * at * tL * tL + a * a * bL * bL + L.z * L.z));
    EXPECT_NEAR(fT, expectedD * expectedV, 1e-9 * fT) << "rotation " << rot;
  }
  // Rotating the material and both directions together changes nothing.
  std::mt19937_64 rng(2);
  for (int i = 0; i < 50; ++i) {
    const Vec3 L = randomDir(rng), V2 = randomDir(rng);
    const double rot = 0.37 + i * 0.1;
    MaterialParams m0 = m, mr = m;
    m0.anisotropyRotation = 0.0f;
    mr.anisotropyRotation = static_cast<float>(rot);
    expectRgbNear(ref::brdf(mr, {}, rotateZ(L, static_cast<float>(rot)), rotateZ(V2, static_cast<float>(rot))),
                  ref::brdf(m0, {}, L, V2), 1e-9, 0.0, "rotation invariance");
  }
}

// ---------------------------------------------------------------------------------------------
// The layered BRDF
// ---------------------------------------------------------------------------------------------

TEST(Reference, ZeroBelowTheHorizon) {
  MaterialParams m;
  m.sheenColor = {1.0f, 1.0f, 1.0f};
  m.sheenRoughness = 0.5f;
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 0.2f;
  const Vec3 up = dir(0.5, 0.3);
  for (Vec3 below : {dir(-0.2, 1.0), dir(0.0, 2.0), Vec3{0.0, 0.0, -1.0}}) {
    const Rgb a = ref::brdf(m, {}, below, up), b = ref::brdf(m, {}, up, below);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(a[c], 0.0);
      EXPECT_EQ(b[c], 0.0);
    }
  }
  EXPECT_GT(ref::brdf(m, {}, up, dir(0.9, 2.0))[0], 0.0);
}

TEST(Reference, ReciprocalWhereTheModelIsSymmetric) {
  std::mt19937_64 rng(3);
  for (const MaterialParams& m : baseAndSheenMaterials()) {
    for (SheenDistribution d : kDists)
      for (SheenVisibility v : kVises)
        for (SheenScaling s : {SheenScaling::None, SheenScaling::Min}) {
          EvalOptions o;
          o.sheenDistribution = d;
          o.sheenVisibility = v;
          o.sheenScaling = s;
          for (int i = 0; i < 10; ++i) {
            const Vec3 L = randomDir(rng), V = randomDir(rng);
            expectRgbNear(ref::brdf(m, o, L, V), ref::brdf(m, o, V, L), 1e-12, 1e-300, m.name.c_str());
          }
        }
  }
}

TEST(Reference, ClearcoatAndViewScalingAreNotReciprocal) {
  // Fc uses N.V (KHR_materials_clearcoat), and View scaling uses E(N.V) only: neither is symmetric in L and V.
  const Vec3 L = dir(0.15, 0.0), V = dir(0.9, 2.5);
  MaterialParams cc;
  cc.clearcoat = 1.0f;
  cc.clearcoatRoughness = 0.3f;
  const double a = ref::brdf(cc, {}, L, V)[0], b = ref::brdf(cc, {}, V, L)[0];
  EXPECT_GT(std::abs(a - b), 1e-3 * std::max(a, b));
  MaterialParams sh;
  sh.sheenColor = {1.0f, 1.0f, 1.0f};
  sh.sheenRoughness = 0.5f;
  EvalOptions o;
  o.sheenScaling = SheenScaling::View;
  const double c = ref::brdf(sh, o, L, V)[0], d = ref::brdf(sh, o, V, L)[0];
  EXPECT_GT(std::abs(c - d), 1e-3 * std::max(c, d));
}

TEST(Reference, LobesSumToAll) {
  std::mt19937_64 rng(4);
  for (int i = 0; i < 400; ++i) {
    MaterialParams m;
    m.baseColor = {uf(rng), uf(rng), uf(rng)};
    m.metallic = uf(rng);
    m.roughness = uf(rng, 0.05, 1.0);
    m.draftSheen = i % 4 == 3;
    if (i % 3 != 0) m.sheenColor = {uf(rng), uf(rng), uf(rng)};
    m.sheenRoughness = uf(rng, 0.05, 1.0);
    m.draftColor = {uf(rng), uf(rng), uf(rng)};
    m.draftIntensity = uf(rng);
    if (i % 2) m.clearcoat = uf(rng);
    m.clearcoatRoughness = uf(rng, 0.05, 1.0);
    if (i % 5 < 2) m.anisotropyStrength = uf(rng);
    m.anisotropyRotation = uf(rng, 0.0, 6.0);
    EvalOptions o;
    o.sheenDistribution = kDists[i % 2];
    o.sheenVisibility = kVises[(i / 2) % 2];
    o.sheenScaling = std::array{SheenScaling::Min, SheenScaling::View, SheenScaling::None}[i % 3];
    const Vec3 L = randomDir(rng), V = randomDir(rng);
    Rgb lobes[4];
    const Lobe which[4] = {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat};
    for (int k = 0; k < 4; ++k) {
      o.lobe = which[k];
      lobes[k] = ref::brdf(m, o, L, V);
    }
    o.lobe = Lobe::All;
    const Rgb all = ref::brdf(m, o, L, V);
    const Rgb sum{lobes[0][0] + lobes[1][0] + lobes[2][0] + lobes[3][0],
                  lobes[0][1] + lobes[1][1] + lobes[2][1] + lobes[3][1],
                  lobes[0][2] + lobes[1][2] + lobes[2][2] + lobes[3][2]};
    expectRgbNear(sum, all, 1e-13, 1e-300, "sum of lobes");
    // Disabled layers contribute nothing.
    for (int c = 0; c < 3; ++c) {
      if (m.clearcoat == 0.0f) {
        EXPECT_EQ(lobes[3][c], 0.0);
      }
      if (!m.draftSheen && m.sheenColor[0] == 0.0f && m.sheenColor[1] == 0.0f && m.sheenColor[2] == 0.0f) {
        EXPECT_EQ(lobes[2][c], 0.0);
      }
    }
  }
  MaterialParams metal;  // metallic = 1: no diffuse at all
  EvalOptions o;
  o.lobe = Lobe::Diffuse;
  EXPECT_EQ(ref::brdf(metal, o, dir(0.5, 0.0), dir(0.7, 2.0))[0], 0.0);
}

TEST(Reference, LayeringFollowsTheSpecFormulas) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 100; ++i) {
    MaterialParams base;
    base.baseColor = {uf(rng), uf(rng), uf(rng)};
    base.metallic = uf(rng);
    base.roughness = uf(rng, 0.05, 1.0);
    const Vec3 L = randomDir(rng), V = randomDir(rng);
    const Vec3 H = normalized({L.x + V.x, L.y + V.y, L.z + V.z});
    const Rgb fBase = ref::brdf(base, {}, L, V);

    // Ratified sheen (KHR_materials_sheen): sheenColor * D * V + scaling * material.
    MaterialParams sh = base;
    sh.sheenColor = {uf(rng), uf(rng), uf(rng)};
    sh.sheenRoughness = uf(rng, 0.05, 1.0);
    const double rs = sh.sheenRoughness, as = rs * rs;
    const double mc = std::max({double(sh.sheenColor[0]), double(sh.sheenColor[1]), double(sh.sheenColor[2])});
    for (SheenDistribution d : kDists)
      for (SheenVisibility v : kVises)
        for (SheenScaling s : {SheenScaling::None, SheenScaling::View, SheenScaling::Min}) {
          EvalOptions o;
          o.sheenDistribution = d;
          o.sheenVisibility = v;
          o.sheenScaling = s;
          const double eV = ref::sheenAlbedo(V.z, rs, d, v), eL = ref::sheenAlbedo(L.z, rs, d, v);
          const double scale = s == SheenScaling::None ? 1.0
                               : s == SheenScaling::View ? 1.0 - mc * eV
                                                         : std::min(1.0 - mc * eV, 1.0 - mc * eL);
          const double dv = ref::sheenD(H.z, as, d) * ref::sheenV(L.z, V.z, as, v);
          Rgb expected;
          for (int c = 0; c < 3; ++c) expected[c] = sh.sheenColor[c] * dv + scale * fBase[c];
          expectRgbNear(ref::brdf(sh, o, L, V), expected, 1e-12, 1e-300, "ratified sheen");
        }

    // Draft sheen (the experimental draft): material + (1 - reflectance) * color * intensity * D_Charlie * V_Ashikhmin,
    // with roughness = material roughness; options and sheenColor do not apply.
    MaterialParams dr = sh;
    dr.draftSheen = true;
    dr.draftColor = {uf(rng), uf(rng), uf(rng)};
    dr.draftIntensity = uf(rng);
    double reflectance = 0.0;
    for (int c = 0; c < 3; ++c)
      reflectance = std::max(reflectance, 0.04 * (1.0 - dr.metallic) + double(dr.baseColor[c]) * dr.metallic);
    const double a = double(dr.roughness) * dr.roughness;
    const double dvDraft = ref::D_Charlie(H.z, a) * ref::V_Ashikhmin(L.z, V.z);
    Rgb expectedDraft;
    for (int c = 0; c < 3; ++c)
      expectedDraft[c] = fBase[c] + (1.0 - reflectance) * dr.draftColor[c] * double(dr.draftIntensity) * dvDraft;
    EvalOptions odd;
    odd.sheenDistribution = SheenDistribution::Ashikhmin;
    odd.sheenVisibility = SheenVisibility::Charlie;
    odd.sheenScaling = SheenScaling::View;
    expectRgbNear(ref::brdf(dr, {}, L, V), expectedDraft, 1e-12, 1e-300, "draft sheen");
    expectRgbNear(ref::brdf(dr, odd, L, V), expectedDraft, 1e-12, 1e-300, "draft sheen, other options");

    // Clearcoat (KHR_materials_clearcoat) on top: (1 - c Fc) * below + c Fc * D_GGX * V_Smith, Fc on N.V.
    MaterialParams cc = sh;
    cc.clearcoat = uf(rng);
    cc.clearcoatRoughness = uf(rng, 0.05, 1.0);
    const double fc = 0.04 + 0.96 * std::pow(1.0 - V.z, 5.0);
    const double ac = double(cc.clearcoatRoughness) * cc.clearcoatRoughness;
    const double coat = ref::D_GGX(H.z, ac) * ref::V_SmithGGXCorrelated(L.z, V.z, ac);
    const Rgb below = ref::brdf(sh, {}, L, V);
    Rgb expectedCoat;
    for (int c = 0; c < 3; ++c)
      expectedCoat[c] = (1.0 - cc.clearcoat * fc) * below[c] + cc.clearcoat * fc * coat;
    expectRgbNear(ref::brdf(cc, {}, L, V), expectedCoat, 1e-12, 1e-300, "clearcoat");
  }
}

TEST(Reference, BaseMatchesAppendixB) {
  // Dielectric and metal mixed by metallic, F on V.H; written out here from Appendix B.
  std::mt19937_64 rng(6);
  for (int i = 0; i < 100; ++i) {
    MaterialParams m;
    m.baseColor = {uf(rng), uf(rng), uf(rng)};
    m.metallic = uf(rng);
    m.roughness = uf(rng, 0.05, 1.0);
    const Vec3 L = randomDir(rng), V = randomDir(rng);
    const Vec3 H = normalized({L.x + V.x, L.y + V.y, L.z + V.z});
    const double a = double(m.roughness) * m.roughness;
    const double spec = ref::D_GGX(H.z, a) * ref::V_SmithGGXCorrelated(L.z, V.z, a);
    const double w = std::pow(1.0 - std::abs(dot(V, H)), 5.0);
    const double F = 0.04 + 0.96 * w;
    Rgb expected;
    for (int c = 0; c < 3; ++c) {
      const double bc = m.baseColor[c];
      const double dielectric = (1.0 - F) * bc / kPi + F * spec;
      const double metal = (bc + (1.0 - bc) * w) * spec;
      expected[c] = (1.0 - m.metallic) * dielectric + m.metallic * metal;
    }
    expectRgbNear(ref::brdf(m, {}, L, V), expected, 1e-12, 1e-300, "Appendix B");
  }
}
