// --profile khronos reads the glTF Sample Renderer's own lut_sheen_E.png (docs/profiles.md
// "Tables"): the carried-over texels are its 8-bit values, sampled as a GPU samples the texture,
// and the direct and image-based sheen albedo scaling come from them, not from brdfcl's E table.
#include <gtest/gtest.h>

#include <cmath>

#include "brdfcl/io.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/scene.hpp"
#include "kernels/common/material_layout.h"
#include "model/engine_tables.hpp"
#include "reference/profiles.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

constexpr int kN = BRDFCL_KHRONOS_SHEEN_E_SIZE;

// Texel (i, j) of the PNG's red channel (high byte of its 16 bits), read off the file:
// row j = sheen roughness, column i = N.V, the PNG's first row first.
struct Texel {
  int i, j, value;
};
constexpr Texel kTexels[] = {{0, 0, 236}, {1023, 0, 2}, {0, 1023, 242}, {1023, 1023, 114},
                             {5, 30, 236}, {100, 300, 198}, {512, 700, 142}, {1000, 700, 85}};

double centre(int i) { return (i + 0.5) / kN; }

// The diffuse lobe of a white dielectric with and without sheen at L = V (N.L = N.V = mu): their
// ratio is the profile's albedo scaling 1 - max3(c) E(mu, r_s).
double diffuseScaling(double mu, float sheenRoughness) {
  MaterialParams m;
  m.baseColor = {1.0f, 1.0f, 1.0f};
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  MaterialParams sheen = m;
  sheen.sheenColor = {1.0f, 0.5f, 0.25f};
  sheen.sheenRoughness = sheenRoughness;
  Samples s;
  s.material = {0, 1};
  const float x = float(std::sqrt(1.0 - mu * mu)), z = float(mu);
  s.L = {x, 0.0f, z, x, 0.0f, z};
  s.V = s.L;
  EvalOptions o;
  o.profile = Profile::Khronos;
  o.lobe = Lobe::Diffuse;
  const auto got = Evaluator(runtime(), o).evaluate({m, sheen}, s);
  return double(got[3]) / double(got[0]);
}

}  // namespace

TEST(KhronosSheenLut, TableHoldsThePngsEightBitTexels) {
  const auto& t = khronosSheenETable();
  ASSERT_EQ(t.size(), std::size_t(kN) * kN);
  for (float v : t) {
    const float steps = v * 255.0f;
    ASSERT_EQ(steps, std::round(steps)) << "every texel is a unorm8 value";
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
  }
  for (const auto& k : kTexels)
    EXPECT_EQ(t[std::size_t(k.j) * kN + std::size_t(k.i)], float(k.value) / 255.0f) << k.i << "," << k.j;
}

TEST(KhronosSheenLut, ReferenceSamplesLikeAGpu) {
  // Texel centres give the texel; halfway between two centres, their mean; beyond the outer
  // centres, the edge texel (CLAMP_TO_EDGE).
  for (const auto& k : kTexels) EXPECT_DOUBLE_EQ(ref::khronosSheenE(centre(k.i), centre(k.j)), k.value / 255.0);
  const auto& t = khronosSheenETable();
  auto at = [&](int i, int j) { return double(t[std::size_t(j) * kN + std::size_t(i)]); };
  EXPECT_NEAR(ref::khronosSheenE((100.0 + 1.0) / kN, centre(300)), 0.5 * (at(100, 300) + at(101, 300)), 1e-7);
  EXPECT_NEAR(ref::khronosSheenE(centre(512), (700.0 + 1.0) / kN), 0.5 * (at(512, 700) + at(512, 701)), 1e-7);
  EXPECT_NEAR(ref::khronosSheenE(0.0, 0.0), 236 / 255.0, 1e-12);
  EXPECT_NEAR(ref::khronosSheenE(1.0, 1.0), 114 / 255.0, 1e-12);
}

// At N.V = 0.0054, r_s = 0.03 brdfcl's own E exceeds 1 (an 8-bit texture holds at most 1), so its
// scaling would be negative; the renderer's texel there is 236/255 and the scaling 1 - 236/255.
TEST(KhronosSheenLut, DirectSheenScalingIsTheRenderersTexel) {
  for (const auto& k : {kTexels[4], kTexels[5], kTexels[6]}) {
    const double want = 1.0 - k.value / 255.0;
    EXPECT_NEAR(diffuseScaling(centre(k.i), float(centre(k.j))), want, 2e-5) << k.i << "," << k.j;
  }
}

// Halfway between texel centres in N.V the GPU's bilinear weight is 1/2 (no texel snapping).
TEST(KhronosSheenLut, DirectSheenScalingIsBilinearBetweenTexels) {
  const auto& t = khronosSheenETable();
  const double e = 0.5 * (double(t[300u * kN + 100u]) + double(t[300u * kN + 101u]));
  EXPECT_NEAR(diffuseScaling(101.0 / kN, float(centre(300))), 1.0 - e, 2e-5);
}

// Image-based light: the renderer scales the base by 1 - max3(c) E(N.V, r_s) from the same
// texture (pbr.frag's albedoSheenScaling) and adds the Charlie radiance times c. With
// c = (1, 0, 0) the green channel carries the scaling alone: green(sheen) / green(no sheen) is
// 1 - E at N.V = 0.098, r_s = 0.293 (texel (100, 300) = 198/255), under a uniform sky and no lights.
TEST(KhronosSheenLut, ImageBasedSheenScalingIsTheRenderersTexel) {
  const double mu = centre(100);
  GBuffer g;
  g.width = 2;
  g.height = 1;
  g.P = std::vector<float>(6, 0.0f);
  g.N = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f};
  const float vx = float(std::sqrt(1.0 - mu * mu)), vz = float(mu);
  g.V = {vx, 0.0f, vz, vx, 0.0f, vz};
  g.baseColor = std::vector<float>(6, 1.0f);
  g.metallic = {0.0f, 0.0f};
  g.roughness = {0.5f, 0.5f};
  g.mask = {1.0f, 1.0f};
  g.sheenColor = {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f};
  g.sheenRoughness = {0.0f, float(centre(300))};
  Scene scene;
  scene.environment.builtinKind = "uniform";
  EvalOptions o;
  o.profile = Profile::Khronos;
  const Image img = Shader(runtime(), scene, o).shade(g);
  const double plain = img.rgb[1], sheen = img.rgb[4];
  ASSERT_GT(plain, 1e-3) << "the uniform sky lights the base";
  EXPECT_NEAR(sheen / plain, 1.0 - 198 / 255.0, 1e-4);
}
