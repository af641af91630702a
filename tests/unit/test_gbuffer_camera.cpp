// The camera a G-buffer carries in its EXR header: round trip, what the spheres and glTF G-buffers
// record, how `shade` uses it and warns when the scene's differs.
#include "gbuffer_camera_fixture.hpp"

namespace brdfcl::test {
namespace {

// ---- Camera attributes ----

TEST(GBufferCamera, AttributesRoundTripPerspectiveAndOrthographic) {
  ScratchDir dir("gbcam-roundtrip");
  for (const GBufferCamera& cam : {perspectiveCamera(), orthographicCamera()}) {
    for (bool half : {false, true}) {
      GBuffer g = validGBuffer(5, 3);
      g.camera = cam;
      writeGBuffer(dir.path("g.exr"), g, half);
      const GBuffer r = readGBuffer(dir.path("g.exr"));
      ASSERT_TRUE(r.camera.has_value()) << "orthographic " << cam.orthographic << " half " << half;
      expectSameCamera(*r.camera, cam);

      // The standard worldToCamera attribute maps the camera's position to the origin and a point
      // ahead of it onto the camera's -Z axis.
      Imf::InputFile in(dir.path("g.exr").c_str());
      ASSERT_TRUE(Imf::hasWorldToCamera(in.header()));
      const Imath::M44f m = Imf::worldToCamera(in.header());
      const Imath::V3f p(cam.position[0], cam.position[1], cam.position[2]);
      const Imath::V3f f(cam.forward[0], cam.forward[1], cam.forward[2]), u(cam.up[0], cam.up[1], cam.up[2]);
      EXPECT_LT((p * m).length(), 1e-5f);
      EXPECT_LT(((p + 2.0f * f) * m - Imath::V3f(0, 0, -2)).length(), 1e-5f);
      EXPECT_LT(((p + u) * m - Imath::V3f(0, 1, 0)).length(), 1e-5f);
      EXPECT_EQ(in.header().findTypedAttribute<Imf::StringAttribute>("brdfcl:cameraProjection")->value(),
                cam.orthographic ? "orthographic" : "perspective");
    }
  }
  // No camera in, none out, and no attribute written.
  writeGBuffer(dir.path("none.exr"), validGBuffer(2, 2));
  EXPECT_FALSE(readGBuffer(dir.path("none.exr")).camera.has_value());
  Imf::InputFile in(dir.path("none.exr").c_str());
  EXPECT_FALSE(Imf::hasWorldToCamera(in.header()));
}

// A G-buffer file with the given header attributes, written with OpenEXR directly.
void writeWithAttributes(const std::string& path, const std::function<void(Imf::Header&)>& attributes) {
  GBuffer g = validGBuffer(2, 2);
  ScratchDir tmp("gbcam-attr");
  writeGBuffer(tmp.path("g.exr"), g);
  Imf::InputFile in(tmp.path("g.exr").c_str());
  Imf::Header header = in.header();
  attributes(header);
  Imf::FrameBuffer fb;
  std::vector<std::vector<float>> planes;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) planes.emplace_back(4);
  std::size_t k = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it, ++k)
    fb.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(planes[k].data()), 4, 8));
  in.setFrameBuffer(fb);
  in.readPixels(0, 1);
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(fb);
  out.writePixels(2);
}

TEST(GBufferCamera, BadCameraAttributesAreOneLineErrors) {
  ScratchDir dir("gbcam-bad");
  const std::string p = dir.path("g.exr");
  // `skip` leaves one attribute out: OpenEXR 3.1's Header::erase leaks the attribute it removes.
  auto perspective = [](Imf::Header& h, const std::string& skip = "") {
    auto put = [&](const char* name, const Imf::Attribute& a) {
      if (skip != name) h.insert(name, a);
    };
    put("brdfcl:cameraProjection", Imf::StringAttribute("perspective"));
    put("brdfcl:cameraPosition", Imf::V3fAttribute(Imath::V3f(0, 0, 5)));
    put("brdfcl:cameraOrientation", Imf::M33fAttribute(Imath::M33f()));
    put("brdfcl:cameraFov", Imf::FloatAttribute(40.0f));
    put("brdfcl:cameraNear", Imf::FloatAttribute(0.0f));
    put("brdfcl:cameraFar", Imf::FloatAttribute(0.0f));
  };
  writeWithAttributes(p, [&](Imf::Header& h) { perspective(h); });
  ASSERT_TRUE(readGBuffer(p).camera.has_value());
  const std::string fix = "; fix the camera attributes (docs/gbuffer.md) or remove every brdfcl:camera attribute";

  writeWithAttributes(p, [](Imf::Header& h) { h.insert("brdfcl:cameraFov", Imf::FloatAttribute(40.0f)); });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }), p + ": missing header attribute brdfcl:cameraProjection" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) { perspective(h, "brdfcl:cameraFov"); });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": missing header attribute brdfcl:cameraFov (required for a perspective camera)" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h, "brdfcl:cameraPosition");
    h.insert("brdfcl:cameraPosition", Imf::StringAttribute("0 0 5"));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": header attribute brdfcl:cameraPosition has type string; expected v3f" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h);
    h.insert("brdfcl:cameraProjection", Imf::StringAttribute("fisheye"));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": header attribute brdfcl:cameraProjection is 'fisheye'; expected perspective or orthographic" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h);
    h.insert("brdfcl:cameraOrientation", Imf::M33fAttribute(Imath::M33f(1, 0, 0, 0, 1, 0, 0, 0, -1)));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": header attribute brdfcl:cameraOrientation is not a rotation; its rows must be the camera's unit "
                "right, up and back (-forward) axes, orthogonal and right-handed" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h);
    h.insert("brdfcl:cameraFov", Imf::FloatAttribute(180.0f));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }), p + ": header attribute brdfcl:cameraFov = 180 is outside (0, 180) degrees" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h);
    h.insert("brdfcl:cameraPosition", Imf::V3fAttribute(Imath::V3f(0, std::numeric_limits<float>::quiet_NaN(), 5)));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }), p + ": header attribute brdfcl:cameraPosition has a non-finite value (nan)" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h);
    h.insert("brdfcl:cameraProjection", Imf::StringAttribute("orthographic"));
    h.insert("brdfcl:cameraXMag", Imf::FloatAttribute(1.0f));
    h.insert("brdfcl:cameraYMag", Imf::FloatAttribute(0.0f));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }), p + ": header attribute brdfcl:cameraYMag = 0 must be a finite number > 0" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h);
    h.insert("brdfcl:cameraNear", Imf::FloatAttribute(-1.0f));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }), p + ": header attribute brdfcl:cameraNear = -1 must be a finite number >= 0" + fix);
  writeWithAttributes(p, [&](Imf::Header& h) {
    perspective(h);
    h.insert("brdfcl:cameraFar", Imf::FloatAttribute(-2.0f));
  });
  EXPECT_EQ(errorOf([&] { readGBuffer(p); }),
            p + ": header attribute brdfcl:cameraFar = -2 must be a finite number >= 0 (0: infinite)" + fix);
  // Only the standard attribute, as another renderer may write it: no brdfcl camera.
  writeWithAttributes(p, [](Imf::Header& h) { Imf::addWorldToCamera(h, Imath::M44f()); });
  EXPECT_FALSE(readGBuffer(p).camera.has_value());
}

// The spheres' G-buffer records the camera it was ray-cast with: the built-in scene's, in
// memory and through `gbuffer`.
TEST(GBufferCamera, SpheresGBufferCarriesItsCamera) {
  GBufferCamera expected;
  expected.position = {0.0f, 0.0f, 13.0f};
  expected.right = {1.0f, 0.0f, 0.0f};
  expected.up = {0.0f, 1.0f, 0.0f};
  expected.forward = {0.0f, 0.0f, -1.0f};
  expected.fovDegrees = 30.0f;
  const GBuffer g = renderSpheresGBuffer(runtime(), spheresScene(), 32, 24);
  ASSERT_TRUE(g.camera.has_value());
  expectSameCamera(*g.camera, expected);

  ScratchDir dir("gbcam-spheres");
  const RunResult a = cli({"gbuffer", "--scene", "spheres", "--size", "32x32", "--out", dir.path("g.exr")}, dir);
  ASSERT_EQ(a.status, 0) << a.describe();
  const GBuffer r = readGBuffer(dir.path("g.exr"));
  ASSERT_TRUE(r.camera.has_value());
  expectSameCamera(*r.camera, expected);
  // render --gbuffer writes renderSpheresGBuffer's G-buffer too (render/render_job.cpp renderPrepared), camera and all.
}

// glTF G-buffers record the view they were traced with: a perspective camera node (the demo
// asset's, through the CLI) and an orthographic one (in memory).
TEST(GBufferCamera, GltfGBufferCarriesItsCamera) {
  ScratchDir dir("gbcam-gltf");
  const std::string glb = dir.path("demo.glb");
  gltf::writeDemoAsset(glb);
  const RunResult a = cli({"gbuffer", "--gltf", glb, "--size", "24x24", "--out", dir.path("g.exr")}, dir);
  ASSERT_EQ(a.status, 0) << a.describe();
  const GBuffer r = readGBuffer(dir.path("g.exr"));
  ASSERT_TRUE(r.camera.has_value());
  const gltf::Asset asset = gltf::load(glb);
  ASSERT_FALSE(asset.cameras.empty());
  const gltf::View v = gltf::chooseView(asset, "", 24, 24);
  const GBufferCamera& c = *r.camera;
  EXPECT_FALSE(c.orthographic);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(c.position[k], float(v.position[k]));
    EXPECT_EQ(c.right[k], float(v.right[k]));
    EXPECT_EQ(c.up[k], float(v.up[k]));
    EXPECT_EQ(c.forward[k], float(v.forward[k]));
  }
  EXPECT_NEAR(c.fovDegrees, asset.cameras[0].yfov * 180.0 / M_PI, 1e-4);
  EXPECT_NEAR(c.fovDegrees, 30.0, 1e-4);  // the demo camera's yfov
  EXPECT_EQ(c.znear, float(asset.cameras[0].znear));
  EXPECT_EQ(c.zfar, 0.0f);

  gltf::Asset as;
  as.materials.emplace_back();
  as.primitives.push_back(quad(-0.5, -0.5, 0.5, 0.5, 0, 0));
  gltf::Camera cam = frontOrtho(0.75, 4.0);
  cam.index = 0;
  cam.znear = 0.5;
  cam.zfar = 20;
  as.cameras.push_back(cam);
  gltf::Raycaster rc(as);
  const gltf::View ov = gltf::chooseView(as, "", 20, 10);
  const GBuffer og = rc.trace(ov, 20, 10);
  ASSERT_TRUE(og.camera.has_value());
  EXPECT_TRUE(og.camera->orthographic);
  EXPECT_EQ(og.camera->ymag, 0.75f);
  EXPECT_EQ(og.camera->xmag, 1.5f);  // ymag times the image's aspect, as the rays are cast
  EXPECT_EQ(og.camera->znear, 0.5f);
  EXPECT_EQ(og.camera->zfar, 20.0f);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(og.camera->position[k], float(ov.position[k]));
  writeGBuffer(dir.path("o.exr"), og);
  const GBuffer orr = readGBuffer(dir.path("o.exr"));
  ASSERT_TRUE(orr.camera.has_value());
  expectSameCamera(*orr.camera, *og.camera);
}

// ---- shade and the camera ----

TEST(GBufferCamera, SceneFileWithoutCameraIsTold) {
  EXPECT_FALSE(parseScene(std::string("{") + kLights + "}", "s.json", "").hasCamera);
  EXPECT_TRUE(parseScene(R"({"camera": {"position": [0, 0, 13]}})", "s.json", "").hasCamera);
  EXPECT_TRUE(spheresScene().hasCamera);
}

// Without a camera in the scene file, shade looks from the G-buffer's camera: the same image,
// bit for bit, as with the scene camera that made it (background pixels included), and not the
// image of the stand-in default camera. In process: the shade command's readGBuffer, readScene
// and Shader.
TEST(GBufferCamera, ShadeWithoutSceneCameraUsesTheGBuffers) {
  ScratchDir dir("gbcam-shade");
  const std::string g = dir.path("g.exr");
  ASSERT_EQ(cli({"gbuffer", "--scene", "spheres", "--size", "32x32", "--out", g}, dir).status, 0);
  std::ofstream(dir.path("none.json")) << "{" << kLights << ", " << tinyEnvironment(dir) << "}";
  std::ofstream(dir.path("same.json")) << R"({"camera": {"position": [0, 0, 13], "target": [0, 0, 0], "fov": 30}, )"
                                       << kLights << ", " << tinyEnvironment(dir) << "}";
  std::ofstream(dir.path("default.json")) << R"({"camera": {"position": [0, 0, 5]}, )" << kLights
                                          << ", " << tinyEnvironment(dir) << "}";
  const GBuffer gb = readGBuffer(g);
  auto shade = [&](const char* name) {
    const Scene scene = readScene(dir.path(std::string(name) + ".json"));
    EXPECT_EQ(shadeCameraWarning(name, scene, "g.exr", gb).empty(), name != std::string("default")) << name;
    return Shader(runtime(), scene).shade(gb).rgb;
  };
  const auto none = shade("none"), same = shade("same");
  EXPECT_EQ(none, same);
  EXPECT_NE(none, shade("default"));
}

// An orthographic G-buffer camera without V: every pixel looks along its forward axis, as if
// the G-buffer carried V = -forward.
TEST(GBufferCamera, OrthographicCameraWithoutVLooksAlongForward) {
  GBuffer g = validGBuffer(8, 4);
  for (std::size_t i = 0; i < g.pixelCount(); i += 3) g.mask[i] = 0.0f;  // some background
  g.camera = orthographicCamera();
  GBuffer withV = g;
  for (std::size_t i = 0; i < g.pixelCount(); ++i)
    for (int k = 0; k < 3; ++k) withV.V.push_back(-g.camera->forward[k]);
  ScratchDir dir("gbcam-ortho");
  tinyEnvironment(dir);
  Scene lighting = spheresScene();
  lighting.environment.builtin = false;
  lighting.environment.path = dir.path("env.exr");
  lighting.hasCamera = false;  // the stand-in camera: the G-buffer's wins
  Shader shader(runtime(), lighting);
  const Image a = shader.shade(g), b = shader.shade(withV);
  EXPECT_LT(maxDifference(a.rgb, b.rgb), 1e-5);
  g.camera.reset();  // the stand-in pinhole gives another image
  EXPECT_GT(maxDifference(shader.shade(g).rgb, b.rgb), 1e-2);
}

TEST(GBufferCamera, ShadeWarnsWhenTheCamerasDiffer) {
  // Through the CLI once: the line as the user sees it, and shade goes on.
  ScratchDir dir("gbcam-warn");
  const std::string g = dir.path("g.exr");
  ASSERT_EQ(cli({"gbuffer", "--scene", "spheres", "--size", "32x32", "--out", g}, dir).status, 0);
  const std::string s = dir.path("s.json");
  std::ofstream(s) << R"({"camera": {"position": [0, 0, 12.2], "fov": 40}, )" << kLights << ", " << tinyEnvironment(dir) << "}";
  const RunResult r = cli({"shade", "--gbuffer", g, "--scene", s, "--out", dir.path("o.exr")}, dir);
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(r.warningLines(),
            std::vector<std::string>{"brdfcl: warning: the camera of " + s + " differs from the one that made " + g +
                                     " (position differs by 0.8 (0, 0, 12.2 vs 0, 0, 13), fov 40° vs 30°); shading "
                                     "with the scene's camera, which " + s +
                                     " gives explicitly (remove its \"camera\" to use the G-buffer's)"});
  // The scene's camera was used: the same image as the scene's camera on a G-buffer without one.
  GBuffer plain = readGBuffer(g);
  plain.camera.reset();
  EXPECT_EQ(readRgb(dir.path("o.exr")), Shader(runtime(), readScene(s)).shade(plain).rgb);

  // A rotated view is named in degrees; so is a rolled one.
  Scene turned = spheresScene();
  turned.cameraTarget = {1, 0, 0};
  const GBufferCamera made = *readGBuffer(g).camera;  // a copy: the G-buffer read is a temporary
  EXPECT_EQ(cameraDifference(turned, made), "view direction differs by 4.4°");
  GBufferCamera rolled = made;
  rolled.up = {0.0f, -1.0f, 0.0f};
  rolled.right = {-1.0f, 0.0f, 0.0f};
  EXPECT_EQ(cameraDifference(spheresScene(), rolled), "up direction differs by 180°");
  GBufferCamera ortho = made;
  ortho.orthographic = true;
  ortho.ymag = 2.0f;
  EXPECT_EQ(cameraDifference(spheresScene(), ortho), "projection perspective (fov 30°) vs orthographic (ymag 2)");
  EXPECT_EQ(cameraDifference(spheresScene(), made), "");
  // Float rounding of a re-derived camera is no difference.
  GBufferCamera nudged = made;
  nudged.position[2] = std::nextafter(13.0f, 14.0f);
  nudged.fovDegrees = std::nextafter(30.0f, 0.0f);
  EXPECT_EQ(cameraDifference(spheresScene(), nudged), "");

  // With V, neither camera is used, and the warning says so.
  GBuffer withView = plain;
  withView.camera = made;
  withView.V.assign(3 * withView.pixelCount(), 1.0f);
  EXPECT_EQ(shadeCameraWarning("s.json", turned, "v.exr", withView),
            "the camera of s.json differs from the one that made v.exr (view direction differs by 4.4°); v.exr's V "
            "channels give every pixel's view, so neither camera changes the image");
  // Neither file has a camera, and the G-buffer has no V: the stand-in default is named.
  const Scene standIn = parseScene("{}", "s.json", "");
  EXPECT_EQ(shadeCameraWarning("s.json", standIn, "g.exr", plain),
            "neither s.json nor g.exr has a camera; shading with the default camera at (0, 0, 5) looking at (0, 0, 0) "
            "(add \"camera\" to s.json)");
  EXPECT_EQ(shadeCameraWarning("s.json", standIn, "g.exr", withView), "");  // V: nothing to say
  EXPECT_EQ(shadeCameraWarning("s.json", standIn, "g.exr", readGBuffer(g)), "");  // the G-buffer's camera is used
}

}  // namespace
}  // namespace brdfcl::test
