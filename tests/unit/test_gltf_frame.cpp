// glTF frames: which lights a render uses (the file's, none, a scene file's, or the default key
// light), the stratified sub-pixel offsets, and the box filter over the samples.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>

#include "host/src/render/gltf_frame.hpp"
#include "process.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

gltf::View tiltedView() {
  gltf::View v;
  const double s = std::sqrt(0.5);
  v.right = {s, 0, -s};
  v.up = {0, 1, 0};
  v.forward = {-s, 0, -s};
  return v;
}

TEST(GltfFrame, DefaultKeyLightFollowsTheView) {
  const gltf::View v = tiltedView();
  const Light key = gltf::defaultKeyLight(v);
  EXPECT_EQ(key.type, Light::Type::Directional);
  EXPECT_FLOAT_EQ(key.intensity, 3.0f);
  // normalize(0.5 right - up + 0.6 forward), written out for this view.
  const double s = std::sqrt(0.5), x = 0.5 * s - 0.6 * s, y = -1.0, z = -0.5 * s - 0.6 * s;
  const double n = std::sqrt(x * x + y * y + z * z);
  EXPECT_NEAR(key.direction[0], x / n, 1e-6);
  EXPECT_NEAR(key.direction[1], y / n, 1e-6);
  EXPECT_NEAR(key.direction[2], z / n, 1e-6);
}

TEST(GltfFrame, LightsComeFromTheFileNoneOrASceneFile) {
  gltf::Asset asset;
  Environment studio;
  studio.builtinKind = "studio";
  // No lights in the file: the default key light.
  Scene s = gltf::frameLighting(asset, tiltedView(), "gltf", studio, false);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.environment.builtinKind, "studio");
  // The file's lights, as they are.
  Light spot;
  spot.type = Light::Type::Spot;
  spot.intensity = 7.0f;
  asset.lights = {spot, Light{}};
  s = gltf::frameLighting(asset, tiltedView(), "gltf", studio, false);
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Spot);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 7.0f);
  EXPECT_TRUE(gltf::frameLighting(asset, tiltedView(), "none", studio, false).lights.empty());

  // A scene file: its lights, and its environment unless --environment was given.
  ScratchDir dir("gltf-frame");
  std::ofstream(dir.path("s.json")) << R"({"lights": [{"type": "point", "intensity": 5, "position": [1, 2, 3]}],
                                           "environment": {"builtin": "uniform", "intensity": 0.5}})";
  s = gltf::frameLighting(asset, tiltedView(), dir.path("s.json"), studio, false);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Point);
  EXPECT_FLOAT_EQ(s.lights[0].position[2], 3.0f);
  EXPECT_EQ(s.environment.builtinKind, "uniform");
  EXPECT_FLOAT_EQ(s.environment.intensity, 0.5f);
  EXPECT_EQ(gltf::frameLighting(asset, tiltedView(), dir.path("s.json"), studio, true).environment.builtinKind, "studio");
}

TEST(GltfFrame, SubpixelOffsetsAreStratified) {
  const auto one = gltf::subpixelOffsets(1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0][0], 0.5f);
  EXPECT_EQ(one[0][1], 0.5f);
  for (int spp : {2, 3, 4, 5, 9, 16, 17}) {
    const auto offsets = gltf::subpixelOffsets(spp);
    ASSERT_EQ(int(offsets.size()), spp);
    const int columns = int(std::ceil(std::sqrt(double(spp)))), rows = (spp + columns - 1) / columns;
    std::set<std::pair<int, int>> cells;
    for (int i = 0; i < spp; ++i) {
      const auto& o = offsets[i];
      ASSERT_GE(o[0], 0.0f);
      ASSERT_LT(o[0], 1.0f);
      ASSERT_GE(o[1], 0.0f);
      ASSERT_LT(o[1], 1.0f);
      const std::pair<int, int> cell{int(o[0] * columns), int(o[1] * rows)};
      EXPECT_EQ(cell, std::make_pair(i % columns, i / columns)) << "spp " << spp << " sample " << i;
      cells.insert(cell);
    }
    EXPECT_EQ(int(cells.size()), spp) << "one sample per cell";
  }
  EXPECT_CONTAINS(errorOf([] { gltf::subpixelOffsets(0); }), "--spp 0 must be at least 1");
}

// A quad that half covers the frame along a diagonal edge: the 4-sample frame is exactly the mean
// of the four one-sample frames shaded at the same offsets.
TEST(GltfFrame, SamplesAreAveraged) {
  gltf::Asset asset;
  gltf::Primitive p;
  p.positions = {-1, -1, 0, 1, -1, 0, -1, 1, 0};
  p.indices = {0, 1, 2};
  asset.primitives.push_back(p);
  asset.materials.emplace_back();
  asset.materials[0].baseColorFactor = {0.8f, 0.4f, 0.2f, 1.0f};
  asset.materials[0].metallicFactor = 0.0f;
  asset.boundsMin = {-1, -1, 0};
  asset.boundsMax = {1, 1, 0};
  const gltf::Raycaster raycaster(asset);
  gltf::View view;
  view.orthographic = true;
  view.position = {0, 0, 5};
  view.halfHeight = 1.0;
  view.aspect = 1.0;
  const int w = 12, h = 12;
  Environment uniform;
  uniform.builtinKind = "uniform";
  Shader shader(runtime(), gltf::frameLighting(asset, view, "gltf", uniform, true));
  const Image four = gltf::renderFrame(shader, raycaster, view, w, h, 4);
  std::vector<double> mean(four.rgb.size(), 0.0);
  for (const auto& o : gltf::subpixelOffsets(4)) {
    const Image one = shader.shade(raycaster.trace(view, w, h, o[0], o[1]));
    for (std::size_t i = 0; i < mean.size(); ++i) mean[i] += one.rgb[i] / 4.0;
  }
  double worst = 0, spread = 0;
  for (std::size_t i = 0; i < mean.size(); ++i) {
    worst = std::max(worst, std::fabs(four.rgb[i] - mean[i]));
    spread = std::max(spread, double(std::fabs(four.rgb[i] - four.rgb[0])));
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(spread, 0.05) << "the frame should hold both the lit quad and the environment";
}

}  // namespace
}  // namespace brdfcl::test
