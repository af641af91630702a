// --ibl exact with the samplers, pdfs and lobe probabilities of `brdfcl sample` (kernels/ibl_exact.cl
// includes sample.cl): the white furnace of sheen-dominated materials, under the Charlie and the
// Ashikhmin sheen, against the reference's directional albedo, and the error estimate at equal samples.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "brdfcl/render.hpp"
#include "furnace.hpp"
#include "reference/reference.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

const std::vector<float> kNdotV = {1.0f, 0.7f, 0.4f, 0.2f, 0.08f};
const int kSamples = 16384;

// Velvets: white sheen over a dark, rough dielectric, where the sheen carries most of the albedo.
std::vector<MaterialParams> velvets() {
  std::vector<MaterialParams> out;
  for (float r : {0.3f, 0.5f, 0.8f, 1.0f}) {
    MaterialParams m;
    m.name = fmt::format("velvet, sheen roughness {}", r);
    m.baseColor = {0.05f, 0.02f, 0.08f};
    m.metallic = 0.0f, m.roughness = 0.9f;
    m.sheenColor = {1.0f, 0.9f, 0.8f}, m.sheenRoughness = r;
    out.push_back(m);
  }
  return out;
}

GBuffer velvetGBuffer(const std::vector<MaterialParams>& ms) {
  GBuffer g;
  g.width = int(kNdotV.size());
  g.height = int(ms.size());
  for (const auto& m : ms)
    for (float mu : kNdotV) addFurnacePixel(g, m, std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0, mu);
  return g;
}

Image furnace(const EvalOptions& o, int samples, ShadeStats* stats = nullptr) {
  ShadeOptions so;
  so.ibl = IblMode::Exact;
  so.iblSamples = samples;
  return Shader(runtime(), builtinEnvironment("uniform"), o).shade(velvetGBuffer(velvets()), so, stats);
}

}  // namespace

// Radiance 1 everywhere: each pixel is its material's directional albedo, for either sheen.
TEST(ExactIblSheen, WhiteFurnaceOfVelvetsGivesTheReferenceAlbedo) {
  for (const SheenDistribution d : {SheenDistribution::Charlie, SheenDistribution::Ashikhmin}) {
    EvalOptions o;
    o.sheenDistribution = d;
    o.sheenVisibility = d == SheenDistribution::Ashikhmin ? SheenVisibility::Ashikhmin : SheenVisibility::Charlie;
    ShadeStats stats;
    const Image img = furnace(o, kSamples, &stats);
    const auto ms = velvets();
    double worst = 0;
    std::string where;
    for (std::size_t m = 0; m < ms.size(); ++m)
      for (std::size_t v = 0; v < kNdotV.size(); ++v) {
        const std::size_t i = m * kNdotV.size() + v;
        const double mu = kNdotV[v], s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
        const ref::Rgb want = ref::directionalAlbedo(ms[m], o, ref::Vec3{s, 0.0, mu}, 1e-6);
        for (int c = 0; c < 3; ++c) {
          const double got = img.rgb[3 * i + c], excess = std::fabs(got - want[c]) / (0.005 * want[c] + 5e-4);
          if (excess > worst) {
            worst = excess;
            where = fmt::format("{}, N.V {}, channel {}: exact {}, reference {}", ms[m].name, mu, c, got, want[c]);
          }
        }
      }
    std::printf("%s: worst error / tolerance %.3f (%s), estimated relative standard error %.4f %%\n",
                d == SheenDistribution::Charlie ? "charlie" : "ashikhmin", worst, where.c_str(),
                100 * stats.relativeStandardError);
    EXPECT_LE(worst, 1.0) << (d == SheenDistribution::Charlie ? "charlie" : "ashikhmin") << ": " << where;
  }
}
