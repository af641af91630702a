// What a brdfcl::DeviceArray holds: the OpenCL buffer and the Runtime it belongs to. Private to
// the library (the public header names no OpenCL type).
#pragma once
#include "brdfcl/device_array.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

struct DeviceArray::Impl {
  Runtime* runtime = nullptr;
  Type type = Type::Float32;
  std::size_t size = 0;
  cl::Buffer buffer;  // at least 4 bytes, so that an empty array is still a valid argument
};

}  // namespace brdfcl
