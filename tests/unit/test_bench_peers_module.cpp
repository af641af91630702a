// `brdfcl bench` and its C++ peers: the CLI links no peer code and loads brdfcl-peers.so from
// beside itself at run time; without the module it names the file and the fix, and a run that
// times the kernel alone (--pairs) needs no module.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_child.hpp"
#include "process.hpp"

namespace fs = std::filesystem;
using brdfcl::test::expectOneLineError;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;

namespace {

// The CLI copied alone into `dir`, so that no brdfcl-peers.so lies beside it.
std::string loneCli(const ScratchDir& dir) {
  const std::string copy = dir.path("brdfcl");
  fs::copy_file(BRDFCL_CLI_PATH, copy);
  return copy;
}

RunResult run(const ScratchDir& dir, const std::string& exe, std::vector<std::string> args) {
  return brdfcl::test::runCli(dir, std::move(args), {}, exe);
}

TEST(BenchPeersModule, TheCliHoldsNoPeerCode) {
  // The peer loops' symbols (bench/peers/peer_loop.cpp, one per workload and flavour). Not the
  // module table's field names (streamTriadBytesPerSecond): the CLI calls through that table, so
  // a build with debug information names them.
  const std::string cli = brdfcl::test::slurp(BRDFCL_CLI_PATH);
  ASSERT_FALSE(cli.empty());
  for (const char* symbol : {"peer_simd_all", "peer_scalar_sheen"})
    EXPECT_EQ(cli.find(symbol), std::string::npos) << symbol;
  EXPECT_TRUE(fs::exists(fs::path(BRDFCL_CLI_PATH).parent_path() / "brdfcl-peers.so"));
}

TEST(BenchPeersModule, AMissingModuleIsNamedWithTheFix) {
  ScratchDir dir("peers-missing");
  const std::string exe = loneCli(dir);
  expectOneLineError(run(dir, exe, {"bench", "--n", "16", "--runs", "1"}),
                     "brdfcl bench compares the kernel with C++ peers from '" + dir.path("brdfcl-peers.so") +
                         "', which is not built; build the CMake target brdfcl-peers ('make build' does), or time "
                         "the kernel alone with --pairs or --profile");
}

TEST(BenchPeersModule, AFileThatIsNoModuleIsRefused) {
  ScratchDir dir("peers-bad");
  const std::string exe = loneCli(dir);
  brdfcl::test::writeFile(dir.path("brdfcl-peers.so"), "not a shared object");
  expectOneLineError(run(dir, exe, {"bench", "--n", "16", "--runs", "1"}),
                     "cannot load the C++ peers '" + dir.path("brdfcl-peers.so") + "': ");
  const RunResult r = run(dir, exe, {"bench", "--n", "16", "--runs", "1"});
  EXPECT_NE(r.err.find("; rebuild the CMake target brdfcl-peers"), std::string::npos) << r.describe();
}

TEST(BenchPeersModule, PairsTimeTheKernelWithoutTheModule) {
  ScratchDir dir("peers-pairs");
  const std::string exe = loneCli(dir);
  // One pair, L = V = +Z: six float32 planes of one value.
  const float planes[6] = {0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 1.0f};
  brdfcl::test::writeFile(dir.path("pairs.f32"), std::string(reinterpret_cast<const char*>(planes), sizeof planes));
  const RunResult r = run(dir, exe, {"bench", "--pairs", dir.path("pairs.f32"), "--runs", "1", "--json"});
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_NE(r.out.find("\"samples_per_second\""), std::string::npos) << r.describe();
}

TEST(BenchPeersModule, TheBuiltModuleGivesThePeerRatios) {
  ScratchDir dir("peers-run");
  const RunResult r = run(dir, BRDFCL_CLI_PATH, {"bench", "--n", "4096", "--runs", "1", "--lobe", "sheen", "--json"});
  EXPECT_EQ(r.status, 0) << r.describe();
  for (const char* key : {"\"openmp_simd_samples_per_second\"", "\"scalar_cpp_samples_per_second\"", "\"vs_openmp_simd\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.describe();
}

}  // namespace
