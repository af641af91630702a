// The on-disk table cache shared by the sheen albedo bake and the environment preparation.
// Files are raw little-endian float32 whose length is checked on load, so a truncated or
// foreign file is recomputed, never trusted.
#include "io/disk_cache.hpp"

#include <cstdlib>
#include <fstream>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"

namespace brdfcl::detail {

std::filesystem::path cacheDirectory() {
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return std::filesystem::path(x) / "brdfcl";
  if (const char* h = std::getenv("HOME"); h && *h) return std::filesystem::path(h) / ".cache" / "brdfcl";
  return {};
}

std::uint64_t contentHash(std::string_view bytes, std::uint64_t seed) {
  std::uint64_t h = seed;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

std::uint64_t contentHash(const std::vector<float>& values, std::uint64_t seed) {
  return contentHash(std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float)), seed);
}

bool loadCachedFloats(const std::string& name, std::vector<float>& out) {
  const auto dir = cacheDirectory();
  if (dir.empty()) return false;
  std::ifstream in(dir / name, std::ios::binary);
  return in.read(reinterpret_cast<char*>(out.data()), std::streamsize(out.size() * sizeof(float))) &&
         in.peek() == std::char_traits<char>::eof();
}

void storeCachedFloats(const std::string& name, const std::vector<float>& values) {
  const auto dir = cacheDirectory();
  if (dir.empty()) return;
  try {
    std::filesystem::create_directories(dir);
    writeAtomically((dir / name).string(), [&](const std::string& tmp) {
      std::ofstream out(tmp, std::ios::binary);
      out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
      if (!out.flush()) throw Error("cannot write " + tmp);
    });
  } catch (const std::exception&) {
  }
}

}  // namespace brdfcl::detail
