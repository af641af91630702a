// Kernel vs the independent double-precision reference (tests/reference), 100k random samples
// per mode over 256 random materials, in the domain where no documented clamp applies.
// Relative tolerance 1e-4 (1e-3 where the baked sheen albedo table enters), absolute floor 1e-6.
// The suite runs at the device's lane width (BRDFCL_LANES=1 runs all of it at W = 1); a
// representative subset runs at W = 1 and W = 4 whatever the device.
#include <gtest/gtest.h>

#include "support.hpp"
#include "host/src/runtime/opencl.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr std::size_t kSamples = 100000;
constexpr std::size_t kMaterials = 256;
constexpr double kAbsFloor = 1e-6;

bool usesTable(const EvalOptions& o) {
  return o.sheenScaling != SheenScaling::None &&
         (o.lobe == Lobe::All || o.lobe == Lobe::Diffuse || o.lobe == Lobe::Specular);
}

// Runs one mode and returns the worst case. With the table, the scaled base is compared relative
// to the unscaled magnitude of the layers (reference with scaling none): the table's error is an
// error in the scale factor, so it is relative to what that factor multiplies.
WorstCase compareMode(const EvalOptions& o, std::uint64_t modeSeed, std::size_t samples = kSamples) {
  std::mt19937_64 rng(seed() ^ modeSeed);
  std::vector<MaterialParams> materials;
  for (std::size_t i = 0; i < kMaterials; ++i) materials.push_back(randomMaterial(rng));
  const Samples s = randomSamples(rng, samples, materials.size());
  Evaluator ev(runtime(), o);
  const auto got = ev.evaluate(materials, s);
  const bool table = usesTable(o);
  EvalOptions unscaled = o;
  unscaled.sheenScaling = SheenScaling::None;
  const double rel = table ? 1e-3 : 1e-4;
  WorstCase w;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto& m = materials[s.material[i]];
    const ref::Vec3 L{s.L[3 * i], s.L[3 * i + 1], s.L[3 * i + 2]}, V{s.V[3 * i], s.V[3 * i + 1], s.V[3 * i + 2]};
    const auto want = ref::brdf(m, o, L, V);
    const auto scale = table ? ref::brdf(m, unscaled, L, V) : want;
    for (int c = 0; c < 3; ++c) {
      w.check(got[3 * i + c], want[c], std::max(std::fabs(want[c]), std::fabs(scale[c])), rel, kAbsFloor, [&] {
        std::ostringstream d;
        d.precision(9);
        d << "channel " << c << ", L(" << L.x << "," << L.y << "," << L.z << ") V(" << V.x << "," << V.y << ","
          << V.z << "), " << describe(m) << "; " << describeOptions(o) << "; seed " << seed();
        return d.str();
      });
    }
  }
  return w;
}

struct ModeName {
  template <class P>
  std::string operator()(const testing::TestParamInfo<P>& info) const {
    const EvalOptions& o = info.param;
    return std::string(toString(o.sheenVisibility)) + "_" + toString(o.sheenDistribution) + "_" +
           toString(o.sheenScaling) + "_" + toString(o.lobe);
  }
};

std::vector<EvalOptions> allModes() {
  std::vector<EvalOptions> modes;
  // Every sheen option combination for the full material...
  for (auto v : {SheenVisibility::Charlie, SheenVisibility::Ashikhmin})
    for (auto d : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin})
      for (auto sc : {SheenScaling::Min, SheenScaling::View, SheenScaling::None})
        modes.push_back({v, d, sc, Lobe::All});
  // ...and each lobe on its own under the defaults.
  for (auto l : {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat})
    modes.push_back({SheenVisibility::Charlie, SheenDistribution::Charlie, SheenScaling::Min, l});
  return modes;
}

class KernelVsReference : public testing::TestWithParam<EvalOptions> {};

TEST_P(KernelVsReference, MatchesWithinTolerance) {
  const auto& o = GetParam();
  const auto w = compareMode(o, std::hash<std::string>{}(describeOptions(o)));
  EXPECT_EQ(w.checked, 3 * kSamples);
  EXPECT_LE(w.worstRatio, 1.0) << "worst: " << w.report;
  RecordProperty("worst_error_over_tolerance", std::to_string(w.worstRatio));
}

INSTANTIATE_TEST_SUITE_P(Modes, KernelVsReference, testing::ValuesIn(allModes()), ModeName());

struct LanesMode {
  int lanes;
  EvalOptions options;
};

// The full material under both sheen models with and without the table, and the specular and
// sheen lobes alone: every code path of the layered kernel at each width, in a few seconds.
std::vector<LanesMode> lanesModes() {
  std::vector<LanesMode> out;
  for (int w : {1, 4}) {
    out.push_back({w, {SheenVisibility::Charlie, SheenDistribution::Charlie, SheenScaling::Min, Lobe::All}});
    out.push_back({w, {SheenVisibility::Ashikhmin, SheenDistribution::Ashikhmin, SheenScaling::None, Lobe::All}});
    out.push_back({w, {SheenVisibility::Charlie, SheenDistribution::Charlie, SheenScaling::Min, Lobe::Specular}});
    out.push_back({w, {SheenVisibility::Charlie, SheenDistribution::Charlie, SheenScaling::Min, Lobe::Sheen}});
  }
  return out;
}

class KernelVsReferenceAtWidth : public testing::TestWithParam<LanesMode> {};

TEST_P(KernelVsReferenceAtWidth, MatchesWithinTolerance) {
  const auto& [lanes, o] = GetParam();
  ForcedLanes forced(lanes);
  ASSERT_EQ(laneShape(runtime().info()).lanes, lanes);
  constexpr std::size_t kSubset = 20000;
  const auto w = compareMode(o, std::hash<std::string>{}(describeOptions(o)) ^ std::size_t(lanes), kSubset);
  EXPECT_EQ(w.checked, 3 * kSubset);
  EXPECT_LE(w.worstRatio, 1.0) << "W = " << lanes << ", worst: " << w.report;
}

INSTANTIATE_TEST_SUITE_P(Subset, KernelVsReferenceAtWidth, testing::ValuesIn(lanesModes()),
                         [](const testing::TestParamInfo<LanesMode>& info) {
                           return "W" + std::to_string(info.param.lanes) + "_" + ModeName()(testing::TestParamInfo<EvalOptions>(info.param.options, info.index));
                         });

// Each width computes the same f for a sample: the lanes only batch independent samples, so
// widths differ at most in the last bits of vectorized vs scalar math builtins.
TEST(KernelLanes, WidthsAgree) {
  std::mt19937_64 rng(seed() ^ 0x1a4e5);
  std::vector<MaterialParams> materials;
  for (int i = 0; i < 32; ++i) materials.push_back(randomMaterial(rng));
  const Samples s = randomSamples(rng, 4099, materials.size());  // not a multiple of 16
  std::vector<std::vector<float>> byWidth;
  for (int w : {16, 8, 4, 1}) {
    ForcedLanes forced(w);
    byWidth.push_back(Evaluator(runtime(), EvalOptions{}).evaluate(materials, s));
  }
  for (std::size_t k = 1; k < byWidth.size(); ++k)
    for (std::size_t i = 0; i < byWidth[0].size(); ++i)
      ASSERT_NEAR(byWidth[k][i], byWidth[0][i], 1e-5 * std::fabs(byWidth[0][i]) + 1e-7) << "width #" << k << ", value " << i;
}

// The lobes are a partition of the layered sum.
TEST(KernelLobes, SumToAll) {
  std::mt19937_64 rng(seed() ^ 0x10be5);
  std::vector<MaterialParams> materials;
  for (int i = 0; i < 64; ++i) materials.push_back(randomMaterial(rng));
  const Samples s = randomSamples(rng, 20000, materials.size());
  std::vector<float> sum(3 * s.size(), 0.0f);
  for (auto l : {Lobe::Diffuse, Lobe::Specular, Lobe::Sheen, Lobe::Clearcoat}) {
    EvalOptions o;
    o.lobe = l;
    auto part = Evaluator(runtime(), o).evaluate(materials, s);
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += part[i];
  }
  const auto all = Evaluator(runtime(), EvalOptions{}).evaluate(materials, s);
  double worst = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double e = std::fabs(sum[i] - all[i]) / (1e-4 * std::fabs(all[i]) + 1e-6);
    if (e > worst) worst = e, at = i;
  }
  EXPECT_LE(worst, 1.0) << "sample " << at / 3 << ": lobes sum to " << sum[at] << ", all gives " << all[at];
}

}  // namespace
