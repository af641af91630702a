// Chi-square goodness of fit of the kernels' samplers (Evaluator::sample), per lobe and for the
// mixture: observed directions binned in (cos theta, phi) against expected counts integrated from
// the double-precision reference pdfs (tests/reference/sampling.hpp), plus mutation checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "reference/reference.hpp"
#include "reference/sampling.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

constexpr int kCosBins = 10, kPhiBins = 20, kCells = kCosBins * kPhiBins + 1;  // + "no direction"
constexpr std::size_t kSamples = 200000;
constexpr double kPi = ref::kPi;

ref::Vec3 viewAt(double thetaDeg, double phi) {
  const double t = thetaDeg * kPi / 180.0;
  return {std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
}

double wrapPhi(double phi) { return phi < 0.0 ? phi + 2.0 * kPi : phi; }

// Regularized upper incomplete gamma Q(a, x): its series below x = a + 1, Lentz's continued
// fraction above (both to double precision).
double gammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double front = std::exp(-x + a * std::log(x) - std::lgamma(a));
  if (x < a + 1.0) {
    double ap = a, del = 1.0 / a, sum = del;
    for (int n = 0; n < 10000 && std::fabs(del) > std::fabs(sum) * 1e-16; ++n) sum += del *= x / ++ap;
    return std::max(0.0, 1.0 - sum * front);
  }
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::fabs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < 1e-16) break;
  }
  return front * h;
}

int cellOf(const float* row) {
  if (!(row[3] > 0.0f)) return kCells - 1;
  const double z = std::clamp(double(row[2]), 0.0, 1.0), phi = wrapPhi(std::atan2(double(row[1]), double(row[0])));
  const int i = std::min(kCosBins - 1, int(z * kCosBins)), j = std::min(kPhiBins - 1, int(phi / (2 * kPi) * kPhiBins));
  return i * kPhiBins + j;
}

// The integral of pdf over each (cos theta, phi) bin of the upper hemisphere, nested adaptive
// Gauss-Kronrod split at the peak (cos theta, phi) of the sharp lobes, which a bin's first nodes
// could otherwise step over.
std::vector<double> binIntegrals(const std::function<double(ref::Vec3)>& pdf, double peakCos, double peakPhi) {
  std::vector<double> out(kCells - 1);
  auto pieces = [](double a, double b, double split, const std::function<double(double)>& f, double tol) {
    if (split > a && split < b) return ref::integrate(f, a, split, tol / 2) + ref::integrate(f, split, b, tol / 2);
    return ref::integrate(f, a, b, tol);
  };
  for (int i = 0; i < kCosBins; ++i)
    for (int j = 0; j < kPhiBins; ++j) {
      const double c0 = double(i) / kCosBins, c1 = double(i + 1) / kCosBins;
      const double p0 = 2 * kPi * j / kPhiBins, p1 = 2 * kPi * (j + 1) / kPhiBins;
      out[i * kPhiBins + j] = pieces(c0, c1, peakCos, [&](double z) {
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        return pieces(p0, p1, peakPhi, [&](double phi) { return pdf({s * std::cos(phi), s * std::sin(phi), z}); }, 1e-10);
      }, 1e-9);
    }
  return out;
}

struct Fit {
  double chi2 = 0, p = 1;
  int dof = 0;
};

// Pearson's statistic over the cells, cells expecting fewer than 5 pooled into one (dropped,
// with their observations, when the pool itself expects fewer than 5).
Fit chiSquare(const std::vector<double>& observed, const std::vector<double>& expected) {
  Fit fit;
  double poolObs = 0, poolExp = 0;
  int cells = 0;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    if (expected[k] < 5.0) {
      poolObs += observed[k];
      poolExp += std::max(expected[k], 0.0);
      continue;
    }
    fit.chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++cells;
  }
  if (poolExp >= 5.0) {
    fit.chi2 += (poolObs - poolExp) * (poolObs - poolExp) / poolExp;
    ++cells;
  } else if (poolObs > 20.0 + 10.0 * poolExp) {
    fit.chi2 = INFINITY;  // many directions where the pdf says almost none may land
  }
  fit.dof = std::max(cells - 1, 1);
  fit.p = std::isinf(fit.chi2) ? 0.0 : gammaQ(0.5 * fit.dof, 0.5 * fit.chi2);
  return fit;
}

struct Case {
  std::string name;
  MaterialParams m;
  EvalOptions o;
  double thetaV;
};

MaterialParams material(float roughness, float metallic, float sheen, float sheenRoughness, float coat,
                        float coatRoughness, float aniso, float rotation) {
  MaterialParams m;
  m.baseColor = {0.8f, 0.5f, 0.3f};
  m.roughness = roughness;
  m.metallic = metallic;
  m.sheenColor = {sheen, 0.8f * sheen, 0.6f * sheen};
  m.sheenRoughness = sheenRoughness;
  m.clearcoat = coat;
  m.clearcoatRoughness = coatRoughness;
  m.anisotropyStrength = aniso;
  m.anisotropyRotation = rotation;
  m.anisotropyExtension = aniso > 0.0f;
  return m;
}

std::vector<Case> cases() {
  const std::vector<std::pair<std::string, MaterialParams>> materials = {
      {"layered", material(0.5f, 0.2f, 0.8f, 0.3f, 0.5f, 0.2f, 0.6f, 0.7f)},
      {"mirrorlike", material(0.02f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f)},
      {"rough_velvet", material(1.0f, 0.0f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f)},
      {"brushed", material(0.2f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, -2.0f)},
      {"satin_coat", material(0.3f, 0.0f, 0.6f, 0.05f, 1.0f, 0.05f, 0.3f, 2.5f)},
  };
  const Lobe lobes[] = {Lobe::All, Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat};
  const double views[] = {0.0, 60.0, 89.0};
  std::vector<Case> out;
  for (const auto& [name, m] : materials)
    for (Lobe lobe : lobes) {
      if (lobe == Lobe::Sheen && m.sheenColor[0] == 0.0f) continue;
      if (lobe == Lobe::Clearcoat && m.clearcoat == 0.0f) continue;
      if (lobe == Lobe::Diffuse && name != "layered") continue;  // one cosine hemisphere is enough
      if (lobe == Lobe::Specular && name == "rough_velvet") continue;  // GGX at alpha = 1: brushed, layered cover it
      for (double t : views) {
        Case c{name + "_" + toString(lobe) + "_" + std::to_string(int(t)), m, EvalOptions{}, t};
        c.o.lobe = lobe;
        out.push_back(c);
      }
    }
  // The Ashikhmin distribution's own sampler.
  for (Lobe lobe : {Lobe::Sheen, Lobe::All})
    for (double t : {30.0, 85.0}) {
      Case c{std::string("velvet_ashikhmin_") + toString(lobe) + "_" + std::to_string(int(t)),
             material(0.6f, 0.0f, 1.0f, 0.4f, 0.0f, 0.0f, 0.0f, 0.0f), EvalOptions{}, t};
      c.o.lobe = lobe;
      c.o.sheenDistribution = SheenDistribution::Ashikhmin;
      c.o.sheenVisibility = SheenVisibility::Ashikhmin;
      out.push_back(c);
    }
  return out;
}

// kSamples directions at V drawn by the kernels with the counter-based uniforms of `seed`.
std::vector<float> draw(const Case& c, ref::Vec3 V, std::uint64_t seed, std::size_t n = kSamples) {
  Evaluator ev(runtime(), c.o);
  std::vector<float> view(3 * n), u(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    view[3 * i] = float(V.x);
    view[3 * i + 1] = float(V.y);
    view[3 * i + 2] = float(V.z);
  }
  Evaluator::drawUniforms(seed, 0, n, u.data());
  return ev.sample({c.m}, {}, view, u);
}

std::vector<double> histogram(const std::vector<float>& rows) {
  std::vector<double> h(kCells, 0.0);
  for (std::size_t i = 0; i < rows.size() / 7; ++i) h[cellOf(&rows[7 * i])] += 1.0;
  return h;
}

// Expected counts: N times each bin's probability, and the rest of N in the "no direction" cell.
std::vector<double> expectedCounts(const Case& c, ref::Vec3 V, double scale = 1.0, std::size_t n = kSamples) {
  const auto p = ref::lobeProbabilities(c.m, c.o, V);
  auto pdf = [&](ref::Vec3 L) {
    double s = 0.0;
    for (int t = 0; t < ref::kLobeCount; ++t)
      if (p[t] > 0.0) s += p[t] * ref::lobePdf(t, c.m, c.o, L, V);
    return s;
  };
  const auto bins = binIntegrals(pdf, V.z, wrapPhi(std::atan2(-V.y, -V.x)));
  std::vector<double> e(kCells);
  double kept = 0.0;
  for (int k = 0; k + 1 < kCells; ++k) {
    e[k] = double(n) * scale * bins[k];
    kept += bins[k];
  }
  e[kCells - 1] = std::max(0.0, double(n) * (1.0 - scale * kept));
  return e;
}

// Significance 0.01 over all the fits of this file, Sidak-corrected.
double threshold() { return 1.0 - std::pow(0.99, 1.0 / double(cases().size())); }

TEST(SamplingChiSquare, EveryLobeAndMixtureFitsTheReferencePdf) {
  const auto all = cases();
  const double alpha = threshold();
  const auto start = std::chrono::steady_clock::now();
  double worst = 1.0;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const Case& c = all[k];
    const ref::Vec3 V = viewAt(c.thetaV, 0.3);
    const auto obs = histogram(draw(c, V, seed() + k));
    const Fit fit = chiSquare(obs, expectedCounts(c, V));
    worst = std::min(worst, fit.p);
    std::printf("  %-32s chi2 %9.1f dof %3d p %.4f\n", c.name.c_str(), fit.chi2, fit.dof, fit.p);
    EXPECT_GT(fit.p, alpha) << c.name << ": chi2 " << fit.chi2 << " with " << fit.dof << " dof (seed " << seed() << ")";
  }
  std::printf("  %zu fits, smallest p %.4f, threshold %.2e, %.1f s\n", all.size(), worst, alpha,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

// The fit has the power to see a wrong pdf or a wrong sampler: both mutations must fail it.
TEST(SamplingChiSquare, MutatedPdfOrDirectionsFail) {
  const double alpha = threshold();
  for (Lobe lobe : {Lobe::All, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat, Lobe::Diffuse}) {
    // Sheen roughness 1: its sampler keeps most directions, so the kept bins hold most samples.
    Case c{std::string("layered_") + toString(lobe), material(0.5f, 0.2f, 0.8f, 1.0f, 0.5f, 0.2f, 0.6f, 0.7f), EvalOptions{}, 45.0};
    c.o.lobe = lobe;
    const ref::Vec3 V = viewAt(c.thetaV, 0.3);
    constexpr std::size_t kMutationSamples = 800000;  // a 2 % error must stand out in every lobe
    auto rows = draw(c, V, seed() + 1000, kMutationSamples);
    const auto expected = expectedCounts(c, V, 1.0, kMutationSamples);
    const Fit good = chiSquare(histogram(rows), expected);
    const Fit scaled = chiSquare(histogram(rows), expectedCounts(c, V, 1.02, kMutationSamples));
    // Directions tilted towards the horizon: cos theta scaled by 0.95.
    for (std::size_t i = 0; i < rows.size() / 7; ++i) {
      float* r = &rows[7 * i];
      if (!(r[3] > 0.0f)) continue;
      const double z = 0.95 * r[2], s = std::sqrt(1.0 - z * z), h = std::hypot(r[0], r[1]);
      if (h > 0) r[0] = float(r[0] / h * s), r[1] = float(r[1] / h * s);
      r[2] = float(z);
    }
    const Fit tilted = chiSquare(histogram(rows), expected);
    std::printf("  %-20s p %.4f, pdf x 1.02: p %.2e, tilted: p %.2e\n", c.name.c_str(), good.p, scaled.p, tilted.p);
    EXPECT_GT(good.p, alpha) << c.name;
    EXPECT_LT(scaled.p, alpha) << c.name << ": a pdf 2 % too large went unnoticed";
    EXPECT_LT(tilted.p, alpha) << c.name << ": perturbed directions went unnoticed";
  }
}

}  // namespace
}  // namespace brdfcl::test
