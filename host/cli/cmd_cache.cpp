// `brdfcl cache --info | --clear`: shows brdfcl's disk cache (folder, budget, entries and bytes by
// kind) or removes its entries. The listing and the removal live in the library (io/cache.hpp).
#include <fmt/format.h>

#include "host/src/io/cache.hpp"
#include "brdfcl/error.hpp"
#include "commands.hpp"

namespace brdfcl::cli {

namespace {
std::string mib(std::uint64_t bytes) { return fmt::format("{:.1f} MiB", double(bytes) / double(1 << 20)); }

void printInfo() {
  const CacheUsage u = cacheUsage();
  if (u.folder.empty()) {
    fmt::print("folder: none (neither XDG_CACHE_HOME nor HOME is set): nothing is cached\n");
    return;
  }
  fmt::print("folder: {}\n", u.folder);
  if (!u.problem.empty()) fmt::print("not used: {}\n", u.problem);
  if (u.budget == 0) fmt::print("budget: 0 (BRDFCL_CACHE_MAX): the cache is off\n");
  else fmt::print("budget: {} bytes ({}; BRDFCL_CACHE_MAX)\n", u.budget, mib(u.budget));
  fmt::print("entries: {}, {} bytes ({})\n", u.entries, u.bytes, mib(u.bytes));
  for (const auto& k : u.kinds) fmt::print("  {:<10} {:>6} entries {:>14} bytes\n", k.kind, k.entries, k.bytes);
}
}  // namespace

void addCacheCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("cache", "Show (--info, the default) or clear (--clear) brdfcl's disk cache");
  auto* info = cmd->add_flag("--info", "print the folder, the budget (BRDFCL_CACHE_MAX) and the entries by kind");
  auto* clear = cmd->add_flag("--clear", "remove brdfcl's entries from the folder (nothing else in it)");
  info->excludes(clear);
  cmd->callback([clear] {
    if (!*clear) {
      printInfo();
      return;
    }
    const CacheCleared c = clearCache();
    if (c.folder.empty()) fmt::print("no cache folder (neither XDG_CACHE_HOME nor HOME is set)\n");
    else fmt::print("removed {} entries ({} bytes) from {}\n", c.entries, c.bytes, c.folder);
  });
}

}  // namespace brdfcl::cli
