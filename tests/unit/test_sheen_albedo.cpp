// The baked sheen albedo table against the reference's own integral of E(mu, r), and the
// convergence of the bake's quadrature. Also pins down where E exceeds 1 (energy gain).
#include <gtest/gtest.h>

#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

struct Combo {
  SheenDistribution d;
  SheenVisibility v;
};

std::string comboName(const testing::TestParamInfo<Combo>& info) {
  return std::string(toString(info.param.d)) + "_D_" + toString(info.param.v) + "_V";
}

class SheenAlbedoTableTest : public testing::TestWithParam<Combo> {};

// Lookups between the nodes (where interpolation error peaks) against the reference integral.
TEST_P(SheenAlbedoTableTest, LookupMatchesReferenceIntegral) {
  const auto [d, v] = GetParam();
  Evaluator ev(runtime(), EvalOptions{v, d, SheenScaling::Min, Lobe::All});
  const auto& table = ev.sheenAlbedo();
  std::mt19937_64 rng(seed() ^ 0xe7ab1e);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worstAbs = 0, worstRel = 0;
  std::string where;
  for (int i = 0; i < 400; ++i) {
    const float mu = float(0.01 + 0.99 * u(rng)), r = float(0.05 + 0.95 * u(rng));
    const double want = ref::sheenAlbedo(mu, r, d, v);
    const double got = table.lookup(mu, r);
    const double err = std::fabs(got - want) / std::max(1.0, want);
    if (err > worstRel) {
      worstRel = err;
      worstAbs = std::fabs(got - want);
      where = "mu " + std::to_string(mu) + ", r " + std::to_string(r) + ": table " + std::to_string(got) +
              ", integral " + std::to_string(want);
    }
  }
  // 1e-4 relative to max(1, E): E reaches ~12 at grazing, low-roughness corners.
  EXPECT_LE(worstRel, 1e-4) << "worst at " << where << " (abs " << worstAbs << ")";
}

// Doubling the quadrature order moves no entry by more than 2e-5 of max(1, E).
TEST_P(SheenAlbedoTableTest, BakeQuadratureHasConverged) {
  const auto [d, v] = GetParam();
  const auto a = bakeSheenAlbedo(runtime(), d, v, 33, 12);
  const auto b = bakeSheenAlbedo(runtime(), d, v, 33, 24);
  double worst = 0;
  for (std::size_t i = 0; i < a.values.size(); ++i)
    worst = std::max(worst, std::fabs(a.values[i] - b.values[i]) / std::max(1.0, double(b.values[i])));
  EXPECT_LE(worst, 2e-5);
}

INSTANTIATE_TEST_SUITE_P(Combos, SheenAlbedoTableTest,
                         testing::Values(Combo{SheenDistribution::Charlie, SheenVisibility::Charlie},
                                         Combo{SheenDistribution::Charlie, SheenVisibility::Ashikhmin},
                                         Combo{SheenDistribution::Ashikhmin, SheenVisibility::Charlie},
                                         Combo{SheenDistribution::Ashikhmin, SheenVisibility::Ashikhmin}),
                         comboName);

}  // namespace
