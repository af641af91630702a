// threejs image-based light as three.js's PhysicalLightingModel indirect() computes it
// (scripts/engine-check runs it under a uniform environment): multiscatter mixed by metalness from
// the dielectric and metallic terms, and N.V clamped to [0, 1] rather than floored.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "brdfcl/io.hpp"
#include "brdfcl/render.hpp"
#include "furnace.hpp"
#include "reference/profiles.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

struct Pixel {
  float V[3];
  float base, metallic, roughness;
  float sheen, sheenRoughness, clearcoat, clearcoatRoughness;
};

// One row of pixels, N = clearcoat N = +Z, shaded under a uniform environment of radiance 1.
Image shadeUniform(const std::vector<Pixel>& px) {
  GBuffer g;
  g.width = static_cast<int>(px.size());
  g.height = 1;
  for (const Pixel& p : px) {
    MaterialParams m;
    m.baseColor = {p.base, p.base, p.base};
    m.metallic = p.metallic;
    m.roughness = p.roughness;
    m.sheenColor = {p.sheen, p.sheen, p.sheen};
    m.sheenRoughness = p.sheenRoughness;
    m.clearcoat = p.clearcoat;
    m.clearcoatRoughness = p.clearcoatRoughness;
    addFurnacePixel(g, m, p.V[0], p.V[1], p.V[2]);
  }
  EvalOptions o;
  o.profile = Profile::Threejs;
  return Shader(runtime(), builtinEnvironment(), o).shade(g);
}

// Fdez-Aguera's single and multiple scattering of f0 from three.js's table at (1, N.V), as
// computeMultiscattering takes them.
struct Scattering {
  double ss, ms;
};
Scattering multiscatter(float f0, float nv) {
  const auto ab = ref::threejsDfg(1.0, nv);
  const double ess = ab[0] + ab[1], ems = 1.0 - ess;
  const double ss = f0 * ab[0] + ab[1], favg = f0 + (1.0 - f0) * 0.047619;
  return {ss, ss * favg / (1.0 - ems * favg) * ems};
}

}  // namespace

// indirectSpecular mixes the dielectric and the metallic (single, multi) scattering by metalness,
// and the diffuse carries (1 - m): the whole is linear in metalness. The multiscatter of the
// blended f0 is not (0.70 against 0.84 here, at roughness 1 where 1 - E_ss is largest).
TEST(ProfileThreejsIbl, MultiscatterIsMixedByMetalness) {
  const float v[3] = {0.6f, 0.0f, 0.8f};
  const Image img = shadeUniform({{{v[0], v[1], v[2]}, 0.9f, 0.0f, 1.0f, 0, 0, 0, 0},
                                  {{v[0], v[1], v[2]}, 0.9f, 0.5f, 1.0f, 0, 0, 0, 0},
                                  {{v[0], v[1], v[2]}, 0.9f, 1.0f, 1.0f, 0, 0, 0, 0}});
  const double half = 0.5 * (img.rgb[0] + img.rgb[6]);
  EXPECT_NEAR(img.rgb[3], half, 1e-5 * half) << "m = 0: " << img.rgb[0] << ", m = 1: " << img.rgb[6];

  // The metal alone, from three.js's table at (rho, N.V) = (1, 0.8): Fdez-Aguera with F0 = 0.9.
  const auto [fss, fms] = multiscatter(0.9f, 0.8f);
  const double metal = fss + fms;
  EXPECT_NEAR(img.rgb[6], metal, 2e-5 * metal);
}

// At N.V = 1e-6 the engine reads the coat's Fcc = 1 - 0.96 (1 - Fs) at 1e-6, not at 1e-4, where it
// lets 4.6e-4 of the base through. rho = rho_c = 1 and N.V < 1/32 sample the table's edge texel
// (15, 0) on both sides.
TEST(ProfileThreejsIbl, GrazingViewCoatIsClampedNotFloored) {
  const float nv = 1e-6f;
  const Image img = shadeUniform({{{1.0f, 0.0f, nv}, 1.0f, 0.0f, 1.0f, 0, 0, 1.0f, 1.0f}});
  const auto ab = ref::threejsDfg(1.0, nv);
  const auto [ss, ms] = multiscatter(0.04f, nv);
  const double base = ss + ms + (1.0 - (ss + ms));
  const double Fs = std::exp2(-(5.55473 * nv + 6.98316) * nv);
  const double Fcc = 0.04f * (1.0 - Fs) + Fs;
  const double col = base * (1.0 - Fcc) + (0.04f * ab[0] + ab[1]);
  EXPECT_NEAR(img.rgb[0], col, 1e-4 * col);
}

// The sheen albedo Ê(N.V) likewise, at N.V = 1e-6 (Ê moves by 2.7e-4 between 1e-6 and 1e-4 at
// sheen roughness 0.5); a black base leaves the dielectric specular under the sheen.
TEST(ProfileThreejsIbl, GrazingViewSheenIsClampedNotFloored) {
  const float nv = 1e-6f;
  const Image img = shadeUniform({{{1.0f, 0.0f, nv}, 0.0f, 0.0f, 1.0f, 1.0f, 0.5f, 0, 0}});
  const auto [ss, ms] = multiscatter(0.04f, nv);
  const double E = ref::threejsSheenAlbedo(nv, 0.5);
  const double col = (ss + ms) * (1.0 - E) + E;
  EXPECT_NEAR(img.rgb[0], col, 2e-5 * col);
}
