// Deferred shading: one G-buffer pixel under one light against batch evaluation, the
// KHR_lights_punctual falloffs, the image-based-light white furnace against the reference's
// directional albedo, and the demo render through the CLI.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "brdfcl/image.hpp"
#include "brdfcl/render.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

// A 1x1 G-buffer at the origin with N = +Z, T = +X: world and shading frames coincide.
GBuffer onePixel(const MaterialParams& m) {
  GBuffer g;
  g.width = g.height = 1;
  g.P = {0, 0, 0};
  g.N = {0, 0, 1};
  g.T = {1, 0, 0};
  g.baseColor = {m.baseColor[0], m.baseColor[1], m.baseColor[2]};
  g.metallic = {m.metallic};
  g.roughness = {m.roughness};
  g.mask = {1};
  g.sheenColor = {m.sheenColor[0], m.sheenColor[1], m.sheenColor[2]};
  g.sheenRoughness = {m.sheenRoughness};
  g.clearcoat = {m.clearcoat};
  g.clearcoatRoughness = {m.clearcoatRoughness};
  g.anisotropyStrength = {m.anisotropyStrength};
  g.anisotropyRotation = {m.anisotropyRotation};
  return g;
}

Scene darkScene(std::array<float, 3> view) {
  Scene s;
  s.cameraPosition = {5 * view[0], 5 * view[1], 5 * view[2]};
  s.cameraTarget = {0, 0, 0};
  s.environment.builtin = true;
  s.environment.builtinKind = "uniform";
  s.environment.intensity = 0.0f;
  return s;
}

std::array<float, 3> unit(float x, float y, float z) {
  const float l = std::sqrt(x * x + y * y + z * z);
  return {x / l, y / l, z / l};
}

TEST(Shading, OnePixelUnderADirectionalLightEqualsBatchEvaluation) {
  std::mt19937_64 rng(seed() ^ 0x5ade);
  for (int trial = 0; trial < 24; ++trial) {
    MaterialParams m = randomMaterial(rng);
    m.draftSheen = false;  // a G-buffer has no draft-sheen channels
    const auto V = randomDirection(rng, 0.05f, false), L = randomDirection(rng, 0.05f, false);
    Scene scene = darkScene(V);
    Light sun;
    sun.type = Light::Type::Directional;
    sun.direction = {-L[0], -L[1], -L[2]};
    sun.intensity = 3.0f;
    sun.color = {1.0f, 0.5f, 0.25f};
    scene.lights = {sun};
    const Image img = Shader(runtime(), scene).shade(onePixel(m));
    Samples s;
    s.L = {L[0], L[1], L[2]};
    s.V = {V[0], V[1], V[2]};
    s.material = {0};
    const auto f = Evaluator(runtime(), EvalOptions{}).evaluate({m}, s);
    for (int c = 0; c < 3; ++c) {
      const double want = f[c] * L[2] * sun.intensity * sun.color[c];
      EXPECT_NEAR(img.rgb[c], want, 1e-4 * std::fabs(want) + 1e-7) << "channel " << c << ", " << describe(m);
    }
  }
}

// Radiance of a lit pixel (dark environment, white dielectric, light straight above).
float litPixel(const Light& light) {
  MaterialParams m;
  m.metallic = 0.0f;
  m.roughness = 0.5f;
  m.baseColor = {0.8f, 0.8f, 0.8f};
  Scene scene = darkScene(unit(0.3f, 0.1f, 1.0f));
  scene.lights = {light};
  return Shader(runtime(), scene).shade(onePixel(m)).rgb[0];
}

TEST(Shading, PointLightFallsOffWithTheInverseSquareAndItsRangeWindow) {
  Light p;
  p.type = Light::Type::Point;
  p.intensity = 10.0f;
  p.position = {0, 0, 1};
  const float near = litPixel(p);
  p.position = {0, 0, 2};
  const float far = litPixel(p);
  EXPECT_NEAR(near / far, 4.0f, 4e-4f);
  // KHR_lights_punctual: window max(min(1 - (d / range)^4, 1), 0) / d^2.
  p.range = 3.0f;
  EXPECT_NEAR(litPixel(p) / far, 1.0f - std::pow(2.0f / 3.0f, 4.0f), 1e-4f);
  p.range = 1.9f;
  EXPECT_EQ(litPixel(p), 0.0f);
}

TEST(Shading, SpotConeFallsOffSmoothlyBetweenInnerAndOuterAngles) {
  Light s;
  s.type = Light::Type::Spot;
  s.intensity = 10.0f;
  s.position = {0, 0, 2};
  s.innerCone = 0.2f;
  s.outerCone = 0.6f;
  auto at = [&](float angle) {  // spot axis tilted by `angle` away from the pixel
    s.direction = {std::sin(angle), 0.0f, -std::cos(angle)};
    return litPixel(s);
  };
  const float full = at(0.0f);
  EXPECT_GT(full, 0.0f);
  EXPECT_NEAR(at(0.15f) / full, 1.0f, 1e-5f);
  EXPECT_EQ(at(0.65f), 0.0f);
  const float angle = 0.4f;
  const float scale = 1.0f / (std::cos(0.2f) - std::cos(0.6f));
  const float t = std::clamp((std::cos(angle) - std::cos(0.6f)) * scale, 0.0f, 1.0f);
  EXPECT_NEAR(at(angle) / full, t * t, 1e-4f);
}

// White furnace: a uniform environment of radiance 1 lights each pixel with its material's
// directional albedo. The split sum (prefiltered radiance = 1 everywhere, DFG table A, B and the
// Fresnel-weighted Lambert term) reproduces the reference albedo with view-only sheen scaling
// (000's simplified form for indirect light) to 1%, anisotropy too (its own table over N.V,
// roughness, strength and the view's azimuth, kernels/aniso_dfg.cl), at every rotation.
TEST(Shading, ImageBasedWhiteFurnaceGivesTheDirectionalAlbedo) {
  struct Case {
    const char* what;
    MaterialParams m;
    double tolerance;
  };
  std::vector<Case> cases;
  auto add = [&](const char* what, auto setup, double tol) {
    MaterialParams m;
    m.baseColor = {0.9f, 0.6f, 0.3f};
    setup(m);
    cases.push_back({what, m, tol});
  };
  add("rough dielectric", [](MaterialParams& m) { m.metallic = 0, m.roughness = 0.7f; }, 0.01);
  add("smooth dielectric", [](MaterialParams& m) { m.metallic = 0, m.roughness = 0.15f; }, 0.01);
  add("rough metal", [](MaterialParams& m) { m.metallic = 1, m.roughness = 0.6f; }, 0.01);
  add("smooth metal", [](MaterialParams& m) { m.metallic = 1, m.roughness = 0.2f; }, 0.01);
  add("sheen", [](MaterialParams& m) { m.metallic = 0, m.roughness = 0.8f, m.sheenColor = {1, 0.8f, 0.6f}, m.sheenRoughness = 0.5f; }, 0.01);
  add("clearcoat", [](MaterialParams& m) { m.metallic = 0, m.roughness = 0.6f, m.clearcoat = 1, m.clearcoatRoughness = 0.2f; }, 0.01);
  add("anisotropic metal", [](MaterialParams& m) { m.metallic = 1, m.roughness = 0.4f, m.anisotropyStrength = 0.5f; }, 0.01);
  for (float rotation : {0.0f, 0.7f, 1.5707964f})
    add("anisotropy 1 metal", [&](MaterialParams& m) { m.metallic = 1, m.roughness = 0.3f, m.anisotropyStrength = 1, m.anisotropyRotation = rotation; }, 0.01);
  add("anisotropy 1 dielectric", [](MaterialParams& m) { m.metallic = 0, m.roughness = 0.5f, m.anisotropyStrength = 1, m.anisotropyRotation = 2.5f; }, 0.01);
  add("anisotropy 0.8 smooth metal", [](MaterialParams& m) { m.metallic = 1, m.roughness = 0.1f, m.anisotropyStrength = 0.8f, m.anisotropyRotation = 0.3f; }, 0.01);
  EvalOptions viewScaling;
  viewScaling.sheenScaling = SheenScaling::View;
  std::map<std::string, double> worst;
  for (const auto& c : cases)
    for (float mu : {0.9f, 0.6f, 0.3f, 0.1f}) {
      const auto V = unit(std::sqrt(1 - mu * mu), 0.0f, mu);
      Scene scene = darkScene(V);
      scene.environment.intensity = 1.0f;
      const Image img = Shader(runtime(), scene).shade(onePixel(c.m));
      const auto want = ref::directionalAlbedo(c.m, viewScaling, ref::Vec3{V[0], V[1], V[2]}, 1e-6);
      for (int ch = 0; ch < 3; ++ch) {
        EXPECT_NEAR(img.rgb[ch], want[ch], c.tolerance * want[ch] + 1e-4) << c.what << ", N.V " << mu << ", channel " << ch;
        worst[c.what] = std::max(worst[c.what], std::abs(img.rgb[ch] / want[ch] - 1));
      }
    }
  for (const auto& [what, err] : worst) std::printf("furnace, split sum: %-28s worst relative error %.2f %%\n", what.c_str(), 100 * err);
}

TEST(Shading, EmissionIsDarkenedByTheClearcoat) {
  MaterialParams m;
  m.clearcoat = 1.0f;
  GBuffer g = onePixel(m);
  g.emissive = {2.0f, 1.0f, 0.5f};
  const auto V = unit(0.0f, 0.0f, 1.0f);
  const Image img = Shader(runtime(), darkScene(V)).shade(g);
  EXPECT_NEAR(img.rgb[0], 2.0f * (1.0f - 0.04f), 1e-4f);  // Fc = 0.04 at N.V = 1
}

TEST(Shading, DemoRenderHasTheRightSizeAndIsNotBlank) {
  const auto dir = std::filesystem::temp_directory_path() / ("brdfcl-shade-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto png = dir / "demo.png";
  const std::string cmd = std::string(BRDFCL_CLI_PATH) + " render --scene spheres --size 96x64 --out " + png.string() +
                          " --exr " + (dir / "demo.exr").string() + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(png, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), {});
  ASSERT_GT(bytes.size(), 24u);
  auto be32 = [&](int at) { return (bytes[at] << 24) | (bytes[at + 1] << 16) | (bytes[at + 2] << 8) | bytes[at + 3]; };
  EXPECT_EQ(be32(16), 96);  // IHDR width
  EXPECT_EQ(be32(20), 64);  // IHDR height
  // Not blank: the linear EXR has both lit spheres and the darker background.
  int w = 0, h = 0;
  const auto rgb = readExrRgb((dir / "demo.exr").string(), w, h);
  const auto [lo, hi] = std::minmax_element(rgb.begin(), rgb.end());
  EXPECT_LT(*lo, 0.1f);
  EXPECT_GT(*hi, 0.5f);
  std::filesystem::remove_all(dir);
}

}  // namespace

namespace {

struct CliRun {
  int status;
  std::string err;
};

CliRun runCli(const std::string& args, const std::filesystem::path& dir) {
  const auto errFile = dir / "stderr.txt";
  const std::string cmd = std::string(BRDFCL_CLI_PATH) + " " + args + " > /dev/null 2> " + errFile.string();
  const int raw = std::system(cmd.c_str());
  std::ifstream in(errFile);
  std::string err((std::istreambuf_iterator<char>(in)), {});
  std::filesystem::remove(errFile);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, err};
}

// Bad G-buffers, scenes and options of shade/render/gbuffer: exit 2, one line naming the
// culprit, and no output left behind.
TEST(ShadingCli, BadInputsGiveOneLineErrorsAndNoOutput) {
  const auto dir = std::filesystem::temp_directory_path() / ("brdfcl-shadecli-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto g = dir / "g.exr", s = dir / "s.json", notExr = dir / "text.exr", out = dir / "img.exr";
  ASSERT_EQ(runCli("gbuffer --scene spheres --size 8x8 --out " + g.string(), dir).status, 0);
  std::ofstream(s) << R"({"camera": {"position": [0, 0, 13]}, "lights": [{"type": "directional", "direction": [0, 0, -1]}],
                        "environment": "builtin"})";
  std::ofstream(notExr) << "not an image";
  std::ofstream(dir / "bad.json") << R"({"lights": [{"type": "laser"}]})";
  ASSERT_EQ(runCli("shade --gbuffer " + g.string() + " --scene " + s.string() + " --out " + out.string(), dir).status, 0);
  std::filesystem::remove(out);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"shade --gbuffer " + notExr.string() + " --scene " + s.string() + " --out " + out.string(), "text.exr"},
      {"shade --gbuffer " + (dir / "missing.exr").string() + " --scene " + s.string() + " --out " + out.string(), "missing.exr"},
      {"shade --gbuffer " + g.string() + " --scene " + (dir / "bad.json").string() + " --out " + out.string(), "bad.json"},
      {"shade --gbuffer " + g.string() + " --scene " + s.string() + " --out " + (dir / "img.json").string(), "--out"},
      {"render --scene teapot --out " + (dir / "x.png").string(), "teapot"},
      {"render --scene spheres --size 12by4 --out " + (dir / "x.png").string(), "--size"},
      {"gbuffer --scene spheres --size 0x4 --out " + g.string() + ".2.exr", "--size"},
  };
  for (const auto& [args, culprit] : cases) {
    const CliRun r = runCli(args, dir);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(culprit), std::string::npos) << args << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
  std::filesystem::remove_all(dir);
}

}  // namespace
