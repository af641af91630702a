// Physics of the kernels: white furnace, reciprocity, closed forms, layers at weight 0, and the
// documented region where the sheen albedo E exceeds 1. All values come from the device.
#include <gtest/gtest.h>

#include "brdfcl/albedo.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

MaterialParams white(float metallic, float roughness) {
  MaterialParams m;
  m.baseColor = {1, 1, 1};
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

float maxAbsRelDiff(const std::vector<float>& a, const std::vector<float>& b, std::size_t* at, double floor = 1e-6) {
  float worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const float e = float(std::fabs(a[i] - b[i]) / (std::fabs(b[i]) + floor));
    if (e > worst) worst = e, *at = i;
  }
  return worst;
}

// White furnace: a white material under uniform light reflects at most what it receives, where
// the specs' model conserves energy. Two places where it does not, both confirmed by the
// reference's own integral, are documented in docs/model.md ("Where the specs' model gains energy") and tested below: the sheen albedo
// E > 1 at grazing, low sheen roughness (SheenAlbedo.ExceedsOneOnlyWhereDocumented), and the
// Appendix B dielectric, whose per-direction mix(diffuse, specular, F(V.H)) gains energy below
// N.V ~ 0.75 (Furnace.AppendixBDielectricGainsEnergyAtGrazing).
std::vector<MaterialParams> furnaceGrid(float metallic) {
  std::vector<MaterialParams> grid;
  for (float roughness : {0.05f, 0.3f, 0.6f, 1.0f})
    for (float sheen : {0.0f, 1.0f})
      for (float sheenRoughness : {0.25f, 0.6f, 1.0f})
        for (float clearcoat : {0.0f, 1.0f}) {
          MaterialParams m = white(metallic, roughness);
          m.sheenColor = {sheen, sheen, sheen};
          m.sheenRoughness = sheenRoughness;
          m.clearcoat = clearcoat;
          m.clearcoatRoughness = 0.1f;
          grid.push_back(m);
        }
  return grid;
}

float worstAlbedo(const std::vector<MaterialParams>& grid, const std::vector<float>& mus, std::string* where) {
  Evaluator ev(runtime(), EvalOptions{});
  const auto a = directionalAlbedo(ev, grid, mus);
  float worst = 0;
  for (std::size_t m = 0; m < grid.size(); ++m)
    for (std::size_t v = 0; v < mus.size(); ++v)
      if (a[3 * (m * mus.size() + v)] > worst) {
        worst = a[3 * (m * mus.size() + v)];
        *where = describe(grid[m]) + ", N.V " + std::to_string(mus[v]);
      }
  return worst;
}

TEST(Furnace, LayeredMetalConservesEnergy) {
  std::string where;
  const float worst = worstAlbedo(furnaceGrid(1.0f), {1.0f, 0.7f, 0.4f, 0.2f, 0.1f, 0.05f}, &where);
  EXPECT_LE(worst, 1.0f + 1e-3f) << "albedo " << worst << " for " << where;
  EXPECT_GT(worst, 0.95f) << "a smooth white metal reflects nearly everything";
}

TEST(Furnace, LayeredDielectricConservesEnergyNearNormal) {
  std::string where;
  const float worst = worstAlbedo(furnaceGrid(0.0f), {1.0f, 0.9f, 0.8f}, &where);
  EXPECT_LE(worst, 1.0f + 1e-3f) << "albedo " << worst << " for " << where;
  EXPECT_GT(worst, 0.95f);
}

// Appendix B weights the diffuse lobe by 1 - F(V.H) per light direction, not by the specular
// lobe's albedo, so a white dielectric reflects more than it receives at grazing view. The
// kernel must reproduce that faithfully (reference albedo by its own adaptive integration).
TEST(Furnace, AppendixBDielectricGainsEnergyAtGrazing) {
  const std::vector<float> mus = {0.7f, 0.3f, 0.05f};
  std::vector<MaterialParams> materials = {white(0.0f, 0.05f), white(0.0f, 0.3f)};
  Evaluator ev(runtime(), EvalOptions{});
  const auto a = directionalAlbedo(ev, materials, mus);
  for (std::size_t m = 0; m < materials.size(); ++m)
    for (std::size_t v = 0; v < mus.size(); ++v) {
      const double mu = mus[v];
      const auto want = ref::directionalAlbedo(materials[m], EvalOptions{}, ref::Vec3{std::sqrt(1 - mu * mu), 0, mu}, 1e-6);
      EXPECT_NEAR(a[3 * (m * mus.size() + v)], want[0], 1e-3 * want[0]) << describe(materials[m]) << ", N.V " << mu;
    }
  EXPECT_GT(a[3 * 2], 1.7f);  // roughness 0.05 at N.V 0.05: 1.7165 by the reference
  EXPECT_GT(a[3 * 1], 1.1f);  // roughness 0.05 at N.V 0.3: 1.1509
}

// Monte Carlo (cosine-weighted, fixed seed) against the deterministic rule used above, where
// the integrand is smooth enough for MC: keeps the quadrature honest.
TEST(Furnace, QuadratureAgreesWithMonteCarlo) {
  MaterialParams m = white(0.0f, 0.7f);
  m.sheenColor = {0.8f, 0.8f, 0.8f};
  m.sheenRoughness = 0.6f;
  m.clearcoat = 0.5f;
  m.clearcoatRoughness = 0.6f;
  const float mu = 0.6f;
  Evaluator ev(runtime(), EvalOptions{});
  const float quad = directionalAlbedo(ev, {m}, {mu})[0];
  std::mt19937_64 rng(seed());
  std::uniform_real_distribution<double> u(0, 1);
  const std::size_t n = 1 << 20;
  Samples s;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = std::sqrt(u(rng)), phi = 2 * M_PI * u(rng);
    s.L.insert(s.L.end(), {float(r * std::cos(phi)), float(r * std::sin(phi)), float(std::sqrt(1 - r * r))});
    s.V.insert(s.V.end(), {float(std::sqrt(1 - mu * mu)), 0.0f, mu});
  }
  const auto f = ev.evaluateGrid({m}, s);
  double sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = M_PI * f[3 * i];  // f cos / pdf with pdf = cos / pi
    sum += x, sum2 += x * x;
  }
  const double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(quad, mean, 5 * sigma + 1e-4) << "MC " << mean << " +- " << sigma;
}

// Reciprocity f(L, V) = f(V, L) for every layer whose formula is symmetric: the base, both sheen
// forms, and min or no albedo scaling. (View scaling and the clearcoat's Fresnel on N.V are not.)
TEST(Reciprocity, SymmetricLayersAreReciprocal) {
  std::mt19937_64 rng(seed() ^ 0x5e1f);
  std::vector<MaterialParams> materials;
  for (int i = 0; i < 64; ++i) {
    auto m = randomMaterial(rng);
    m.clearcoat = 0.0f;
    materials.push_back(m);
  }
  Domain d;
  d.belowHorizon = 0.0;
  const Samples s = randomSamples(rng, 20000, materials.size(), d);
  Samples swapped = s;
  std::swap(swapped.L, swapped.V);
  for (auto scaling : {SheenScaling::Min, SheenScaling::None})
    for (auto vis : {SheenVisibility::Charlie, SheenVisibility::Ashikhmin})
      for (auto dist : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin}) {
        Evaluator ev(runtime(), EvalOptions{vis, dist, scaling, Lobe::All});
        const auto a = ev.evaluate(materials, s), b = ev.evaluate(materials, swapped);
        std::size_t at = 0;
        // Only float rounding differs; s f_base + f_sheen can cancel, so the floor is 1e-6 / 1e-4.
        EXPECT_LE(maxAbsRelDiff(a, b, &at, 1e-2), 1e-4)
            << describeOptions(ev.options()) << ": f(L,V) " << a[at] << " vs f(V,L) " << b[at] << " for "
            << describe(materials[s.material[at / 3]]);
      }
}

// 002's GGX at the peak: with L = V = N, D = 1/(pi alpha^2) and V_Smith = 1/4, and a white metal
// has F = 1, so f = 1/(4 pi alpha^2).
TEST(ClosedForm, GgxPeakAtNormalIncidence) {
  std::vector<MaterialParams> materials;
  for (float r : {0.05f, 0.1f, 0.3f, 0.7f, 1.0f}) materials.push_back(white(1.0f, r));
  Samples s;
  s.L = {0, 0, 1};
  s.V = {0, 0, 1};
  EvalOptions o;
  o.lobe = Lobe::Specular;
  const auto f = Evaluator(runtime(), o).evaluateGrid(materials, s);
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const double alpha = double(materials[i].roughness) * materials[i].roughness;
    const double want = 1.0 / (4.0 * M_PI * alpha * alpha);
    EXPECT_NEAR(f[3 * i], want, 1e-5 * want) << "roughness " << materials[i].roughness;
  }
}

// Anisotropy at strength 0 is the isotropic model, whatever the rotation: the anisotropic code
// path (compiled in because one material of the batch is anisotropic) against the isotropic one.
TEST(ClosedForm, AnisotropyAtStrengthZeroIsIsotropic) {
  std::mt19937_64 rng(seed() ^ 0xa150);
  std::vector<MaterialParams> iso, withAniso;
  for (int i = 0; i < 32; ++i) {
    auto m = randomMaterial(rng);
    m.anisotropyStrength = 0.0f;
    m.anisotropyRotation = 0.0f;
    iso.push_back(m);
    m.anisotropyRotation = float(i) * 0.37f;
    withAniso.push_back(m);
  }
  auto anisotropic = withAniso[0];
  anisotropic.anisotropyStrength = 0.9f;
  withAniso.push_back(anisotropic);
  const Samples s = randomSamples(rng, 4096, 0);
  Evaluator ev(runtime(), EvalOptions{});
  const auto a = ev.evaluateGrid(iso, s);
  auto b = ev.evaluateGrid(withAniso, s);
  b.resize(a.size());
  std::size_t at = 0;
  EXPECT_LE(maxAbsRelDiff(b, a, &at), 1e-4) << "material " << at / (3 * s.size()) << ": " << b[at] << " vs " << a[at];
}

// A layer at weight 0 leaves the core material: sheenColor 0 and clearcoat 0 in a batch that
// compiles those layers in equal the core model compiled without them.
TEST(ClosedForm, ZeroSheenAndClearcoatEqualTheCore) {
  std::mt19937_64 rng(seed() ^ 0xc07e);
  std::vector<MaterialParams> core, layered;
  for (int i = 0; i < 32; ++i) {
    MaterialParams m = white(float(i % 3) * 0.5f, 0.05f + 0.03f * float(i));
    m.baseColor = {0.2f, 0.5f, 0.9f};
    core.push_back(m);
    m.sheenRoughness = 0.5f;        // no sheen colour: the layer is off
    m.clearcoatRoughness = 0.3f;    // no clearcoat weight: the layer is off
    layered.push_back(m);
  }
  auto on = layered[0];
  on.sheenColor = {1, 1, 1};
  on.clearcoat = 1.0f;
  layered.push_back(on);
  const Samples s = randomSamples(rng, 4096, 0);
  for (auto scaling : {SheenScaling::Min, SheenScaling::View}) {
    Evaluator ev(runtime(), EvalOptions{SheenVisibility::Charlie, SheenDistribution::Charlie, scaling, Lobe::All});
    const auto a = ev.evaluateGrid(core, s);
    auto b = ev.evaluateGrid(layered, s);
    b.resize(a.size());
    std::size_t at = 0;
    EXPECT_LE(maxAbsRelDiff(b, a, &at), 1e-6) << "material " << at / (3 * s.size());
  }
}

// Where the sheen albedo E exceeds 1 (energy gain, and albedo scaling s < 0), per D x V, over
// mu in [0.01, 1] and r in [0.05, 1]. Measured with the baked table, checked against the
// region docs/model.md documents: the Charlie D variants gain energy at grazing, low-roughness
// corners; the Ashikhmin D variants never do.
struct Excess {
  SheenDistribution d;
  SheenVisibility v;
  double maxE;        // documented maximum (at mu = 0.01, r = 0.05 for the Charlie D variants)
  double rBound;      // E > 1 only for r below this
  double muBound;     // and N.V below this
};

TEST(SheenAlbedo, ExceedsOneOnlyWhereDocumented) {
  const Excess cases[] = {
      {SheenDistribution::Charlie, SheenVisibility::Charlie, 3.153, 0.25, 0.055},
      {SheenDistribution::Charlie, SheenVisibility::Ashikhmin, 5.321, 0.42, 0.095},
      {SheenDistribution::Ashikhmin, SheenVisibility::Charlie, 0.962, 0.0, 0.0},
      {SheenDistribution::Ashikhmin, SheenVisibility::Ashikhmin, 0.801, 0.0, 0.0},
  };
  for (const auto& c : cases) {
    Evaluator ev(runtime(), EvalOptions{c.v, c.d, SheenScaling::Min, Lobe::All});
    const auto& t = ev.sheenAlbedo();
    double maxE = 0, rMax = 0, muMax = 0;
    for (int j = 0; j <= 190; ++j)
      for (int i = 0; i <= 198; ++i) {
        const float r = 0.05f + 0.005f * j, mu = 0.01f + 0.005f * i;
        const double e = t.lookup(mu, r);
        maxE = std::max(maxE, e);
        if (e > 1.0) rMax = std::max<double>(rMax, r), muMax = std::max<double>(muMax, mu);
      }
    const std::string name = std::string(toString(c.d)) + " D x " + toString(c.v) + " V";
    EXPECT_NEAR(maxE, c.maxE, 2e-3 * c.maxE) << name;
    EXPECT_LE(rMax, c.rBound) << name;
    EXPECT_LE(muMax, c.muBound) << name;
    if (c.maxE > 1.0) {
      EXPECT_GT(rMax, c.rBound - 0.03) << name << ": the documented region is tight";
    }
    std::printf("[ sheen E ] %s: max E %.4f, E > 1 for r <= %.3f and N.V <= %.3f\n", name.c_str(), maxE, rMax, muMax);
  }
}

}  // namespace
