// The command line's front door and its checks before work: unknown subcommands and options named
// first with "did you mean", --version, help, the subcommand's help in every parse error, options
// that do not apply, and bad values or outputs refused at once with nothing written.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "brdfcl/albedo.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/frame_budget.hpp"
#include "brdfcl/io.hpp"
#include "cli_child.hpp"
#include "process.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using namespace brdfcl;
using brdfcl::test::expectOneLineError;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::errorOf;

namespace {

// Sanitizer builds start processes several times slower; the limit is about brdfcl's own work.
#if defined(__SANITIZE_ADDRESS__)
constexpr double kEarlyLimitSeconds = 2.0;
#else
constexpr double kEarlyLimitSeconds = 0.5;
#endif

RunResult cli(const ScratchDir& dir, std::vector<std::string> args, std::map<std::string, std::string> env = {},
              std::size_t addressSpaceMiB = 0) {
  brdfcl::test::ProcessOptions o;
  o.env = std::move(env);
  o.addressSpaceMiB = addressSpaceMiB;
  return brdfcl::test::runCli(dir, std::move(args), std::move(o));
}

TEST(CliMessages, UnknownSubcommandIsNamedWithSuggestion) {
  ScratchDir dir("climsg");
  expectOneLineError(cli(dir, {"evl"}), "unknown subcommand 'evl' (did you mean 'eval'?); see 'brdfcl --help'");
  expectOneLineError(cli(dir, {"rendr", "--out", "x.png"}), "did you mean 'render'?");
  expectOneLineError(cli(dir, {"version"}), "unknown subcommand 'version' (did you mean 'brdfcl --version'?)");
  // Nothing close: no suggestion, but the word is named.
  const RunResult far = cli(dir, {"frobnicate"});
  expectOneLineError(far, "unknown subcommand 'frobnicate'; see 'brdfcl --help'");
}

TEST(CliMessages, UnknownOptionIsNamedBeforeMissingRequiredOnes) {
  ScratchDir dir("climsg");
  expectOneLineError(cli(dir, {"--frobnicate"}), "unknown option '--frobnicate'");
  const RunResult r = cli(dir, {"eval", "--frobnicate"});
  expectOneLineError(r, "eval: unknown option '--frobnicate'; see 'brdfcl eval --help'");
  EXPECT_EQ(r.err.find("--materials"), std::string::npos) << r.err;
  expectOneLineError(cli(dir, {"eval", "--materils", "m.json"}), "unknown option '--materils' (did you mean '--materials'?)");
  expectOneLineError(cli(dir, {"render", "--expsure=1", "--out", "x.png"}), "(did you mean '--exposure'?)");
  // A negative number and "-" are values, not options.
  expectOneLineError(cli(dir, {"render", "--env-rotation", "-0.5", "--exposure", "nan", "--out", "x.png"}), "--exposure");
}

TEST(CliMessages, ParseErrorsPointToTheSubcommandsHelp) {
  ScratchDir dir("climsg");
  expectOneLineError(cli(dir, {"eval", "--materials", "m.json", "--samples", "s.csv"}), "see 'brdfcl eval --help'");
  expectOneLineError(cli(dir, {"lut", "--kind"}), "see 'brdfcl lut --help'");
}

TEST(CliMessages, NoArgumentsPrintsHelpAndSucceeds) {
  ScratchDir dir("climsg");
  const RunResult r = cli(dir, {});
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_NE(r.out.find("Subcommands:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("eval"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

TEST(CliMessages, VersionNamesTheCommitAndTheOpenCLDevices) {
  ScratchDir dir("climsg");
  const RunResult r = cli(dir, {"--version"});
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_NE(r.out.find("brdfcl 0."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(commit "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("OpenCL device [0]: "), std::string::npos) << r.out;
  // Without a platform it still answers, and says so.
  const RunResult none = cli(dir, {"--version"}, {{"OCL_ICD_VENDORS", dir.path("no-vendors")}});
  EXPECT_EQ(none.status, 0) << none.describe();
  EXPECT_NE(none.out.find("OpenCL: no OpenCL platform found"), std::string::npos) << none.out;
}

TEST(CliMessages, DeviceErrorsSayWhereTheNameCameFrom) {
  ScratchDir dir("climsg");
  const std::vector<std::string> lut = {"lut", "--kind", "ggx-dfg", "--size", "2", "--out", "x.csv"};
  expectOneLineError(cli(dir, lut, {{"BRDFCL_DEVICE", "99"}}), "BRDFCL_DEVICE 99: device index out of range");
  std::vector<std::string> named = lut;
  named.insert(named.end(), {"--device", "no-such-device"});
  expectOneLineError(cli(dir, named), "--device 'no-such-device': no OpenCL device matches");
  expectOneLineError(cli(dir, lut, {{"BRDFCL_DEVICE", "no-such-device"}}), "BRDFCL_DEVICE 'no-such-device'");
  EXPECT_FALSE(fs::exists(dir.path("x.csv")));
}

TEST(CliMessages, LutRefusesSheenOptionsForDfgKinds) {
  ScratchDir dir("climsg");
  expectOneLineError(cli(dir, {"lut", "--kind", "charlie-dfg", "--sheen-visibility", "ashikhmin", "--out", "x.csv"}),
                     "--sheen-visibility applies to --kind sheen-e only");
  expectOneLineError(cli(dir, {"lut", "--kind", "ggx-dfg", "--sheen-distribution", "ashikhmin", "--out", "x.csv"}),
                     "--sheen-distribution applies to --kind sheen-e only");
  EXPECT_FALSE(fs::exists(dir.path("x.csv")));
  const RunResult ok = cli(dir, {"lut", "--kind", "sheen-e", "--size", "4", "--sheen-visibility", "ashikhmin", "--out", "x.csv"});
  EXPECT_EQ(ok.status, 0) << ok.describe();
}

// Each bad value or output is refused before any work: at once, with no file anywhere.
TEST(CliMessages, EarlyChecksRefuseBeforeAnyWork) {
  ScratchDir dir("climsg");
  fs::create_directories(dir.path("outdir"));
  std::ofstream(dir.path("m.json")) << R"({"materials": [{}]})";
  const std::string missingDir = dir.path("no-such-dir");
  struct Case {
    std::vector<std::string> args;
    std::string text;
    // The largest frame, refused for lack of memory: the child gets 16 GiB of address space, since
    // a 128 GiB machine has room for it (under ASan, which needs its address space, such a
    // machine skips the case).
    bool frame = false;
  };
  const std::vector<Case> cases = {
      // The G-buffer does not exist: the option is judged before the input is read.
      {{"shade", "--gbuffer", "none.exr", "--scene", "none.json", "--out", "o.exr", "--png", "outdir/o.png", "--exposure", "nan"},
       "--exposure nan is not a finite number"},
      {{"shade", "--gbuffer", "none.exr", "--scene", "none.json", "--out", "outdir/o.exr", "--png", missingDir + "/o.png"},
       "--png '" + missingDir + "/o.png': cannot write"},
      {{"shade", "--gbuffer", "none.exr", "--scene", "none.json", "--out", "outdir"}, "must end in .exr or .png"},
      {{"render", "--exposure", "inf", "--out", "outdir/o.png"}, "--exposure inf"},
      {{"render", "--out", missingDir + "/o.png"}, "cannot write"},
      {{"render", "--out", "outdir/o.png", "--exr", missingDir + "/o.exr"}, "--exr"},
      {{"render", "--out", "outdir/o.png", "--gbuffer", "outdir"}, "--gbuffer 'outdir' must end in .exr"},
      {{"render", "--size", "16384x16384", "--out", "outdir/o.png"}, "the largest size of that shape that fits is", true},
      {{"gbuffer", "--size", "16384x16384", "--out", "outdir/g.exr"}, "the largest size of that shape that fits is", true},
      {{"eval", "--materials", "m.json", "--samples", "none.csv", "--out", missingDir + "/o.csv"}, "--out '" + missingDir},
      {{"lut", "--kind", "ggx-dfg", "--out", missingDir + "/l.exr"}, "cannot write"},
      {{"demo", "--exposure", "nan"}, "--exposure nan"},
      {{"demo", "--size", "4by4"}, "--size '4by4'"},
  };
  for (const auto& c : cases) {
    std::size_t addressSpaceMiB = 0;
    if (c.frame && !brdfcl::test::kAddressSanitizer) addressSpaceMiB = 16384;
    else if (c.frame && usableHostMemory() >= frameHostBytes(c.args[0] == "render" ? FrameJob::Render : FrameJob::GBuffer,
                                                              16384, 16384)) {
      std::printf("skipped '%s --size 16384x16384': this machine has the memory for it\n", c.args[0].c_str());
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = cli(dir, c.args, {}, addressSpaceMiB);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    SCOPED_TRACE(c.args[0] + " ... " + c.args.back());
    expectOneLineError(r, c.text);
    EXPECT_LT(seconds, kEarlyLimitSeconds) << r.describe();
    EXPECT_TRUE(fs::is_empty(dir.path("outdir"))) << r.describe();
    EXPECT_FALSE(fs::exists(dir.path("out"))) << r.describe();
  }
}

TEST(CliMessages, DemoRefusesAnOutThatIsNotADirectory) {
  ScratchDir dir("climsg");
  std::ofstream(dir.path("out")) << "a file the user keeps";
  const RunResult r = cli(dir, {"demo"});
  expectOneLineError(r, "cannot write the demo into 'out': it exists and is not a directory");
  EXPECT_EQ(brdfcl::test::slurp(dir.path("out")), "a file the user keeps");
}

TEST(FrameBudget, RefusesWhatCannotFitAndNamesASizeThatDoes) {
  const std::uint64_t host = 4ull << 30;
  EXPECT_NO_THROW(checkFrameFits(FrameJob::Render, 1920, 1080, host));
  const std::string e = errorOf([&] { checkFrameFits(FrameJob::Render, 16384, 8192, host); });
  EXPECT_NE(e.find("--size 16384x8192 needs about "), std::string::npos) << e;
  EXPECT_NE(e.find("this process may use 4.0 GiB"), std::string::npos) << e;
  // The size it names fits, keeps the aspect, and is the largest such: a little more would not fit.
  int w = 0, h = 0;
  ASSERT_EQ(std::sscanf(e.substr(e.rfind(' ') + 1).c_str(), "%dx%d", &w, &h), 2) << e;
  EXPECT_NO_THROW(checkFrameFits(FrameJob::Render, w, h, host));
  EXPECT_NEAR(double(w) / h, 2.0, 0.01);
  EXPECT_THROW(checkFrameFits(FrameJob::Render, w + 4, h + 2, host), Error);
  // A G-buffer alone needs less than a render.
  EXPECT_GT(frameHostBytes(FrameJob::Render, 1000, 1000), frameHostBytes(FrameJob::GBuffer, 1000, 1000));
  EXPECT_GT(usableHostMemory(), 256ull << 20);
}

TEST(CliMessages, AlbedoOfTheUsersOwnMaterials) {
  ScratchDir dir("climsg");
  const std::string json =
      R"({"materials": [{"name": "red plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1],
          "metallicFactor": 0, "roughnessFactor": 0.5}},
         {"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.3},
          "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.5}}}]})";
  std::ofstream(dir.path("m.json")) << json;
  const RunResult all = cli(dir, {"albedo", "--materials", "m.json"});
  ASSERT_EQ(all.status, 0) << all.describe();
  EXPECT_NE(all.out.find("red plastic\n"), std::string::npos) << all.out;
  EXPECT_NE(all.out.find("materials[1]\n"), std::string::npos) << all.out;
  const RunResult one = cli(dir, {"albedo", "--materials", "m.json", "--material", "1"});
  ASSERT_EQ(one.status, 0) << one.describe();
  EXPECT_EQ(one.out.find("red plastic"), std::string::npos) << one.out;
  // The printed "all" row at normal view is the library's directional albedo of that material.
  const auto materials = parseMaterials(json, "m.json");
  EvalOptions o;
  Evaluator ev(brdfcl::test::runtime(), o);
  const auto a = directionalAlbedo(ev, {materials[1]}, {1.0f});
  const double y = 0.2126 * a[0] + 0.7152 * a[1] + 0.0722 * a[2];
  const auto row = one.out.find("  all");
  ASSERT_NE(row, std::string::npos) << one.out;
  double printed = 0;
  ASSERT_EQ(std::sscanf(one.out.c_str() + row, " all %lf", &printed), 1) << one.out;
  EXPECT_NEAR(printed, y, 6e-5) << one.out;
  expectOneLineError(cli(dir, {"albedo", "--materials", "m.json", "--material", "2"}), "--material 2 is out of range");
  expectOneLineError(cli(dir, {"albedo", "--material", "0"}), "--material applies to --materials FILE");
  // The materials reader's typo rules hold here too: a warning, or with --strict the error.
  std::ofstream(dir.path("typo.json")) << R"({"materials": [{"pbrMetallicRoughness": {"metalicFactor": 0}}]})";
  const RunResult warned = cli(dir, {"albedo", "--materials", "typo.json"});
  EXPECT_EQ(warned.status, 0) << warned.describe();
  ASSERT_EQ(warned.warningLines().size(), 1u) << warned.describe();
  EXPECT_NE(warned.warningLines()[0].find("did you mean metallicFactor?"), std::string::npos) << warned.err;
  expectOneLineError(cli(dir, {"albedo", "--materials", "typo.json", "--strict"}), "(an error under --strict)");
  expectOneLineError(cli(dir, {"albedo", "--strict"}), "--strict applies to --materials FILE");
}

// shade writes what --out names: a PNG alone (one run: each prepares its environment).
TEST(CliMessages, ShadeWritesThePngAloneWhenOutIsAPng) {
  ScratchDir dir("climsg");
  ASSERT_EQ(cli(dir, {"gbuffer", "--size", "8x8", "--out", "g.exr"}).status, 0);
  std::ofstream(dir.path("s.json")) << R"({"lights": [{"type": "directional", "direction": [0, 0, -1]}], "environment": "builtin"})";
  const RunResult png = cli(dir, {"shade", "--gbuffer", "g.exr", "--scene", "s.json", "--out", "o.png"});
  ASSERT_EQ(png.status, 0) << png.describe();
  EXPECT_TRUE(fs::exists(dir.path("o.png")));
  EXPECT_FALSE(fs::exists(dir.path("o.exr")));
  expectOneLineError(cli(dir, {"shade", "--gbuffer", "g.exr", "--scene", "s.json", "--out", "q.png", "--png", "r.png"}),
                     "--out is already the PNG");
}

}  // namespace
