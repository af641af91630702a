// The layer check of host/src (scripts/check-layers, host/src/LAYERS): the checkout passes, and a copy
// of host/src with a module including a header of one above it, or with a folder LAYERS does not
// list, fails with a line naming the file and the fix.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "process.hpp"

namespace {

using brdfcl::test::runProcess;
using brdfcl::test::ScratchDir;

const std::string kSource = BRDFCL_SOURCE_DIR;

brdfcl::test::RunResult checkLayers(const ScratchDir& scratch, const std::string& src) {
  return runProcess({kSource + "/scripts/check-layers", "--src", src}, scratch.dir());
}

// A copy of the checkout's host/src in the scratch folder, for planting files into.
std::string copyOfSources(const ScratchDir& scratch) {
  const std::string src = scratch.path("src");
  std::filesystem::copy(kSource + "/host/src", src, std::filesystem::copy_options::recursive);
  return src;
}

TEST(Layers, CheckoutFollowsItsLayers) {
  ScratchDir scratch("layers");
  const auto r = checkLayers(scratch, kSource + "/host/src");
  EXPECT_EQ(r.status, 0) << r.describe();
}

TEST(Layers, IncludeOfAHigherModuleFails) {
  ScratchDir scratch("layers");
  const std::string src = copyOfSources(scratch);
  // io is the lowest layer and render is above it.
  brdfcl::test::writeFile(src + "/io/planted.cpp", "#include \"io/files.hpp\"\n#include \"render/exact_ibl.hpp\"\n");
  const auto r = checkLayers(scratch, src);
  EXPECT_EQ(r.status, 1) << r.describe();
  EXPECT_NE(r.err.find("host/src/io/planted.cpp:2: module 'io' includes \"render/exact_ibl.hpp\" of 'render'"),
            std::string::npos) << r.err;
}

TEST(Layers, FolderMissingFromLayersFails) {
  ScratchDir scratch("layers");
  const std::string src = copyOfSources(scratch);
  std::filesystem::create_directory(src + "/newmodule");
  brdfcl::test::writeFile(src + "/newmodule/a.cpp", "#include \"io/files.hpp\"\n");
  const auto r = checkLayers(scratch, src);
  EXPECT_EQ(r.status, 1) << r.describe();
  EXPECT_NE(r.err.find("host/src/newmodule/ is not in"), std::string::npos) << r.err;
}

TEST(Layers, SelfTestPasses) {
  ScratchDir scratch("layers");
  const auto r = runProcess({kSource + "/scripts/check-layers", "--self-test"}, scratch.dir());
  EXPECT_EQ(r.status, 0) << r.describe();
}

}  // namespace
