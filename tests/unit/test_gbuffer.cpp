// Tests of the G-buffer EXR reader/writer, the scene JSON reader and the image helpers (EXR RGB,
// PBR Neutral, sRGB, PNG): round trips, every accepted naming, and every error path with the
// file (and JSON key path) in its one-line message. Each test works in its own temporary directory.
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
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/scene.hpp"

namespace fs = std::filesystem;
using brdfcl::Error;
using brdfcl::test::errorOf;
using brdfcl::GBuffer;

namespace {

std::atomic<int> dirCounter{0};

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("brdfcl-gb-" + std::to_string(::getpid()) + "-" + info->name() + "-" +
                                        std::to_string(dirCounter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(path(name), std::ios::binary) << content;
    return path(name);
  }
  std::vector<std::string> listDir() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }
  fs::path dir_;
};

class Gbuffer : public TempDir {};
class Scene : public TempDir {};
class Image : public TempDir {};


// The round-trip and naming tests below hold random or counting values, not a G-buffer's (normals
// of any length, factors beyond 1): they read without the value check, which
// test_gbuffer_camera.cpp tests.
GBuffer readUnchecked(const std::string& p) {
  brdfcl::GBufferReadOptions o;
  o.check = false;
  return brdfcl::readGBuffer(p, o);
}

std::vector<float> randomVec(std::mt19937& rng, std::size_t n, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = u(rng);
  return v;
}

GBuffer makeGBuffer(int w, int h, bool optional, std::uint32_t seed = 7) {
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
float rawValue(std::size_t c, std::size_t i) { return static_cast<float>(c) + static_cast<float>(i % 64) / 64.0f; }

struct RawChannel {
  std::string name;
  int ySampling = 1;
  bool uint = false;
};

// Writes an EXR with arbitrary channel names (FLOAT), the value rawValue(channel index, pixel).
void writeRawExr(const std::string& path, int w, int h, const std::vector<RawChannel>& channels,
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

std::vector<RawChannel> requiredChannels(const std::string& normalPrefix = "N", const std::string& posPrefix = "P") {
  return {{posPrefix + ".X"}, {posPrefix + ".Y"}, {posPrefix + ".Z"}, {normalPrefix + ".X"}, {normalPrefix + ".Y"},
          {normalPrefix + ".Z"}, {"baseColor.R"}, {"baseColor.G"}, {"baseColor.B"}, {"metallic"}, {"roughness"},
          {"mask"}};
}

void expectSameGBuffer(const GBuffer& a, const GBuffer& b, float relTol) {
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

std::string readBytes(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}

// ---------------------------------------------------------------- G-buffer

TEST_F(Gbuffer, RoundTripFloatEveryChannel) {
  const GBuffer g = makeGBuffer(7, 5, true);
  brdfcl::writeGBuffer(path("g.exr"), g);
  const GBuffer r = readUnchecked(path("g.exr"));
  expectSameGBuffer(g, r, 0.0f);
  EXPECT_TRUE(r.hasTangent());
  EXPECT_TRUE(r.hasEmissive());
  EXPECT_TRUE(r.hasSheen());
  EXPECT_TRUE(r.hasClearcoat());
  EXPECT_TRUE(r.hasAnisotropy());
  EXPECT_EQ(listDir(), std::vector<std::string>{"g.exr"});
}

TEST_F(Gbuffer, RoundTripHalfEveryChannel) {
  const GBuffer g = makeGBuffer(6, 9, true);
  brdfcl::writeGBuffer(path("g.exr"), g, true);
  const GBuffer r = readUnchecked(path("g.exr"));
  expectSameGBuffer(g, r, 1.0f / 1024);  // half has a 10-bit mantissa
  // The file really holds half channels: about half the size of the float file.
  brdfcl::writeGBuffer(path("f.exr"), g, false);
  EXPECT_LT(fs::file_size(path("g.exr")), fs::file_size(path("f.exr")));
}

TEST_F(Gbuffer, RequiredOnlyLeavesOptionalEmpty) {
  const GBuffer g = makeGBuffer(3, 4, false);
  brdfcl::writeGBuffer(path("g.exr"), g);
  const GBuffer r = readUnchecked(path("g.exr"));
  expectSameGBuffer(g, r, 0.0f);
  EXPECT_FALSE(r.hasTangent());
  EXPECT_FALSE(r.hasEmissive());
  EXPECT_FALSE(r.hasSheen());
  EXPECT_FALSE(r.hasClearcoat());
  EXPECT_FALSE(r.hasAnisotropy());
}

TEST_F(Gbuffer, RowMajorFromTopLeftInterleaved) {
  writeRawExr(path("g.exr"), 4, 3, requiredChannels());
  const GBuffer r = readUnchecked(path("g.exr"));
  ASSERT_EQ(r.width, 4);
  ASSERT_EQ(r.height, 3);
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(r.P[3 * i + 0], rawValue(0, i));
    EXPECT_EQ(r.P[3 * i + 2], rawValue(2, i));
    EXPECT_EQ(r.N[3 * i + 1], rawValue(4, i));
    EXPECT_EQ(r.mask[i], rawValue(11, i));
  }
}

TEST_F(Gbuffer, BlenderPassNamesAccepted) {
  auto channels = requiredChannels("ViewLayer.Normal", "ViewLayer.Position");
  channels.push_back({"ViewLayer.Combined.R"});  // other Blender passes are ignored
  writeRawExr(path("b.exr"), 5, 2, channels);
  const GBuffer r = readUnchecked(path("b.exr"));
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_EQ(r.P[3 * i + 1], rawValue(1, i));
    EXPECT_EQ(r.N[3 * i + 2], rawValue(5, i));
  }
  // Any single layer name works.
  writeRawExr(path("c.exr"), 2, 2, requiredChannels("My Layer.Normal", "My Layer.Position"));
  EXPECT_EQ(readUnchecked(path("c.exr")).N.size(), 12u);
}

TEST_F(Gbuffer, CanonicalNamesWinOverBlender) {
  auto channels = requiredChannels();
  channels.push_back({"ViewLayer.Normal.X"});
  channels.push_back({"ViewLayer.Normal.Y"});
  channels.push_back({"ViewLayer.Normal.Z"});
  writeRawExr(path("g.exr"), 2, 2, channels);
  const GBuffer r = readUnchecked(path("g.exr"));
  EXPECT_EQ(r.N[0], rawValue(3, 0));
}

TEST_F(Gbuffer, TwoBlenderLayersAreAmbiguous) {
  auto channels = requiredChannels("A.Normal");
  channels.push_back({"B.Normal.X"});
  channels.push_back({"B.Normal.Y"});
  channels.push_back({"B.Normal.Z"});
  writeRawExr(path("g.exr"), 2, 2, channels);
  const std::string m = errorOf([&] { brdfcl::readGBuffer(path("g.exr")); });
  EXPECT_CONTAINS(m, path("g.exr") + ": several layers have a Normal pass (A B)");
}

TEST_F(Gbuffer, MissingRequiredChannel) {
  auto channels = requiredChannels();
  channels.pop_back();  // mask
  writeRawExr(path("g.exr"), 2, 2, channels);
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(path("g.exr")); }),
            path("g.exr") + ": missing required channel mask; see docs/gbuffer.md for the channel names");

  auto noNormal = requiredChannels();
  noNormal.erase(noNormal.begin() + 3, noNormal.begin() + 6);
  writeRawExr(path("n.exr"), 2, 2, noNormal);
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(path("n.exr")); }),
            path("n.exr") +
                ": missing required channels N.X N.Y N.Z (or Blender's <layer>.Normal.X/Y/Z); see docs/gbuffer.md "
                "for the channel names");
}

TEST_F(Gbuffer, IncompleteVector) {
  auto channels = requiredChannels();
  channels.push_back({"T.X"});
  channels.push_back({"T.Y"});
  writeRawExr(path("g.exr"), 2, 2, channels);
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(path("g.exr")); }),
            path("g.exr") + ": incomplete T vector: missing T.Z; write all of T.X T.Y T.Z");
}

TEST_F(Gbuffer, SubsampledChannelRejected) {
  auto channels = requiredChannels();
  channels[4].ySampling = 2;  // N.Y
  writeRawExr(path("g.exr"), 4, 4, channels);
  const std::string m = errorOf([&] { brdfcl::readGBuffer(path("g.exr")); });
  EXPECT_CONTAINS(m, path("g.exr") + ": channel 'N.Y' has x/y sampling 1/2");
}

TEST_F(Gbuffer, UintChannelRejected) {
  auto channels = requiredChannels();
  channels.back().uint = true;  // mask
  writeRawExr(path("g.exr"), 2, 2, channels);
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(path("g.exr")); }),
            path("g.exr") + ": channel 'mask' is UINT; expected HALF or FLOAT");
}

TEST_F(Gbuffer, DataWindowMustEqualDisplayWindow) {
  const Imath::Box2i dw(Imath::V2i(1, 1), Imath::V2i(3, 2));
  writeRawExr(path("g.exr"), 5, 4, requiredChannels(), &dw);
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(path("g.exr")); }),
            path("g.exr") +
                ": the data window (1,1)-(3,2) differs from the display window (0,0)-(4,3); write the full, "
                "uncropped image");
}

TEST_F(Gbuffer, TruncatedFile) {
  brdfcl::writeGBuffer(path("g.exr"), makeGBuffer(64, 64, true));
  const std::string bytes = readBytes(path("g.exr"));
  for (const std::size_t keep : {bytes.size() * 3 / 4, bytes.size() / 2, std::size_t{300}, std::size_t{40},
                                 std::size_t{6}}) {
    const std::string p = write("t" + std::to_string(keep) + ".exr", bytes.substr(0, keep));
    const std::string m = errorOf([&] { brdfcl::readGBuffer(p); });
    EXPECT_EQ(m.rfind(p + ": ", 0), 0u) << m;
    EXPECT_CONTAINS(m, "truncated");
  }
}

TEST_F(Gbuffer, NotAnExrFile) {
  const std::string p = write("text.exr", "P.X,P.Y,P.Z\n1,2,3\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(p); }),
            p + ": not an OpenEXR file (no EXR magic number); save the image as OpenEXR (.exr)");
  const std::string e = write("empty.exr", "");
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(e); }),
            e + ": not an OpenEXR file (the file is empty); save the image as OpenEXR (.exr)");
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(path("absent.exr")); }),
            "cannot read '" + path("absent.exr") + "': No such file or directory");
}

TEST_F(Gbuffer, MultiPartRejected) {
  std::vector<Imf::Header> headers(2, Imf::Header(2, 2));
  std::vector<float> data(4, 0.5f);
  for (int i = 0; i < 2; ++i) {
    headers[i].setName("part" + std::to_string(i));
    headers[i].setType(Imf::SCANLINEIMAGE);
    headers[i].channels().insert("mask", Imf::Channel(Imf::FLOAT));
  }
  {
    Imf::MultiPartOutputFile out(path("m.exr").c_str(), headers.data(), 2);
    for (int i = 0; i < 2; ++i) {
      Imf::OutputPart part(out, i);
      Imf::FrameBuffer fb;
      fb.insert("mask", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.data()), sizeof(float), 2 * sizeof(float)));
      part.setFrameBuffer(fb);
      part.writePixels(2);
    }
  }
  EXPECT_EQ(errorOf([&] { brdfcl::readGBuffer(path("m.exr")); }),
            path("m.exr") + ": multi-part OpenEXR file; brdfcl reads single-part files only: save all channels in one part");
}

TEST_F(Gbuffer, WriteFailureLeavesNoFile) {
  GBuffer g = makeGBuffer(2, 2, false);
  EXPECT_CONTAINS(errorOf([&] { brdfcl::writeGBuffer(path("missing/g.exr"), g); }), "cannot write");
  g.mask.pop_back();
  EXPECT_THROW(brdfcl::writeGBuffer(path("g.exr"), g), std::invalid_argument);
  g.mask.clear();
  EXPECT_THROW(brdfcl::writeGBuffer(path("g.exr"), g), std::invalid_argument);
  EXPECT_TRUE(listDir().empty());
}

// ---------------------------------------------------------------- Image

TEST_F(Image, ExrRgbRoundTripAndLuminance) {
  std::mt19937 rng(3);
  const std::vector<float> rgb = randomVec(rng, 3 * 5 * 4, 0, 100);
  brdfcl::writeExrRgb(path("e.exr"), 5, 4, rgb);
  int w = 0, h = 0;
  EXPECT_EQ(brdfcl::readExrRgb(path("e.exr"), w, h), rgb);
  EXPECT_EQ(w, 5);
  EXPECT_EQ(h, 4);

  writeRawExr(path("y.exr"), 3, 2, {{"Y"}});
  const std::vector<float> grey = brdfcl::readExrRgb(path("y.exr"), w, h);
  ASSERT_EQ(grey.size(), 18u);
  for (std::size_t i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(grey[3 * i + c], rawValue(0, i));

  writeRawExr(path("rg.exr"), 1, 1, {{"R"}, {"G"}});
  EXPECT_EQ(errorOf([&] { brdfcl::readExrRgb(path("rg.exr"), w, h); }),
            path("rg.exr") + ": expected channels R, G, B (or Y alone), found: G R");
  const std::string t = write("t.exr", "hello");
  EXPECT_CONTAINS(errorOf([&] { brdfcl::readExrRgb(t, w, h); }), t + ": not an OpenEXR file");
}

TEST_F(Image, PbrNeutralProperties) {
  EXPECT_EQ(brdfcl::toneMapPbrNeutral(0.0f), 0.0f);
  // Below the compression start only the Fresnel offset applies: a quadratic toe up to 0.08,
  // then a constant 0.04 (peak - 0.04 < 0.76).
  for (float x = 0.0f; x < 0.8f; x += 0.001f) {
    const float expected = x < 0.08f ? 6.25f * x * x : x - 0.04f;
    EXPECT_NEAR(brdfcl::toneMapPbrNeutral(x), expected, 1e-6f) << x;
  }
  float previous = -1.0f;
  for (float x = 0.0f; x < 1e4f; x = x * 1.01f + 1e-4f) {
    const float y = brdfcl::toneMapPbrNeutral(x);
    EXPECT_GE(y, previous) << x;
    EXPECT_LT(y, 1.0f) << x;
    previous = y;
  }
  // Continuous where compression begins.
  EXPECT_NEAR(brdfcl::toneMapPbrNeutral(0.8f - 1e-5f), brdfcl::toneMapPbrNeutral(0.8f + 1e-5f), 1e-4f);
  // Colours: every channel stays in [0, 1), order is kept, highlights desaturate towards white.
  const brdfcl::Rgb hot = brdfcl::toneMapPbrNeutral(brdfcl::Rgb{50.0f, 5.0f, 0.5f});
  EXPECT_LT(hot[0], 1.0f);
  EXPECT_GT(hot[0], hot[1]);
  EXPECT_GT(hot[1], hot[2]);
  EXPECT_GT(hot[2] / hot[0], 0.5f / 50.0f);
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  // Negative and NaN components count as 0; +inf saturates to white.
  const brdfcl::Rgb odd = brdfcl::toneMapPbrNeutral(brdfcl::Rgb{-1.0f, nan, 0.5f});
  EXPECT_EQ(odd, brdfcl::toneMapPbrNeutral(brdfcl::Rgb{0.0f, 0.0f, 0.5f}));
  for (float c : brdfcl::toneMapPbrNeutral(brdfcl::Rgb{0.0f, 1.0f, inf})) EXPECT_TRUE(c >= 0.99f && c <= 1.0f) << c;
  std::vector<float> v{0.5f, 0.5f, 0.5f, 2.0f, 2.0f, 2.0f};
  brdfcl::toneMapPbrNeutral(v);
  EXPECT_FLOAT_EQ(v[0], 0.46f);
  EXPECT_FLOAT_EQ(v[3], brdfcl::toneMapPbrNeutral(2.0f));
}

TEST_F(Image, KnownValues) {
  EXPECT_EQ(brdfcl::encodeSrgb8(0.0f), 0);
  EXPECT_EQ(brdfcl::encodeSrgb8(1.0f), 255);
  EXPECT_EQ(brdfcl::encodeSrgb8(0.0031308f), 10);  // 12.92 * 0.0031308 * 255 = 10.31, rounded to nearest
  EXPECT_EQ(brdfcl::encodeSrgb8(0.5f), 188);       // 0.73536 * 255 = 187.52
  EXPECT_EQ(brdfcl::encodeSrgb8(0.18f), 118);      // middle grey
  EXPECT_EQ(brdfcl::encodeSrgb8(-1.0f), 0);
  EXPECT_EQ(brdfcl::encodeSrgb8(7.0f), 255);
  EXPECT_EQ(brdfcl::encodeSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  for (int i = 1; i < 1000; ++i) EXPECT_GE(brdfcl::encodeSrgb8(i / 1000.0f), brdfcl::encodeSrgb8((i - 1) / 1000.0f));
}

std::uint32_t bigEndian32(const std::string& s, std::size_t at) {
  return (std::uint32_t(std::uint8_t(s[at])) << 24) | (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
}

TEST_F(Image, PngHasTheRightSize) {
  const int w = 13, h = 7;
  std::vector<float> rgb(3 * w * h, 0.25f);
  brdfcl::writePng(path("o.png"), w, h, rgb, 1.0f);
  const std::string bytes = readBytes(path("o.png"));
  ASSERT_GE(bytes.size(), 33u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(bytes.substr(12, 4), "IHDR");
  EXPECT_EQ(bigEndian32(bytes, 16), std::uint32_t(w));
  EXPECT_EQ(bigEndian32(bytes, 20), std::uint32_t(h));
  EXPECT_EQ(bytes[24], 8);  // bit depth
  EXPECT_EQ(bytes[25], 2);  // colour type RGB
  EXPECT_EQ(listDir(), std::vector<std::string>{"o.png"});
}

TEST_F(Image, PngFailureLeavesNoFile) {
  std::vector<float> rgb(3 * 4, 1.0f);
  EXPECT_EQ(errorOf([&] { brdfcl::writePng(path("no/dir/o.png"), 2, 2, rgb, 0.0f); }),
            "cannot write '" + path("no/dir/o.png") + "': No such file or directory");
  EXPECT_THROW(brdfcl::writePng(path("o.png"), 3, 2, rgb, 0.0f), std::invalid_argument);
  EXPECT_CONTAINS(errorOf([&] { brdfcl::writePng(path("o.png"), 2, 2, rgb, std::nanf("")); }), "exposure");
  // An existing file stays untouched when the new write fails.
  write("keep.png", "old");
  EXPECT_THROW(brdfcl::writePng(path("keep.png"), 1, 1, rgb, 0.0f), std::invalid_argument);
  EXPECT_EQ(readBytes(path("keep.png")), "old");
  EXPECT_EQ(listDir(), std::vector<std::string>{"keep.png"});
}

// ---------------------------------------------------------------- Scene

TEST_F(Scene, Defaults) {
  const brdfcl::Scene s = brdfcl::parseScene("{}", "s.json", "");
  EXPECT_EQ(s.cameraPosition, (std::array<float, 3>{0, 0, 5}));
  EXPECT_EQ(s.cameraTarget, (std::array<float, 3>{0, 0, 0}));
  EXPECT_EQ(s.fovDegrees, 40.0f);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_TRUE(s.environment.builtin);
  EXPECT_EQ(s.environment.builtinKind, "sky");
  EXPECT_EQ(s.environment.intensity, 1.0f);
  EXPECT_EQ(s.environment.rotation, 0.0f);

  const brdfcl::Scene t = brdfcl::parseScene(R"({
    "camera": {"position": [1, 2, 3]},
    "lights": [
      {"type": "point", "position": [0, 4, 0]},
      {"type": "spot", "position": [1, 1, 1], "direction": [0, -2, 0]},
      {"type": "directional", "direction": [3, 0, -4]}
    ],
    "environment": "builtin"})",
                                             "s.json", "");
  EXPECT_EQ(t.cameraPosition, (std::array<float, 3>{1, 2, 3}));
  EXPECT_EQ(t.cameraTarget, (std::array<float, 3>{0, 0, 0}));
  ASSERT_EQ(t.lights.size(), 3u);
  const brdfcl::Light& p = t.lights[0];
  EXPECT_EQ(p.type, brdfcl::Light::Type::Point);
  EXPECT_EQ(p.color, (std::array<float, 3>{1, 1, 1}));
  EXPECT_EQ(p.intensity, 1.0f);
  EXPECT_EQ(p.range, 0.0f);
  EXPECT_EQ(p.position, (std::array<float, 3>{0, 4, 0}));
  const brdfcl::Light& sp = t.lights[1];
  EXPECT_EQ(sp.type, brdfcl::Light::Type::Spot);
  EXPECT_EQ(sp.innerCone, 0.0f);
  EXPECT_FLOAT_EQ(sp.outerCone, 0.78539816f);  // pi/4
  EXPECT_EQ(sp.direction, (std::array<float, 3>{0, -1, 0}));
  const brdfcl::Light& d = t.lights[2];
  EXPECT_EQ(d.type, brdfcl::Light::Type::Directional);
  EXPECT_NEAR(d.direction[0], 0.6f, 1e-7f);
  EXPECT_NEAR(d.direction[2], -0.8f, 1e-7f);
  EXPECT_TRUE(t.environment.builtin);
}

TEST_F(Scene, EveryKey) {
  write("env.exr", "x");
  const std::string text = R"({
    "camera": {"position": [0, 1, 6], "target": [0, 1, 0], "fov": 55},
    "lights": [{"type": "spot", "name": "key", "color": [1, 0.5, 0.25], "intensity": 80, "range": 12,
                "position": [2, 3, 4], "direction": [0, 0, -1],
                "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}, "extras": {"x": 1}}],
    "environment": {"path": "env.exr", "intensity": 0.5, "rotation": 1.25}})";
  write("scene.json", text);
  const brdfcl::Scene s = brdfcl::readScene(path("scene.json"));
  EXPECT_EQ(s.cameraTarget, (std::array<float, 3>{0, 1, 0}));
  EXPECT_EQ(s.fovDegrees, 55.0f);
  const brdfcl::Light& l = s.lights.at(0);
  EXPECT_EQ(l.color, (std::array<float, 3>{1, 0.5f, 0.25f}));
  EXPECT_EQ(l.intensity, 80.0f);
  EXPECT_EQ(l.range, 12.0f);
  EXPECT_EQ(l.position, (std::array<float, 3>{2, 3, 4}));
  EXPECT_FLOAT_EQ(l.innerCone, 0.2f);
  EXPECT_FLOAT_EQ(l.outerCone, 0.6f);
  EXPECT_FALSE(s.environment.builtin);
  EXPECT_EQ(fs::path(s.environment.path), dir_ / "env.exr");  // relative to the scene file
  EXPECT_EQ(s.environment.intensity, 0.5f);
  EXPECT_EQ(s.environment.rotation, 1.25f);

  const brdfcl::Scene b =
      brdfcl::parseScene(R"({"environment": {"builtin": "studio", "intensity": 2, "rotation": -1}})", "s.json", "");
  EXPECT_TRUE(b.environment.builtin);
  EXPECT_EQ(b.environment.builtinKind, "studio");
  EXPECT_EQ(b.environment.intensity, 2.0f);
  EXPECT_EQ(b.environment.rotation, -1.0f);
  // pi/2 written with a few digits is accepted as pi/2.
  const brdfcl::Scene h = brdfcl::parseScene(
      R"({"lights": [{"type": "spot", "position": [0,0,0], "direction": [0,0,-1], "spot": {"outerConeAngle": 1.5708}}]})",
      "s.json", "");
  EXPECT_FLOAT_EQ(h.lights[0].outerCone, 1.5707964f);
}

TEST_F(Scene, ErrorsNameFileAndKeyPath) {
  const std::string P = R"("position": [0, 0, 0])", D = R"("direction": [0, 0, -1])";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[1]", "s.json: expected a JSON object at the top level, got an array of 1 element"},
      {"{", "s.json: invalid JSON: "},
      {R"({"lights": [], "camra": {}})", "s.json: camra: unknown key; expected one of camera, lights, environment"},
      {R"({"camera": 1})", "s.json: camera: expected an object, got 1"},
      {R"({"camera": {}})", "s.json: camera: missing \"position\": [x, y, z]"},
      {R"({"camera": {"position": [1, 2]}})", "s.json: camera.position: expected an array of 3 finite numbers, got an array of 2 elements"},
      {R"({"camera": {"position": [1, "a", 2]}})", "s.json: camera.position[1]: expected a finite number, got string \"a\""},
      {R"({"camera": {"position": [1, 1e999, 2]}})", "s.json: invalid JSON: "},
      {R"({"camera": {"position": [0, 0, 0]}})", "s.json: camera.position: the camera position equals its target"},
      {R"({"camera": {"position": [1, 0, 0], "target": [1, 0, 0]}})", "s.json: camera.target: the camera position equals its target"},
      {R"({"camera": {"position": [1, 0, 0], "fov": 180}})", "s.json: camera.fov: expected a number of degrees in (0, 180), got 180"},
      {R"({"camera": {"position": [1, 0, 0], "fov": 0}})", "s.json: camera.fov: expected a number of degrees in (0, 180), got 0"},
      {R"({"camera": {"position": [1, 0, 0], "postion": [1, 0, 0]}})", "s.json: camera.postion: unknown key; expected one of position, target, fov"},
      {R"({"lights": {}})", "s.json: lights: expected an array of light objects, got an object"},
      {R"({"lights": [3]})", "s.json: lights[0]: expected an object, got 3"},
      {R"({"lights": [{}]})", "s.json: lights[0]: missing \"type\""},
      {R"({"lights": [{"type": "area"}]})", "s.json: lights[0].type: expected \"directional\", \"point\" or \"spot\", got string \"area\""},
      {R"({"lights": [{"type": "point"}]})", "s.json: lights[0]: missing \"position\": [x, y, z] (required for point lights)"},
      {R"({"lights": [{"type": "spot", )" + P + "}]}", "s.json: lights[0]: missing \"direction\": [x, y, z], the way the light travels (required for spot lights)"},
      {R"({"lights": [{"type": "directional"}]})", "s.json: lights[0]: missing \"direction\""},
      {R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})", "s.json: lights[0].direction: the direction has zero length"},
      {R"({"lights": [{"type": "directional", )" + D + ", " + P + "}]}", "s.json: lights[0].position: unknown key; expected one of type, color, intensity, direction"},
      {R"({"lights": [{"type": "directional", "range": 3, )" + D + "}]}", "s.json: lights[0].range: unknown key"},
      {R"({"lights": [{"type": "point", "spot": {}, )" + P + "}]}", "s.json: lights[0].spot: unknown key"},
      {R"({"lights": [{"type": "point", "color": [1, -1, 1], )" + P + "}]}", "s.json: lights[0].color[1]: expected a number >= 0, got -1"},
      {R"({"lights": [{"type": "point", "color": 1, )" + P + "}]}", "s.json: lights[0].color: expected an array of 3 numbers >= 0, got 1"},
      {R"({"lights": [{"type": "point", "intensity": -2, )" + P + "}]}", "s.json: lights[0].intensity: expected a number >= 0, got -2"},
      {R"({"lights": [{"type": "point", "intensity": "1", )" + P + "}]}", "s.json: lights[0].intensity: expected a number >= 0, got string \"1\""},
      {R"({"lights": [{"type": "point", "range": 0, )" + P + "}]}", "s.json: lights[0].range: expected a number > 0 (omit the key for infinite range), got 0"},
      {R"({"lights": [{"type": "spot", "spot": 1, )" + P + ", " + D + "}]}", "s.json: lights[0].spot: expected an object, got 1"},
      {R"({"lights": [{"type": "spot", "spot": {"outerConeAngle": 2}, )" + P + ", " + D + "}]}", "s.json: lights[0].spot.outerConeAngle: expected a number in (0, pi/2], got 2"},
      {R"({"lights": [{"type": "spot", "spot": {"outerConeAngle": 0}, )" + P + ", " + D + "}]}", "s.json: lights[0].spot.outerConeAngle: expected a number in (0, pi/2], got 0"},
      {R"({"lights": [{"type": "spot", "spot": {"innerConeAngle": 0.8}, )" + P + ", " + D + "}]}", "s.json: lights[0].spot.innerConeAngle: expected a number in [0, outerConeAngle) = [0, 0.785398"},
      {R"({"lights": [{"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.5}, )" + P + ", " + D + "}]}", "s.json: lights[0].spot.innerConeAngle: expected a number in [0, outerConeAngle) = [0, 0.5), got 0.5"},
      {R"({"lights": [{"type": "spot", "spot": {"innerConeAngle": -0.1}, )" + P + ", " + D + "}]}", "s.json: lights[0].spot.innerConeAngle: expected a number in [0, outerConeAngle)"},
      {R"({"lights": [{"type": "spot", "spot": {"inner": 0.1}, )" + P + ", " + D + "}]}", "s.json: lights[0].spot.inner: unknown key; expected one of innerConeAngle, outerConeAngle"},
      {R"({"environment": "sky"})", "s.json: environment: expected \"builtin\" or an object"},
      {R"({"environment": 3})", "s.json: environment: expected \"builtin\" or an object with \"path\" or \"builtin\", got 3"},
      {R"({"environment": {}})", "s.json: environment: needs \"path\": \"env.exr\" or \"builtin\": \"sky\"|\"studio\""},
      {R"({"environment": {"path": "a.exr", "builtin": "sky"}})", "s.json: environment: has both \"path\" and \"builtin\"; keep one"},
      {R"({"environment": {"builtin": "forest"}})", "s.json: environment.builtin: expected \"sky\", \"studio\" or \"uniform\", got string \"forest\""},
      {R"({"environment": {"path": ""}})", "s.json: environment.path: expected a non-empty file name string, got string \"\""},
      {R"({"environment": {"path": 5}})", "s.json: environment.path: expected a non-empty file name string, got 5"},
      {R"({"environment": {"path": "nope.exr"}})", "s.json: environment.path: cannot read '"},
      {R"({"environment": {"builtin": "sky", "intensity": -1}})", "s.json: environment.intensity: expected a number >= 0, got -1"},
      {R"({"environment": {"builtin": "sky", "rotation": "x"}})", "s.json: environment.rotation: expected a finite number, got string \"x\""},
      {R"({"environment": {"builtin": "sky", "rotate": 1}})", "s.json: environment.rotate: unknown key; expected one of path, builtin, intensity, rotation"},
  };
  for (const auto& [json, expected] : cases) {
    const std::string m = errorOf([&] { brdfcl::parseScene(json, "s.json", dir_.string()); });
    EXPECT_EQ(m.rfind(expected, 0), 0u) << json << "\n got: " << m << "\n want prefix: " << expected;
  }
}

TEST_F(Scene, ReadSceneFileErrors) {
  EXPECT_EQ(errorOf([&] { brdfcl::readScene(path("absent.json")); }),
            "cannot read '" + path("absent.json") + "': No such file or directory");
  EXPECT_EQ(errorOf([&] { brdfcl::readScene(dir_.string()); }), "cannot read '" + dir_.string() + "': Is a directory");
  write("bad.json", R"({"lights": [{"type": "point"}]})");
  EXPECT_EQ(errorOf([&] { brdfcl::readScene(path("bad.json")); }),
            path("bad.json") + ": lights[0]: missing \"position\": [x, y, z] (required for point lights)");
  // The environment path is resolved against the scene file's directory, not the working one.
  write("env.json", R"({"environment": {"path": "sub/env.exr"}})");
  EXPECT_EQ(errorOf([&] { brdfcl::readScene(path("env.json")); }),
            path("env.json") + ": environment.path: cannot read '" + path("sub/env.exr") + "': No such file or directory");
}

}  // namespace
