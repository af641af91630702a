// Runtime tests: device listing, selection errors, include expansion, the program cache and the
// profiling queue.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "host/src/runtime/opencl.hpp"
#include "host/src/io/disk_cache.hpp"
#include "process.hpp"
#include "scratch_cache_home.hpp"
#include "support.hpp"

using namespace brdfcl;

namespace brdfcl::detail {
const std::map<std::string, std::string>& embeddedKernels();
}
using brdfcl::test::ScratchCacheHome;

TEST(Runtime, ListsAtLeastOneDevice) {
  auto devices = listDevices();
  ASSERT_FALSE(devices.empty());
  EXPECT_FALSE(devices[0].name.empty());
  EXPECT_GT(devices[0].computeUnits, 0u);
  EXPECT_GT(devices[0].maxAlloc, 0u);
}

// Run in a child by the test below: the value PoCL sees once brdfcl has made its first OpenCL call.
TEST(Runtime, DISABLED_PoclAffinitySeenByPocl) {
  listDevices();
  const char* want = std::getenv("BRDFCL_EXPECT_POCL_AFFINITY");
  const char* got = std::getenv("POCL_AFFINITY");
  ASSERT_NE(want, nullptr);
  ASSERT_NE(got, nullptr);
  EXPECT_STREQ(got, want);
}

// PoCL's worker threads are pinned one a core (runtime.cpp, pinPoclWorkers), unless the user set
// POCL_AFFINITY, whose value is then kept.
TEST(Runtime, PinsPoclWorkersUnlessTheUserChose) {
  // The child runs the one test named, whatever shard of the suite this process runs
  // (scripts/test-shards): the sharding variables are not passed on.
  const std::string env = "env -u GTEST_TOTAL_SHARDS -u GTEST_SHARD_INDEX ";
  const std::string child =
      " /proc/" + std::to_string(::getpid()) + "/exe --gtest_also_run_disabled_tests"
      " --gtest_filter=Runtime.DISABLED_PoclAffinitySeenByPocl > /dev/null 2>&1";
  EXPECT_EQ(std::system((env + "-u POCL_AFFINITY BRDFCL_EXPECT_POCL_AFFINITY=1" + child).c_str()), 0);
  EXPECT_EQ(std::system((env + "POCL_AFFINITY=0 BRDFCL_EXPECT_POCL_AFFINITY=0" + child).c_str()), 0);
  EXPECT_NE(std::system((env + "POCL_AFFINITY=0 BRDFCL_EXPECT_POCL_AFFINITY=1" + child).c_str()), 0)
      << "the child check cannot fail";
}

TEST(Runtime, UnknownDeviceNameIsAnError) {
  try {
    Runtime rt("no-such-device-xyz");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.exitCode(), 2);
    EXPECT_NE(std::string(e.what()).find("no-such-device-xyz"), std::string::npos);
  }
}

TEST(Runtime, DeviceIndexOutOfRangeIsAnError) { EXPECT_THROW(Runtime rt("999"), Error); }

TEST(Runtime, IncludesAreExpandedOnce) {
  auto src = kernelSource("eval.cl");
  EXPECT_EQ(src.find("#include \""), std::string::npos);  // <cstdint> stays: host-only branch
  // material_layout.h is reached through several headers but must appear once.
  auto first = src.find("typedef struct brdfcl_material");
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(src.find("typedef struct brdfcl_material", first + 1), std::string::npos);
}

// Every device compiles the kernels as OpenCL C 1.2, which has no variadic macros. PoCL's clang
// accepts them anyway; NVIDIA's compiler fails the build ("variadic macros not supported in
// OpenCL"), so nothing CI runs would otherwise notice one.
TEST(Runtime, KernelsDefineNoVariadicMacros) {
  const std::regex variadic(R"(#[ \t]*define[ \t]+\w+\([^)]*\.\.\.)");
  const auto& files = detail::embeddedKernels();
  ASSERT_GT(files.size(), 10u);
  // Continued lines joined first, so that a parameter list broken across lines is seen whole.
  const auto joined = [](const std::string& text) { return std::regex_replace(text, std::regex(R"(\\\r?\n)"), " "); };
  for (const auto& [name, text] : files) {
    std::smatch m;
    const std::string whole = joined(text);
    EXPECT_FALSE(std::regex_search(whole, m, variadic)) << name << " defines a variadic macro: " << m.str();
  }
  // The check itself finds one, on one line and continued.
  EXPECT_TRUE(std::regex_search(joined("#define LIST(F, ...) F(__VA_ARGS__)"), variadic));
  EXPECT_TRUE(std::regex_search(joined("#define LIST(F, \\\n   ...) F(__VA_ARGS__)"), variadic));
}

TEST(Runtime, ProgramCacheReturnsTheSameProgram) {
  Runtime rt;
  auto a = rt.opencl().program("eval.cl", "-DBRDFCL_W=16");
  auto b = rt.opencl().program("eval.cl", "-DBRDFCL_W=16");
  EXPECT_EQ(a(), b());
  auto c = rt.opencl().program("eval.cl", "-DBRDFCL_W=8");
  EXPECT_NE(a(), c());
}

TEST(Runtime, BuildFailureCarriesTheBuildLog) {
  Runtime rt;
  try {
    rt.opencl().program("eval.cl", "-DBRDFCL_W=3");  // lanes.h rejects widths other than 1, 4, 8, 16
    FAIL() << "expected a build error";
  } catch (const Error& e) {
    std::string what = e.what();
    EXPECT_NE(what.find("build log"), std::string::npos) << what;
    EXPECT_NE(what.find("BRDFCL_W must be"), std::string::npos) << what;
  }
}

// The queue profiles, so a batch reports its launch's device time: more than nothing, and no
// more than the whole run that contains it.
TEST(Runtime, BatchReportsItsLaunchTime) {
  std::mt19937_64 rng(test::seed() + 5);
  Evaluator ev(test::runtime(), EvalOptions{});
  const std::vector<MaterialParams> materials = {test::randomMaterial(rng)};
  const Samples s = test::randomSamples(rng, 1 << 16, 1);
  SoaBatch batch(ev, materials, s.size());
  EXPECT_EQ(batch.lastKernelSeconds(), 0.0);
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < s.size(); ++i) {
      batch.direction(c)[i] = s.L[3 * i + std::size_t(c)];
      batch.direction(3 + c)[i] = s.V[3 * i + std::size_t(c)];
    }
  batch.setCount(s.size());
  batch.run();  // program build
  const auto t0 = std::chrono::steady_clock::now();
  batch.run();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GT(batch.lastKernelSeconds(), 0.0);
  EXPECT_LE(batch.lastKernelSeconds(), wall);
}

// Programs go to brdfcl's disk cache as binaries. A fresh Runtime builds from them and computes
// the same bits; a damaged binary is rebuilt from source (and stored again).
TEST(Runtime, ProgramBinariesComeBackFromTheDiskCache) {
  test::ScratchDir dir("binaries");
  ScratchCacheHome home(dir);
  std::mt19937_64 rng(test::seed() + 13);
  const std::vector<MaterialParams> materials = {test::randomMaterial(rng), test::randomMaterial(rng)};
  const Samples s = test::randomSamples(rng, 1000, 2);
  const auto evaluate = [&](Runtime& rt) { return Evaluator(rt, EvalOptions{}).evaluate(materials, s); };
  const auto binaries = [&] {
    std::vector<std::filesystem::path> found;
    for (const auto& e : std::filesystem::directory_iterator(dir.path("brdfcl")))
      if (e.path().filename().string().rfind("program_", 0) == 0) found.push_back(e.path());
    return found;
  };
  Runtime first;
  const std::vector<float> want = evaluate(first);
  EXPECT_EQ(first.programsFromDiskCache(), 0u);
  ASSERT_FALSE(binaries().empty());

  Runtime second;
  EXPECT_EQ(evaluate(second), want);
  EXPECT_GT(second.programsFromDiskCache(), 0u);

  for (const auto& p : binaries()) std::ofstream(p, std::ios::binary) << "not a program";
  Runtime third;
  EXPECT_EQ(evaluate(third), want);
  EXPECT_EQ(third.programsFromDiskCache(), 0u);
  // The eval program was rebuilt and stored again (the bake's is not needed: its table is cached).
  std::size_t restored = 0;
  for (const auto& p : binaries()) restored += std::filesystem::file_size(p) > 100;
  EXPECT_GE(restored, 1u);

}

// The binaries are pruned to the most recently used 512 when a new one is stored.
TEST(Runtime, ProgramBinaryCacheKeepsTheMostRecentlyUsed) {
  test::ScratchDir dir("binaries-pruned");
  ScratchCacheHome home(dir);
  const auto cache = std::filesystem::path(dir.path("brdfcl"));
  std::filesystem::create_directories(cache);
  const auto now = std::filesystem::file_time_type::clock::now();
  for (int i = 0; i < 600; ++i) {
    const auto p = cache / ("program_old_" + std::to_string(i) + ".bin");
    std::ofstream(p) << "old";
    std::filesystem::last_write_time(p, now - std::chrono::hours(1000 - i));
  }
  std::ofstream(cache / "sheen_e_kept.f32") << "a table, not a program";
  std::mt19937_64 rng(test::seed() + 17);
  const std::vector<MaterialParams> materials = {test::randomMaterial(rng)};
  Runtime rt;
  Evaluator(rt, EvalOptions{}).evaluate(materials, test::randomSamples(rng, 100, 1));
  std::size_t programs = 0, fresh = 0;
  for (const auto& e : std::filesystem::directory_iterator(cache)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("program_", 0) != 0) continue;
    ++programs;
    fresh += name.rfind("program_old_", 0) != 0;
  }
  EXPECT_EQ(programs, 512u);
  EXPECT_GE(fresh, 1u);
  EXPECT_FALSE(std::filesystem::exists(cache / "program_old_0.bin"));
  EXPECT_TRUE(std::filesystem::exists(cache / "program_old_599.bin"));
  EXPECT_TRUE(std::filesystem::exists(cache / "sheen_e_kept.f32"));
}

// A hit moves an hour-old mark to now and leaves a recent one alone, so warm starts write no metadata.
TEST(Runtime, CacheHitsMarkUseAtMostHourly) {
  test::ScratchDir dir("binaries-marked");
  ScratchCacheHome home(dir);
  detail::storeCachedBytes("program_mark.bin", {1, 2, 3});
  const auto file = detail::cacheDirectory() / "program_mark.bin";
  ASSERT_TRUE(std::filesystem::exists(file));
  const auto now = std::filesystem::file_time_type::clock::now();
  const auto recent = now - std::chrono::minutes(10), stale = now - std::chrono::hours(3);
  std::filesystem::last_write_time(file, recent);
  EXPECT_EQ(detail::loadCachedBytes("program_mark.bin").size(), 3u);
  EXPECT_EQ(std::filesystem::last_write_time(file), recent);
  std::filesystem::last_write_time(file, stale);
  EXPECT_EQ(detail::loadCachedBytes("program_mark.bin").size(), 3u);
  EXPECT_GT(std::filesystem::last_write_time(file), now - std::chrono::minutes(1));
}
