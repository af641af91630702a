// Self-checks of the engine-profile reference (tests/reference/profiles.cpp), not of the kernels:
// lobe split, delegation of spec, where khronos must equal spec, NaN reproduction, per-engine
// layering properties, the three.js DFG data and MaterialX fits, and closed forms at L = V = N.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "reference/profiles.hpp"
#include "reference/reference.hpp"

namespace {

using brdfcl::EvalOptions;
using brdfcl::Lobe;
using brdfcl::MaterialParams;
using brdfcl::Profile;
using ref::kPi;
using ref::Rgb;
using ref::Vec3;

constexpr Lobe kParts[4] = {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat};
constexpr Vec3 kN{0.0, 0.0, 1.0};

Vec3 dir(double cosTheta, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

// |a - b| relative to max(|a|, |b|, floor); NaN when either is NaN (so comparisons fail).
double relDiff(double a, double b, double floor = 1e-300) {
  return std::abs(a - b) / std::max({std::abs(a), std::abs(b), floor});
}

struct Sampler {
  std::mt19937_64 rng;
  std::uniform_real_distribution<double> u{0.0, 1.0};
  explicit Sampler(std::uint64_t seed) : rng(seed) {}
  double operator()(double a, double b) { return a + (b - a) * u(rng); }
  float f(double a, double b) { return static_cast<float>((*this)(a, b)); }

  // Cosines kept >= 0.02 so the sheen E lookups stay in the table's domain (fast).
  Vec3 direction() { return dir((*this)(0.02, 1.0), (*this)(0.0, 2.0 * kPi)); }

  // Sheen, coat and anisotropy each switched on half the time; sheen roughness >= 0.05 (table).
  MaterialParams material() {
    MaterialParams m;
    m.baseColor = {f(0, 1), f(0, 1), f(0, 1)};
    m.metallic = f(0, 1);
    m.roughness = f(0.02, 1);
    if (u(rng) < 0.5) {
      m.sheenColor = {f(0, 1), f(0, 1), f(0, 1)};
      m.sheenRoughness = f(0.05, 1);
    }
    if (u(rng) < 0.5) {
      m.clearcoat = f(0.05, 1);
      m.clearcoatRoughness = f(0.02, 1);
    }
    if (u(rng) < 0.5) {
      m.anisotropyStrength = f(0.05, 1);
      m.anisotropyRotation = f(-kPi, kPi);
    }
    m.ior = f(1.2, 2.0);
    return m;
  }
};

std::string profileName(Profile p) { return brdfcl::toString(p); }

// ---- Structure ----

TEST(ProfileReference, LobesSumToAllForEveryProfile) {
  Sampler s(0x10be5);
  for (Profile p : brdfcl::kAllProfiles) {
    double worst = 0.0;
    for (int i = 0; i < 150; ++i) {
      const MaterialParams m = s.material();
      const Vec3 L = s.direction(), V = s.direction();
      const Rgb all = ref::profileBrdf(m, p, Lobe::All, L, V);
      Rgb sum{}, magnitude{};
      for (Lobe l : kParts) {
        const Rgb part = ref::profileBrdf(m, p, l, L, V);
        for (int c = 0; c < 3; ++c) {
          sum[c] += part[c];
          magnitude[c] += std::abs(part[c]);
        }
      }
      // Relative to the sum of magnitudes: a sheen scaling above 1 makes parts negative.
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(all[c])) << profileName(p) << " sample " << i;
        worst = std::max(worst, std::abs(sum[c] - all[c]) / (magnitude[c] + 1e-12));
      }
    }
    EXPECT_LE(worst, 1e-12) << profileName(p);
  }
}

TEST(ProfileReference, BelowHorizonIsZero) {
  MaterialParams m;
  m.sheenColor = {1, 1, 1};
  m.sheenRoughness = 0.5f;
  m.clearcoat = 1.0f;
  const Vec3 up = dir(0.7, 0.3), down{0.3, 0.2, -0.5};
  for (Profile p : brdfcl::kAllProfiles)
    for (Lobe l : {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat}) {
      EXPECT_EQ(ref::profileBrdf(m, p, l, down, up), (Rgb{0, 0, 0})) << profileName(p);
      EXPECT_EQ(ref::profileBrdf(m, p, l, up, down), (Rgb{0, 0, 0})) << profileName(p);
    }
}

TEST(ProfileReference, SpecDelegatesToReferenceBrdf) {
  Sampler s(0x5bec);
  for (int i = 0; i < 100; ++i) {
    const MaterialParams m = s.material();
    const Vec3 L = s.direction(), V = s.direction();
    for (Lobe l : {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat}) {
      EvalOptions o;
      o.lobe = l;
      EXPECT_EQ(ref::profileBrdf(m, Profile::Spec, l, L, V), ref::brdf(m, o, L, V));
    }
  }
}

// Unnormalised inputs give the same answer as normalised ones (L, V are normalised inside).
TEST(ProfileReference, NormalisesInputs) {
  Sampler s(0x0e11);
  for (Profile p : brdfcl::kAllProfiles) {
    const MaterialParams m = s.material();
    const Vec3 L = s.direction(), V = s.direction();
    const Rgb a = ref::profileBrdf(m, p, Lobe::All, L, V);
    const Rgb b = ref::profileBrdf(m, p, Lobe::All, {3 * L.x, 3 * L.y, 3 * L.z}, {0.5 * V.x, 0.5 * V.y, 0.5 * V.z});
    // Rounding of the normalisation, amplified by a sharp lobe (D ~ 1/alpha^2 near its peak).
    for (int c = 0; c < 3; ++c) EXPECT_LE(relDiff(a[c], b[c], 1e-12), 1e-9) << profileName(p);
  }
}

// ---- khronos ----

// docs/profiles.md: khronos differs from spec only through the V_CK clamp, the IOR, anisotropy
// with alpha < 0.001 or N.H < 0.001, the sheen table roughness, and r = 0. Without sheen, at
// ior 1.5, roughness >= 0.05 and away from those corners they must agree. The engine's
// anisotropic V is also clamped to <= 1 (spec's is not); samples where it bites are skipped.
TEST(ProfileReference, KhronosEqualsSpecWhereDocsSayItMust) {
  Sampler s(0x4b40);
  int compared = 0, skipped = 0, anisoCompared = 0;
  double worst = 0.0;
  for (int i = 0; i < 400; ++i) {
    MaterialParams m = s.material();
    m.sheenColor = {0, 0, 0};
    m.ior = 1.5f;
    m.roughness = s.f(0.05, 1);
    m.clearcoatRoughness = s.f(0.05, 1);
    const Vec3 L = s.direction(), V = s.direction();
    if (m.anisotropyStrength > 0) {
      const double alpha = double(m.roughness) * m.roughness;
      const double s2 = double(m.anisotropyStrength) * m.anisotropyStrength;
      const double at = alpha * (1 - s2) + s2, ab = alpha;
      const double th = m.anisotropyRotation;
      const Vec3 T{std::cos(th), std::sin(th), 0}, B{-std::sin(th), std::cos(th), 0};
      const Vec3 Hu{L.x + V.x, L.y + V.y, L.z + V.z};
      const double NdotH = Hu.z / std::sqrt(Hu.x * Hu.x + Hu.y * Hu.y + Hu.z * Hu.z);
      auto d = [](Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
      const double vis = ref::V_GGX_Anisotropic(L.z, V.z, d(T, V), d(B, V), d(T, L), d(B, L), at, ab);
      if (vis > 1.0 || NdotH < 0.001) {
        ++skipped;
        continue;
      }
    }
    ++compared;
    if (m.anisotropyStrength > 0) ++anisoCompared;
    for (Lobe l : {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat}) {
      EvalOptions o;
      o.lobe = l;
      const Rgb k = ref::profileBrdf(m, Profile::Khronos, l, L, V);
      const Rgb sp = ref::brdf(m, o, L, V);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, relDiff(k[c], sp[c], 1e-12));
    }
  }
  // Same formulas in another order: rounding, amplified up to ~1/alpha^2 near a sharp peak.
  EXPECT_LE(worst, 1e-9);
  EXPECT_GE(compared, 300) << "skipped " << skipped;
  EXPECT_GE(anisoCompared, 100) << "skipped " << skipped;
}

// The engine takes both F0s (base and coat) from the material IOR; spec keeps 0.04.
TEST(ProfileReference, KhronosReadsIorInBaseAndCoat) {
  MaterialParams m;
  m.metallic = 0.0f;
  m.roughness = 0.4f;
  m.clearcoat = 1.0f;
  m.clearcoatRoughness = 0.3f;
  m.ior = 1.8f;
  const Vec3 L = dir(0.8, 0.1), V = dir(0.6, 2.9);
  EvalOptions o;
  for (Lobe l : {Lobe::Diffuse, Lobe::Specular, Lobe::Clearcoat}) {
    o.lobe = l;
    EXPECT_GT(relDiff(ref::profileBrdf(m, Profile::Khronos, l, L, V)[0], ref::brdf(m, o, L, V)[0]), 1e-3)
        << brdfcl::toString(l);
  }
  // Closed form of the coat lobe at L = V = N: cc f0_ior D_GGX(alpha_c, 1) V_GGX(1, 1).
  const double ior = m.ior, f0 = std::pow((ior - 1.0) / (ior + 1.0), 2.0);
  const double alphaC = double(m.clearcoatRoughness) * m.clearcoatRoughness;
  const double want = 1.0 * f0 / (kPi * alphaC * alphaC) * 0.25;
  EXPECT_LE(relDiff(ref::profileBrdf(m, Profile::Khronos, Lobe::Clearcoat, kN, kN)[0], want), 1e-12);
}

// D_GGX has no alpha floor in the engine: 0/0 at r = 0, N.H = 1 is reproduced, not hidden.
TEST(ProfileReference, KhronosNaNAtZeroRoughnessMirror) {
  MaterialParams m;
  m.roughness = 0.0f;
  m.metallic = 0.5f;
  EXPECT_TRUE(std::isnan(ref::profileBrdf(m, Profile::Khronos, Lobe::Specular, kN, kN)[0]));
  EXPECT_TRUE(std::isnan(ref::profileBrdf(m, Profile::Khronos, Lobe::All, kN, kN)[1]));
  EXPECT_TRUE(std::isfinite(ref::profileBrdf(m, Profile::Khronos, Lobe::Diffuse, kN, kN)[2]));
  // Off the mirror direction r = 0 gives a clean 0 specular.
  EXPECT_EQ(ref::profileBrdf(m, Profile::Khronos, Lobe::Specular, dir(0.9, 0), dir(0.8, 1))[0], 0.0);
  // A coat with r_c = 0 is NaN there too; the base is then smooth elsewhere.
  m.roughness = 0.5f;
  m.clearcoat = 0.5f;
  m.clearcoatRoughness = 0.0f;
  EXPECT_TRUE(std::isnan(ref::profileBrdf(m, Profile::Khronos, Lobe::Clearcoat, kN, kN)[0]));
  // The other engines floor alpha (or clamp D) and stay finite at the same point.
  m.roughness = 0.0f;
  for (Profile p : {Profile::Threejs, Profile::Filament, Profile::Babylon, Profile::Materialx})
    for (double v : ref::profileBrdf(m, p, Lobe::All, kN, kN)) EXPECT_TRUE(std::isfinite(v)) << profileName(p);
}

// ---- babylon ----

// At L = V = N only D differs in the dielectric specular (V = 0.25, F = f0 for both): babylon's
// specular is spec's times (alpha / alphaG)^2 times its multiscatter factor ec, alphaG = alpha +
// 0.0005. So babylon differs at every roughness, and the alphaG part of the difference shrinks
// as roughness grows; over r <= 0.4 it dominates, so the whole relative difference shrinks there
// (above ~0.5 the growing ec takes over: 7 % at r = 1).
TEST(ProfileReference, BabylonDiffersFromSpecAndConvergesWithRoughness) {
  MaterialParams m;
  m.metallic = 0.0f;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  double lastBias = HUGE_VAL, lastRaw = HUGE_VAL;
  for (double r : {0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0}) {
    m.roughness = float(r);
    const double alpha = double(m.roughness) * m.roughness, alphaG = alpha + 0.0005;
    const double spec = ref::profileBrdf(m, Profile::Spec, Lobe::Specular, kN, kN)[0];
    const double bab = ref::profileBrdf(m, Profile::Babylon, Lobe::Specular, kN, kN)[0];
    const double ec = 1.0 + 0.04 * (1.0 / ref::babylonBrdf(1.0, m.roughness)[1] - 1.0);
    // 2e-7: babylon's N.V is 1 + 1e-7 (absEps), which moves its V_GGX by up to 1e-7; D's
    // (alpha^2 - 1) + 1 at N.H = 1 keeps ~1e-16 / alpha^2 of relative precision.
    EXPECT_LE(relDiff(bab, spec * std::pow(alpha / alphaG, 2.0) * ec), 2e-7) << "r " << r;
    const double bias = std::abs(bab / ec - spec) / spec;
    EXPECT_GT(bias, 1e-7) << "r " << r;
    EXPECT_LT(bias, lastBias) << "r " << r;
    lastBias = bias;
    // And off the mirror direction, all lobes together.
    const Vec3 L = dir(0.8, 0.0), V = dir(0.6, kPi * 0.7);
    EXPECT_GT(relDiff(ref::profileBrdf(m, Profile::Babylon, Lobe::All, L, V)[0],
                      ref::profileBrdf(m, Profile::Spec, Lobe::All, L, V)[0]),
              1e-6)
        << "r " << r;
    if (r <= 0.4) {
      const double raw = std::abs(bab - spec) / spec;
      EXPECT_LT(raw, lastRaw) << "r " << r;
      lastRaw = raw;
    }
  }
}

// Closed form of the coat at L = V = N: cc 0.04 D_GGX(r_c^2 + 0.0005, 1) 0.25 (Kelemen V at V.H = 1)
// times the coat's multiscatter factor 1 + f0 (1/E_ss(N.V, r_c) - 1), f0 = 1 for the default metal,
// E_ss = .y of Babylon's BRDF texture.
TEST(ProfileReference, BabylonCoatClosedFormAtNormal) {
  MaterialParams m;
  m.clearcoat = 0.7f;
  m.clearcoatRoughness = 0.3f;
  const double aG = double(m.clearcoatRoughness) * m.clearcoatRoughness + 0.0005;
  const double want =
      double(m.clearcoat) * 0.04 / (kPi * aG * aG) * 0.25 / ref::babylonBrdf(1.0 + 1e-7, m.clearcoatRoughness)[1];
  EXPECT_LE(relDiff(ref::profileBrdf(m, Profile::Babylon, Lobe::Clearcoat, kN, kN)[0], want), 1e-12);
}

// ---- filament ----

// Filament scales diffuse and specular by 1 - max3(c) E_CN(N.V) only (no N.L), so without a coat
// the diffuse lobe over Lambert is one number for every L at fixed V. khronos's min rule is not.
TEST(ProfileReference, FilamentSheenScalingIndependentOfLight) {
  MaterialParams m;
  m.metallic = 0.2f;
  m.baseColor = {0.6f, 0.4f, 0.3f};
  m.roughness = 0.5f;
  m.sheenColor = {0.9f, 0.7f, 0.5f};
  m.sheenRoughness = 0.3f;
  const Vec3 V = dir(0.7, 0.4);
  const double lambert = (1.0 - m.metallic) * m.baseColor[0] / kPi;
  std::vector<double> filament, khronos;
  for (double cl : {0.03, 0.1, 0.3, 0.6, 0.95})
    for (double phi : {0.0, 2.0, 4.0}) {
      filament.push_back(ref::profileBrdf(m, Profile::Filament, Lobe::Diffuse, dir(cl, phi), V)[0] / lambert);
      khronos.push_back(ref::profileBrdf(m, Profile::Khronos, Lobe::Diffuse, dir(cl, phi), V)[0]);
    }
  for (double f : filament) EXPECT_LE(relDiff(f, filament.front()), 1e-14);
  const double want = 1.0 - double(m.sheenColor[0]) * ref::sheenAlbedo(0.7, m.sheenRoughness,
                                                                       brdfcl::SheenDistribution::Charlie,
                                                                       brdfcl::SheenVisibility::Ashikhmin);
  EXPECT_LE(relDiff(filament.front(), want), 1e-9);  // V.z = 0.7 up to the normalisation's rounding
  EXPECT_LT(filament.front(), 1.0);
  // khronos's diffuse carries (1 - F_d(V.H)) and min(E(V), E(L)): it does move with L.
  EXPECT_GT(relDiff(khronos.front(), khronos.back()), 1e-3);
}

// Closed form of the coat at L = V = N: cc 0.04 D(alpha_c, 1) 0.25 with Filament's
// D = min(1/alpha, 453.5)^2 / pi there (k capped at 453.5); r_c = 0.01 is floored to 0.045, where
// 1/alpha = 494 hits the cap.
TEST(ProfileReference, FilamentCoatClosedFormAtNormal) {
  MaterialParams m;
  m.clearcoat = 0.8f;
  for (float rc : {0.5f, 0.2f, 0.01f}) {
    m.clearcoatRoughness = rc;
    const double rho = std::max(double(rc), 0.045), alphaC = rho * rho;
    const double k = std::min(1.0 / alphaC, 453.5);
    const double want = double(m.clearcoat) * 0.04 * (k * k / kPi) * 0.25;
    EXPECT_LE(relDiff(ref::profileBrdf(m, Profile::Filament, Lobe::Clearcoat, kN, kN)[0], want), 1e-12)
        << "r_c " << rc;
  }
}

// The coat raises the base roughness: r = mix(r, max(r, r_c), cc). A smooth base under a rough
// full coat has the coat's roughness, so its specular equals that of a rough uncoated base
// scaled by (1 - Fcc).
TEST(ProfileReference, FilamentCoatRaisesBaseRoughness) {
  MaterialParams smooth;
  smooth.metallic = 1.0f;
  smooth.roughness = 0.1f;
  smooth.clearcoat = 1.0f;
  smooth.clearcoatRoughness = 0.6f;
  MaterialParams rough = smooth;
  rough.roughness = 0.6f;
  rough.clearcoat = 0.0f;
  const Vec3 L = dir(0.8, 0.2), V = dir(0.5, 3.0);
  const Vec3 Hu{L.x + V.x, L.y + V.y, L.z + V.z};
  const double VdotH = (V.x * Hu.x + V.y * Hu.y + V.z * Hu.z) / std::sqrt(Hu.x * Hu.x + Hu.y * Hu.y + Hu.z * Hu.z);
  const double kCoat = 1.0 - (0.04 + 0.96 * std::pow(1.0 - VdotH, 5.0));
  const double a = ref::profileBrdf(smooth, Profile::Filament, Lobe::Specular, L, V)[0];
  const double b = ref::profileBrdf(rough, Profile::Filament, Lobe::Specular, L, V)[0];
  EXPECT_LE(relDiff(a, kCoat * b), 1e-12);
}

// ---- threejs ----

// TSL finish(): the sheen is added after the coat's attenuation, so the sheen lobe does not see
// the coat at all; the other engines put it under the coat.
TEST(ProfileReference, ThreejsSheenNotAttenuatedByCoat) {
  MaterialParams m;
  m.metallic = 0.0f;
  m.roughness = 0.4f;
  m.sheenColor = {0.8f, 0.5f, 0.2f};
  m.sheenRoughness = 0.4f;
  m.clearcoatRoughness = 0.2f;
  MaterialParams coated = m;
  coated.clearcoat = 1.0f;
  const Vec3 L = dir(0.5, 0.3), V = dir(0.4, 2.5);
  EXPECT_EQ(ref::profileBrdf(m, Profile::Threejs, Lobe::Sheen, L, V),
            ref::profileBrdf(coated, Profile::Threejs, Lobe::Sheen, L, V));
  EXPECT_GT(ref::profileBrdf(m, Profile::Threejs, Lobe::Sheen, L, V)[0], 0.0);
  EXPECT_LT(ref::profileBrdf(coated, Profile::Threejs, Lobe::Diffuse, L, V)[0],
            ref::profileBrdf(m, Profile::Threejs, Lobe::Diffuse, L, V)[0]);
  for (Profile p : {Profile::Khronos, Profile::Filament, Profile::Babylon, Profile::Materialx})
    EXPECT_LT(ref::profileBrdf(coated, p, Lobe::Sheen, L, V)[0], ref::profileBrdf(m, p, Lobe::Sheen, L, V)[0])
        << profileName(p);
}

// Closed form of the coat at L = V = N: cc F3(0.04, 1, 1) D_GGX(alpha_c, 1) 0.25, F3 with Epic's
// exp2 weight (not 0 at x = 1: 2^-12.53789).
TEST(ProfileReference, ThreejsCoatClosedFormAtNormal) {
  MaterialParams m;
  m.clearcoat = 0.6f;
  m.clearcoatRoughness = 0.35f;
  const double aC = double(m.clearcoatRoughness) * m.clearcoatRoughness;
  const double Fs = std::exp2(-5.55473 - 6.98316);
  const double F = 0.04 * (1.0 - Fs) + Fs;
  const double want = double(m.clearcoat) * F / (kPi * aC * aC) * 0.25;
  EXPECT_LE(relDiff(ref::profileBrdf(m, Profile::Threejs, Lobe::Clearcoat, kN, kN)[0], want), 1e-12);
  EXPECT_GT(F, 0.04);
}

// The data carried over from DFGLUT.js: texel (i, j) is bits [(16 j + i) * 2 + {0, 1}]; corner
// halves decoded by hand. Clamp-to-edge: everything beyond an outer texel centre is that texel.
TEST(ProfileReference, ThreejsDfgTableCorners) {
  // (0, 0): 0x30b5 = 1.1767578125 / 8, 0x3ad1 = 1.7041015625 / 2.
  const double a00 = 0.1470947265625, b00 = 0.852050781250;
  // (15, 0): 0x3ae1 = (1 + 737/1024) / 2, 0x28ff = (1 + 255/1024) / 32.
  const double a150 = (1.0 + 737.0 / 1024) / 2, b150 = (1.0 + 255.0 / 1024) / 32;
  // (0, 15): 0x3c00 = 1, 0x0000 = 0. (15, 15): 0x3586 = (1 + 390/1024) / 4, 0x049f = (1 + 159/1024) 2^-14.
  const double a1515 = (1.0 + 390.0 / 1024) / 4, b1515 = (1.0 + 159.0 / 1024) * std::ldexp(1.0, -14);
  auto expectTexel = [](double u, double v, double a, double b) {
    const auto ab = ref::threejsDfg(u, v);
    EXPECT_EQ(ab[0], a) << "u " << u << " v " << v;
    EXPECT_EQ(ab[1], b) << "u " << u << " v " << v;
  };
  for (double u : {-0.5, 0.0, 0.5 / 16})
    for (double v : {-1.0, 0.0, 0.5 / 16}) expectTexel(u, v, a00, b00);
  for (double u : {15.5 / 16, 1.0, 2.0})
    for (double v : {0.0, 0.5 / 16}) expectTexel(u, v, a150, b150);
  for (double v : {15.5 / 16, 1.0}) {
    expectTexel(0.0, v, 1.0, 0.0);
    expectTexel(1.0, v, a1515, b1515);
  }
  EXPECT_EQ(ref::threejsDfgEss(1.0, 1.0), a1515 + b1515);
  // Between two texel centres the fetch is the linear blend.
  const double mid = ref::threejsDfgEss(1.0 / 16, 0.5 / 16);
  const double t0 = ref::threejsDfgEss(0.5 / 16, 0.5 / 16), t1 = ref::threejsDfgEss(1.5 / 16, 0.5 / 16);
  EXPECT_LE(relDiff(mid, 0.5 * (t0 + t1)), 1e-15);
  EXPECT_EQ(ref::halfToDouble(0x3c00), 1.0);
  EXPECT_EQ(ref::halfToDouble(0xc000), -2.0);
  EXPECT_EQ(ref::halfToDouble(0x0001), std::ldexp(1.0, -24));
  EXPECT_TRUE(std::isinf(ref::halfToDouble(0x7c00)));
}

// The table is GGX's albedo with u = roughness, v = NdotV (docs/profiles.md's orientation):
// two independent carried-over data sets, three.js's table and MaterialX's fit at alpha = r^2,
// agree to within the fit's error (~4 %), which a transposed table would not.
TEST(ProfileReference, ThreejsDfgAgreesWithMaterialxFit) {
  double worst = 0.0;
  for (double r : {0.25, 0.45, 0.65, 0.85, 1.0})
    for (double mu : {0.2, 0.4, 0.6, 0.8, 1.0}) {
      const auto ab = ref::mxGgxAlbedoFit(mu, r * r);
      worst = std::max(worst, std::abs(ab[0] + ab[1] - ref::threejsDfgEss(r, mu)));
    }
  EXPECT_LE(worst, 0.05);
  // Transposed, they do not agree.
  EXPECT_GT(std::abs(ref::threejsDfgEss(0.9, 0.3) - ref::threejsDfgEss(0.3, 0.9)), 0.2);
}

TEST(ProfileReference, FitsStayInRange) {
  for (double mu = 0.0; mu <= 1.0; mu += 0.05)
    for (double r = 0.0; r <= 1.0; r += 0.05) {
      const auto ab = ref::mxGgxAlbedoFit(mu, r * r);
      EXPECT_TRUE(ab[0] >= 0 && ab[0] <= 1 && ab[1] >= 0 && ab[1] <= 1);
      const double e = ref::mxSheenAlbedo(mu, r * r), t = ref::threejsSheenAlbedo(mu, r);
      EXPECT_TRUE(e >= 0 && e <= 1);
      EXPECT_TRUE(t >= 0 && t <= 1);
    }
  // The sheen albedo fits fall with N.V at a mid roughness (grazing views see more sheen).
  EXPECT_GT(ref::threejsSheenAlbedo(0.1, 0.5), ref::threejsSheenAlbedo(0.9, 0.5));
  EXPECT_GT(ref::mxSheenAlbedo(0.1, 0.25), ref::mxSheenAlbedo(0.9, 0.25));
}

// ---- materialx ----

// layer(): f = coat + t_c (sheen + t_s base) with t_c = 1 - cc (0.04 A_c + B_c) comp_c,
// comp_c = 1 + Favg (1 - E)/E tinted by the average Fresnel Favg = 0.04 + 0.96/21 of the ior-1.5
// coat. Every non-coat lobe of a coated material is t_c times the uncoated one.
TEST(ProfileReference, MaterialxCoatThroughput) {
  MaterialParams m;
  m.metallic = 0.3f;
  m.baseColor = {0.7f, 0.5f, 0.2f};
  m.roughness = 0.45f;
  m.sheenColor = {0.5f, 0.6f, 0.7f};
  m.sheenRoughness = 0.5f;
  m.clearcoatRoughness = 0.25f;
  MaterialParams coated = m;
  coated.clearcoat = 0.75f;
  const Vec3 L = dir(0.65, 0.9), V = dir(0.55, 3.6);
  const double alphaC = double(m.clearcoatRoughness) * m.clearcoatRoughness;
  const auto ab = ref::mxGgxAlbedoFit(V.z, alphaC);
  const double E = ab[0] + ab[1];
  const double favg = 0.04 + 0.96 / 21.0;
  const double tc = 1 - 0.75 * (0.04 * ab[0] + ab[1]) * (1 + favg * (1 - E) / E);
  EXPECT_GT(tc, 0.9);
  EXPECT_LT(tc, 1.0);
  for (Lobe l : {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen}) {
    const Rgb a = ref::profileBrdf(coated, Profile::Materialx, l, L, V);
    const Rgb b = ref::profileBrdf(m, Profile::Materialx, l, L, V);
    for (int i = 0; i < 3; ++i) EXPECT_LE(relDiff(a[i], tc * b[i]), 1e-12) << brdfcl::toString(l);
  }
  // At L = V = N the exact Fresnel is 0.04 and V_GGX = 0.25: coat = cc D 0.25 0.04 comp_c.
  const auto abN = ref::mxGgxAlbedoFit(1.0, alphaC);
  const double EN = abN[0] + abN[1];
  const double want = 0.75 / (kPi * alphaC * alphaC) * 0.25 * 0.04 * (1 + favg * (1 - EN) / EN);
  EXPECT_LE(relDiff(ref::profileBrdf(coated, Profile::Materialx, Lobe::Clearcoat, kN, kN)[0], want), 1e-12);
}

// ---- all engines ----

// The draft sheen exists in no engine: under every engine profile a draft-sheen material is the
// material without sheen (spec does evaluate it).
TEST(ProfileReference, DraftSheenHasNoSheenUnderEngines) {
  MaterialParams m;
  m.metallic = 0.1f;
  m.roughness = 0.6f;
  m.clearcoat = 0.3f;
  m.clearcoatRoughness = 0.4f;
  MaterialParams draft = m;
  draft.draftSheen = true;
  draft.draftIntensity = 2.0f;
  draft.draftColor = {0.9f, 0.8f, 0.7f};
  draft.sheenColor = {0.5f, 0.5f, 0.5f};  // ignored with the draft keys, as in spec
  draft.sheenRoughness = 0.5f;
  const Vec3 L = dir(0.7, 0.2), V = dir(0.5, 2.0);
  for (Profile p : {Profile::Khronos, Profile::Threejs, Profile::Filament, Profile::Babylon, Profile::Materialx}) {
    EXPECT_EQ(ref::profileBrdf(draft, p, Lobe::All, L, V), ref::profileBrdf(m, p, Lobe::All, L, V)) << profileName(p);
    EXPECT_EQ(ref::profileBrdf(draft, p, Lobe::Sheen, L, V), (Rgb{0, 0, 0})) << profileName(p);
  }
  EXPECT_GT(ref::profileBrdf(draft, Profile::Spec, Lobe::Sheen, L, V)[0], 0.0);
}

// Profiles are different functions: at a generic sheen + coat + anisotropy point no two agree
// (khronos needs an IOR other than 1.5 to leave spec at this point, see above).
TEST(ProfileReference, ProfilesAreDistinct) {
  MaterialParams m;
  m.metallic = 0.4f;
  m.baseColor = {0.8f, 0.6f, 0.4f};
  m.roughness = 0.35f;
  m.sheenColor = {0.4f, 0.5f, 0.6f};
  m.sheenRoughness = 0.45f;
  m.clearcoat = 0.5f;
  m.clearcoatRoughness = 0.3f;
  m.anisotropyStrength = 0.5f;
  m.anisotropyRotation = 0.7f;
  m.ior = 1.4f;
  const Vec3 L = dir(0.75, 0.4), V = dir(0.6, 3.0);
  std::vector<double> v;
  for (Profile p : brdfcl::kAllProfiles) v.push_back(ref::profileBrdf(m, p, Lobe::All, L, V)[1]);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      EXPECT_GT(relDiff(v[i], v[j]), 1e-4) << profileName(brdfcl::kAllProfiles[i]) << " vs "
                                           << profileName(brdfcl::kAllProfiles[j]);
}

}  // namespace
