// The disk cache of prepared image-based light: a warm run reads the prefiltered chains,
// irradiance and DFG table instead of recomputing them and renders the same bytes; a truncated,
// corrupt or foreign cache file is recomputed, and another environment gets another entry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "host/src/io/disk_cache.hpp"
#include "process.hpp"

namespace fs = std::filesystem;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;

namespace {

// A 16 x 8 Radiance HDR of constant radiance: small, so a cold preparation takes little time.
void writeTinyHdr(const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n";
  for (int i = 0; i < 16 * 8; ++i) out << char(128) << char(140) << char(160) << char(129);
}

// The child gets a cache directory of its own, seeded with the sheen tables this process already
// baked (so that only the environment is cold), and keeps PoCL's kernel cache, which XDG_CACHE_HOME
// would otherwise move.
std::map<std::string, std::string> childEnvironment(const ScratchDir& dir) {
  const fs::path mine = brdfcl::detail::cacheDirectory(), theirs = dir.path("cache/brdfcl");
  fs::create_directories(theirs);
  std::error_code ec;
  if (!mine.empty() && fs::is_directory(mine, ec))
    for (const auto& e : fs::directory_iterator(mine, ec))
      if (e.path().filename().string().rfind("sheen_e_", 0) == 0) fs::copy_file(e.path(), theirs / e.path().filename(), ec);
  const std::string pocl = brdfcl::test::poclCacheDir();
  std::map<std::string, std::string> env{{"XDG_CACHE_HOME", dir.path("cache")}};
  if (!pocl.empty()) env["POCL_CACHE_DIR"] = pocl;
  return env;
}

RunResult render(const ScratchDir& dir, const std::string& out, std::vector<std::string> extra = {}) {
  std::vector<std::string> args{BRDFCL_CLI_PATH, "render", "--size", "16x16", "--environment", "tiny.hdr", "--out", out};
  args.insert(args.end(), extra.begin(), extra.end());
  brdfcl::test::ProcessOptions o;
  o.env = childEnvironment(dir);
  o.cwd = dir.dir();
  return brdfcl::test::runProcess(std::move(args), dir.dir(), o);
}

std::vector<fs::path> entries(const ScratchDir& dir, const std::string& prefix) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir.path("cache/brdfcl")))
    if (e.path().filename().string().rfind(prefix, 0) == 0) found.push_back(e.path());
  return found;
}

TEST(EnvironmentCache, WarmRunReadsTheCacheAndRendersTheSameBytes) {
  ScratchDir dir("envcache");
  writeTinyHdr(dir.path("tiny.hdr"));
  const RunResult cold = render(dir, "cold.png");
  ASSERT_EQ(cold.status, 0) << cold.describe();
  const auto env = entries(dir, "env_");
  ASSERT_EQ(env.size(), 1u);
  ASSERT_EQ(entries(dir, "ggx_dfg_").size(), 1u);
  const auto size = fs::file_size(env[0]);

  const RunResult warm = render(dir, "warm.png");
  ASSERT_EQ(warm.status, 0) << warm.describe();
  EXPECT_EQ(brdfcl::test::slurp(dir.path("cold.png")), brdfcl::test::slurp(dir.path("warm.png")));

  // The cache is what a warm run reads: a well-formed entry of zeros changes the image.
  const std::string name = env[0].filename().string(), whole = brdfcl::test::slurp(env[0].string());
  const auto payload = brdfcl::detail::parseCacheEntry(whole, name);
  ASSERT_TRUE(payload.has_value());
  std::ofstream(env[0], std::ios::binary | std::ios::trunc)
      << brdfcl::detail::encodeCacheEntry(name, std::string(payload->size(), '\0'));
  ASSERT_EQ(render(dir, "poisoned.png").status, 0);
  EXPECT_NE(brdfcl::test::slurp(dir.path("cold.png")), brdfcl::test::slurp(dir.path("poisoned.png")));

  // Zeros of the right length without the entry's header and checksum are refused with one
  // warning, recomputed, and rewritten whole.
  std::ofstream(env[0], std::ios::binary | std::ios::trunc) << std::string(std::size_t(size), '\0');
  const RunResult refused = render(dir, "refused.png");
  ASSERT_EQ(refused.status, 0) << refused.describe();
  std::size_t aboutIt = 0;
  for (const auto& w : refused.warningLines()) aboutIt += w.find(name) != std::string::npos;
  EXPECT_EQ(aboutIt, 1u) << refused.err;
  EXPECT_EQ(brdfcl::test::slurp(dir.path("cold.png")), brdfcl::test::slurp(dir.path("refused.png")));
  EXPECT_EQ(brdfcl::test::slurp(env[0].string()), whole);

  // A truncated entry is not trusted: recomputed, rewritten whole, same bytes as the first run.
  fs::resize_file(env[0], size / 2);
  ASSERT_EQ(render(dir, "again.png").status, 0);
  EXPECT_EQ(fs::file_size(env[0]), size);
  EXPECT_EQ(brdfcl::test::slurp(dir.path("cold.png")), brdfcl::test::slurp(dir.path("again.png")));

  // Another environment (the same file, twice as bright) is another entry.
  ASSERT_EQ(render(dir, "bright.png", {"--env-intensity", "2"}).status, 0);
  EXPECT_EQ(entries(dir, "env_").size(), 2u);
}

TEST(EnvironmentCache, ContentHashSeesEveryByte) {
  std::vector<float> a(1000, 1.0f);
  const auto h = brdfcl::detail::contentHash(a);
  a[999] = std::nextafter(1.0f, 2.0f);
  EXPECT_NE(brdfcl::detail::contentHash(a), h);
  EXPECT_NE(brdfcl::detail::contentHash("abc"), brdfcl::detail::contentHash("abd"));
  EXPECT_NE(brdfcl::detail::contentHash("abc", 1), brdfcl::detail::contentHash("abc", 2));
}

}  // namespace
