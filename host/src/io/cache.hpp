// brdfcl's disk cache as users see it (`brdfcl cache`): where it is, its size budget, what it
// holds by kind, clearing it, and where its warnings go.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace brdfcl {

// The budget when BRDFCL_CACHE_MAX is not set: 1 GiB.
constexpr std::uint64_t kDefaultCacheBudget = std::uint64_t(1) << 30;

// BRDFCL_CACHE_MAX in bytes (digits with an optional K, M, G or T suffix, binary multiples; 0
// turns the cache off), or kDefaultCacheBudget when it is unset. Throws brdfcl::Error naming the
// variable for any other value.
std::uint64_t cacheBudget();

// The kinds of entry, by file-name prefix: "sheen_e", "env", "ggx_dfg", "aniso_dfg", "program".
const std::vector<std::string>& cacheKinds();

struct CacheKindUsage {
  std::string kind;
  std::size_t entries = 0;
  std::uint64_t bytes = 0;
};

struct CacheUsage {
  std::string folder;   // empty when neither XDG_CACHE_HOME nor HOME is set
  std::string problem;  // why the folder is not used ("" when it is, or does not exist yet)
  std::uint64_t budget = 0;
  std::vector<CacheKindUsage> kinds;  // one per cacheKinds(), in that order
  std::size_t entries = 0;
  std::uint64_t bytes = 0;
};

// Lists the folder's entries without changing anything. Names that are not brdfcl's entries
// are not counted, and links are not followed.
CacheUsage cacheUsage();

struct CacheCleared {
  std::string folder;
  std::size_t entries = 0;
  std::uint64_t bytes = 0;
};

// Removes brdfcl's entries (and the temporaries dead brdfcl processes left) from the folder,
// nothing else: other files, subfolders and the targets of links stay. Throws brdfcl::Error when
// the folder exists but is not a directory owned by this user.
CacheCleared clearCache();

// Where the cache's warnings go (one line each, without "brdfcl: warning: "), and the library's
// other warnings that no call returns (an environment file that is not 2:1). By default they
// are printed to stderr as "brdfcl: warning: <text>". An empty handler restores the default.
void setCacheWarningHandler(std::function<void(const std::string&)> handler);

}  // namespace brdfcl
