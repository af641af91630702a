// emissiveFactor above the glTF schema's [0, 1]: the materials file and the glTF loader both clamp
// it to 1 with one warning a component, refuse it under --strict, and refuse negative values; the
// library readers and the CLI are checked alike.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/gltf.hpp"
#include "brdfcl/io.hpp"
#include "cli_child.hpp"
#include "gltf_builder.hpp"
#include "support.hpp"

namespace {

namespace fs = std::filesystem;
using brdfcl::test::errorOf;
using brdfcl::test::quadWithMaterial;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::writeFile;

const char* const kHint = "KHR_materials_emissive_strength gives brighter emission";

std::string warningText(const std::string& source, const std::string& component, const std::string& value) {
  return source + ": materials[0].emissiveFactor[" + component + "]: " + value +
         " is above 1, the glTF schema's maximum, clamped to 1; " + kHint;
}
std::string strictText(const std::string& source, const std::string& component, const std::string& value) {
  return source + ": materials[0].emissiveFactor[" + component + "]: " + value + " is above 1, the glTF schema's maximum; " +
         kHint + " (an error under --strict)";
}

class EmissiveFactor : public ::testing::Test {
 protected:
  ScratchDir dir_{"emissive-factor"};
  std::string write(const std::string& name, const std::string& bytes) const {
    writeFile(dir_.path(name), bytes);
    return dir_.path(name);
  }
  RunResult run(const std::vector<std::string>& args) const { return brdfcl::test::runCli(dir_, args); }
};

TEST_F(EmissiveFactor, MaterialsFileClampsAboveOneWithAWarningEach) {
  const std::string m = write("m.json", R"({"materials": [{"emissiveFactor": [1.1, 0.5, 1000]}]})");
  std::vector<std::string> warnings;
  const auto ms = brdfcl::readMaterials(m, {[&](const std::string& w) { warnings.push_back(w); }, false});
  ASSERT_EQ(ms.size(), 1u);
  EXPECT_EQ(ms[0].emissive, (brdfcl::Rgb{1.0f, 0.5f, 1.0f}));
  EXPECT_EQ(warnings, (std::vector<std::string>{warningText(m, "0", "1.1"), warningText(m, "2", "1000")}));
}

TEST_F(EmissiveFactor, MaterialsFileRefusesAboveOneUnderStrictAndNegativeAlways) {
  const std::string m = write("m.json", R"({"materials": [{"emissiveFactor": [0, 2, 0]}]})");
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(m, {{}, true}); }), strictText(m, "1", "2"));
  const std::string n = write("n.json", R"({"materials": [{"emissiveFactor": [0, -1, 0]}]})");
  EXPECT_EQ(errorOf([&] { brdfcl::readMaterials(n, {{}, false}); }),
            n + ": materials[0].emissiveFactor[1]: expected a number >= 0, got -1");
  // The schema's own bounds are taken silently.
  const std::string b = write("b.json", R"({"materials": [{"emissiveFactor": [0, 1, 0.25]}]})");
  std::vector<std::string> warnings;
  const auto ms = brdfcl::readMaterials(b, {[&](const std::string& w) { warnings.push_back(w); }, true});
  EXPECT_EQ(ms[0].emissive, (brdfcl::Rgb{0.0f, 1.0f, 0.25f}));
  EXPECT_TRUE(warnings.empty());
}

TEST_F(EmissiveFactor, GltfLoaderClampsWarnsAndRefusesAlike) {
  const std::string p = quadWithMaterial({{"emissiveFactor", {0, 2, 0.5}}}).write(dir_.dir(), "a.gltf");
  const brdfcl::gltf::Asset a = brdfcl::gltf::load(p);
  ASSERT_EQ(a.materials.size(), 1u);
  EXPECT_EQ(a.materials[0].emissiveFactor, (std::array<float, 3>{0.0f, 1.0f, 0.5f}));
  EXPECT_NE(std::find(a.warnings.begin(), a.warnings.end(), warningText(p, "1", "2")), a.warnings.end());

  brdfcl::gltf::LoadOptions strict;
  strict.strict = true;
  EXPECT_EQ(errorOf([&] { brdfcl::gltf::load(p, strict); }), strictText(p, "1", "2"));
  const std::string n = quadWithMaterial({{"emissiveFactor", {0, 0, -0.5}}}).write(dir_.dir(), "n.gltf");
  EXPECT_EQ(errorOf([&] { brdfcl::gltf::load(n); }), n + ": materials[0].emissiveFactor[2]: expected a number >= 0, got -0.5");
}

TEST_F(EmissiveFactor, CliWarnsOnceAndStrictIsOneLineExitTwoWithNoOutput) {
  const std::string m = write("m.json", R"({"materials": [{"emissiveFactor": [3, 0, 0]}]})");
  const std::string s = write("s.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n");
  const std::string out = dir_.path("o.csv");
  const RunResult r = run({"eval", "--materials", m, "--samples", s, "--out", out});
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(r.warningLines(), std::vector<std::string>{"brdfcl: warning: " + warningText(m, "0", "3")});
  fs::remove(out);
  const RunResult strict = run({"eval", "--materials", m, "--samples", s, "--out", out, "--strict"});
  EXPECT_EQ(strict.status, 2) << strict.describe();
  EXPECT_EQ(strict.errorLines(), std::vector<std::string>{"brdfcl: " + strictText(m, "0", "3")});
  EXPECT_FALSE(fs::exists(out));

  const std::string g = quadWithMaterial({{"emissiveFactor", {0, 0, 1.5}}}).write(dir_.dir(), "g.gltf");
  const RunResult gs = run({"gbuffer", "--gltf", g, "--size", "8x8", "--out", dir_.path("g.exr"), "--strict"});
  EXPECT_EQ(gs.status, 2) << gs.describe();
  EXPECT_EQ(gs.errorLines(), std::vector<std::string>{"brdfcl: " + strictText(g, "2", "1.5")});
  EXPECT_FALSE(fs::exists(dir_.path("g.exr")));
}

}  // namespace
