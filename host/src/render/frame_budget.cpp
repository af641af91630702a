// Frame memory estimates and the up-front size check of gbuffer, shade and render. The figures
// per pixel are peak RSS slopes measured with /usr/bin/time between 512² and 1024² frames.
#include "brdfcl/frame_budget.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "common/shading_layout.h"

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

FrameNeeds frameNeeds(FrameJob job, int width, int height) {
  const std::uint64_t px = std::uint64_t(width) * std::uint64_t(height);
  FrameNeeds n;
  n.hostBytes = kBaseBytes + px * hostBytesPerPixel(job);
  n.deviceBuffer = px * GB_PLANES * sizeof(float);
  return n;
}

std::uint64_t usableHostMemory() {
  std::uint64_t limit = std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGESIZE));
  rlimit rl{};
  if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) limit = std::min<std::uint64_t>(limit, rl.rlim_cur);
  return std::min(limit, cgroupLimit());
}

void checkFrameFits(FrameJob job, int width, int height, std::uint64_t hostLimit, const DeviceInfo* device,
                    const std::string& option) {
  const FrameNeeds need = frameNeeds(job, width, height);
  const bool hostFits = need.hostBytes <= hostLimit;
  const bool deviceFits = !device || need.deviceBuffer <= device->maxAlloc;
  if (hostFits && deviceFits) return;
  // The largest pixel count both limits allow, then the same aspect at that count.
  const FrameNeeds perPixel = frameNeeds(job, 1, 1);
  const std::uint64_t hostPx = hostLimit > kBaseBytes ? (hostLimit - kBaseBytes) / (perPixel.hostBytes - kBaseBytes) : 0;
  std::uint64_t maxPx = hostPx;
  if (device) maxPx = std::min<std::uint64_t>(maxPx, device->maxAlloc / perPixel.deviceBuffer);
  const double scale = std::sqrt(double(maxPx) / (double(width) * double(height)));
  const int fitW = std::max(1, int(std::floor(width * scale))), fitH = std::max(1, int(std::floor(height * scale)));
  std::string why;
  if (!hostFits)
    why = fmt::format("about {:.1f} GiB of memory, but this process may use {:.1f} GiB", gib(need.hostBytes), gib(hostLimit));
  else
    why = fmt::format("a {:.1f} GiB G-buffer on the device, but '{}' allows {:.1f} GiB per buffer", gib(need.deviceBuffer),
                      device->name, gib(device->maxAlloc));
  throw Error(fmt::format("{} {}x{} needs {}; the largest size of that shape that fits is {}x{}", option, width, height,
                          why, fitW, fitH));
}

}  // namespace brdfcl
