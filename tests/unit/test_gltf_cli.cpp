// `brdfcl gbuffer/render --gltf` as a user runs them: render --spp 1 equals gbuffer followed by
// shade under the same lights and environment (perspective and orthographic cameras), the demo
// goes through the glTF path, and the glTF options' own errors (exit 2, one line, no output).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "host/src/gltf/demo_asset.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/image.hpp"
#include "gltf_builder.hpp"
#include "process.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

// Runs the CLI with its working directory in `dir` (the demo writes to ./out).
RunResult cli(const std::vector<std::string>& args, const ScratchDir& dir) {
  std::vector<std::string> argv{BRDFCL_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  ProcessOptions o;
  o.timeout = std::chrono::seconds(600);
  o.cwd = dir.dir();
  return runProcess(argv, dir.dir(), o);
}

// What a run left in `dir`, less the runner's own captures of stdout and stderr.
std::vector<std::string> leftFiles(const ScratchDir& dir) {
  std::vector<std::string> names;
  for (const auto& n : dir.list())
    if (n != "stdout" && n != "stderr") names.push_back(n);
  return names;
}

// The lights of a loaded asset as scene JSON (docs/gbuffer.md), so that shade sees what render saw.
std::string sceneJson(const std::vector<Light>& lights, const std::string& environment) {
  std::string items;
  for (const auto& l : lights) {
    const char* type = l.type == Light::Type::Directional ? "directional" : l.type == Light::Type::Point ? "point" : "spot";
    std::string item = fmt::format(R"({{"type": "{}", "color": [{:.9g}, {:.9g}, {:.9g}], "intensity": {:.9g})", type,
                                   l.color[0], l.color[1], l.color[2], l.intensity);
    if (l.type != Light::Type::Directional)
      item += fmt::format(R"(, "position": [{:.9g}, {:.9g}, {:.9g}])", l.position[0], l.position[1], l.position[2]);
    if (l.type != Light::Type::Point)
      item += fmt::format(R"(, "direction": [{:.9g}, {:.9g}, {:.9g}])", l.direction[0], l.direction[1], l.direction[2]);
    if (l.range > 0 && l.type != Light::Type::Directional) item += fmt::format(R"(, "range": {:.9g})", l.range);
    if (l.type == Light::Type::Spot)
      item += fmt::format(R"(, "spot": {{"innerConeAngle": {:.9g}, "outerConeAngle": {:.9g}}})", l.innerCone, l.outerCone);
    items += (items.empty() ? "" : ", ") + item + "}";
  }
  return fmt::format(R"({{"lights": [{}], "environment": {}}})", items, environment);
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// The render's linear EXR and the shaded G-buffer must agree bit for bit: the same kernel on the
// same inputs (the G-buffer is written as FLOAT, so the file holds exactly what render shaded).
void expectRenderEqualsGbufferThenShade(const std::string& asset, const std::vector<std::string>& extra,
                                        const ScratchDir& dir) {
  const gltf::Asset loaded = gltf::load(asset);
  std::vector<std::string> common{"--gltf", asset, "--size", "40x30"};
  common.insert(common.end(), extra.begin(), extra.end());

  std::vector<std::string> render{"render"};
  render.insert(render.end(), common.begin(), common.end());
  render.insert(render.end(), {"--spp", "1", "--environment", "studio", "--out", dir.path("r.png"), "--exr",
                               dir.path("r.exr"), "--gbuffer", dir.path("rg.exr")});
  const auto r = cli(render, dir);
  ASSERT_EQ(r.status, 0) << r.describe();

  auto gbuffer = common;
  gbuffer.insert(gbuffer.begin(), "gbuffer");
  gbuffer.insert(gbuffer.end(), {"--out", dir.path("g.exr")});
  const auto g = cli(gbuffer, dir);
  ASSERT_EQ(g.status, 0) << g.describe();

  const std::vector<Light> lights = loaded.lights;
  ASSERT_FALSE(lights.empty()) << "the test asset should carry KHR_lights_punctual lights";
  writeText(dir.path("scene.json"), sceneJson(lights, R"({"builtin": "studio"})"));
  const auto s = cli({"shade", "--gbuffer", dir.path("g.exr"), "--scene", dir.path("scene.json"), "--out", dir.path("s.exr")}, dir);
  ASSERT_EQ(s.status, 0) << s.describe();

  EXPECT_EQ(slurp(dir.path("g.exr")), slurp(dir.path("rg.exr"))) << "gbuffer and render --gbuffer wrote different files";
  int rw = 0, rh = 0, sw = 0, sh = 0;
  const auto rendered = readExrRgb(dir.path("r.exr"), rw, rh);
  const auto shaded = readExrRgb(dir.path("s.exr"), sw, sh);
  ASSERT_EQ(rw, sw);
  ASSERT_EQ(rh, sh);
  std::size_t differ = 0, first = 0;
  for (std::size_t i = 0; i < rendered.size(); ++i)
    if (std::memcmp(&rendered[i], &shaded[i], sizeof(float)) != 0) first = differ++ ? first : i;
  EXPECT_EQ(differ, 0u) << "first difference at pixel " << first / 3 << ": render " << rendered[first] << ", shade "
                        << shaded[first];
  // And the image is not trivially equal: the asset covers part of the frame and is lit.
  const GBuffer gb = readGBuffer(dir.path("g.exr"));
  double cover = 0;
  for (float m : gb.mask) cover += m;
  EXPECT_GT(cover, 0.05 * gb.mask.size());
  EXPECT_TRUE(gb.hasView()) << "a glTF G-buffer carries V";
}

TEST(GltfConsistency, RenderAtOneSampleEqualsGbufferThenShadePerspective) {
  ScratchDir dir("gltf-consistency");
  gltf::writeDemoAsset(dir.path("demo.glb"));
  expectRenderEqualsGbufferThenShade(dir.path("demo.glb"), {}, dir);
}

// An orthographic camera has one view direction for every pixel; the G-buffer's V channel carries
// it, so shade reproduces the render though the scene file's camera cannot express it.
TEST(GltfConsistency, RenderAtOneSampleEqualsGbufferThenShadeOrthographic) {
  ScratchDir dir("gltf-consistency-ortho");
  GltfBuilder b;
  b.useExtension("KHR_materials_sheen");
  b.useExtension("KHR_materials_clearcoat");
  const int material = b.addMaterial(
      {{"pbrMetallicRoughness", {{"baseColorFactor", {0.6, 0.3, 0.2, 1}}, {"metallicFactor", 0.2}, {"roughnessFactor", 0.5}}},
       {"extensions",
        {{"KHR_materials_sheen", {{"sheenColorFactor", {0.9, 0.8, 0.7}}, {"sheenRoughnessFactor", 0.4}}},
         {"KHR_materials_clearcoat", {{"clearcoatFactor", 0.7}, {"clearcoatRoughnessFactor", 0.2}}}}}});
  // A 2 x 2 quad facing +Z, tilted 30 degrees about X by its node.
  const int quad = b.addTriangles({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, {0, 1, 2, 0, 2, 3}, material,
                                  {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
  const int mesh = b.addMeshNode(quad, {{"rotation", {std::sin(0.2618), 0, 0, std::cos(0.2618)}}});
  // The camera sits on a child node (translation) of a parent turned 20 degrees about Y.
  const int camera = b.addCamera({{"type", "orthographic"},
                                  {"orthographic", {{"xmag", 1.6}, {"ymag", 1.2}, {"znear", 0.1}, {"zfar", 20}}}});
  const int eye = b.addNode({{"camera", camera}, {"translation", {0, 0, 6}}});
  const int rig = b.addNode({{"children", {eye}}, {"rotation", {0, std::sin(0.1745), 0, std::cos(0.1745)}}});
  const int spot = b.addLight({{"type", "spot"}, {"intensity", 40}, {"color", {1, 0.9, 0.8}},
                               {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}});
  const int point = b.addLight({{"type", "point"}, {"intensity", 15}, {"range", 30}});
  const int spotNode = b.addNode({{"translation", {0, 0, 4}}, {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
  const int pointNode = b.addNode({{"translation", {2, 2, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", point}}}}}});
  b.addScene({mesh, rig, spotNode, pointNode});
  const std::string path = b.write(dir.dir(), "ortho.gltf");
  ASSERT_TRUE(gltf::load(path).cameras.at(0).orthographic);
  expectRenderEqualsGbufferThenShade(path, {}, dir);
}

TEST(GltfCli, DemoRendersThroughTheGltfPath) {
  ScratchDir dir("gltf-demo");
  const auto r = cli({"demo", "--size", "48x48", "--spp", "1"}, dir);  // writes into <cwd>/out/
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_CONTAINS(r.out, "demo.glb");
  const gltf::Asset demo = gltf::load(dir.path("out/demo.glb"));
  EXPECT_EQ(demo.materials.size(), 36u);
  int w = 0, h = 0;
  const auto rgb = readExrRgb(dir.path("out/demo.exr"), w, h);
  EXPECT_EQ(w, 48);
  EXPECT_EQ(h, 48);
  const auto [lo, hi] = std::minmax_element(rgb.begin(), rgb.end());
  EXPECT_LT(*lo, 0.1f);
  EXPECT_GT(*hi, 0.5f);
}

TEST(GltfCli, OptionErrorsAreOneLineAndWriteNothing) {
  ScratchDir dir("gltf-cli-errors");
  gltf::writeDemoAsset(dir.path("demo.glb"));
  const std::string glb = dir.path("demo.glb"), png = dir.path("o.png");
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"render", "--gltf", glb, "--scene", "spheres", "--out", png}, "--scene and --gltf are alternatives"},
      {{"render", "--camera", "0", "--out", png}, "--camera applies to glTF assets; add --gltf FILE"},
      {{"gbuffer", "--variant", "x", "--out", dir.path("g.exr")}, "--variant applies to glTF assets"},
      {{"render", "--spp", "2", "--out", png}, "--spp applies to glTF assets"},
      {{"render", "--gltf", glb, "--spp", "0", "--out", png}, "--spp 0 is out of range; use 1 to 1024"},
      {{"render", "--gltf", glb, "--out", png, "--gbuffer", dir.path("g.png")}, "must end in .exr"},
      {{"render", "--gltf", glb, "--camera", "7", "--out", png}, "7"},
      {{"render", "--gltf", glb, "--camera", "front", "--out", png}, "front"},
      {{"render", "--gltf", glb, "--variant", "velvet", "--out", png}, "velvet"},
      {{"render", "--gltf", glb, "--gltf-scene", "3", "--out", png}, "3"},
      {{"render", "--gltf", glb, "--lights", dir.path("missing.json"), "--out", png}, "missing.json"},
      {{"render", "--gltf", glb, "--environment", "forest", "--out", png}, "--environment"},
      {{"render", "--gltf", dir.path("nothing.glb"), "--out", png}, "nothing.glb"},
  };
  for (const auto& c : cases) {
    const auto r = cli(c.args, dir);
    EXPECT_EQ(r.status, 2) << r.describe();
    ASSERT_EQ(r.errorLines().size(), 1u) << r.describe();
    EXPECT_CONTAINS(r.errorLines()[0], c.message);
    EXPECT_EQ(leftFiles(dir), std::vector<std::string>{"demo.glb"}) << "output left by: " << r.describe();
  }
}

}  // namespace
}  // namespace brdfcl::test
