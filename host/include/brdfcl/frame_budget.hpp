// Memory a frame of a given size needs, checked before any work: a size that cannot fit is
// refused at once with the largest size of the same shape that does, instead of failing late.
#pragma once
#include <cstdint>
#include <string>

#include "brdfcl/runtime.hpp"

namespace brdfcl {

enum class FrameJob { GBuffer, Shade, Render };

struct FrameNeeds {
  std::uint64_t hostBytes = 0;     // peak resident memory of the process, approximately
  std::uint64_t deviceBuffer = 0;  // the largest single device allocation (the G-buffer planes)
};

// Measured peak resident memory per pixel (docs/gbuffer.md gives the figures), plus the
// device's one buffer of GB_PLANES floats per pixel.
FrameNeeds frameNeeds(FrameJob job, int width, int height);

// The memory this process may use: the smallest of physical memory, RLIMIT_AS and the cgroup's
// memory.max.
std::uint64_t usableHostMemory();

// Throws brdfcl::Error when the frame needs more than `hostLimit` bytes, or (with a device) a
// buffer larger than the device's maximum allocation. The message names the size, what it
// needs, the limit, and the largest width x height with the same aspect that fits.
// `option` names the size on the command line ("--size").
void checkFrameFits(FrameJob job, int width, int height, std::uint64_t hostLimit, const DeviceInfo* device,
                    const std::string& option = "--size");

}  // namespace brdfcl
