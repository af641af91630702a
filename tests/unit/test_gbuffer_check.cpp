// readGBuffer's value check (factors in [0, 1], unit normals, --no-check), through the library and
// `shade`, on brdfcl's own G-buffers too.
#include "gbuffer_camera_fixture.hpp"

namespace brdfcl::test {
namespace {

// ---- The value check ----

TEST(GBufferCheck, OutOfRangeValuesAreErrorsNamingPixelAndChannel) {
  ScratchDir dir("gbcheck");
  const std::string p = dir.path("g.exr");
  const std::string fix = "; fix the G-buffer or pass --no-check";
  struct Case {
    std::function<void(GBuffer&)> spoil;
    std::string message;
  };
  const std::size_t i = 2 * 7 + 4;  // pixel (4, 2) of 7 x 5
  const std::vector<Case> cases = {
      {[&](GBuffer& g) { g.roughness[i] = 1.3f; }, "pixel (4, 2): channel roughness = 1.3 is outside [0, 1]"},
      {[&](GBuffer& g) { g.metallic[i] = -0.25f; }, "pixel (4, 2): channel metallic = -0.25 is outside [0, 1]"},
      {[&](GBuffer& g) { g.baseColor[3 * i + 1] = 1.5f; }, "pixel (4, 2): channel baseColor.G = 1.5 is outside [0, 1]"},
      {[&](GBuffer& g) { g.sheenColor[3 * i + 2] = 2.0f; }, "pixel (4, 2): channel sheenColor.B = 2 is outside [0, 1]"},
      {[&](GBuffer& g) { g.sheenRoughness[i] = 1.01f; }, "pixel (4, 2): channel sheenRoughness = 1.01 is outside [0, 1]"},
      {[&](GBuffer& g) { g.clearcoat[i] = 3.0f; }, "pixel (4, 2): channel clearcoat = 3 is outside [0, 1]"},
      {[&](GBuffer& g) { g.clearcoatRoughness[i] = -1.0f; }, "pixel (4, 2): channel clearcoatRoughness = -1 is outside [0, 1]"},
      {[&](GBuffer& g) { g.anisotropyStrength[i] = 1.125f; }, "pixel (4, 2): channel anisotropyStrength = 1.125 is outside [0, 1]"},
      {[&](GBuffer& g) { g.occlusion[i] = 1.5f; }, "pixel (4, 2): channel occlusion = 1.5 is outside [0, 1]"},
      {[&](GBuffer& g) { g.emissive[3 * i] = -0.5f; }, "pixel (4, 2): channel emissive.R = -0.5 is outside [0, inf)"},
      {[&](GBuffer& g) { g.N[3 * i] = 0.0f, g.N[3 * i + 1] = 0.0f, g.N[3 * i + 2] = 1.01f; },
       "pixel (4, 2): vector N = (0, 0, 1.01) has length 1.01, not 1 within 0.001"},
      {[&](GBuffer& g) { g.clearcoatN[3 * i] *= 0.9f, g.clearcoatN[3 * i + 1] *= 0.9f, g.clearcoatN[3 * i + 2] *= 0.9f; },
       "pixel (4, 2): vector clearcoatN = "},
      {[&](GBuffer& g) { g.T[3 * i] = g.T[3 * i + 1] = g.T[3 * i + 2] = 0.0f; },
       "pixel (4, 2): vector T = (0, 0, 0) has length 0, not 1 within 0.001"},
  };
  for (const Case& c : cases) {
    GBuffer g = validGBuffer(7, 5);
    c.spoil(g);
    writeGBuffer(p, g);
    const std::string m = errorOf([&] { readGBuffer(p); });
    EXPECT_EQ(m.rfind(p + ": " + c.message, 0), 0u) << m;
    EXPECT_EQ(m.substr(m.size() - fix.size()), fix) << m;
    // The check of a G-buffer in memory (Python's dict) says the same, naming its source and switch.
    const std::string inMemory = errorOf([&] { checkGBufferValues(g, "<gbuffer>", "check=False"); });
    EXPECT_EQ(inMemory, "<gbuffer>: " + m.substr(p.size() + 2, m.size() - p.size() - 2 - fix.size()) +
                            "; fix the G-buffer or pass check=False");
    // Passes unchecked; and the same value on a background pixel is nobody's concern.
    GBufferReadOptions unchecked;
    unchecked.check = false;
    EXPECT_NO_THROW(readGBuffer(p, unchecked)) << c.message;
    g.mask[i] = 0.0f;
    writeGBuffer(p, g);
    EXPECT_NO_THROW(readGBuffer(p)) << c.message;
    EXPECT_NO_THROW(checkGBufferValues(g, "<gbuffer>", "check=False")) << c.message;
  }
  // The first failure in raster order is the one named.
  GBuffer g = validGBuffer(7, 5);
  g.roughness[30] = 2.0f;
  g.metallic[9] = 2.0f;
  g.occlusion[9] = 2.0f;
  writeGBuffer(p, g);
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }), p + ": pixel (2, 1): channel metallic = 2 is outside [0, 1]" + fix);
  // A length within the tolerance passes.
  g = validGBuffer(7, 5);
  for (int k = 0; k < 3; ++k) g.N[3 * i + k] *= 1.0009f;
  writeGBuffer(p, g);
  EXPECT_NO_THROW(readGBuffer(p));
}

// The same through shade: exit 2 and one line naming pixel and channel, an image with
// --no-check. A NaN is refused either way: no image can be made of it.
TEST(GBufferCheck, ShadeRefusesOutOfRangeUnlessNoCheck) {
  ScratchDir dir("gbcheck-cli");
  const std::string s = dir.path("s.json");
  std::ofstream(s) << R"({"camera": {"position": [0, 0, 5]}, )" << kLights << ", " << tinyEnvironment(dir) << "}";
  const std::string g = dir.path("g.exr"), out = dir.path("o.exr");
  auto refused = [&](const std::function<void(GBuffer&)>& spoil, const std::string& message) {
    GBuffer gb = validGBuffer(8, 4);
    spoil(gb);
    writeGBuffer(g, gb);
    const RunResult r = cli({"shade", "--gbuffer", g, "--scene", s, "--out", out}, dir);
    EXPECT_EQ(r.status, 2) << r.describe();
    EXPECT_EQ(r.errorLines(), std::vector<std::string>{"brdfcl: " + g + ": " + message}) << r.describe();
    EXPECT_FALSE(std::filesystem::exists(out));
  };
  auto roughness = [](GBuffer& gb) { gb.roughness[5] = 1.3f; };
  auto normal = [](GBuffer& gb) { gb.N[3 * 9] = 0.0f, gb.N[3 * 9 + 1] = 0.0f, gb.N[3 * 9 + 2] = 1.01f; };
  refused(roughness, "pixel (5, 0): channel roughness = 1.3 is outside [0, 1]; fix the G-buffer or pass --no-check");
  refused(normal, "pixel (1, 1): vector N = (0, 0, 1.01) has length 1.01, not 1 within 0.001; fix the G-buffer or pass --no-check");
  // Both at once pass unchecked.
  GBuffer gb = validGBuffer(8, 4);
  roughness(gb);
  normal(gb);
  writeGBuffer(g, gb);
  RunResult r = cli({"shade", "--gbuffer", g, "--scene", s, "--out", out, "--no-check"}, dir);
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(std::filesystem::exists(out));
  std::filesystem::remove(out);
  // A NaN: refused by the reader with or without the check.
  gb.metallic[2] = std::numeric_limits<float>::quiet_NaN();
  writeGBuffer(g, gb);
  for (const char* extra : {"--exposure=0", "--no-check"}) {
    r = cli({"shade", "--gbuffer", g, "--scene", s, "--out", out, extra}, dir);
    EXPECT_EQ(r.status, 2) << r.describe();
    EXPECT_EQ(r.errorLines(), std::vector<std::string>{"brdfcl: " + g +
                                                       ": pixel (2, 0) has a non-finite value (nan) in channel "
                                                       "'metallic'; fix the renderer's output"})
        << r.describe();
    EXPECT_FALSE(std::filesystem::exists(out));
  }
}

// brdfcl's own G-buffers pass the check, FLOAT and HALF: the spheres, and every glTF sample
// asset that is present (normal-mapped, anisotropic, clearcoated, textured).
TEST(GBufferCheck, BrdfclsOwnGBuffersPass) {
  ScratchDir dir("gbcheck-own");
  for (bool half : {false, true}) {
    writeGBuffer(dir.path("s.exr"), renderSpheresGBuffer(runtime(), spheresScene(), 96, 96), half);
    const GBuffer r = readGBuffer(dir.path("s.exr"));
    EXPECT_TRUE(r.camera.has_value());
  }
  const std::string assets = assetsDir();
  if (assets.empty()) GTEST_SKIP() << "no sample assets ($BRDFCL_ASSETS)";
  int checked = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(assets)) {
    const std::string ext = e.path().extension().string();
    // The KTX2 lamp is refused on load (docs/gltf.md); its plain glTF variant is checked.
    if ((ext != ".gltf" && ext != ".glb") || e.path().string().find("KTX2") != std::string::npos) continue;
    SCOPED_TRACE(e.path().string());
    const gltf::Asset asset = gltf::load(e.path().string());
    gltf::Raycaster rc(asset);
    for (const char* camera : {"", "auto"}) {
      const GBuffer g = rc.trace(gltf::chooseView(asset, camera, 64, 48), 64, 48);
      for (bool half : {false, true}) {
        writeGBuffer(dir.path("a.exr"), g, half);
        EXPECT_NO_THROW(readGBuffer(dir.path("a.exr"))) << camera << " half " << half;
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace brdfcl::test
