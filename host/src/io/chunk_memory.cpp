// detail::allocateChunk / freeChunk (brdfcl/io.hpp): chunk buffers mapped 2 MiB-aligned and offered
// to transparent huge pages, small ones from the ordinary heap.
#include <sys/mman.h>

#include <cstdint>
#include <new>

#include "brdfcl/io.hpp"

namespace brdfcl::detail {
namespace {
constexpr std::size_t kHuge = std::size_t(2) << 20;
std::size_t mapped(std::size_t bytes) { return (bytes + kHuge - 1) / kHuge * kHuge; }
}  // namespace

void* allocateChunk(std::size_t bytes) {
  if (bytes < kHuge) return ::operator new(bytes);
  if (bytes > SIZE_MAX - 2 * kHuge) throw std::bad_alloc();
  // Over-map by one huge page and trim, so the block starts on a 2 MiB boundary.
  const std::size_t size = mapped(bytes);
  void* m = ::mmap(nullptr, size + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (m == MAP_FAILED) throw std::bad_alloc();
  const auto base = reinterpret_cast<std::uintptr_t>(m);
  const std::uintptr_t start = (base + kHuge - 1) / kHuge * kHuge;
  if (start > base) ::munmap(m, start - base);
  if (base + kHuge > start) ::munmap(reinterpret_cast<void*>(start + size), base + kHuge - start);
  void* p = reinterpret_cast<void*>(start);
  ::madvise(p, size, MADV_HUGEPAGE);  // advice only: without THP the pages stay small
  return p;
}

void freeChunk(void* p, std::size_t bytes) noexcept {
  if (!p) return;
  if (bytes < kHuge)
    ::operator delete(p);
  else
    ::munmap(p, mapped(bytes));
}

}  // namespace brdfcl::detail
