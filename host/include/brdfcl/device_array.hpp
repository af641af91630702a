// Arrays that stay in a device's memory between calls (DeviceArray): inputs uploaded once and
// results left where the next kernel reads them, so chained work does not cross the bus.
// Evaluator::evaluate and Evaluator::sample take them (evaluator.hpp).
#pragma once
#include <cstddef>
#include <memory>

#include "brdfcl/runtime.hpp"

namespace brdfcl {

// `size` elements of one type in the memory of one Runtime's device, zero-filled. Copies of a
// DeviceArray share the same memory (a handle); the memory goes with the last copy, which may
// outlive the Runtime's use but not the Runtime itself. Throws "out of device memory allocating
// <n> MiB for a device array" when the device cannot hold it. Thread safety: distinct arrays may
// be used from any threads; one array from one thread at a time (as a std::vector).
class DeviceArray {
 public:
  enum class Type { Float32, UInt32 };

  DeviceArray(Runtime& rt, Type type, std::size_t size);

  Type type() const;
  std::size_t size() const;  // elements
  // Whether the array lives on `rt` (evaluators refuse arrays of another Runtime).
  bool belongsTo(const Runtime& rt) const;

  // Copies `count` elements from host memory into elements [offset, offset + count), and back;
  // both wait for the copy. Throws "device array of <n> elements: elements [a, b) are out of range"
  // for a range past the end.
  void upload(const void* data, std::size_t count, std::size_t offset = 0);
  void download(void* data, std::size_t count, std::size_t offset = 0) const;

  struct Impl;  // the device buffer (host/src/eval/device_array.hpp)
  Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<Impl> impl_;
};

}  // namespace brdfcl
