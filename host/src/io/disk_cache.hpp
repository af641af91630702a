// brdfcl's on-disk cache ($XDG_CACHE_HOME/brdfcl or ~/.cache/brdfcl): baked float tables and
// program binaries under names whose hash covers everything that made them, each file a checked
// entry (a header naming its key, a checksum of the payload), created privately and renamed in.
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brdfcl::detail {

// The cache directory; empty when neither XDG_CACHE_HOME nor HOME is set (nothing is cached).
std::filesystem::path cacheDirectory();

// 64-bit FNV-1a, continued from `seed`: a content key, not a checksum against tampering.
// The default seed is FNV's offset basis moved by the entry format's version: entries written in
// an older format then have other names, are never read as this format's, and age out by the
// budget's least-recently-used pruning instead of each costing a warning.
inline constexpr std::uint64_t kEntryFormatSeed = 0xcbf29ce484222325ull ^ 0x2;
std::uint64_t contentHash(std::string_view bytes, std::uint64_t seed = kEntryFormatSeed);
std::uint64_t contentHash(const std::vector<float>& values, std::uint64_t seed = kEntryFormatSeed);

// The entry format, little-endian:
//   0  8  magic "BRDFCLCE"
//   8  8  XXH3-64 of every byte from offset 16 to the end
//  16  4  format version (kCacheEntryVersion)
//  20  4  key length K (at most kCacheKeyMax)
//  24  8  payload length P
//  32  K  key (the entry's file name, so that a renamed entry is refused)
//  32+K P payload
// The file is exactly 32 + K + P bytes.
constexpr std::size_t kCacheHeaderSize = 32;
constexpr std::uint32_t kCacheEntryVersion = 1;
constexpr std::size_t kCacheKeyMax = 4096;
std::string encodeCacheEntry(std::string_view key, std::string_view payload);
// The payload of `bytes` when they are a whole, intact entry for `key`; nullopt otherwise. A pure
// function of its arguments (the fuzz harness calls it directly); the view points into `bytes`.
std::optional<std::string_view> parseCacheEntry(std::string_view bytes, std::string_view key);

// The whole payload of entry `name`, or empty when the cache does not hold an intact one (a bad
// entry is removed, with a warning). A hit marks the file as used (its modification time, moved
// to now when older than kUseMarkInterval), for pruning.
constexpr std::chrono::hours kUseMarkInterval{1};
std::vector<unsigned char> loadCachedBytes(const std::string& name);
// The same payload as a string, read once and never copied (program binaries at start-up).
std::string loadCachedPayload(const std::string& name);
// Stores `bytes` as `name`; as storeCachedFloats, a failure costs a warning and a recompute.
void storeCachedBytes(const std::string& name, const std::vector<unsigned char>& bytes);
// Keeps the `keep` most recently used entries whose names start with `prefix`, removing the rest.
void pruneCached(const std::string& prefix, std::size_t keep);

// True, with `out` filled, when the cache holds an intact `name` of exactly out.size() floats.
bool loadCachedFloats(const std::string& name, std::vector<float>& out);

// Stores `values` as `name`, then prunes the cache to its budget. A read-only or full cache only
// costs this and later runs a recompute: the first failure is one warning naming the folder, and
// the process stops writing there.
void storeCachedFloats(const std::string& name, const std::vector<float>& values);

// Hands one line (without "brdfcl: warning: ") to the handler of setCacheWarningHandler: the
// cache's warnings and PoCL's kernel-cache fallback share it.
void cacheWarning(const std::string& text);

// Whether `name` is one of the cache's own entry names (a kind's prefix and suffix around a plain
// name); sets `kind` to the kind's index in cacheKinds().
bool isCacheEntryName(const std::string& name, std::size_t* kind = nullptr);

}  // namespace brdfcl::detail
