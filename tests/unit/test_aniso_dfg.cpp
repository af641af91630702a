// The anisotropic split-sum table against the double-precision reference: F0 A + B at a texel is
// the directional albedo of the anisotropic specular lobe (metal of base colour 1 gives A + B,
// of base colour 0 gives B), at every strength and view azimuth the grid holds.
#include <gtest/gtest.h>

#include <cmath>

#include <fmt/format.h>

#include "kernels/common/shading_layout.h"
#include "host/src/render/aniso_dfg.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr int kNv = BRDFCL_ANISO_DFG_NV, kR = BRDFCL_ANISO_DFG_R, kS = BRDFCL_ANISO_DFG_S, kPsi = BRDFCL_ANISO_DFG_PSI;

struct Texel {
  int i, j, k, l;
};

std::size_t at(const Texel& t) { return 2 * ((std::size_t(t.l) * kS + t.k) * kR + t.j) * kNv + 2 * std::size_t(t.i); }

ref::Rgb referenceAlbedo(const Texel& t, float baseColor) {
  MaterialParams m;
  m.metallic = 1.0f;
  m.baseColor = {baseColor, baseColor, baseColor};
  m.roughness = float(t.j) / (kR - 1);
  m.anisotropyStrength = float(t.k) / (kS - 1);
  const double nv = std::max(double(t.i) / (kNv - 1), 1e-4), psi = M_PI / 2 * t.l / (kPsi - 1);
  const double s = std::sqrt(1 - nv * nv);
  return ref::directionalAlbedo(m, EvalOptions{}, ref::Vec3{s * std::cos(psi), s * std::sin(psi), nv}, 1e-7);
}

TEST(AnisotropicDfg, TexelsAreTheReferenceAlbedo) {
  const auto table = cachedAnisotropicDfg(runtime());  // what the shader reads: baked by this kernel
  std::vector<Texel> texels;
  for (int i : {3, 14, kNv - 1})
    for (int j : {2, 9, kR - 1})
      for (int k : {0, kS / 2, kS - 1})
        for (int l : {0, kPsi / 2, kPsi - 1}) texels.push_back({i, j, k, l});
  double worst = 0;
  std::string worstAt;
  for (const Texel& t : texels) {
    const double a = table[at(t)], b = table[at(t) + 1];
    const double white = referenceAlbedo(t, 1.0f)[0], black = referenceAlbedo(t, 0.0f)[0];
    for (const auto& [got, want] : {std::pair{a + b, white}, std::pair{b, black}}) {
      const double err = std::abs(got - want) / std::max(want, 0.05);
      if (err > worst) {
        worst = err;
        worstAt = fmt::format("N.V {:.3f}, r {:.3f}, s {:.3f}, psi {:.3f}: table {:.6f}, reference {:.6f}", t.i / double(kNv - 1),
                              t.j / double(kR - 1), t.k / double(kS - 1), M_PI / 2 * t.l / (kPsi - 1), got, want);
      }
    }
  }
  EXPECT_LT(worst, 5e-3) << "worst relative error " << worst << " at " << worstAt;
  std::printf("anisotropic DFG: worst relative error %.2e at %s\n", worst, worstAt.c_str());
}

}  // namespace
