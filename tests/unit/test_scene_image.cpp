// Tests of the image helpers (EXR RGB, PBR Neutral, sRGB, PNG) and the scene JSON reader: round
// trips, known values, and every error path with the file and JSON key path in its one-line message.
#include "gbuffer_fixture.hpp"

namespace {

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
  const std::string bytes = readFile(path("o.png"));
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
  EXPECT_EQ(readFile(path("keep.png")), "old");
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
