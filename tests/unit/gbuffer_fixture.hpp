// What the G-buffer, scene and image I/O tests share (test_gbuffer, test_scene_image): a temporary
// directory per test, G-buffers of random or counting values, and EXR files with any channel names.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support.hpp"
#include "tempdir_fixture.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/scene.hpp"

namespace fs = std::filesystem;
using brdfcl::Error;
using brdfcl::test::errorOf;
using brdfcl::GBuffer;

// A named namespace, not an anonymous one: the fixtures must be one class in every test file
// (GoogleTest refuses a suite whose fixture differs between translation units).
namespace gbuffer_test {

using brdfcl::test::readFile;

class TempDir : public brdfcl::test::TempDirTest {
 protected:
  TempDir() : TempDirTest("gb") {}
};

class Gbuffer : public TempDir {};
class Scene : public TempDir {};
class Image : public TempDir {};


// The round-trip and naming tests below hold random or counting values, not a G-buffer's (normals
// of any length, factors beyond 1): they read without the value check, which
// test_gbuffer_camera.cpp tests.
inline GBuffer readUnchecked(const std::string& p) {
  brdfcl::GBufferReadOptions o;
  o.check = false;
  return brdfcl::readGBuffer(p, o);
}

inline std::vector<float> randomVec(std::mt19937& rng, std::size_t n, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = u(rng);
  return v;
}

inline GBuffer makeGBuffer(int w, int h, bool optional, std::uint32_t seed = 7) {
  std::mt19937 rng(seed);
  const std::size_t n = static_cast<std::size_t>(w) * h;
  GBuffer g;
  g.width = w;
  g.height = h;
  g.P = randomVec(rng, 3 * n, -10, 10);
  g.N = randomVec(rng, 3 * n, -1, 1);
  g.baseColor = randomVec(rng, 3 * n, 0, 1);
  g.metallic = randomVec(rng, n, 0, 1);
  g.roughness = randomVec(rng, n, 0, 1);
  g.mask = randomVec(rng, n, 0, 1);
  if (optional) {
    g.T = randomVec(rng, 3 * n, -1, 1);
    g.emissive = randomVec(rng, 3 * n, 0, 5);
    g.sheenColor = randomVec(rng, 3 * n, 0, 1);
    g.sheenRoughness = randomVec(rng, n, 0, 1);
    g.clearcoat = randomVec(rng, n, 0, 1);
    g.clearcoatRoughness = randomVec(rng, n, 0, 1);
    g.clearcoatN = randomVec(rng, 3 * n, -1, 1);
    g.anisotropyStrength = randomVec(rng, n, 0, 1);
    g.anisotropyRotation = randomVec(rng, n, -3, 3);
  }
  return g;
}

// A channel value that identifies channel index c and pixel i, exact in half precision.
inline float rawValue(std::size_t c, std::size_t i) { return static_cast<float>(c) + static_cast<float>(i % 64) / 64.0f; }

struct RawChannel {
  std::string name;
  int ySampling = 1;
  bool uint = false;
};

// Writes an EXR with arbitrary channel names (FLOAT), the value rawValue(channel index, pixel).
inline void writeRawExr(const std::string& path, int w, int h, const std::vector<RawChannel>& channels,
                 const Imath::Box2i* dataWindow = nullptr) {
  Imf::Header header(w, h);
  if (dataWindow) header.dataWindow() = *dataWindow;
  const Imath::Box2i dw = header.dataWindow();
  const int dwW = dw.max.x - dw.min.x + 1, dwH = dw.max.y - dw.min.y + 1;
  std::vector<std::vector<float>> planes(channels.size(), std::vector<float>(static_cast<std::size_t>(dwW) * dwH));
  Imf::FrameBuffer fb;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    for (std::size_t i = 0; i < planes[c].size(); ++i) planes[c][i] = rawValue(c, i);
    // UINT channels get the same bits reinterpreted: only the type matters to these tests.
    const Imf::PixelType type = channels[c].uint ? Imf::UINT : Imf::FLOAT;
    header.channels().insert(channels[c].name, Imf::Channel(type, 1, channels[c].ySampling));
    const std::size_t xs = sizeof(float), ys = sizeof(float) * dwW;
    char* base = reinterpret_cast<char*>(planes[c].data()) - dw.min.x * static_cast<std::ptrdiff_t>(xs) -
                 (dw.min.y / channels[c].ySampling) * static_cast<std::ptrdiff_t>(ys);
    fb.insert(channels[c].name, Imf::Slice(type, base, xs, ys, 1, channels[c].ySampling));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(fb);
  out.writePixels(dwH);
}

inline std::vector<RawChannel> requiredChannels(const std::string& normalPrefix = "N", const std::string& posPrefix = "P") {
  return {{posPrefix + ".X"}, {posPrefix + ".Y"}, {posPrefix + ".Z"}, {normalPrefix + ".X"}, {normalPrefix + ".Y"},
          {normalPrefix + ".Z"}, {"baseColor.R"}, {"baseColor.G"}, {"baseColor.B"}, {"metallic"}, {"roughness"},
          {"mask"}};
}

inline void expectSameGBuffer(const GBuffer& a, const GBuffer& b, float relTol) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  const std::vector<float> GBuffer::*members[] = {
      &GBuffer::P, &GBuffer::N, &GBuffer::baseColor, &GBuffer::metallic, &GBuffer::roughness, &GBuffer::mask,
      &GBuffer::T, &GBuffer::emissive, &GBuffer::sheenColor, &GBuffer::sheenRoughness, &GBuffer::clearcoat,
      &GBuffer::clearcoatRoughness, &GBuffer::clearcoatN, &GBuffer::anisotropyStrength, &GBuffer::anisotropyRotation};
  for (std::size_t m = 0; m < std::size(members); ++m) {
    const auto& va = a.*members[m];
    const auto& vb = b.*members[m];
    ASSERT_EQ(va.size(), vb.size()) << "member " << m;
    for (std::size_t i = 0; i < va.size(); ++i)
      ASSERT_NEAR(va[i], vb[i], relTol * std::fabs(va[i]) + 1e-7f) << "member " << m << " index " << i;
  }
}

}  // namespace gbuffer_test

using namespace gbuffer_test;
