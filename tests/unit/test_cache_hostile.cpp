// The disk cache against planted and damaged entries: links, corrupt or truncated tables and
// program binaries, FIFOs, devices and directories in an entry's place, a folder of another user,
// an unwritable or full cache, PoCL's own cache folder, the size budget and `brdfcl cache`.
// Every test gives the cache a scratch XDG_CACHE_HOME, so the user's real cache is never touched.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <iterator>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "host/src/io/cache.hpp"
#include "brdfcl/error.hpp"
#include "host/src/io/disk_cache.hpp"
#include "process.hpp"
#include "support.hpp"

namespace fs = std::filesystem;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::writeFile;
using brdfcl::test::slurp;

namespace {

constexpr bool kAsan = brdfcl::test::kAddressSanitizer;

const char* kMaterials = R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 0.5},
  "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.4, 0.3], "sheenRoughnessFactor": 0.4}}}]})";
const char* kSamples = "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n0,0.5,0,1,0,0.25,1\n0,-0.5,0.5,1,0.5,0,1\n";

// A scratch folder with eval's inputs and its own cache home (`cache/brdfcl` below it).
struct Case {
  ScratchDir dir;
  explicit Case(const std::string& tag) : dir(tag) {
    writeFile(dir.path("m.json"), kMaterials);
    writeFile(dir.path("s.csv"), kSamples);
  }
  fs::path cache() const { return fs::path(dir.path("cache")) / "brdfcl"; }

  // PoCL keeps its compiled kernels where this process has them, so that only brdfcl's cache is cold.
  std::map<std::string, std::string> env() const {
    std::map<std::string, std::string> e{{"XDG_CACHE_HOME", dir.path("cache")}, {"TMPDIR", dir.dir()}};
    const std::string pocl = brdfcl::test::poclCacheDir();
    if (!pocl.empty()) e["POCL_CACHE_DIR"] = pocl;
    return e;
  }

  RunResult run(std::vector<std::string> args, std::map<std::string, std::string> env,
                std::chrono::seconds timeout = std::chrono::seconds(120), std::size_t asMiB = 0) const {
    args.insert(args.begin(), BRDFCL_CLI_PATH);
    brdfcl::test::ProcessOptions o;
    o.env = std::move(env);
    o.cwd = dir.dir();
    o.timeout = timeout;
    o.addressSpaceMiB = asMiB;
    return brdfcl::test::runProcess(std::move(args), dir.dir(), o);
  }

  RunResult eval(const std::map<std::string, std::string>& env,
                 std::chrono::seconds timeout = std::chrono::seconds(120), std::size_t asMiB = 0) const {
    return run({"eval", "--materials", "m.json", "--samples", "s.csv", "--out", "out.csv"}, env, timeout, asMiB);
  }
  RunResult eval() const { return eval(env()); }
  std::string out() const { return slurp(dir.path("out.csv")); }
};

// One cold run, shared by the tests: its entries (copied into each test's cache so that only
// the entry under test is recomputed) and its output, the result every later run must give.
struct Primed {
  std::vector<fs::path> entries;
  std::string output;
};
const Primed& primed() {
  static Case c("cache-primed");
  static const Primed p = [] {
    Primed r;
    const RunResult cold = c.eval();
    EXPECT_EQ(cold.status, 0) << cold.describe();
    r.output = c.out();
    for (const auto& e : fs::directory_iterator(c.cache())) r.entries.push_back(e.path());
    return r;
  }();
  return p;
}

void prime(const Case& c) {
  fs::create_directories(c.cache());
  for (const auto& e : primed().entries) fs::copy_file(e, c.cache() / e.filename());
}

std::vector<fs::path> entriesOf(const Case& c, const std::string& prefix) {
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(c.cache()))
    if (e.path().filename().string().rfind(prefix, 0) == 0) found.push_back(e.path());
  return found;
}

std::string describeWarnings(const RunResult& r) {
  std::string s;
  for (const auto& w : r.warningLines()) s += w + "\n";
  return s;
}

// The run succeeded with the clean cache's output and exactly `warnings` warning lines, each
// naming `folder`.
void expectRecovered(const Case& c, const RunResult& r, std::size_t warnings, const std::string& folder,
                     const std::string& what) {
  EXPECT_EQ(r.status, 0) << what << ": " << r.describe();
  EXPECT_EQ(c.out(), primed().output) << what;
  EXPECT_EQ(r.warningLines().size(), warnings) << what << ":\n" << describeWarnings(r);
  for (const auto& w : r.warningLines()) EXPECT_NE(w.find(folder), std::string::npos) << what << ": " << w;
  EXPECT_TRUE(r.errorLines().empty()) << what << ": " << r.err;
}

// Sets a variable for the test's lifetime, restoring the old value (or its absence) after.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// Collects the in-process cache warnings for the test's lifetime.
class CapturedWarnings {
 public:
  CapturedWarnings() {
    brdfcl::setCacheWarningHandler([this](const std::string& w) { lines.push_back(w); });
  }
  ~CapturedWarnings() { brdfcl::setCacheWarningHandler({}); }
  std::vector<std::string> lines;
};

std::vector<unsigned char> bytesOf(std::size_t n, unsigned char seed) {
  std::vector<unsigned char> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<unsigned char>(seed + i * 7);
  return v;
}

// ---- the entry format ----

TEST(CacheEntry, RoundTripsAndRefusesAnyChange) {
  const std::string key = "program_00000000deadbeef.bin";
  const std::string payload("a program binary\0with a zero", 28);
  const std::string entry = brdfcl::detail::encodeCacheEntry(key, payload);
  EXPECT_EQ(entry.size(), brdfcl::detail::kCacheHeaderSize + key.size() + payload.size());
  const auto back = brdfcl::detail::parseCacheEntry(entry, key);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(*back, payload);
  // A renamed entry, and every flipped bit and cut end, are refused.
  EXPECT_FALSE(brdfcl::detail::parseCacheEntry(entry, "program_00000000deadbeee.bin"));
  for (std::size_t i = 0; i < entry.size(); ++i)
    for (int bit = 0; bit < 8; ++bit) {
      std::string bad = entry;
      bad[i] = char(bad[i] ^ (1 << bit));
      EXPECT_FALSE(brdfcl::detail::parseCacheEntry(bad, key)) << "byte " << i << " bit " << bit;
    }
  for (std::size_t n = 0; n < entry.size(); ++n)
    EXPECT_FALSE(brdfcl::detail::parseCacheEntry(std::string_view(entry).substr(0, n), key)) << n;
  EXPECT_FALSE(brdfcl::detail::parseCacheEntry(entry + "x", key));
}

TEST(CacheEntry, ARenamedEntryIsRefusedWithOneWarning) {
  ScratchDir dir("cache-renamed");
  ScopedEnv home("XDG_CACHE_HOME", dir.dir());
  CapturedWarnings warnings;
  brdfcl::detail::storeCachedBytes("program_aaaa.bin", bytesOf(100, 1));
  ASSERT_EQ(brdfcl::detail::loadCachedBytes("program_aaaa.bin"), bytesOf(100, 1));
  fs::rename(dir.path("brdfcl/program_aaaa.bin"), dir.path("brdfcl/program_bbbb.bin"));
  EXPECT_TRUE(brdfcl::detail::loadCachedBytes("program_bbbb.bin").empty());
  ASSERT_EQ(warnings.lines.size(), 1u);
  EXPECT_NE(warnings.lines[0].find(dir.path("brdfcl/program_bbbb.bin")), std::string::npos) << warnings.lines[0];
  EXPECT_FALSE(fs::exists(dir.path("brdfcl/program_bbbb.bin")));
}

// The folder and its entries are the user's alone.
TEST(CacheEntry, FolderIsCreatedPrivate) {
  ScratchDir dir("cache-private");
  ScopedEnv home("XDG_CACHE_HOME", dir.path("new/home"));
  brdfcl::detail::storeCachedBytes("program_mode.bin", bytesOf(10, 2));
  EXPECT_EQ(fs::status(dir.path("new/home/brdfcl")).permissions() & fs::perms::all, fs::perms::owner_all);
  EXPECT_EQ(fs::status(dir.path("new/home/brdfcl/program_mode.bin")).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
}

// A zero-length table is not a hit, and a table of the wrong length is removed and recomputed.
TEST(CacheEntry, TableOfTheWrongLengthIsRemoved) {
  ScratchDir dir("cache-length");
  ScopedEnv home("XDG_CACHE_HOME", dir.dir());
  CapturedWarnings warnings;
  brdfcl::detail::storeCachedFloats("sheen_e_len.f32", std::vector<float>(10, 1.0f));
  std::vector<float> eleven(11);
  EXPECT_FALSE(brdfcl::detail::loadCachedFloats("sheen_e_len.f32", eleven));
  EXPECT_EQ(warnings.lines.size(), 1u);
  EXPECT_FALSE(fs::exists(dir.path("brdfcl/sheen_e_len.f32")));
}

// ---- the budget ----

TEST(CacheBudget, PrunesTheLeastRecentlyUsed) {
  ScratchDir dir("cache-budget");
  ScopedEnv home("XDG_CACHE_HOME", dir.dir());
  CapturedWarnings warnings;
  const std::size_t payload = 1000, entry = brdfcl::detail::kCacheHeaderSize + std::string("program_aa.bin").size() + payload;
  ScopedEnv budget("BRDFCL_CACHE_MAX", std::to_string(2 * entry + 10));
  const auto file = [&](const std::string& n) { return fs::path(dir.path("brdfcl")) / n; };
  brdfcl::detail::storeCachedBytes("program_aa.bin", bytesOf(payload, 1));
  brdfcl::detail::storeCachedBytes("program_bb.bin", bytesOf(payload, 2));
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(file("program_aa.bin"), now - std::chrono::hours(3));
  fs::last_write_time(file("program_bb.bin"), now - std::chrono::hours(2));
  // aa is used now: its mark moves, and bb becomes the least recently used.
  ASSERT_EQ(brdfcl::detail::loadCachedBytes("program_aa.bin"), bytesOf(payload, 1));
  brdfcl::detail::storeCachedBytes("program_cc.bin", bytesOf(payload, 3));
  EXPECT_TRUE(fs::exists(file("program_aa.bin")));
  EXPECT_FALSE(fs::exists(file("program_bb.bin")));
  EXPECT_TRUE(fs::exists(file("program_cc.bin")));
  EXPECT_TRUE(warnings.lines.empty());

  // An entry larger than the whole budget is not stored, with a warning.
  brdfcl::detail::storeCachedBytes("program_dd.bin", bytesOf(3 * payload, 4));
  EXPECT_FALSE(fs::exists(file("program_dd.bin")));
  EXPECT_EQ(warnings.lines.size(), 1u);
  EXPECT_TRUE(fs::exists(file("program_aa.bin")));

  const brdfcl::CacheUsage u = brdfcl::cacheUsage();
  EXPECT_EQ(u.budget, 2 * entry + 10);
  EXPECT_EQ(u.entries, 2u);
  EXPECT_EQ(u.bytes, 2 * entry);
}

TEST(CacheBudget, ParsesSizesAndRefusesTheRest) {
  const std::map<std::string, std::uint64_t> good{
      {"0", 0}, {"123", 123}, {"4K", 4096}, {"2m", 2u << 20}, {"1G", 1u << 30}, {"3GiB", 3ull << 30}, {"1T", 1ull << 40}};
  for (const auto& [text, bytes] : good) {
    ScopedEnv v("BRDFCL_CACHE_MAX", text);
    EXPECT_EQ(brdfcl::cacheBudget(), bytes) << text;
  }
  for (const std::string text : {"", "abc", "-1", "1.5G", "12 M", "1X", "99999999999999999999", "20000000T"}) {
    ScopedEnv v("BRDFCL_CACHE_MAX", text);
    try {
      brdfcl::cacheBudget();
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const brdfcl::Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("BRDFCL_CACHE_MAX '", 0), 0u) << e.what();
    }
  }
}

TEST(CacheBudget, BadValueIsOneLineError) {
  Case c("cache-bad-budget");
  auto env = c.env();
  env["BRDFCL_CACHE_MAX"] = "lots";
  const RunResult r = c.eval(env);
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.err,
            "brdfcl: BRDFCL_CACHE_MAX 'lots': not a size; give bytes with an optional K, M, G or T suffix (e.g. "
            "512M), or 0 to turn the cache off\n");
  EXPECT_FALSE(fs::exists(c.dir.path("out.csv")));
}

// ---- planted and damaged entries, through the CLI ----

TEST(CacheHostile, PlantedLinksNeverRedirectAWrite) {
  Case c("cache-links");
  prime(c);
  const std::string victim = c.dir.path("victim");
  writeFile(victim, "precious");
  const auto tables = entriesOf(c, "sheen_e_"), programs = entriesOf(c, "program_");
  ASSERT_FALSE(tables.empty());
  ASSERT_FALSE(programs.empty());
  for (const auto& e : tables) {
    fs::remove(e);
    fs::create_symlink(victim, e);
  }
  for (const auto& e : programs) {
    fs::remove(e);
    fs::create_symlink(victim, e);
  }
  const RunResult r = c.eval();
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(c.out(), primed().output);
  EXPECT_EQ(slurp(victim), "precious");
  for (const auto& w : r.warningLines()) EXPECT_NE(w.find(c.cache().string()), std::string::npos) << w;
  EXPECT_FALSE(r.warningLines().empty());
  // The tables were recomputed and stored as files of their own.
  for (const auto& e : tables) EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(e))) << e;
}

// Each damage, alone, costs one warning and a recompute, and the result is the clean run's.
TEST(CacheHostile, CorruptEntriesAreRecomputed) {
  struct Damage {
    std::string what, prefix;
    void (*apply)(const fs::path&);
  };
  const std::vector<Damage> damages{
      {"program truncated", "program_", [](const fs::path& p) { fs::resize_file(p, fs::file_size(p) / 2); }},
      {"program with a flipped bit", "program_",
       [](const fs::path& p) {
         std::string b = slurp(p.string());
         b[b.size() / 2] = char(b[b.size() / 2] ^ 0x10);
         writeFile(p.string(), b);
       }},
      {"program emptied", "program_", [](const fs::path& p) { fs::resize_file(p, 0); }},
      {"table with a flipped bit", "sheen_e_",
       [](const fs::path& p) {
         std::string b = slurp(p.string());
         b[b.size() / 3] = char(b[b.size() / 3] ^ 0x40);
         writeFile(p.string(), b);
       }},
      {"table truncated", "sheen_e_", [](const fs::path& p) { fs::resize_file(p, fs::file_size(p) - 4); }},
  };
  for (const auto& d : damages) {
    Case c("cache-corrupt");
    prime(c);
    // The program eval builds is one of them: damage all, and only what the run reads warns.
    const auto targets = entriesOf(c, d.prefix);
    ASSERT_FALSE(targets.empty()) << d.what;
    if (d.prefix == "program_") {
      for (const auto& p : targets) d.apply(p);
    } else {
      d.apply(targets[0]);
    }
    const RunResult r = c.eval();
    expectRecovered(c, r, 1, c.cache().string(), d.what);
    // The damaged entry the run read was stored again whole. A program binary's size may differ
    // from the first store's (PoCL includes the work-group variants its own cache holds by then),
    // so "whole" means that the entry parses and checks out under its name.
    const std::vector<fs::path> damaged =
        d.prefix == "program_" ? targets : std::vector<fs::path>{targets[0]};
    std::size_t whole = 0;
    for (const auto& p : damaged)
      whole += fs::exists(p) && brdfcl::detail::parseCacheEntry(slurp(p.string()), p.filename().string()).has_value();
    EXPECT_GE(whole, 1u) << d.what;
  }
}

// A directory, a FIFO or a link to /dev/zero where an entry should be: no hang, no huge read.
TEST(CacheHostile, NonRegularEntriesDoNotHang) {
  struct Plant {
    std::string what;
    void (*apply)(const fs::path&);
  };
  const std::vector<Plant> plants{
      {"directory", [](const fs::path& p) { fs::create_directory(p); }},
      {"FIFO", [](const fs::path& p) { ASSERT_EQ(::mkfifo(p.c_str(), 0600), 0); }},
      {"link to /dev/zero", [](const fs::path& p) { fs::create_symlink("/dev/zero", p); }},
  };
  for (const auto& plant : plants)
    for (const std::string prefix : {"program_", "sheen_e_"}) {
      const std::string what = plant.what + " for " + prefix;
      Case c("cache-nonregular");
      prime(c);
      for (const auto& p : entriesOf(c, prefix)) {
        fs::remove(p);
        plant.apply(p);
      }
      RunResult r;
      try {
        r = c.eval(c.env(), std::chrono::seconds(60), kAsan ? 0 : 16384);
      } catch (const std::exception& e) {
        ADD_FAILURE() << what << ": " << e.what();
        continue;
      }
      EXPECT_EQ(r.status, 0) << what << ": " << r.describe();
      EXPECT_EQ(c.out(), primed().output) << what;
      EXPECT_GE(r.warningLines().size(), 1u) << what;
      for (const auto& w : r.warningLines()) EXPECT_NE(w.find(c.cache().string()), std::string::npos) << w;
    }
}

// ---- the folder ----

TEST(CacheHostile, FolderOfAnotherUserIsNotUsed) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to give the cache folder to another user";
  Case c("cache-foreign");
  prime(c);
  const auto table = entriesOf(c, "sheen_e_").at(0);
  // Were the folder used, this table would give another result.
  std::string b = slurp(table.string());
  b[b.size() / 2] = char(b[b.size() / 2] ^ 0x40);
  writeFile(table.string(), b);
  ASSERT_EQ(::chown(c.cache().c_str(), 65534, 65534), 0);
  const auto count = std::distance(fs::directory_iterator(c.cache()), fs::directory_iterator());

  const RunResult r = c.eval();
  expectRecovered(c, r, 1, c.cache().string(), "foreign folder");
  EXPECT_NE(r.err.find("owned by uid 65534"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(table.string()), b);
  EXPECT_EQ(std::distance(fs::directory_iterator(c.cache()), fs::directory_iterator()), count);
}

TEST(CacheHostile, EntryOfAnotherUserIsNotRead) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to give an entry to another user";
  Case c("cache-foreign-entry");
  prime(c);
  for (const auto& p : entriesOf(c, "sheen_e_")) ASSERT_EQ(::chown(p.c_str(), 65534, 65534), 0);
  const RunResult r = c.eval();
  expectRecovered(c, r, 1, c.cache().string(), "foreign entry");
}

// A cache home below a regular file: neither brdfcl's folder nor PoCL's can be created (root
// included). The run computes everything, with one warning for each folder, and PoCL's private
// temporary folder is gone afterwards. An empty POCL_CACHE_DIR lets PoCL choose its own folder.
TEST(CacheHostile, UncreatableCacheDegrades) {
  Case c("cache-uncreatable");
  writeFile(c.dir.path("file"), "not a folder");
  fs::create_directories(c.dir.path("tmp"));
  std::map<std::string, std::string> env{
      {"XDG_CACHE_HOME", c.dir.path("file/cache")}, {"POCL_CACHE_DIR", ""}, {"TMPDIR", c.dir.path("tmp")}};
  const RunResult r = c.eval(env, std::chrono::seconds(300));
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(c.out(), primed().output);
  ASSERT_EQ(r.warningLines().size(), 2u) << r.err;
  EXPECT_NE(r.err.find("cache folder '" + c.dir.path("file/cache/brdfcl") + "'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("PoCL's kernel cache '" + c.dir.path("file/cache/pocl/kcache") + "'"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::is_empty(c.dir.path("tmp")));

  // With no temporary folder either, PoCL finds no device: the warning says what to set.
  env["TMPDIR"] = c.dir.path("file/tmp");
  const RunResult none = c.eval(env);
  EXPECT_EQ(none.status, 2) << none.describe();
  EXPECT_NE(none.err.find("no temporary folder could be made (Not a directory); set POCL_CACHE_DIR"),
            std::string::npos)
      << none.err;
}

TEST(CacheHostile, EmptyPoclCacheDirIsIgnored) {
  Case c("cache-empty-pocl");
  auto env = c.env();
  env["POCL_CACHE_DIR"] = "";
  const RunResult r = c.run({"devices"}, env);
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.warningLines().empty()) << r.err;
}

// A cache on a full disk (a tiny tmpfs): brdfcl's writes fail with one warning, PoCL gets a
// temporary folder, and the result is the clean run's.
TEST(CacheHostile, FullDiskDegrades) {
  Case c("cache-full");
  const std::string mnt = c.dir.path("full");
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << "); needs root and CAP_SYS_ADMIN";
  struct Unmount {
    std::string path;
    ~Unmount() { ::umount2(path.c_str(), MNT_DETACH); }
  } unmount{mnt};
  fs::create_directories(c.dir.path("tmp"));
  std::map<std::string, std::string> env{{"XDG_CACHE_HOME", mnt}, {"POCL_CACHE_DIR", ""}, {"TMPDIR", c.dir.path("tmp")}};
  const RunResult r = c.eval(env, std::chrono::seconds(300));
  EXPECT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(c.out(), primed().output);
  EXPECT_EQ(r.warningLines().size(), 2u) << r.err;
  EXPECT_NE(r.err.find("cannot write to the cache folder '" + mnt + "/brdfcl': No space left on device"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("PoCL's kernel cache '" + mnt + "/pocl/kcache' has only"), std::string::npos) << r.err;
  // No temporary was left behind on the full disk.
  for (const auto& e : fs::directory_iterator(mnt + "/brdfcl"))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

// ---- brdfcl cache ----

TEST(CacheCommand, InfoListsAndClearRemovesOnlyEntries) {
  Case c("cache-command");
  prime(c);
  const std::string victim = c.dir.path("victim.f32");
  writeFile(victim, "keep me");
  writeFile((c.cache() / "notes.txt").string(), "not brdfcl's");
  fs::create_symlink(victim, c.cache() / "sheen_e_planted.f32");
  fs::create_directory(c.cache() / "program_folder.bin");
  writeFile((c.cache() / "program_folder.bin" / "inside").string(), "x");

  const RunResult info = c.run({"cache", "--info"}, c.env());
  ASSERT_EQ(info.status, 0) << info.describe();
  EXPECT_NE(info.out.find("folder: " + c.cache().string() + "\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("budget: 1073741824 bytes"), std::string::npos) << info.out;
  std::uintmax_t bytes = 0;
  for (const auto& e : primed().entries) bytes += fs::file_size(e);
  // The planted link is an entry name: counted, with no bytes.
  EXPECT_NE(info.out.find("entries: " + std::to_string(primed().entries.size() + 1) + ", " + std::to_string(bytes) +
                          " bytes"),
            std::string::npos)
      << info.out;
  for (const std::string kind : {"sheen_e", "env", "ggx_dfg", "aniso_dfg", "program"})
    EXPECT_NE(info.out.find("  " + kind + " "), std::string::npos) << info.out;

  const RunResult clear = c.run({"cache", "--clear"}, c.env());
  ASSERT_EQ(clear.status, 0) << clear.describe();
  EXPECT_NE(clear.out.find("removed " + std::to_string(primed().entries.size() + 1) + " entries"), std::string::npos)
      << clear.out;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(c.cache())) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"notes.txt", "program_folder.bin"}));
  EXPECT_EQ(slurp(victim), "keep me");
  EXPECT_TRUE(fs::exists(c.cache() / "program_folder.bin" / "inside"));

  const RunResult empty = c.run({"cache"}, c.env());
  ASSERT_EQ(empty.status, 0) << empty.describe();
  EXPECT_NE(empty.out.find("entries: 0, 0 bytes"), std::string::npos) << empty.out;

  EXPECT_EQ(c.run({"cache", "--info", "--clear"}, c.env()).status, 2);
}

TEST(CacheCommand, ClearRefusesAFolderOfAnotherUser) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to give the cache folder to another user";
  Case c("cache-command-foreign");
  prime(c);
  ASSERT_EQ(::chown(c.cache().c_str(), 65534, 65534), 0);
  const RunResult r = c.run({"cache", "--clear"}, c.env());
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.err, "brdfcl: cache folder '" + c.cache().string() + "': owned by uid 65534, not by this user (uid 0); "
                   "nothing removed\n");
  EXPECT_EQ(entriesOf(c, "").size(), primed().entries.size());
}

}  // namespace
