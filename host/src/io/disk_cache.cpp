// The on-disk cache shared by the sheen albedo bake, the environment preparation and the program
// binaries. Tables are raw little-endian float32 whose length is checked on load, and a binary the
// device rejects is rebuilt from source, so a truncated or foreign file is recomputed, never trusted.
#include "io/disk_cache.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>

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

namespace {
void storeCached(const std::string& name, const char* data, std::size_t size) {
  const auto dir = cacheDirectory();
  if (dir.empty()) return;
  try {
    std::filesystem::create_directories(dir);
    writeAtomically((dir / name).string(), [&](const std::string& tmp) {
      std::ofstream out(tmp, std::ios::binary);
      out.write(data, std::streamsize(size));
      if (!out.flush()) throw Error("cannot write " + tmp);
    });
  } catch (const std::exception&) {
  }
}
}  // namespace

void storeCachedFloats(const std::string& name, const std::vector<float>& values) {
  storeCached(name, reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
}

std::vector<unsigned char> loadCachedBytes(const std::string& name) {
  const auto dir = cacheDirectory();
  if (dir.empty()) return {};
  std::ifstream in(dir / name, std::ios::binary);
  std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!bytes.empty()) {
    // Marked at most once an hour: a use order to the hour is all pruning needs, and a process
    // start then costs no metadata write per program.
    std::error_code ec;
    const auto now = std::filesystem::file_time_type::clock::now();
    const auto marked = std::filesystem::last_write_time(dir / name, ec);
    if (!ec && now - marked > kUseMarkInterval) std::filesystem::last_write_time(dir / name, now, ec);
  }
  return bytes;
}

void pruneCached(const std::string& prefix, std::size_t keep) {
  const auto dir = cacheDirectory();
  if (dir.empty()) return;
  std::vector<std::pair<std::filesystem::file_time_type, std::filesystem::path>> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    if (e.path().filename().string().rfind(prefix, 0) != 0) continue;
    std::error_code tc;
    const auto t = e.last_write_time(tc);
    if (!tc) files.emplace_back(t, e.path());
  }
  if (files.size() <= keep) return;
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = keep; i < files.size(); ++i) std::filesystem::remove(files[i].second, ec);
}

void storeCachedBytes(const std::string& name, const std::vector<unsigned char>& bytes) {
  storeCached(name, reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

}  // namespace brdfcl::detail
