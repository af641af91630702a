// Memory a frame of a given size needs, checked before any work: a size that cannot fit is
// refused at once with the largest size of the same shape that does, instead of failing late.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "brdfcl/runtime.hpp"

namespace brdfcl {

enum class FrameJob { GBuffer, Shade, Render };

// Peak resident memory of the process for a frame, approximately, from measured slopes per pixel.
std::uint64_t frameHostBytes(FrameJob job, int width, int height);

// The memory this process may use: the smallest of physical memory, RLIMIT_AS and the cgroup's
// memory.max.
std::uint64_t usableHostMemory();

// Throws brdfcl::Error when the frame needs more than `hostLimit` bytes. The message names the
// size, what it needs, the limit, and the largest width x height with the same aspect that fits.
// `option` names the size on the command line ("--size"). The device sets no limit: launches
// are split into bands of rows (bandRows).
void checkFrameFits(FrameJob job, int width, int height, std::uint64_t hostLimit, const std::string& option = "--size");

// Rows per launch such that a band of `bytesPerPixel` per pixel stays within the device's largest
// allocation, or within BRDFCL_MAX_LAUNCH_BYTES when that is set (a smaller limit, for tests and
// for sharing a device); at least one row. Throws brdfcl::Error for a malformed variable.
int bandRows(const DeviceInfo& device, int width, std::size_t bytesPerPixel);

}  // namespace brdfcl
