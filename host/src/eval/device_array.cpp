// DeviceArray: a device buffer of float32 or uint32 elements behind an opaque handle, with
// blocking copies to and from host memory.
#include "eval/device_array.hpp"

#include <algorithm>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"

namespace brdfcl {

namespace {

void checkRange(const DeviceArray& a, std::size_t count, std::size_t offset) {
  if (offset > a.size() || count > a.size() - offset)
    throw Error(fmt::format("device array of {} elements: elements [{}, {}) are out of range", a.size(), offset,
                            offset + count));
}

}  // namespace

DeviceArray::DeviceArray(Runtime& rt, Type type, std::size_t size) : impl_(std::make_shared<Impl>()) {
  impl_->runtime = &rt;
  impl_->type = type;
  impl_->size = size;
  const std::size_t bytes = std::max<std::size_t>(size, 1) * 4;
  if (size > SIZE_MAX / 8 || bytes > rt.info().maxAlloc)
    throw Error(ErrorKind::Memory, fmt::format("out of device memory allocating {:.0f} MiB for a device array",
                                               double(size) * 4 / double(1 << 20)));
  auto& cl = rt.opencl();
  try {
    impl_->buffer = cl::Buffer(cl.context(), CL_MEM_READ_WRITE, bytes);
    const cl_uint zero = 0;
    cl.queue().enqueueFillBuffer(impl_->buffer, zero, 0, bytes);
    cl.queue().finish();
  } catch (const cl::Error& e) {
    if (e.err() == CL_MEM_OBJECT_ALLOCATION_FAILURE || e.err() == CL_OUT_OF_RESOURCES || e.err() == CL_OUT_OF_HOST_MEMORY)
      throw Error(ErrorKind::Memory, fmt::format("out of device memory allocating {:.0f} MiB for a device array",
                                                 double(size) * 4 / double(1 << 20)));
    rethrowOpenCL("allocating a device array");
  }
}

DeviceArray::Type DeviceArray::type() const { return impl_->type; }
std::size_t DeviceArray::size() const { return impl_->size; }
bool DeviceArray::belongsTo(const Runtime& rt) const { return impl_->runtime == &rt; }

void DeviceArray::upload(const void* data, std::size_t count, std::size_t offset) {
  checkRange(*this, count, offset);
  if (count == 0) return;
  try {
    impl_->runtime->opencl().queue().enqueueWriteBuffer(impl_->buffer, CL_TRUE, 4 * offset, 4 * count, data);
  } catch (const cl::Error&) {
    rethrowOpenCL("copying into a device array");
  }
}

void DeviceArray::download(void* data, std::size_t count, std::size_t offset) const {
  checkRange(*this, count, offset);
  if (count == 0) return;
  try {
    impl_->runtime->opencl().queue().enqueueReadBuffer(impl_->buffer, CL_TRUE, 4 * offset, 4 * count, data);
  } catch (const cl::Error&) {
    rethrowOpenCL("copying out of a device array");
  }
}

}  // namespace brdfcl
