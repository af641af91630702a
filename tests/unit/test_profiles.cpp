// The engine profiles' kernels against the independent double-precision references
// (tests/reference/profiles.cpp): 100k random samples per profile and lobe, relative tolerance
// 1e-4 (1e-3 of the unscaled layers where a baked sheen E table enters), absolute floor 1e-6.
// Then each documented deviation where it should show, and nowhere else, on the kernels.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "process.hpp"
#include "reference/profiles.hpp"
#include "profile_eval.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr std::size_t kSamples = 100000;
constexpr std::size_t kMaterials = 256;
constexpr double kAbsFloor = 1e-6;

const Profile kEngines[] = {Profile::Khronos, Profile::Threejs, Profile::Filament, Profile::Babylon, Profile::Materialx};
const Lobe kLobes[] = {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat};

// Profiles whose sheen scaling reads brdfcl's E table (docs/profiles.md "Tables").
bool usesTable(Profile p, Lobe l) {
  return (p == Profile::Khronos || p == Profile::Filament || p == Profile::Babylon) &&
         (l == Lobe::All || l == Lobe::Diffuse || l == Lobe::Specular);
}

// Random materials as the spec's accuracy test draws them, plus an IOR (KHR_materials_ior) on
// half of them. The sheen roughness stays >= 0.05, where the reference's E is tabulated.
std::vector<MaterialParams> profileMaterials(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> ior(1.0f, 2.5f);
  std::vector<MaterialParams> out;
  for (std::size_t i = 0; i < kMaterials; ++i) {
    MaterialParams m = randomMaterial(rng);
    if (i % 2) m.ior = ior(rng);
    out.push_back(m);
  }
  return out;
}

ref::Vec3 vec(const float* p) { return {p[0], p[1], p[2]}; }

struct Mode {
  Profile profile;
  Lobe lobe;
};

class ProfileKernelVsReference : public testing::TestWithParam<Mode> {};

TEST_P(ProfileKernelVsReference, MatchesWithinTolerance) {
  const Mode mode = GetParam();
  std::mt19937_64 rng(seed() ^ (0x9e3779b97f4a7c15ull * (1 + int(mode.profile) * 8 + int(mode.lobe))));
  const auto materials = profileMaterials(rng);
  const Samples s = randomSamples(rng, kSamples, materials.size());
  EvalOptions o;
  o.profile = mode.profile;
  o.lobe = mode.lobe;
  const auto got = Evaluator(runtime(), o).evaluate(materials, s);
  const bool table = usesTable(mode.profile, mode.lobe);
  const double rel = table ? 1e-3 : 1e-4;
  WorstCase w;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto& m = materials[s.material[i]];
    const ref::Vec3 L = vec(&s.L[3 * i]), V = vec(&s.V[3 * i]);
    const auto want = ref::profileBrdf(m, mode.profile, mode.lobe, L, V);
    // The table's error is an error in the scale factor: relative to what that factor multiplies.
    ref::Rgb scale = want;
    if (table) {
      MaterialParams unscaled = m;
      unscaled.sheenColor = {0.0f, 0.0f, 0.0f};
      scale = ref::profileBrdf(unscaled, mode.profile, mode.lobe, L, V);
    }
    for (int c = 0; c < 3; ++c)
      w.check(got[3 * i + c], want[c], std::max(std::fabs(want[c]), std::fabs(scale[c])), rel, kAbsFloor, [&] {
        std::ostringstream d;
        d.precision(9);
        d << "channel " << c << ", L(" << L.x << "," << L.y << "," << L.z << ") V(" << V.x << "," << V.y << "," << V.z
          << "), " << describe(m) << " ior " << m.ior << "; profile " << toString(mode.profile) << ", lobe "
          << toString(mode.lobe) << "; seed " << seed();
        return d.str();
      });
  }
  EXPECT_EQ(w.checked, 3 * kSamples);
  EXPECT_LE(w.worstRatio, 1.0) << "worst: " << w.report;
  RecordProperty("worst_error_over_tolerance", std::to_string(w.worstRatio));
}

std::vector<Mode> allModes() {
  std::vector<Mode> modes;
  for (Profile p : kEngines)
    for (Lobe l : kLobes) modes.push_back({p, l});
  return modes;
}

struct ModeName {
  std::string operator()(const testing::TestParamInfo<Mode>& info) const {
    return std::string(toString(info.param.profile)) + "_" + toString(info.param.lobe);
  }
};

INSTANTIATE_TEST_SUITE_P(Profiles, ProfileKernelVsReference, testing::ValuesIn(allModes()), ModeName());

// ---- Deviations where documented, and nowhere else ----



double maxRelDiff(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::fabs(double(a[i]) - b[i]) / std::max(std::fabs(double(b[i])), 1e-6));
  return worst;
}

// khronos equals spec for materials without sheen at IOR 1.5 and roughness >= 0.05 (no clamp of
// either side applies, the anisotropic V stays <= 1 away from grazing), and leaves it at
// another IOR, and for sheen where V_Charlie > 1 (grazing).
TEST(ProfileDeviations, KhronosEqualsSpecWhereNoDeviationApplies) {
  std::mt19937_64 rng(seed() ^ 0x5eedull);
  Domain d;
  d.minCos = 0.2f;
  d.belowHorizon = 0;
  d.draftShare = 0;
  d.zeroLayerShare = 1.0;  // no sheen, no clearcoat, no anisotropy...
  std::vector<MaterialParams> materials;
  for (int i = 0; i < 64; ++i) {
    MaterialParams m = randomMaterial(rng, d);
    if (i % 2) {  // ...then a coat on half of them: F0 0.04 from the IOR 1.5
      m.clearcoat = 0.7f;
      m.clearcoatRoughness = 0.05f + 0.9f * float(i) / 64;
    }
    materials.push_back(m);
  }
  const Samples s = randomSamples(rng, 20000, materials.size(), d);
  EvalOptions spec, khronos;
  khronos.profile = Profile::Khronos;
  const auto a = Evaluator(runtime(), spec).evaluate(materials, s);
  const auto b = Evaluator(runtime(), khronos).evaluate(materials, s);
  EXPECT_LE(maxRelDiff(b, a), 2e-5);
  // Another IOR: the base and coat F0 follow it under khronos, not under spec.
  for (auto& m : materials) m.ior = 1.8f;
  const auto c = Evaluator(runtime(), khronos).evaluate(materials, s);
  EXPECT_GT(maxRelDiff(c, a), 0.05);
  // Sheen at a grazing retro-reflection (N.H = N.L, where Charlie peaks): V_Charlie > 1 there,
  // clamped under khronos.
  MaterialParams sheen;
  sheen.metallic = 0.0f;
  sheen.sheenColor = {1.0f, 1.0f, 1.0f};
  sheen.sheenRoughness = 0.3f;
  const float z = 0.02f, t = std::sqrt(1 - z * z);
  const Samples grazing = pairsOf({{t, 0, z, t, 0, z}});
  const auto sk = evalProfile(sheen, Profile::Khronos, Lobe::Sheen, grazing), ss = evalProfile(sheen, Profile::Spec, Lobe::Sheen, grazing);
  EXPECT_LT(sk[0], ss[0] * 0.9) << "khronos " << sk[0] << ", spec " << ss[0];
  // ...and not at normal incidence, where V_Charlie < 1.
  const Samples normal = pairsOf({{0.3f, 0, 0.9539392f, -0.3f, 0, 0.9539392f}});
  EXPECT_NEAR(evalProfile(sheen, Profile::Khronos, Lobe::Sheen, normal)[0], evalProfile(sheen, Profile::Spec, Lobe::Sheen, normal)[0],
              1e-5 * evalProfile(sheen, Profile::Spec, Lobe::Sheen, normal)[0]);
}

// Babylon's alpha + 0.0005: its sheen lobe is the spec's Charlie-Ashikhmin sheen lobe at
// alpha_s + 0.0005, so against spec with --sheen-visibility ashikhmin it differs at every sheen
// roughness, by less as the roughness grows.
TEST(ProfileDeviations, BabylonBiasDiffersAtEveryRoughnessAndShrinks) {
  // Low N.H, where the Charlie lobe of a small alpha is not 0 in float.
  const float z = 0.3f, t = 0.9539392f;
  const Samples s = pairsOf({{t, 0, z, t, 0, z}, {t, 0, z, 0, t, z}});
  EvalOptions ashikhmin;
  ashikhmin.sheenVisibility = SheenVisibility::Ashikhmin;
  ashikhmin.lobe = Lobe::Sheen;
  EvalOptions babylon;
  babylon.profile = Profile::Babylon;
  babylon.lobe = Lobe::Sheen;
  double previous = INFINITY;
  for (float r : {0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.7f, 1.0f}) {
    MaterialParams m;
    m.metallic = 0.0f;
    m.sheenColor = {0.8f, 0.8f, 0.8f};
    m.sheenRoughness = r;
    const auto a = Evaluator(runtime(), babylon).evaluate({m}, s);
    const auto b = Evaluator(runtime(), ashikhmin).evaluate({m}, s);
    const double d = std::fabs(a[0] - b[0]) / b[0];
    EXPECT_GT(d, 1e-6) << "sheen roughness " << r;
    EXPECT_LT(d, previous) << "sheen roughness " << r;
    previous = d;
  }
}

// Filament (and Babylon) scale the base by the view's albedo only: the diffuse lobe over the
// Lambert term does not move with L. Under spec, min(E(V), E(L)) does.
TEST(ProfileDeviations, FilamentSheenScalingDoesNotDependOnL) {
  MaterialParams m;
  m.metallic = 0.0f;
  m.baseColor = {0.5f, 0.5f, 0.5f};
  m.sheenColor = {1.0f, 0.8f, 0.6f};
  m.sheenRoughness = 0.4f;
  std::vector<std::array<float, 6>> pairs;
  for (float zl : {0.05f, 0.3f, 0.6f, 0.95f}) {
    const float tl = std::sqrt(1 - zl * zl);
    pairs.push_back({tl, 0, zl, -0.6f, 0, 0.8f});
  }
  const Samples s = pairsOf(pairs);
  MaterialParams plain = m;
  plain.sheenColor = {0.0f, 0.0f, 0.0f};
  const auto f = evalProfile(m, Profile::Filament, Lobe::Diffuse, s);
  const auto f0 = evalProfile(plain, Profile::Filament, Lobe::Diffuse, s);
  for (std::size_t i = 1; i < pairs.size(); ++i) EXPECT_NEAR(f[3 * i] / f0[3 * i], f[0] / f0[0], 1e-6) << "pair " << i;
  EXPECT_LT(f[0] / f0[0], 0.99);  // the scaling is there
  const auto spec = evalProfile(m, Profile::Spec, Lobe::Diffuse, s);
  const auto spec0 = evalProfile(plain, Profile::Spec, Lobe::Diffuse, s);
  EXPECT_GT(std::fabs(spec[0] / spec0[0] - spec[9] / spec0[9]), 1e-3);
}

// three.js (TSL) adds the sheen above the coat; every other profile puts it under.
TEST(ProfileDeviations, ThreejsSheenIsNotUnderTheCoat) {
  MaterialParams m;
  m.metallic = 0.0f;
  m.sheenColor = {1.0f, 1.0f, 1.0f};
  m.sheenRoughness = 0.5f;
  MaterialParams coated = m;
  coated.clearcoat = 1.0f;
  coated.clearcoatRoughness = 0.2f;
  const Samples s = pairsOf({{0.6f, 0, 0.8f, -0.8f, 0, 0.6f}, {0, 0.3f, 0.9539392f, 0.2f, 0, 0.9797959f}});
  for (Profile p : kAllProfiles) {
    const auto a = evalProfile(m, p, Lobe::Sheen, s), b = evalProfile(coated, p, Lobe::Sheen, s);
    if (p == Profile::Threejs)
      EXPECT_EQ(a, b);
    else
      EXPECT_GT(maxRelDiff(b, a), 0.01) << toString(p);
  }
}

// The lobes partition every profile's sum.
TEST(ProfileDeviations, LobesSumToAllUnderEveryProfile) {
  std::mt19937_64 rng(seed() ^ 0x10be5ull);
  const auto materials = profileMaterials(rng);
  const Samples s = randomSamples(rng, 20000, materials.size());
  for (Profile p : kEngines) {
    std::vector<float> sum(3 * s.size(), 0.0f);
    for (Lobe l : {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat}) {
      EvalOptions o;
      o.profile = p;
      o.lobe = l;
      const auto part = Evaluator(runtime(), o).evaluate(materials, s);
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += part[i];
    }
    EvalOptions o;
    o.profile = p;
    const auto all = Evaluator(runtime(), o).evaluate(materials, s);
    double worst = 0;
    for (std::size_t i = 0; i < sum.size(); ++i)
      worst = std::max(worst, std::fabs(sum[i] - all[i]) / (1e-4 * std::fabs(all[i]) + 1e-6));
    EXPECT_LE(worst, 1.0) << toString(p);
  }
}

// NaN is the engine's answer at khronos's alpha = 0, N.H = 1 (D_GGX = 0/0), and the spec's clamp
// keeps it finite there.
TEST(ProfileDeviations, KhronosReproducesItsNaNAndSpecStaysFinite) {
  MaterialParams m;
  m.roughness = 0.0f;
  const Samples s = pairsOf({{0, 0, 1, 0, 0, 1}, {0.6f, 0, 0.8f, -0.6f, 0, 0.8f}, {0.6f, 0, 0.8f, 0, 0.6f, 0.8f}});
  const auto k = evalProfile(m, Profile::Khronos, Lobe::All, s);
  EXPECT_TRUE(std::isnan(k[0]) && std::isnan(k[3]));  // mirror pairs: N.H = 1
  EXPECT_TRUE(std::isfinite(k[6]));                   // off the mirror: D = 0
  for (float v : evalProfile(m, Profile::Spec, Lobe::All, s)) EXPECT_TRUE(std::isfinite(v));
  for (Profile p : {Profile::Threejs, Profile::Filament, Profile::Babylon, Profile::Materialx})
    for (float v : evalProfile(m, p, Lobe::All, s)) EXPECT_TRUE(std::isfinite(v)) << toString(p);
}

// A spec-only option with an engine profile is refused, naming both.
TEST(ProfileDeviations, SpecSheenOptionsAreRefusedUnderAnEngineProfile) {
  EvalOptions o;
  o.profile = Profile::Filament;
  o.sheenScaling = SheenScaling::View;
  EXPECT_EQ(errorOf([&] { Evaluator(runtime(), o); }),
            "--sheen-scaling applies to --profile spec only; --profile filament uses its engine's own sheen "
            "(docs/profiles.md)");
}

// Through the CLI: option clashes and a bad IOR are one line and exit 2, before any output.
TEST(ProfileDeviations, ProfileOptionsAreCheckedBeforeWork) {
  ScratchDir dir("profile-options");
  const std::string materials = dir.path("m.json"), samples = dir.path("s.csv");
  {
    std::ofstream(materials) << R"({"materials": [{"extensions": {"KHR_materials_ior": {"ior": 0.5}}}]})";
    std::ofstream(samples) << "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n";
  }
  const auto clash = runProcess({BRDFCL_CLI_PATH, "eval", "--materials", materials, "--samples", samples, "--out",
                                 dir.path("o.csv"), "--profile", "babylon", "--sheen-visibility", "ashikhmin"},
                                dir.dir());
  EXPECT_EQ(clash.status, 2) << clash.describe();
  EXPECT_EQ(clash.errorLines(), std::vector<std::string>{"brdfcl: --sheen-visibility applies to --profile spec only; "
                                                         "--profile babylon uses its engine's own sheen (docs/profiles.md)"});
  const auto ior = runProcess({BRDFCL_CLI_PATH, "eval", "--materials", materials, "--samples", samples, "--out",
                               dir.path("o.csv"), "--profile", "khronos"},
                              dir.dir());
  EXPECT_EQ(ior.status, 2) << ior.describe();
  ASSERT_EQ(ior.errorLines().size(), 1u) << ior.describe();
  EXPECT_CONTAINS(ior.errorLines()[0], "materials[0].extensions.KHR_materials_ior.ior: expected 0 or a number >= 1, got 0.5");
  EXPECT_FALSE(std::filesystem::exists(dir.path("o.csv")));
  const auto bench = runProcess({BRDFCL_CLI_PATH, "bench", "--pairs", samples, "--profile", "threejs"}, dir.dir());
  EXPECT_EQ(bench.status, 2) << bench.describe();
  EXPECT_EQ(bench.errorLines(), std::vector<std::string>{"brdfcl: --pairs and --profile are separate measurements; give one"});
  // The library refuses the same IOR.
  MaterialParams m;
  m.ior = 0.5f;
  EXPECT_EQ(errorOf([&] { Evaluator(runtime(), EvalOptions{}).evaluate({m}, pairsOf({{0, 0, 1, 0, 0, 1}})); }),
            "material 0: ior must be 0 or a number >= 1, got 0.5");
}

}  // namespace
