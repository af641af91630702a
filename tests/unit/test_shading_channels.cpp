// The G-buffer's occlusion and view-direction channels (file round trip, errors, what the shader
// does with them), Radiance HDR environments (RGBE decoding, orientation, every rejection), the
// command line's environment spec, and the shared environment assets when they are present.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/scene.hpp"
#include "tests/assets_dir.hpp"
#include "process.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

// A 1x1 surface pixel at the origin, N = +Z, T = +X, with every layer that adds image-based light.
GBuffer layeredPixel() {
  GBuffer g;
  g.width = g.height = 1;
  g.P = {0, 0, 0};
  g.N = {0, 0, 1};
  g.T = {1, 0, 0};
  g.baseColor = {0.8f, 0.5f, 0.3f};
  g.metallic = {0.3f};
  g.roughness = {0.45f};
  g.mask = {1};
  g.sheenColor = {0.6f, 0.4f, 0.2f};
  g.sheenRoughness = {0.5f};
  g.clearcoat = {0.7f};
  g.clearcoatRoughness = {0.2f};
  return g;
}

Scene sceneLookingFrom(std::array<float, 3> eye, const char* builtin, float intensity) {
  Scene s;
  s.cameraPosition = eye;
  s.cameraTarget = {0, 0, 0};
  s.environment.builtin = true;
  s.environment.builtinKind = builtin;
  s.environment.intensity = intensity;
  return s;
}

// Header of a Radiance file of w x h pixels, top row first.
std::string radianceHeader(int w, int h) {
  return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
}

void writeBytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// stb_image's RGBE decoding (stbi__hdr_convert): m * 2^(e - 136), 0 when e = 0.
float rgbeValue(std::uint8_t m, std::uint8_t e) { return e == 0 ? 0.0f : std::ldexp(float(m), int(e) - 136); }

// Writes the G-buffer's required channels (1 pixel, valid values) plus `extra` channels with the
// given values, FLOAT, under exactly these names.
void writeWithExtraChannels(const std::string& path, const std::vector<std::pair<std::string, float>>& extra) {
  std::vector<std::pair<std::string, float>> channels = {
      {"P.X", 0}, {"P.Y", 0}, {"P.Z", 0}, {"N.X", 0}, {"N.Y", 0}, {"N.Z", 1}, {"baseColor.R", 0.5f},
      {"baseColor.G", 0.5f}, {"baseColor.B", 0.5f}, {"metallic", 0}, {"roughness", 0.5f}, {"mask", 1}};
  channels.insert(channels.end(), extra.begin(), extra.end());
  Imf::Header header(1, 1);
  Imf::FrameBuffer fb;
  std::vector<float> values(channels.size());
  for (std::size_t c = 0; c < channels.size(); ++c) {
    values[c] = channels[c].second;
    header.channels().insert(channels[c].first, Imf::Channel(Imf::FLOAT));
    fb.insert(channels[c].first, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(&values[c]), 4, 4));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(fb);
  out.writePixels(1);
}

// ------------------------------------------------------------------------------- occlusion

TEST(ShadingChannels, OcclusionScalesImageBasedLightOnly) {
  const Scene furnace = sceneLookingFrom({1.5f, 1.0f, 4.0f}, "uniform", 1.0f);
  GBuffer g = layeredPixel();
  Shader shader(runtime(), furnace);
  const Image absent = shader.shade(g);
  g.occlusion = {1.0f};
  const Image one = shader.shade(g);
  g.occlusion = {0.25f};
  const Image quarter = shader.shade(g);
  for (int c = 0; c < 3; ++c) {
    ASSERT_GT(one.rgb[c], 0.05f) << "channel " << c;
    EXPECT_EQ(absent.rgb[c], one.rgb[c]) << "channel " << c << ": a missing occlusion must mean 1";
    EXPECT_EQ(quarter.rgb[c], 0.25f * one.rgb[c]) << "channel " << c;
  }

  // A directional light and emission in the dark: occlusion changes nothing.
  Scene lit = sceneLookingFrom({1.5f, 1.0f, 4.0f}, "uniform", 0.0f);
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = {-0.3f, -0.2f, -0.93f};
  sun.intensity = 3.0f;
  lit.lights = {sun};
  GBuffer e = layeredPixel();
  e.emissive = {0.5f, 0.25f, 0.125f};
  Shader litShader(runtime(), lit);
  e.occlusion = {1.0f};
  const Image litOne = litShader.shade(e);
  e.occlusion = {0.25f};
  const Image litQuarter = litShader.shade(e);
  for (int c = 0; c < 3; ++c) {
    ASSERT_GT(litOne.rgb[c], 0.05f) << "channel " << c;
    EXPECT_EQ(litQuarter.rgb[c], litOne.rgb[c]) << "channel " << c;
  }
}

// ------------------------------------------------------------------------------- view direction

// The camera ray of pixel (x, y), as kernels/common/shading_layout.h defines brdfcl_camera.
std::array<double, 3> cameraRay(const Scene& s, int x, int y, int w, int h) {
  auto norm = [](std::array<double, 3> a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return std::array<double, 3>{a[0] / l, a[1] / l, a[2] / l};
  };
  auto cross = [](std::array<double, 3> a, std::array<double, 3> b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const auto f = norm({s.cameraTarget[0] - s.cameraPosition[0], s.cameraTarget[1] - s.cameraPosition[1],
                       s.cameraTarget[2] - s.cameraPosition[2]});
  const std::array<double, 3> worldUp = std::fabs(f[1]) > 0.999 ? std::array<double, 3>{0, 0, -1} : std::array<double, 3>{0, 1, 0};
  const auto r = norm(cross(f, worldUp)), u = cross(r, f);
  const double t = std::tan(s.fovDegrees * M_PI / 360.0), aspect = double(w) / h;
  const double sx = (2.0 * (x + 0.5) / w - 1.0) * t * aspect, sy = (1.0 - 2.0 * (y + 0.5) / h) * t;
  return norm({f[0] + sx * r[0] + sy * u[0], f[1] + sx * r[1] + sy * u[1], f[2] + sx * r[2] + sy * u[2]});
}

TEST(ShadingChannels, ExplicitViewEqualsTheCameraView) {
  const Scene scene = spheresScene();
  const int w = 40, h = 32;
  GBuffer g = renderSpheresGBuffer(runtime(), scene, w, h);
  Shader shader(runtime(), scene);
  const Image fromCamera = shader.shade(g);
  g.V.resize(3 * g.pixelCount());
  int surface = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      std::array<double, 3> v;
      if (g.mask[i] > 0.5f) {
        ++surface;
        for (int c = 0; c < 3; ++c) v[c] = double(scene.cameraPosition[c]) - g.P[3 * i + c];
      } else {
        const auto d = cameraRay(scene, x, y, w, h);
        for (int c = 0; c < 3; ++c) v[c] = -d[c];
      }
      const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (int c = 0; c < 3; ++c) g.V[3 * i + c] = float(v[c] / l);
    }
  ASSERT_GT(surface, 100);
  ASSERT_LT(surface, w * h);
  const Image fromV = shader.shade(g);
  // Only float rounding separates the two: the host's normalization of V against the kernel's
  // (1.1e-6 relative at worst when measured).
  double worst = 0;
  for (std::size_t k = 0; k < fromV.rgb.size(); ++k) {
    const double err = std::fabs(double(fromV.rgb[k]) - fromCamera.rgb[k]) / std::max(1.0, std::fabs(double(fromCamera.rgb[k])));
    worst = std::max(worst, err);
    EXPECT_LE(err, 4e-6) << "pixel " << k / 3 << " channel " << k % 3 << ": " << fromV.rgb[k] << " vs " << fromCamera.rgb[k];
  }
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", worst);
  RecordProperty("worst_relative_difference", text);

  // And V does matter: the opposite view changes surface pixels.
  for (float& v : g.V) v = -v;
  const Image flipped = shader.shade(g);
  int changed = 0;
  for (std::size_t k = 0; k < flipped.rgb.size(); ++k) changed += std::fabs(flipped.rgb[k] - fromCamera.rgb[k]) > 1e-3f;
  EXPECT_GT(changed, 100);
}

// What V is for: an orthographic view of a plane under a directional light and an environment
// shades every pixel alike, which no pinhole camera gives.
TEST(ShadingChannels, OrthographicViewShadesAPlaneUniformly) {
  Scene scene = sceneLookingFrom({0.0f, 0.0f, 3.0f}, "sky", 1.0f);
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = {-0.2f, -0.3f, -0.93f};
  scene.lights = {sun};
  GBuffer g = layeredPixel();
  g.width = g.height = 4;
  const std::size_t n = g.pixelCount();
  auto spread = [&](std::vector<float>& v) {
    const std::vector<float> one = v;
    v.clear();
    for (std::size_t i = 0; i < n; ++i) v.insert(v.end(), one.begin(), one.end());
  };
  for (auto* v : {&g.N, &g.T, &g.baseColor, &g.metallic, &g.roughness, &g.mask, &g.sheenColor, &g.sheenRoughness,
                  &g.clearcoat, &g.clearcoatRoughness})
    spread(*v);
  g.P.clear();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) g.P.insert(g.P.end(), {0.5f * (x - 1.5f), 0.5f * (1.5f - y), 0.0f});
  Shader shader(runtime(), scene);
  const Image pinhole = shader.shade(g);
  g.V.clear();
  for (std::size_t i = 0; i < n; ++i) g.V.insert(g.V.end(), {0.28f, 0.0f, 0.96f});
  const Image ortho = shader.shade(g);
  float pinholeSpread = 0;
  for (std::size_t i = 1; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(ortho.rgb[3 * i + c], ortho.rgb[c]) << "pixel " << i << " channel " << c;
      pinholeSpread = std::max(pinholeSpread, std::fabs(pinhole.rgb[3 * i + c] - pinhole.rgb[c]));
    }
  EXPECT_GT(pinholeSpread, 1e-3f);
}

// Background pixels show the environment in direction -V: texel centres of a small .hdr whose
// texels are all different, read through the scene JSON.
TEST(ShadingChannels, BackgroundLooksUpMinusV) {
  ScratchDir dir("shading-channels");
  const int ew = 16, eh = 8;
  std::mt19937 rng(11);
  std::string bytes = radianceHeader(ew, eh);
  for (int i = 0; i < ew * eh; ++i) {
    for (int c = 0; c < 3; ++c) bytes += char(64 + rng() % 192);
    bytes += char(128 + rng() % 4);
  }
  writeBytes(dir.path("env.hdr"), bytes);
  writeBytes(dir.path("scene.json"), R"({"camera": {"position": [0, 0, 5], "target": [0, 0, 0]},
                                         "environment": {"path": "env.hdr"}})");
  const Scene scene = readScene(dir.path("scene.json"));
  int w = 0, h = 0;
  const std::vector<float> texels = readEnvironmentRgb(dir.path("env.hdr"), w, h);
  ASSERT_EQ(w, ew);
  ASSERT_EQ(h, eh);

  // One background pixel per texel of rows 1..6 (the poles blend across the whole row).
  GBuffer g;
  g.width = ew;
  g.height = eh - 2;
  const std::size_t n = g.pixelCount();
  g.P.assign(3 * n, 0.0f);
  g.N.assign(3 * n, 0.0f);
  g.baseColor.assign(3 * n, 0.5f);
  g.metallic.assign(n, 0.0f);
  g.roughness.assign(n, 0.5f);
  g.mask.assign(n, 0.0f);
  g.V.resize(3 * n);
  for (int y = 1; y < eh - 1; ++y)
    for (int x = 0; x < ew; ++x) {
      // The inverse of env_uv (kernels/common/environment.h) at the texel centre.
      const double phi = ((x + 0.5) / ew - 0.5) * 2 * M_PI, theta = (y + 0.5) / eh * M_PI;
      const double d[3] = {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
      const std::size_t i = std::size_t(y - 1) * ew + x;
      for (int c = 0; c < 3; ++c) g.V[3 * i + c] = float(-d[c]);
    }
  const Image img = Shader(runtime(), scene).shade(g);
  for (int y = 1; y < eh - 1; ++y)
    for (int x = 0; x < ew; ++x)
      for (int c = 0; c < 3; ++c) {
        const float want = texels[3 * (std::size_t(y) * ew + x) + c];
        const float got = img.rgb[3 * (std::size_t(y - 1) * ew + x) + c];
        EXPECT_NEAR(got, want, 1e-3f * want) << "texel (" << x << ", " << y << ") channel " << c;
      }
}

// ------------------------------------------------------------------------------- file format

TEST(ShadingChannels, OcclusionAndViewRoundTrip) {
  ScratchDir dir("shading-channels");
  GBuffer g = layeredPixel();
  g.width = 3;
  g.height = 1;
  for (auto* v : {&g.P, &g.N, &g.T, &g.baseColor, &g.sheenColor}) *v = {(*v)[0], (*v)[1], (*v)[2], (*v)[0], (*v)[1], (*v)[2], (*v)[0], (*v)[1], (*v)[2]};
  for (auto* v : {&g.metallic, &g.roughness, &g.mask, &g.sheenRoughness, &g.clearcoat, &g.clearcoatRoughness})
    *v = {(*v)[0], (*v)[0], (*v)[0]};
  g.occlusion = {0.0f, 0.25f, 1.0f};
  g.V = {0.0f, 0.0f, 1.0f, 0.6f, 0.0f, 0.8f, 0.0f, -1.0f, 0.0f};
  for (bool half : {false, true}) {
    writeGBuffer(dir.path("g.exr"), g, half);
    const GBuffer r = readGBuffer(dir.path("g.exr"));
    EXPECT_TRUE(r.hasOcclusion());
    EXPECT_TRUE(r.hasView());
    const float tol = half ? 1e-3f : 0.0f;
    ASSERT_EQ(r.occlusion.size(), g.occlusion.size());
    ASSERT_EQ(r.V.size(), g.V.size());
    for (std::size_t i = 0; i < g.occlusion.size(); ++i) EXPECT_NEAR(r.occlusion[i], g.occlusion[i], tol) << i;
    for (std::size_t i = 0; i < g.V.size(); ++i) EXPECT_NEAR(r.V[i], g.V[i], tol) << i;
  }
  GBuffer plain = layeredPixel();
  writeGBuffer(dir.path("plain.exr"), plain);
  const GBuffer r = readGBuffer(dir.path("plain.exr"));
  EXPECT_FALSE(r.hasOcclusion());
  EXPECT_FALSE(r.hasView());
}

TEST(ShadingChannels, ChannelErrorsNameFileChannelAndPixel) {
  ScratchDir dir("shading-channels");
  const std::string p = dir.path("g.exr");
  writeWithExtraChannels(p, {{"V.X", 0.0f}, {"V.Y", 1.0f}});
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }), p + ": incomplete V vector: missing V.Z; write all of V.X V.Y V.Z");
  writeWithExtraChannels(p, {{"occlusion", std::nanf("")}});
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": pixel (0, 0) has a non-finite value (nan) in channel 'occlusion'; fix the renderer's output");
  writeWithExtraChannels(p, {{"V.X", 0.0f}, {"V.Y", 0.0f}, {"V.Z", 0.0f}});
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": pixel (0, 0) has a zero-length view direction V; write the unit direction towards the viewer, or "
                "leave V.X V.Y V.Z out to use the scene camera");
  writeWithExtraChannels(p, {{"V.X", 0.0f}, {"V.Y", std::numeric_limits<float>::infinity()}, {"V.Z", 1.0f}});
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": pixel (0, 0) has a non-finite value (inf) in channel 'V.Y'; fix the renderer's output");

  // The same checks on a G-buffer made in memory, when it is shaded.
  Shader shader(runtime(), sceneLookingFrom({0, 0, 5}, "uniform", 1.0f));
  GBuffer g = layeredPixel();
  g.occlusion = {std::nanf("")};
  EXPECT_EQ(errorOf([&] { shader.shade(g); }),
            "G-buffer pixel (0, 0) has a non-finite value (nan) in channel 'occlusion'; fix the renderer's output");
  g.occlusion.clear();
  g.V = {0.0f, 0.0f, 0.0f};
  EXPECT_EQ(errorOf([&] { shader.shade(g); }),
            "G-buffer pixel (0, 0) has a zero-length view direction V; write the unit direction towards the viewer, "
            "or leave V out to use the scene camera");
}

// ------------------------------------------------------------------------------- Radiance HDR

TEST(EnvironmentHdr, FlatRgbeDecodesAsStbImageTopRowFirst) {
  ScratchDir dir("environment-hdr");
  // 3 x 2, flat (width < 8): each pixel's mantissas and exponent differ.
  const std::uint8_t px[6][4] = {{128, 64, 32, 129}, {255, 0, 1, 136}, {10, 20, 30, 0},
                                 {200, 100, 50, 120}, {1, 2, 3, 200}, {90, 91, 92, 128}};
  std::string bytes = radianceHeader(3, 2);
  for (const auto& p : px) bytes.append(reinterpret_cast<const char*>(p), 4);
  writeBytes(dir.path("env.hdr"), bytes);
  int w = 0, h = 0;
  const auto rgb = readEnvironmentRgb(dir.path("env.hdr"), w, h);
  ASSERT_EQ(w, 3);
  ASSERT_EQ(h, 2);
  ASSERT_EQ(rgb.size(), 18u);
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb[3 * i + c], rgbeValue(px[i][c], px[i][3])) << "pixel " << i << " channel " << c;
  EXPECT_EQ(rgb[0], 1.0f);  // 128 * 2^(129 - 136)
  EXPECT_EQ(rgb[3], 255.0f);
  // #?RGBE is the other magic line stb_image accepts.
  writeBytes(dir.path("rgbe.hdr"), "#?RGBE" + bytes.substr(10));
  EXPECT_EQ(readRadianceHdr(dir.path("rgbe.hdr"), w, h), rgb);
}

TEST(EnvironmentHdr, RunLengthEncodedScanLines) {
  ScratchDir dir("environment-hdr");
  const int w = 10, h = 2;
  std::string bytes = radianceHeader(w, h);
  // Each scan line: marker 2 2 w, then per component a run of 6 and a dump of 4.
  for (int y = 0; y < h; ++y) {
    bytes += std::string{2, 2, 0, char(w)};
    for (int c = 0; c < 4; ++c) {
      const std::uint8_t run = c == 3 ? std::uint8_t(130 + y) : std::uint8_t(50 + 10 * c + y);
      bytes += char(128 + 6);
      bytes += char(run);
      bytes += char(4);
      for (int k = 0; k < 4; ++k) bytes += char(c == 3 ? 128 : 100 + k + c);
    }
  }
  writeBytes(dir.path("rle.hdr"), bytes);
  int ww = 0, hh = 0;
  const auto rgb = readRadianceHdr(dir.path("rle.hdr"), ww, hh);
  ASSERT_EQ(ww, w);
  ASSERT_EQ(hh, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const std::uint8_t m = x < 6 ? std::uint8_t(50 + 10 * c + y) : std::uint8_t(100 + (x - 6) + c);
        const std::uint8_t e = x < 6 ? std::uint8_t(130 + y) : 128;
        EXPECT_EQ(rgb[3 * (y * w + x) + c], rgbeValue(m, e)) << x << "," << y << " channel " << c;
      }
  // Cut inside the second scan line: stb_image 2.27 would spin on the zero packets it reads past the end.
  writeBytes(dir.path("cut.hdr"), bytes.substr(0, bytes.size() - 20));
  EXPECT_EQ(errorOf([&] { readRadianceHdr(dir.path("cut.hdr"), ww, hh); }),
            dir.path("cut.hdr") + ": cannot decode Radiance HDR (scan line 1 ends early); the file is truncated or "
                                  "corrupt: write it again");
}

// A small fuzz run in the unit tests: byte flips and cuts of a run-length encoded file must give
// an image of the header's size or a one-line brdfcl::Error, never a hang, crash or other exception.
TEST(EnvironmentHdr, MutatedFilesAreReadOrRefusedCleanly) {
  ScratchDir dir("environment-hdr");
  const int w = 12, h = 3;
  std::string good = radianceHeader(w, h);
  const std::size_t header = good.size();
  for (int y = 0; y < h; ++y) {
    good += std::string{2, 2, 0, char(w)};
    for (int c = 0; c < 4; ++c) good += std::string{char(128 + 5), char(90 + c), char(7), 1, 2, 3, 4, 5, 6, char(130)};
  }
  std::mt19937 rng(seed() & 0xffffffffu);
  int read = 0, refused = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    std::string bytes = good;
    const int kind = trial % 3;
    if (kind == 0) {
      bytes.resize(rng() % bytes.size());
    } else {
      // Mostly the pixel data; sometimes the header.
      for (int k = 0, flips = 1 + int(rng() % 4); k < flips; ++k) {
        const std::size_t at = rng() % 8 == 0 ? rng() % header : header + rng() % (bytes.size() - header);
        bytes[at] = char(kind == 1 ? rng() % 256 : bytes[at] ^ (1 << (rng() % 8)));
      }
    }
    writeBytes(dir.path("m.hdr"), bytes);
    int ww = 0, hh = 0;
    try {
      const auto rgb = readEnvironmentRgb(dir.path("m.hdr"), ww, hh);
      ASSERT_EQ(rgb.size(), 3u * ww * hh) << "trial " << trial;
      ++read;
    } catch (const Error& e) {
      const std::string m = e.what();
      ASSERT_EQ(m.find('\n'), std::string::npos) << m;
      ASSERT_NE(m.find(dir.path("m.hdr")), std::string::npos) << m;
      ++refused;
    } catch (const std::exception& e) {
      FAIL() << "trial " << trial << ": " << e.what();
    }
  }
  EXPECT_GT(read, 30) << refused << " refused";
  EXPECT_GT(refused, 300) << read << " read";
}

TEST(EnvironmentHdr, RejectionsAreOneLineAndNameTheFile) {
  ScratchDir dir("environment-hdr");
  int w = 0, h = 0;
  auto err = [&](const std::string& name, const std::string& bytes) {
    writeBytes(dir.path(name), bytes);
    return errorOf([&] { readEnvironmentRgb(dir.path(name), w, h); });
  };
  const std::string four(4 * 3 * 2, char(100));
  EXPECT_EQ(err("short.hdr", radianceHeader(3, 2) + four.substr(5)),
            dir.path("short.hdr") + ": cannot decode Radiance HDR (flat pixel data of 19 bytes, expected 24); the file "
                                    "is truncated or corrupt: write it again");
  EXPECT_EQ(err("xyze.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 3\n" + four),
            dir.path("xyze.hdr") + ": cannot decode Radiance HDR (pixel format '32-bit_rle_xyze'; only 32-bit_rle_rgbe "
                                   "is read); write it again as RGBE, top row first");
  EXPECT_EQ(err("flip.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 2 +X 3\n" + four),
            dir.path("flip.hdr") + ": cannot decode Radiance HDR (image size line '+Y 2 +X 3'; expected '-Y <height> "
                                   "+X <width>'); write it again as RGBE, top row first");
  EXPECT_EQ(err("noformat.hdr", "#?RADIANCE\n\n-Y 2 +X 3\n" + four),
            dir.path("noformat.hdr") + ": cannot decode Radiance HDR (no FORMAT=32-bit_rle_rgbe line); write it again "
                                       "as RGBE, top row first");
  EXPECT_EQ(err("huge.hdr", radianceHeader(70000, 2) + four),
            dir.path("huge.hdr") + ": unsupported image size 70000x2 (at most 268435456 pixels and 65536 on a side)");
  EXPECT_EQ(err("noline.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n"),
            dir.path("noline.hdr") + ": cannot decode Radiance HDR (the header ends before the image size line); write "
                                     "it again as RGBE, top row first");
  EXPECT_EQ(err("env.png", "\x89PNG\r\n\x1a\n...."),
            dir.path("env.png") + ": not an environment image: expected OpenEXR or Radiance HDR (.hdr, starting with "
                                  "#?RADIANCE)");
  EXPECT_EQ(errorOf([&] { readEnvironmentRgb(dir.path("missing.hdr"), w, h); }),
            "cannot read '" + dir.path("missing.hdr") + "': No such file or directory");
  EXPECT_EQ(errorOf([&] { readRadianceHdr(dir.path("env.png"), w, h); }),
            dir.path("env.png") + ": not a Radiance HDR file (it does not start with #?RADIANCE or #?RGBE)");
  // A sparse file: the size is refused before anything is read.
  {
    std::ofstream(dir.path("big.hdr"), std::ios::binary) << radianceHeader(3, 2);
    std::filesystem::resize_file(dir.path("big.hdr"), (std::uintmax_t(1) << 31) + 16);
  }
  EXPECT_EQ(errorOf([&] { readEnvironmentRgb(dir.path("big.hdr"), w, h); }),
            dir.path("big.hdr") + ": cannot decode Radiance HDR (the file is larger than 2 GiB, stb_image's limit); use "
                                  "OpenEXR");
  // An EXR is recognised by its magic number whatever its name.
  const std::vector<float> grey(3 * 8 * 4, 0.5f);
  writeExrRgb(dir.path("really-exr.hdr"), 8, 4, grey);
  EXPECT_EQ(readEnvironmentRgb(dir.path("really-exr.hdr"), w, h), grey);
}

TEST(EnvironmentHdr, CommandLineSpec) {
  ScratchDir dir("environment-hdr");
  const Environment sky = parseEnvironmentSpec("builtin", 1.5f, 0.25f);
  EXPECT_TRUE(sky.builtin);
  EXPECT_EQ(sky.builtinKind, "sky");
  EXPECT_EQ(sky.intensity, 1.5f);
  EXPECT_EQ(sky.rotation, 0.25f);
  for (const char* kind : {"sky", "studio", "uniform"}) EXPECT_EQ(parseEnvironmentSpec(kind, 1, 0).builtinKind, kind);
  writeBytes(dir.path("a.HDR"), radianceHeader(1, 1) + "abcd");
  const Environment file = parseEnvironmentSpec(dir.path("a.HDR"), 1, 0);
  EXPECT_FALSE(file.builtin);
  EXPECT_EQ(file.path, dir.path("a.HDR"));
  writeBytes(dir.path("b.exr"), "x");
  EXPECT_FALSE(parseEnvironmentSpec(dir.path("b.exr"), 1, 0).builtin);
  EXPECT_EQ(errorOf([&] { parseEnvironmentSpec(dir.path("c.exr"), 1, 0); }),
            "--environment '" + dir.path("c.exr") + "': cannot read: No such file or directory");
  EXPECT_EQ(errorOf([&] { parseEnvironmentSpec("env.png", 1, 0); }),
            "--environment 'env.png': expected builtin, sky, studio, uniform, or an equirectangular .hdr or .exr file");
  EXPECT_EQ(errorOf([&] { parseEnvironmentSpec("studio", -1, 0); }),
            "--env-intensity -1 is not a finite number >= 0; give a radiance scale such as 1 or 0.5");
  EXPECT_EQ(errorOf([&] { parseEnvironmentSpec("studio", 1, std::nanf("")); }),
            "--env-rotation nan is not a finite number of radians; give an angle such as 0 or 1.5708");
}

TEST(EnvironmentHdr, NonFiniteTexelsRejectedNegativeOnesClamped) {
  ScratchDir dir("environment-hdr");
  std::vector<float> rgb(3 * 8 * 4, -0.5f);
  rgb[3 * (8 * 2 + 5) + 1] = std::nanf("");
  writeExrRgb(dir.path("nan.exr"), 8, 4, rgb);
  int w = 0, h = 0;
  EXPECT_EQ(errorOf([&] { readEnvironmentRgb(dir.path("nan.exr"), w, h); }),
            dir.path("nan.exr") + ": texel (5, 2) has a non-finite value (nan) in channel G; an environment needs "
                                  "finite radiance");
  rgb[3 * (8 * 2 + 5) + 1] = -0.5f;
  writeExrRgb(dir.path("negative.exr"), 8, 4, rgb);
  Environment env;
  env.builtin = false;
  env.path = dir.path("negative.exr");
  const std::vector<float> planes = environmentPlanes(env, w, h);
  for (float v : planes) ASSERT_EQ(v, 0.0f);
}

// ------------------------------------------------------------------------------- shared assets

void expectPlausibleEnvironment(const std::string& path) {
  int w = 0, h = 0;
  const auto rgb = readEnvironmentRgb(path, w, h);
  EXPECT_EQ(w, 1024) << path;
  EXPECT_EQ(h, 512) << path;
  ASSERT_EQ(rgb.size(), 3u * w * h);
  double sum = 0, lowest = 0;
  for (float v : rgb) {
    ASSERT_TRUE(std::isfinite(v)) << path;
    sum += v;
    lowest = std::min(lowest, double(v));
  }
  const double mean = sum / double(rgb.size());
  // DWAB is lossy: its ringing leaves texels slightly below zero (to -0.004; environmentPlanes
  // clamps them), never far below.
  EXPECT_GT(lowest, -0.05 * mean) << path;
  EXPECT_GT(mean, 1e-3) << path;
  EXPECT_LT(mean, 1e3) << path;
  ::testing::Test::RecordProperty(std::filesystem::path(path).filename().string() + "_mean", std::to_string(mean));
}

TEST(EnvironmentHdr, SharedAssetsDecode) {
  const std::string assets = assetsDir();
  if (assets.empty()) GTEST_SKIP() << "no shared assets: set BRDFCL_ASSETS to the assets directory";
  // Every Poly Haven .hdr (run-length encoded RGBE) and every Blender studio light (DWAB EXR).
  int count = 0;
  for (const char* sub : {"polyhaven", "blender_studiolights"})
    for (const auto& e : std::filesystem::directory_iterator(assets + "/environments/" + sub)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".hdr" && ext != ".exr") continue;
      expectPlausibleEnvironment(e.path().string());
      ++count;
    }
  EXPECT_GE(count, 2);
}

}  // namespace
