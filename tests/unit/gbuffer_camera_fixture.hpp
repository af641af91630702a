// What the G-buffer camera and value-check tests share (test_gbuffer_camera, test_gbuffer_check):
// a synthetic G-buffer with every channel, relative differences, the sample assets' folder, and the
// lights and small environment of the scene files that `shade` runs with.
#pragma once

#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfVecAttribute.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "host/src/gltf/demo_asset.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/gltf_render.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/scene.hpp"
#include "gltf_support.hpp"
#include "tests/assets_dir.hpp"
#include "process.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

inline RunResult cli(const std::vector<std::string>& args, const ScratchDir& dir) {
  std::vector<std::string> argv{BRDFCL_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  return runProcess(argv, dir.dir());
}

// A w x h G-buffer: a unit-sphere-ish surface on every pixel, every optional channel present and
// in range, V absent (so the camera matters).
inline GBuffer validGBuffer(int w, int h) {
  GBuffer g;
  g.width = w;
  g.height = h;
  const std::size_t n = g.pixelCount();
  for (std::size_t i = 0; i < n; ++i) {
    const float x = float(i % w) / w - 0.5f, y = float(i / w) / h - 0.5f, z = std::sqrt(1.0f - x * x - y * y);
    for (float v : {x, y, z}) g.P.push_back(v), g.N.push_back(v), g.clearcoatN.push_back(v);
    const float tl = std::sqrt(z * z + x * x);
    for (float v : {z / tl, 0.0f, -x / tl}) g.T.push_back(v);
    for (float v : {0.8f, 0.5f, 0.2f}) g.baseColor.push_back(v), g.sheenColor.push_back(v * 0.5f);
    for (float v : {0.0f, 2.5f, 0.1f}) g.emissive.push_back(v);
    g.metallic.push_back(0.3f);
    g.roughness.push_back(0.6f);
    g.mask.push_back(1.0f);
    g.sheenRoughness.push_back(0.4f);
    g.clearcoat.push_back(1.0f);
    g.clearcoatRoughness.push_back(0.0f);
    g.anisotropyStrength.push_back(0.5f);
    g.anisotropyRotation.push_back(-4.0f);  // radians: any value
    g.occlusion.push_back(0.9f);
  }
  return g;
}

inline GBufferCamera perspectiveCamera() {
  GBufferCamera c;
  c.position = {1.5f, -2.25f, 7.0f};
  // A rolled, tilted frame: right x up = -forward.
  const float s = std::sqrt(0.5f);
  c.right = {s, s, 0.0f};
  c.up = {-s, s, 0.0f};
  c.forward = {0.0f, 0.0f, -1.0f};
  c.fovDegrees = 37.5f;
  c.znear = 0.125f;
  c.zfar = 250.0f;
  return c;
}

inline GBufferCamera orthographicCamera() {
  GBufferCamera c;
  c.orthographic = true;
  c.position = {0.0f, 3.0f, 0.0f};
  c.right = {1.0f, 0.0f, 0.0f};
  c.up = {0.0f, 0.0f, -1.0f};
  c.forward = {0.0f, -1.0f, 0.0f};
  c.xmag = 2.5f;
  c.ymag = 1.25f;
  c.znear = 0.0f;
  c.zfar = 0.0f;
  return c;
}

inline void expectSameCamera(const GBufferCamera& a, const GBufferCamera& b) {
  EXPECT_EQ(a.orthographic, b.orthographic);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.right, b.right);
  EXPECT_EQ(a.up, b.up);
  EXPECT_EQ(a.forward, b.forward);
  if (a.orthographic) {
    EXPECT_EQ(a.xmag, b.xmag);
    EXPECT_EQ(a.ymag, b.ymag);
  } else {
    EXPECT_EQ(a.fovDegrees, b.fovDegrees);
  }
  EXPECT_EQ(a.znear, b.znear);
  EXPECT_EQ(a.zfar, b.zfar);
}

// Largest difference relative to the value (absolute below 1).
inline double maxDifference(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) return INFINITY;
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    m = std::max(m, std::fabs(double(a[i]) - b[i]) / std::max(1.0, std::fabs(double(b[i]))));
  return m;
}

inline std::vector<float> readRgb(const std::string& path) {
  int w = 0, h = 0;
  return readExrRgb(path, w, h);
}

constexpr const char* kLights = R"("lights": [{"type": "directional", "direction": [0.3, -0.6, -0.7], "intensity": 2}])";

// A 16 x 8 environment that varies with direction: prepared in milliseconds, where a built-in
// one takes seconds in every child process. Returns the scene file's "environment" member.
inline std::string tinyEnvironment(const ScratchDir& dir) {
  std::vector<float> rgb;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      for (float v : {0.1f + 0.1f * x, 0.2f + 0.3f * y, 1.0f}) rgb.push_back(v);
  writeExrRgb(dir.path("env.exr"), 16, 8, rgb);
  return R"("environment": {"path": "env.exr"})";  // beside the scene files, which are in `dir` too
}

}  // namespace
}  // namespace brdfcl::test
