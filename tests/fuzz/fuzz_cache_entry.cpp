// libFuzzer harness: the disk cache's entry parser (parseCacheEntry), a pure function on bytes,
// plus the round trip through encodeCacheEntry. Seeds: tests/fuzz/corpus/cache_entry/.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "host/src/io/disk_cache.hpp"

namespace {
// The key the seeds were written for: a program binary's entry name.
constexpr std::string_view kKey = "program_0123456789abcdef.bin";

void check(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  using brdfcl::detail::encodeCacheEntry;
  using brdfcl::detail::parseCacheEntry;

  // Whatever the file holds: a payload only when it is a whole entry for this key, and then
  // exactly the bytes that encode back to the same file.
  if (const auto payload = parseCacheEntry(bytes, kKey)) {
    check(payload->data() >= bytes.data() && payload->data() + payload->size() == bytes.data() + bytes.size());
    check(encodeCacheEntry(kKey, *payload) == bytes);
  }
  // An entry is never accepted for another key.
  check(!parseCacheEntry(bytes, "program_0123456789abcdeF.bin"));

  // The input as a payload: its entry reads back, and a changed byte or a cut end is refused.
  const std::string entry = encodeCacheEntry(kKey, bytes);
  const auto back = parseCacheEntry(entry, kKey);
  check(back && *back == bytes);
  if (size > 0) {
    std::string flipped = entry;
    const std::size_t at = (std::size_t(data[0]) * 131 + size) % entry.size();
    flipped[at] = char(flipped[at] ^ (data[size - 1] | 1));
    check(!parseCacheEntry(flipped, kKey));
    check(!parseCacheEntry(std::string_view(entry).substr(0, entry.size() - 1 - data[0] % size), kKey));
  }
  return 0;
}
