// Tests of the G-buffer EXR reader/writer: round trips, every accepted naming, and every error path
// with the file in its one-line message. Each test works in its own temporary directory.
#include "gbuffer_fixture.hpp"

namespace {

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
  const std::string bytes = readFile(path("g.exr"));
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

}  // namespace
