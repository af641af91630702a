// The per-device shape of the batch kernels: lane width (BRDFCL_W) and work-group size, chosen
// from the device type, with $BRDFCL_LANES forcing the width for tests and tuning.
#include <algorithm>
#include <cstdlib>
#include <string>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {
// Measured on PoCL's pthread device (docs/performance.md, "Work-group size") against its own
// choice: +20 % on sheen, +30 % on the layered material.
constexpr std::size_t kCpuGroup = 512;
// GPUs want 64-256 work-items a group; 128 keeps two or more groups per compute unit resident.
constexpr std::size_t kGpuGroup = 128;
}  // namespace

LaneShape laneShape(const DeviceInfo& device) {
  LaneShape shape;
  if (device.type == "CPU") {
    shape = {16, kCpuGroup};
  } else {
    shape = {1, kGpuGroup};
  }
  // Read on every call (it is cheap) so that a test can switch widths within one process.
  if (const char* e = std::getenv("BRDFCL_LANES")) {
    const std::string v = e;
    if (v != "1" && v != "4" && v != "8" && v != "16")
      throw Error(fmt::format("BRDFCL_LANES={} is not supported; use 1, 4, 8 or 16", v));
    shape.lanes = std::stoi(v);
  }
  return shape;
}

std::size_t groupSizeFor(const LaneShape& shape, const cl::Kernel& kernel, const cl::Device& device) {
  std::size_t local = std::min(shape.groupSize, kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(device));
  if (device.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) {
    const std::size_t multiple = kernel.getWorkGroupInfo<CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE>(device);
    if (multiple > 0 && local >= multiple) local = local / multiple * multiple;
  }
  return std::max<std::size_t>(local, 1);
}

}  // namespace brdfcl
