// Small things a new user meets first: an out-of-range --material refused before any warning,
// messages that name the option they are about, the warning for an environment that is not 2:1,
// and the kind every brdfcl::Error carries.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/image.hpp"
#include "brdfcl/runtime.hpp"
#include "cli_child.hpp"
#include "process.hpp"
#include "support.hpp"

using brdfcl::test::runCli;
using brdfcl::test::expectOneLineError;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;

namespace {

int countContaining(const std::vector<std::string>& lines, const std::string& text) {
  int n = 0;
  for (const auto& l : lines) n += l.find(text) != std::string::npos;
  return n;
}

// A materials file whose one material references a texture: reading it warns.
constexpr const char* kTextured = R"({"asset": {"version": "2.0"}, "materials": [
  {"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]})";

}  // namespace

TEST(Papercuts, AlbedoMaterialOutOfRangeIsTheOnlyLine) {
  ScratchDir dir("papercuts");
  std::ofstream(dir.path("m.gltf")) << kTextured;
  const RunResult bad = runCli(dir, {"albedo", "--materials", "m.gltf", "--material", "9"});
  expectOneLineError(bad, "--material 9 is out of range: m.gltf has 1 material(s), 0 to 0");
  EXPECT_TRUE(bad.warningLines().empty()) << bad.describe();
  // In range, the reader's warning is still printed.
  const RunResult good = runCli(dir, {"albedo", "--materials", "m.gltf", "--material", "0"});
  ASSERT_EQ(good.status, 0) << good.describe();
  EXPECT_EQ(countContaining(good.warningLines(), "texture references are ignored"), 1) << good.describe();
}

TEST(Papercuts, MessagesNameTheirOption) {
  ScratchDir dir("papercuts");
  std::filesystem::create_directory(dir.path("folder"));
  const std::vector<std::string> render = {"render", "--scene", "spheres", "--size", "8x8", "--out", "o.png"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = render;
    args.insert(args.end(), extra.begin(), extra.end());
    return runCli(dir, args);
  };
  expectOneLineError(with({"--lights", "nolights"}),
                     "--lights 'nolights': cannot read: No such file or directory; give gltf, none, or a scene .json file");
  expectOneLineError(with({"--lights", "folder"}), "--lights 'folder': cannot read: Is a directory");
  expectOneLineError(with({"--env-intensity", "-1"}), "--env-intensity -1 is not a finite number >= 0");
  expectOneLineError(with({"--env-rotation", "inf"}), "--env-rotation inf is not a finite number of radians");
  expectOneLineError(runCli(dir, {"lut", "--kind", "sheen-e", "--out", "folder"}),
                     "--out 'folder': cannot write: it is a directory; name a file inside it");
  EXPECT_FALSE(std::filesystem::exists(dir.path("o.png")));
}

TEST(Papercuts, EnvironmentThatIsNotTwoToOneWarnsOnceNamingFileAndSize) {
  ScratchDir dir("papercuts");
  brdfcl::writeExrRgb(dir.path("square.exr"), 16, 16, std::vector<float>(3 * 16 * 16, 0.5f));
  brdfcl::writeExrRgb(dir.path("wide.exr"), 16, 8, std::vector<float>(3 * 16 * 8, 0.5f));
  // Two profiles read the environment twice; the warning still comes once.
  const RunResult square = runCli(dir, {"render", "--scene", "spheres", "--size", "8x8", "--environment", "square.exr",
                                     "--profile", "khronos", "--diff-against", "spec", "--out", "d.png"});
  ASSERT_EQ(square.status, 0) << square.describe();
  EXPECT_EQ(countContaining(square.warningLines(), "square.exr: environment of 16x16 texels is not 2:1"), 1)
      << square.describe();
  const RunResult wide = runCli(dir, {"render", "--scene", "spheres", "--size", "8x8", "--environment", "wide.exr",
                                   "--out", "w.png"});
  ASSERT_EQ(wide.status, 0) << wide.describe();
  EXPECT_EQ(countContaining(wide.warningLines(), "not 2:1"), 0) << wide.describe();
}

TEST(Papercuts, ErrorsCarryTheirKind) {
  using brdfcl::Error;
  using brdfcl::ErrorKind;
  EXPECT_EQ(Error("bad value").kind(), ErrorKind::Input);
  EXPECT_EQ(Error("internal: broken", 3).kind(), ErrorKind::Internal);
  EXPECT_EQ(Error(ErrorKind::Device, "x").kind(), ErrorKind::Device);
  EXPECT_EQ(Error(ErrorKind::Device, "x").exitCode(), 2);
  EXPECT_STREQ(brdfcl::toString(ErrorKind::Environment), "environment");
  EXPECT_STREQ(brdfcl::toString(ErrorKind::Memory), "memory");
  // A frame larger than the memory allowed: memory, though the user fixes it with --size.
  try {
    brdfcl::checkFrameFits(brdfcl::FrameJob::Render, 16384, 16384, std::uint64_t(1) << 30);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Memory) << e.what();
  }
  // A device selector that matches nothing is the user's to fix.
  try {
    brdfcl::Runtime rt("no-such-device-name");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
  }
}
