// The engine and pinned source each profile names (model/profile_version.hpp): every profile has
// one, every commit it names is the one docs/profiles.md pins, and `compare` (table and JSON) and
// `render`/`shade --profile` print it; a failed run still prints its one error line only.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "brdfcl/material.hpp"
#include "host/src/model/profile_version.hpp"
#include "process.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

const char* kMaterials = R"({"materials": [
  {"name": "plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.5, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 0.6}}
]})";

RunResult cli(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), BRDFCL_CLI_PATH);
  return runProcess(std::move(args), dir.dir(), dir.dir());
}

TEST(ProfileVersions, EveryProfileNamesItsEngineAndAPinFromTheDocs) {
  const std::string docs = slurp(std::string(BRDFCL_SOURCE_DIR) + "/docs/profiles.md");
  ASSERT_FALSE(docs.empty());
  const std::regex hash("(?:@|commit )([0-9a-f]{8})");
  for (Profile p : kAllProfiles) {
    SCOPED_TRACE(toString(p));
    const EngineVersion v = profileEngineVersion(p);
    ASSERT_NE(v.engine, nullptr);
    ASSERT_NE(v.version, nullptr);
    EXPECT_NE(std::string(v.engine), "");
    EXPECT_NE(std::string(v.version), "");
    EXPECT_EQ(describeProfile(p), std::string(toString(p)) + ": " + v.engine + " " + v.version);
    const std::string text = v.version;
    int hashes = 0;
    for (std::sregex_iterator it(text.begin(), text.end(), hash), end; it != end; ++it, ++hashes)
      EXPECT_NE(docs.find((*it)[1].str()), std::string::npos) << (*it)[1] << " is not pinned in docs/profiles.md";
    if (p != Profile::Spec) EXPECT_GT(hashes, 0) << "an engine profile names the commit it is pinned to";
  }
  const std::string mx = profileEngineVersion(Profile::Materialx).version;
  EXPECT_CONTAINS(mx, "4177b2cb");
  EXPECT_CONTAINS(mx, "2026-07-01");
  EXPECT_CONTAINS(mx, "v1.39.5");
  EXPECT_CONTAINS(docs, "v1.39.5");
}

TEST(ProfileVersions, CompareNamesBothEnginesInTheTableAndTheJson) {
  ScratchDir dir("profile-versions-compare");
  std::ofstream(dir.path("m.json")) << kMaterials;
  const RunResult t = cli(dir, {"compare", "--materials", "m.json", "--profile", "materialx", "--against", "khronos",
                                "--pairs", "100"});
  ASSERT_EQ(t.status, 0) << t.describe();
  EXPECT_CONTAINS(t.out, "A = " + describeProfile(Profile::Materialx) + "\n");
  EXPECT_CONTAINS(t.out, "B = " + describeProfile(Profile::Khronos) + "\n");
  EXPECT_CONTAINS(t.out, "MaterialX gltf_pbr 1.39.5+ at commit 4177b2cb");

  const RunResult j = cli(dir, {"compare", "--materials", "m.json", "--profile", "materialx", "--pairs", "100", "--json"});
  ASSERT_EQ(j.status, 0) << j.describe();
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["profile_engine"]["engine"], "MaterialX gltf_pbr");
  EXPECT_EQ(doc["profile_engine"]["version"], profileEngineVersion(Profile::Materialx).version);
  EXPECT_EQ(doc["against_engine"]["engine"], profileEngineVersion(Profile::Spec).engine);
}

TEST(ProfileVersions, RenderWithProfileNamesTheEngineOnStderr) {
  ScratchDir dir("profile-versions-render");
  const RunResult r = cli(dir, {"render", "--size", "16x16", "--profile", "materialx", "--out", "m.png"});
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(r.err, "brdfcl: profile " + describeProfile(Profile::Materialx) + "\n");
  EXPECT_CONTAINS(r.err, "brdfcl: profile materialx: MaterialX gltf_pbr 1.39.5+ at commit 4177b2cb");

  // Both profiles of a difference render are named.
  const RunResult d = cli(dir, {"render", "--size", "16x16", "--profile", "filament", "--diff-against", "babylon",
                                "--out", "d.png"});
  ASSERT_EQ(d.status, 0) << d.describe();
  EXPECT_CONTAINS(d.err, "brdfcl: profile " + describeProfile(Profile::Filament) + "\n");
  EXPECT_CONTAINS(d.err, "brdfcl: profile " + describeProfile(Profile::Babylon) + "\n");

  // Without --profile nothing is added; a failed run keeps its one error line.
  const RunResult plain = cli(dir, {"render", "--size", "16x16", "--out", "s.png"});
  ASSERT_EQ(plain.status, 0) << plain.describe();
  EXPECT_EQ(plain.err, "");
  const RunResult bad = cli(dir, {"render", "--size", "16x16", "--profile", "materialx", "--ibl", "exact", "--out", "x.png"});
  EXPECT_EQ(bad.status, 2) << bad.describe();
  EXPECT_EQ(bad.errorLines().size(), 1u) << bad.describe();
}

TEST(ProfileVersions, ShadeWithProfileNamesTheEngineOnStderr) {
  ScratchDir dir("profile-versions-shade");
  ASSERT_EQ(cli(dir, {"gbuffer", "--size", "8x8", "--out", "g.exr"}).status, 0);
  std::ofstream(dir.path("s.json")) << R"({"lights": [{"type": "directional", "direction": [0, 0, -1]}]})";
  const RunResult r = cli(dir, {"shade", "--gbuffer", "g.exr", "--scene", "s.json", "--profile", "threejs", "--out", "o.exr"});
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(r.err, "brdfcl: profile " + describeProfile(Profile::Threejs) + "\n");
}

}  // namespace
}  // namespace brdfcl::test
