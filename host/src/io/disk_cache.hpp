// brdfcl's on-disk cache ($XDG_CACHE_HOME/brdfcl or ~/.cache/brdfcl): baked float tables and
// program binaries under names whose hash covers everything that made them, written atomically.
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace brdfcl::detail {

// The cache directory; empty when neither XDG_CACHE_HOME nor HOME is set (nothing is cached).
std::filesystem::path cacheDirectory();

// 64-bit FNV-1a, continued from `seed`: a content key, not a checksum against tampering.
std::uint64_t contentHash(std::string_view bytes, std::uint64_t seed = 0xcbf29ce484222325ull);
std::uint64_t contentHash(const std::vector<float>& values, std::uint64_t seed = 0xcbf29ce484222325ull);

// The whole file `name`, or empty when the cache does not hold it. A hit marks the file as used
// (its modification time, moved to now when older than kUseMarkInterval), for pruneCached.
constexpr std::chrono::hours kUseMarkInterval{1};
std::vector<unsigned char> loadCachedBytes(const std::string& name);
// Stores `bytes` as `name`; as storeCachedFloats, failures are silent.
void storeCachedBytes(const std::string& name, const std::vector<unsigned char>& bytes);
// Keeps the `keep` most recently used files whose names start with `prefix`, removing the rest.
void pruneCached(const std::string& prefix, std::size_t keep);

// True, with `out` filled, when the cache holds `name` with exactly out.size() floats.
bool loadCachedFloats(const std::string& name, std::vector<float>& out);

// Stores `values` as `name`. A read-only or full cache only costs the next run a recompute, so
// failures are silent.
void storeCachedFloats(const std::string& name, const std::vector<float>& values);

}  // namespace brdfcl::detail
