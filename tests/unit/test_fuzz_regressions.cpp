// Regression tests for what fuzzing the readers found (tests/fuzz): each feeds the input kept in
// tests/fuzz/corpus/<reader>/ to the reader, which must refuse it with a one-line brdfcl::Error
// naming the file (or read it, where the input was valid), quickly and without large allocations.
#include <gtest/gtest.h>
#include <unistd.h>

#include "brdfcl/gltf.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfTiledOutputFile.h>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "support.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/gbuffer.hpp"
#include "brdfcl/image.hpp"

namespace fs = std::filesystem;
using brdfcl::test::errorOf;

namespace {

std::string corpus(const std::string& reader, const std::string& name) {
  return std::string(BRDFCL_SOURCE_DIR) + "/tests/fuzz/corpus/" + reader + "/" + name;
}

// A kB figure from /proc/self/status ("VmRSS:", "VmHWM:"), or -1.
long statusKb(const std::string& key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) return std::stol(line.substr(key.size()));
  return -1;
}

// How far the peak resident set rose above the resident set while f ran, in MiB; -1 where the
// kernel cannot reset the peak (writing 5 to clear_refs, Linux >= 4.0).
long peakGrowthMib(const std::function<void()>& f) {
  {
    std::ofstream clear("/proc/self/clear_refs");
    if (!(clear << "5" << std::flush)) return -1;
  }
  const long before = statusKb("VmRSS:");
  f();
  const long peak = statusKb("VmHWM:");
  return before < 0 || peak < 0 ? -1 : (peak - before) / 1024;
}

// Every G-buffer finding is also read as an environment map: both go through readExrChannels.
std::string gbufferError(const std::string& p) { return errorOf([&] { brdfcl::readGBuffer(p); }); }
std::string environmentError(const std::string& p) {
  int w = 0, h = 0;
  return errorOf([&] { brdfcl::readExrRgb(p, w, h); });
}

// OpenEXR allocated what an attribute's size field claimed (here 1.8 GB, 124 bytes into the
// file) before finding the file too short: seconds and gigabytes under the sanitizers.
TEST(FuzzRegressions, ExrAttributeSizeBeyondTheFile) {
  for (const char* name : {"slow_attribute_claims_2gb.exr", "slow_string_claims_2gb.exr"}) {
    const std::string p = corpus("gbuffer", name);
    EXPECT_EQ(gbufferError(p), p + ": truncated OpenEXR file (ends inside the header); write the file again");
    EXPECT_EQ(environmentError(p), p + ": truncated OpenEXR file (ends inside the header); write the file again");
  }
}

// OpenEXR reads a channel list up to its empty name, past its declared size, and took the bytes
// inside that size for the next attribute, one claiming 2 GB.
TEST(FuzzRegressions, ExrChannelListPastItsSize) {
  const std::string p = corpus("gbuffer", "slow_chlist_past_its_size.exr");
  EXPECT_EQ(gbufferError(p), p + ": corrupt OpenEXR header (the channel list 'channels' does not end where its size "
                                 "of 296 bytes says); write the file again");
}

TEST(FuzzRegressions, ExrPreviewLargerThanItsAttribute) {
  const std::string p = corpus("gbuffer", "oom_preview_claims_16gb.exr");
  EXPECT_EQ(gbufferError(p), p + ": corrupt OpenEXR header (attribute 'preview' of type 'preview' has 8 bytes, "
                                 "expected 8 + 4 * width * height of the preview); write the file again");
}

// 2.6 kB claiming 65536 x 4096 pixels in 256 ZIP chunks, all one corrupt chunk: the reader
// took 1 GiB for each of the 12 required planes before decoding anything.
TEST(FuzzRegressions, ExrSmallFileClaimingAHugeImage) {
  const std::string p = corpus("gbuffer", "oom_claims_2e28_pixels.exr");
  std::string m;
  // Past the frame budget (which refuses this size from the header on most machines), so that
  // the corrupt chunk itself is what the reader meets.
  ::setenv("BRDFCL_MAX_IMAGE_PIXELS", "268435456", 1);
  const long growth = peakGrowthMib([&] { m = gbufferError(p); });
  ::unsetenv("BRDFCL_MAX_IMAGE_PIXELS");
  EXPECT_EQ(m.rfind(p + ": cannot read OpenEXR data (", 0), 0u) << m;
  EXPECT_CONTAINS(m, "the file is truncated or corrupt");
  if (growth >= 0) {
    EXPECT_LT(growth, 512) << "MiB taken for a corrupt 2.6 kB file";
  }
}

TEST(FuzzRegressions, ExrSizesBeyondTheLimits) {
  const std::string wide = corpus("gbuffer", "oom_one_line_2e28_wide.exr");
  EXPECT_EQ(gbufferError(wide),
            wide + ": unsupported image size 268435456x1 (at most 268435456 pixels and 65536 on a side)");
  const std::string tiles = corpus("gbuffer", "oom_tiles_1x1_2e28.exr");
  EXPECT_EQ(gbufferError(tiles), tiles + ": truncated OpenEXR file (too short for the offsets of its 268435456 "
                                         "chunks of pixels); write the file again");
  const std::string tile = corpus("gbuffer", "oom_tile_2e30_square.exr");
  EXPECT_EQ(environmentError(tile),
            tile + ": unsupported OpenEXR layout: decoding one chunk of 1073741824x1073741824 pixels of 12 channels "
                   "would take more than 1024 MiB; write it with fewer channels, smaller tiles or another compression");
}

// A data window that starts at negative x: the slice base was computed with wrapping pointer
// arithmetic (UBSan: "subtraction of unsigned offset ... overflowed").
TEST(FuzzRegressions, ExrNegativeDataWindowOrigin) {
  // Its values are a counting pattern, not a G-buffer's (N of length 7, factors beyond 1).
  brdfcl::GBufferReadOptions unchecked;
  unchecked.check = false;
  const brdfcl::GBuffer g = brdfcl::readGBuffer(corpus("gbuffer", "offset_windows.exr"), unchecked);
  EXPECT_EQ(g.width, 4);
  EXPECT_EQ(g.height, 4);
  ASSERT_EQ(g.mask.size(), 16u);
  // The seed's value for pixel i of channel c (in the order written) is 0.1 * (i % 7) + c, as HALF.
  EXPECT_NEAR(g.mask[9], 0.1f * 2 + 11, 0.01f);
  EXPECT_NEAR(g.P[3 * 5 + 1], 0.1f * 5 + 1, 0.01f);
}

// The reader now decodes in bands of whole chunks (about 2^20 pixels); every pixel must still
// land in its place, scan-line and tiled, with band edges inside and across chunks.
class ExrBands : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() / ("brdfcl-fuzzreg-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

std::vector<float> pattern(int w, int h) {
  std::vector<float> rgb(3 * static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(i % 1000003) * 0.25f;
  return rgb;
}

TEST_F(ExrBands, ScanLinesKeepEveryPixel) {
  const int w = 32, h = 40001;  // bands of 32768 lines: two, the second partial
  const std::vector<float> rgb = pattern(w, h);
  const std::string p = (dir_ / "tall.exr").string();
  brdfcl::writeExrRgb(p, w, h, rgb);
  int rw = 0, rh = 0;
  EXPECT_EQ(brdfcl::readExrRgb(p, rw, rh), rgb);
  EXPECT_EQ(rw, w);
  EXPECT_EQ(rh, h);
}

TEST_F(ExrBands, TilesKeepEveryPixel) {
  const int w = 33, h = 40003;  // 4x7 tiles: bands of 31773 lines, whole tile rows
  const std::vector<float> rgb = pattern(w, h);
  const std::string p = (dir_ / "tiled.exr").string();
  {
    Imf::Header header(w, h);
    header.setTileDescription(Imf::TileDescription(4, 7, Imf::ONE_LEVEL));
    Imf::FrameBuffer fb;
    const char* names[] = {"R", "G", "B"};
    char* base = const_cast<char*>(reinterpret_cast<const char*>(rgb.data()));
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 3 * sizeof(float), 3 * sizeof(float) * w));
    }
    Imf::TiledOutputFile out(p.c_str(), header);
    out.setFrameBuffer(fb);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
  }
  int rw = 0, rh = 0;
  EXPECT_EQ(brdfcl::readExrRgb(p, rw, rh), rgb);
  EXPECT_EQ(rh, h);
}

// fuzz_gltf: a PNG whose first IDAT chunk is empty made stb_image memcpy zero bytes to NULL
// (undefined; UBSan aborted). Under make test-asan this test aborts if images.cpp is built with
// UBSan again; in any build the file loads or is refused in one line.
TEST(FuzzRegressions, GltfPngWithAnEmptyFirstIdat) {
  const std::string p = corpus("gltf", "finding_png_empty_idat.gltf");
  try {
    const brdfcl::gltf::Asset a = brdfcl::gltf::load(p);
    EXPECT_FALSE(a.images.empty());
  } catch (const brdfcl::Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

}  // namespace
