// The defaults that `brdfcl render --help` states are the ones the command uses: without
// --environment a glTF asset is lit by the built-in sky and the spheres by the studio.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_child.hpp"
#include "process.hpp"

using brdfcl::test::runCli;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::slurp;

namespace {

// The help line of one option, "" when the help has none.
std::string helpLine(const std::string& help, const std::string& option) {
  const std::size_t at = help.find("  " + option + " ");
  if (at == std::string::npos) return "";
  const std::size_t end = help.find('\n', at);
  return help.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

}  // namespace

TEST(HelpDefaults, RenderEnvironmentNamesTheSkyForGltfAndTheStudioForTheSpheres) {
  ScratchDir dir("helpdefaults");
  const RunResult r = runCli(dir, {"render", "--help"});
  ASSERT_EQ(r.status, 0) << r.describe();
  const std::string line = helpLine(r.out, "--environment");
  ASSERT_FALSE(line.empty()) << r.out;
  const std::size_t d = line.find("default");
  ASSERT_NE(d, std::string::npos) << line;
  const std::string stated = line.substr(d);
  EXPECT_NE(stated.find("sky with --gltf"), std::string::npos) << line;
  EXPECT_NE(stated.find("studio for the spheres"), std::string::npos) << line;
}

TEST(HelpDefaults, SpheresWithoutEnvironmentRenderAsUnderTheStudio) {
  ScratchDir dir("helpdefaults");
  const RunResult plain = runCli(dir, {"render", "--size", "24x24", "--exr", "plain.exr", "--out", "plain.png"});
  ASSERT_EQ(plain.status, 0) << plain.describe();
  const RunResult studio =
      runCli(dir, {"render", "--size", "24x24", "--environment", "studio", "--exr", "studio.exr", "--out", "studio.png"});
  ASSERT_EQ(studio.status, 0) << studio.describe();
  const RunResult sky =
      runCli(dir, {"render", "--size", "24x24", "--environment", "sky", "--exr", "sky.exr", "--out", "sky.png"});
  ASSERT_EQ(sky.status, 0) << sky.describe();
  EXPECT_EQ(slurp(dir.path("plain.png")), slurp(dir.path("studio.png")));
  EXPECT_NE(slurp(dir.path("plain.png")), slurp(dir.path("sky.png")));
}
