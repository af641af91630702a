// Memory bounded by what an input honestly claims: images refused from their headers (textures,
// environments, diff images, G-buffers) before decoding, the JSON and stream byte cap, the CSV
// line cap, the variables that move the limits, and the out-of-memory message naming the input.
#include <gtest/gtest.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/image.hpp"
#include "gltf_builder.hpp"
#include "io/input_limits.hpp"
#include "cli_child.hpp"
#include "process.hpp"
#include "support.hpp"

using namespace brdfcl;
using brdfcl::test::expectOneLineError;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::writeFile;

namespace {

// Memory for a child that must refuse an input from its header; the old behaviour (decoding
// gigabytes) fails inside it. 0 under AddressSanitizer, whose shadow memory needs the address space.
std::size_t childAddressSpaceMiB() { return brdfcl::test::kAddressSanitizer ? 0 : 2048; }

RunResult cli(const ScratchDir& dir, std::vector<std::string> args, std::map<std::string, std::string> env = {},
              std::size_t addressSpaceMiB = childAddressSpaceMiB()) {
  brdfcl::test::ProcessOptions o;
  o.env = std::move(env);
  o.addressSpaceMiB = addressSpaceMiB;
  o.timeout = std::chrono::seconds(60);
  return brdfcl::test::runCli(dir, std::move(args), std::move(o));
}

// A refusal from the header reads a few kilobytes: far below the gigabytes the image declares.
// Under AddressSanitizer the CLI starts at about 0.7 GiB resident (shadow memory and PoCL), so
// the bound there is 1.5 GiB, still well below what decoding the declared images would take.
void expectSmall(const RunResult& r) {
  const long limitKiB = (brdfcl::test::kAddressSanitizer ? 1536 : 400) * 1024;
  EXPECT_LT(r.maxRssKiB, limitKiB) << r.describe();
}

// Sets an environment variable for the object's lifetime, then restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* v = std::getenv(name)) saved_ = v, had_ = true;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { had_ ? ::setenv(name_, saved_.c_str(), 1) : ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::string saved_;
  bool had_ = false;
};

std::uint32_t crc32(const std::string& bytes, std::size_t from, std::size_t to) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = from; i < to; ++i) {
    c ^= std::uint8_t(bytes[i]);
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

void putBe32(std::string& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + i] = char(v >> (24 - 8 * i));
}

// A 2x2 PNG whose IHDR (with a correct CRC) declares width x height: a few hundred bytes that
// claim gigabytes once decoded.
std::string pngDeclaring(std::uint32_t width, std::uint32_t height) {
  std::string png = brdfcl::test::encodePng8(2, 2, 3, std::vector<std::uint8_t>(12, 128));
  putBe32(png, 16, width);
  putBe32(png, 20, height);
  putBe32(png, 29, crc32(png, 12, 29));
  return png;
}

// A textured quad whose only image is `png`, stored as the external file big.png.
std::string gltfWithTexture(const ScratchDir& dir, const std::string& png) {
  brdfcl::test::GltfBuilder b;
  const int texture = b.addTexture(b.addImage(png, "image/png", "big.png"));
  const int material = b.addMaterial({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
  b.addScene({b.addMeshNode(b.addTriangles({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 0, 2, 3}, material, {},
                                           {0, 0, 1, 0, 1, 1, 0, 1}))});
  return b.write(dir.dir(), "m.gltf", brdfcl::test::Storage::ExternalFiles);
}

// A Radiance HDR of width x height whose scan lines are valid run-length data of one colour:
// about a kilobyte per line for 16384 pixels, so a 16384x8192 image is 8.5 MB.
std::string rleHdr(int width, int height) {
  std::string s = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
  std::string line = {2, 2, char(width >> 8), char(width & 0xFF)};
  for (int c = 0; c < 4; ++c)
    for (int x = 0; x < width;) {
      const int n = std::min(127, width - x);
      line += char(128 + n);
      line += char(c == 3 ? 128 : 100);
      x += n;
    }
  s.reserve(s.size() + line.size() * std::size_t(height));
  for (int y = 0; y < height; ++y) s += line;
  return s;
}

// An EXR of width x height FLOAT channels, all zero, written from one row (a zero y stride): a
// large image in a small file, as a real flat render compresses.
void writeZeroExr(const std::string& path, int width, int height, const std::vector<std::string>& channels,
                  Imf::Compression compression = Imf::ZIP_COMPRESSION) {
  std::vector<float> row(std::size_t(width), 0.0f);
  Imf::Header header(width, height);
  header.compression() = compression;
  Imf::FrameBuffer fb;
  for (const auto& c : channels) {
    header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    fb.insert(c, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(row.data()), sizeof(float), 0));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(fb);
  out.writePixels(height);
}

const std::vector<std::string> kGBufferChannels = {"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "baseColor.R", "baseColor.G",
                                                  "baseColor.B", "metallic", "roughness", "mask"};

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

double secondsOf(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const char* const kMaterials =
    R"({"materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "roughnessFactor": 0.5}}]})";

}  // namespace

TEST(InputBounds, TextureDeclaringMorePixelsThanTheLimitIsRefusedFromItsHeader) {
  ScratchDir dir("bounds");
  const std::string path = gltfWithTexture(dir, pngDeclaring(16384, 16384));
  std::string e;
  const double s = secondsOf([&] { e = errorOf([&] { gltf::load(path); }); });
  EXPECT_NE(e.find("m.gltf: images[0] ('big.png') declares 16384x16384 pixels (268M), more than the 67M a texture may "
                   "have; set BRDFCL_MAX_IMAGE_PIXELS to allow it"),
            std::string::npos)
      << e;
  EXPECT_LT(s, 1.0);
}

TEST(InputBounds, ImagePixelsVariableMovesTheTextureLimitBothWays) {
  ScratchDir dir("bounds");
  const std::string path = gltfWithTexture(dir, brdfcl::test::encodePng8(16, 16, 3, std::vector<std::uint8_t>(768, 9)));
  {
    ScopedEnv env("BRDFCL_MAX_IMAGE_PIXELS", "255");
    EXPECT_NE(errorOf([&] { gltf::load(path); })
                  .find("images[0] ('big.png') declares 16x16 pixels (256), more than BRDFCL_MAX_IMAGE_PIXELS=255 allows"),
              std::string::npos);
  }
  {
    ScopedEnv env("BRDFCL_MAX_IMAGE_PIXELS", "256");
    EXPECT_EQ(errorOf([&] { gltf::load(path); }), "");
  }
  // Raised above the defaults, the larger images pass the check (decoding is then the caller's risk).
  ScopedEnv env("BRDFCL_MAX_IMAGE_PIXELS", std::to_string(1LL << 28));
  EXPECT_EQ(detail::imagePixelRefusal(detail::ImageKind::Texture, 16384, 16384), "");
  EXPECT_EQ(detail::imagePixelRefusal(detail::ImageKind::Environment, 16384, 8192), "");
  EXPECT_EQ(detail::imagePixelRefusal(detail::ImageKind::DiffImage, 8192, 8192), "");
}

TEST(InputBounds, DefaultPixelLimitsPerKind) {
  ::unsetenv("BRDFCL_MAX_IMAGE_PIXELS");
  EXPECT_EQ(detail::imagePixelRefusal(detail::ImageKind::Texture, 8192, 8192), "");
  EXPECT_NE(detail::imagePixelRefusal(detail::ImageKind::Texture, 8193, 8192), "");
  EXPECT_EQ(detail::imagePixelRefusal(detail::ImageKind::Environment, 8192, 8192), "");
  EXPECT_EQ(detail::imagePixelRefusal(detail::ImageKind::Environment, 16384, 8192),
            "declares 16384x8192 pixels (134M), more than the 67M an environment may have; set "
            "BRDFCL_MAX_IMAGE_PIXELS to allow it");
  EXPECT_EQ(detail::imagePixelRefusal(detail::ImageKind::DiffImage, 8192, 4096), "");
  EXPECT_NE(detail::imagePixelRefusal(detail::ImageKind::DiffImage, 8192, 8192), "");
}

TEST(InputBounds, BadLimitVariablesAreOneLineErrors) {
  ScratchDir dir("bounds");
  writeFile(dir.path("m.json"), kMaterials);
  writeFile(dir.path("s.csv"), "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n");
  expectOneLineError(cli(dir, {"eval", "--materials", "m.json", "--samples", "s.csv", "--grid", "--out", "o.csv"},
                         {{"BRDFCL_MAX_JSON_BYTES", "lots"}}),
                     "BRDFCL_MAX_JSON_BYTES=lots is not a positive whole number; unset it or give e.g. 1073741824");
  ScopedEnv env("BRDFCL_MAX_IMAGE_PIXELS", "-5");
  EXPECT_EQ(errorOf([] { detail::imagePixelRefusal(detail::ImageKind::Texture, 1, 1); }),
            "BRDFCL_MAX_IMAGE_PIXELS=-5 is not a positive whole number; unset it or give e.g. 268435456");
}

TEST(InputBounds, RleHdrEnvironmentDeclaringMorePixelsThanTheLimitIsRefusedBeforeDecoding) {
  ScratchDir dir("bounds");
  writeFile(dir.path("sky.hdr"), rleHdr(16384, 8192));
  int w = 0, h = 0;
  std::string e;
  const double s = secondsOf([&] { e = errorOf([&] { readEnvironmentRgb(dir.path("sky.hdr"), w, h); }); });
  EXPECT_NE(e.find("sky.hdr declares 16384x8192 pixels (134M), more than the 67M an environment may have; set "
                   "BRDFCL_MAX_IMAGE_PIXELS to allow it"),
            std::string::npos)
      << e;
  EXPECT_LT(s, 2.0);
  // The same encoding at a size within the limit decodes.
  writeFile(dir.path("small.hdr"), rleHdr(64, 32));
  EXPECT_EQ(readEnvironmentRgb(dir.path("small.hdr"), w, h).size(), 3u * 64 * 32);
}

TEST(InputBounds, ExrEnvironmentIsCheckedFromItsHeader) {
  ScratchDir dir("bounds");
  writeZeroExr(dir.path("env.exr"), 64, 32, {"R", "G", "B"});
  int w = 0, h = 0;
  ScopedEnv env("BRDFCL_MAX_IMAGE_PIXELS", "2047");
  EXPECT_NE(errorOf([&] { readEnvironmentRgb(dir.path("env.exr"), w, h); })
                .find("env.exr declares 64x32 pixels (2048), more than BRDFCL_MAX_IMAGE_PIXELS=2047 allows"),
            std::string::npos);
}

TEST(InputBounds, DiffOfExrDeclaringMorePixelsThanTheLimitIsRefusedFromItsHeader) {
  ScratchDir dir("bounds");
  writeZeroExr(dir.path("a.exr"), 8192, 8192, {"Y"});
  writeZeroExr(dir.path("b.exr"), 16, 16, {"Y"});
  // The first named file is checked, whichever is large, before either is decoded.
  for (const auto& args : {std::vector<std::string>{"diff", "a.exr", "b.exr"}, std::vector<std::string>{"diff", "b.exr", "a.exr"}}) {
    const RunResult r = cli(dir, args);
    expectOneLineError(r, "a.exr declares 8192x8192 pixels (67M), more than the 33M an image to diff may have; set "
                          "BRDFCL_MAX_IMAGE_PIXELS to allow it");
    expectSmall(r);
  }
}

TEST(InputBounds, ShadeChecksTheFrameBudgetFromTheGBufferHeader) {
  if (brdfcl::test::kAddressSanitizer) GTEST_SKIP() << brdfcl::test::kNoAddressSpaceLimitUnderAsan;
  ScratchDir dir("bounds");
  writeZeroExr(dir.path("g.exr"), 4096, 4096, kGBufferChannels, Imf::RLE_COMPRESSION);
  writeFile(dir.path("scene.json"), "{}");
  const RunResult r = cli(dir, {"shade", "--gbuffer", "g.exr", "--scene", "scene.json", "--out", "o.exr"});
  expectOneLineError(r, "g.exr 4096x4096 needs about 7.8 GiB of memory, but this process may use 2.0 GiB");
  expectSmall(r);
  EXPECT_FALSE(std::filesystem::exists(dir.path("o.exr")));
}

TEST(InputBounds, LongCsvLineIsRefusedWithItsLineNumber) {
  ScratchDir dir("bounds");
  writeFile(dir.path("m.json"), kMaterials);
  const std::string longField(2 << 20, '1');
  writeFile(dir.path("header.csv"), "Lx,Ly,Lz,Vx,Vy," + longField + "\n0,0,1,0,0,1\n");
  writeFile(dir.path("row.csv"), "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n0,0,1,0,0," + longField + "\n0,0,1,0,0,1\n");
  const std::vector<std::string> base = {"eval", "--materials", "m.json", "--grid", "--out", "o.csv", "--samples"};
  auto with = [&](const std::string& samples) {
    std::vector<std::string> args = base;
    args.push_back(samples);
    return args;
  };
  RunResult r = cli(dir, with("header.csv"));
  expectOneLineError(r, "header.csv: line 1 is longer than 1 MiB; a samples line holds 6 or 7 numbers");
  expectSmall(r);
  r = cli(dir, with("row.csv"));
  expectOneLineError(r, "row.csv: line 3 is longer than 1 MiB");
  expectSmall(r);
  EXPECT_FALSE(std::filesystem::exists(dir.path("o.csv")));
}

TEST(InputBounds, EndlessInputsAreCutAtTheCap) {
  ScratchDir dir("bounds");
  writeFile(dir.path("m.json"), kMaterials);
  writeFile(dir.path("s.csv"), "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n");
  writeZeroExr(dir.path("g.exr"), 4, 4, kGBufferChannels);
  const std::string cap = "'/dev/zero' is not a regular file and gives more than 256 MiB (BRDFCL_MAX_JSON_BYTES); give a "
                          "regular file, or set BRDFCL_MAX_JSON_BYTES to allow more";
  expectOneLineError(cli(dir, {"eval", "--materials", "/dev/zero", "--samples", "s.csv", "--grid", "--out", "o.csv"}), cap);
  expectOneLineError(cli(dir, {"eval", "--materials", "m.json", "--samples", "/dev/zero", "--grid", "--out", "o.csv"}), cap);
  expectOneLineError(cli(dir, {"shade", "--gbuffer", "g.exr", "--scene", "/dev/zero", "--out", "o.exr"}), cap);
  expectOneLineError(cli(dir, {"render", "--gltf", "/dev/zero", "--out", "o.png"}), cap);
  // A smaller cap, the same message with its number.
  expectOneLineError(cli(dir, {"render", "--gltf", "/dev/zero", "--out", "o.png"}, {{"BRDFCL_MAX_JSON_BYTES", "1000"}}),
                     "gives more than 1000 bytes (BRDFCL_MAX_JSON_BYTES)");
}

TEST(InputBounds, JsonFilesAboveTheCapAreRefused) {
  ScratchDir dir("bounds");
  writeFile(dir.path("m.json"), kMaterials);
  writeFile(dir.path("s.csv"), "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n");
  const std::string size = std::to_string(std::string(kMaterials).size());
  expectOneLineError(cli(dir, {"eval", "--materials", "m.json", "--samples", "s.csv", "--grid", "--out", "o.csv"},
                         {{"BRDFCL_MAX_JSON_BYTES", "50"}}),
                     "'m.json' has " + size + " bytes, more than 50 bytes (BRDFCL_MAX_JSON_BYTES); set "
                     "BRDFCL_MAX_JSON_BYTES to allow more");
  const RunResult ok = cli(dir, {"eval", "--materials", "m.json", "--samples", "s.csv", "--grid", "--out", "o.csv"},
                           {{"BRDFCL_MAX_JSON_BYTES", size}});
  EXPECT_EQ(ok.status, 0) << ok.describe();
}

TEST(InputBounds, OutOfMemoryWhileReadingNamesTheInput) {
  // Its own thread: the name of the input stays with the thread after the exception, as it must
  // for the handler at the top of the CLI.
  std::string message, plain;
  std::thread([&] {
    plain = outOfMemoryMessage();
    try {
      const detail::ReadingInput reading("sky.hdr");
      throw std::bad_alloc();
    } catch (const std::bad_alloc&) {
      message = outOfMemoryMessage();
    }
  }).join();
  EXPECT_EQ(plain, "out of memory; try a smaller --size or --chunk, or free memory");
  EXPECT_EQ(message, "out of memory while reading 'sky.hdr'; free memory, or check that the file is what it claims to be");
}

TEST(InputBounds, OutOfMemoryDecodingAnExrNamesTheFile) {
  if (brdfcl::test::kAddressSanitizer) GTEST_SKIP() << brdfcl::test::kNoAddressSpaceLimitUnderAsan;
  ScratchDir dir("bounds");
  writeZeroExr(dir.path("a.exr"), 8192, 8192, {"Y"});
  writeZeroExr(dir.path("b.exr"), 16, 16, {"Y"});
  // Allowed by the variable, the first image (256 MiB decoded, 768 MiB as RGB) does not fit the
  // 1 GiB the child may use.
  const RunResult r =
      cli(dir, {"diff", "a.exr", "b.exr"}, {{"BRDFCL_MAX_IMAGE_PIXELS", std::to_string(1 << 28)}}, 1024);
  expectOneLineError(r, "out of memory while reading 'a.exr'");
}

TEST(InputBounds, GlbJsonChunkAboveTheCapIsRefused) {
  ScratchDir dir("bounds");
  brdfcl::test::GltfBuilder b;
  b.addScene({b.addMeshNode(b.addTriangles({0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 1, 2}))});
  const std::string path = b.write(dir.dir(), "m.glb", brdfcl::test::Storage::Glb);
  EXPECT_EQ(errorOf([&] { gltf::load(path); }), "");
  ScopedEnv env("BRDFCL_MAX_JSON_BYTES", "100");
  EXPECT_NE(errorOf([&] { gltf::load(path); }).find("m.glb: its JSON chunk has "), std::string::npos);
  EXPECT_NE(errorOf([&] { gltf::load(path); }).find(" bytes, more than 100 bytes (BRDFCL_MAX_JSON_BYTES); set BRDFCL_MAX_JSON_BYTES to allow more"),
            std::string::npos);
}
