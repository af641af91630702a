// Frame memory estimates and the up-front size check of gbuffer, shade and render. The figures
// per pixel are peak RSS slopes measured with /usr/bin/time between 512² and 1024² frames.
#include "brdfcl/frame_budget.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "io/option_style.hpp"

namespace brdfcl {

namespace {
// Measured slopes were 264 B (spheres G-buffer), 391 B (spheres render) and 427 B (glTF render,
// SheenChair, 2 spp) per pixel; these add about 15 % for allocator slack and EXR/PNG encoding.
std::uint64_t hostBytesPerPixel(FrameJob job) {
  switch (job) {
    case FrameJob::GBuffer: return 300;
    case FrameJob::Shade: return 480;
    case FrameJob::Render: return 500;
  }
  return 500;
}
// Kernels, the BVH of a typical asset, environment chains: the part that does not scale with size.
constexpr std::uint64_t kBaseBytes = 256ull << 20;

double gib(std::uint64_t bytes) { return double(bytes) / double(1ull << 30); }

std::uint64_t cgroupLimit() {
  std::ifstream in("/sys/fs/cgroup/memory.max");
  std::string v;
  if (!(in >> v) || v == "max") return UINT64_MAX;
  try {
    return std::stoull(v);
  } catch (...) {
    return UINT64_MAX;
  }
}
}  // namespace

std::uint64_t frameHostBytes(FrameJob job, int width, int height) {
  return kBaseBytes + std::uint64_t(width) * std::uint64_t(height) * hostBytesPerPixel(job);
}

std::uint64_t usableHostMemory() {
  std::uint64_t limit = std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGESIZE));
  rlimit rl{};
  if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) limit = std::min<std::uint64_t>(limit, rl.rlim_cur);
  return std::min(limit, cgroupLimit());
}

void checkFrameFits(FrameJob job, int width, int height, std::uint64_t hostLimit, const std::string& option) {
  const std::uint64_t need = frameHostBytes(job, width, height);
  if (need <= hostLimit) return;
  // The largest pixel count the limit allows, then the same aspect at that count.
  const std::uint64_t maxPx = hostLimit > kBaseBytes ? (hostLimit - kBaseBytes) / hostBytesPerPixel(job) : 0;
  const double scale = std::sqrt(double(maxPx) / (double(width) * double(height)));
  const int fitW = std::max(1, int(std::floor(width * scale))), fitH = std::max(1, int(std::floor(height * scale)));
  throw Error(ErrorKind::Memory, fmt::format("{} needs about {:.1f} GiB of memory, but this process may use {:.1f} GiB; the largest "
                          "size of that shape that fits is {}x{}",
                          optionWithValue(option, fmt::format("{}x{}", width, height)), gib(need), gib(hostLimit),
                          fitW, fitH));
}

int bandRows(const DeviceInfo& device, int width, std::size_t bytesPerPixel) {
  std::uint64_t limit = device.maxAlloc;
  if (const char* v = std::getenv("BRDFCL_MAX_LAUNCH_BYTES"); v && *v) {
    char* end = nullptr;
    errno = 0;
    const unsigned long long n = std::strtoull(v, &end, 10);
    if (*end != '\0' || errno != 0 || n == 0 || v[0] == '-')
      throw Error(fmt::format("BRDFCL_MAX_LAUNCH_BYTES={} is not a positive number of bytes; unset it or give e.g. 1048576",
                              v));
    limit = std::min<std::uint64_t>(limit, n);
  }
  const std::uint64_t row = std::uint64_t(width) * bytesPerPixel;
  return int(std::clamp<std::uint64_t>(limit / std::max<std::uint64_t>(row, 1), 1, 1u << 30));
}

}  // namespace brdfcl
