// A compute device for brdfcl: chosen by index or name, it holds the device's context, queue and
// compiled kernels out of sight (the OpenCL objects are private to the library). Every failing
// device call throws brdfcl::Error naming the call and its error code.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace brdfcl {

struct DeviceInfo {
  std::size_t index;  // position in the flattened list of all platforms' devices
  std::string name;
  std::string platform;
  std::string type;  // CPU, GPU, ACCELERATOR, ...
  unsigned computeUnits;
  std::string openclC;  // the device's OpenCL C version
  std::uint64_t maxAlloc;
  std::uint64_t globalMem;
};

// All devices of all platforms. Throws "no OpenCL platform found; ..." (exit 2) if none.
std::vector<DeviceInfo> listDevices();

// Thread safety. One Runtime may be shared by any number of threads, each evaluating through
// its own (or a shared) Evaluator: its kernel cache is guarded by a mutex (concurrent first
// requests for one variant wait for a single build), and info() and standardOption() are fixed
// after construction. All threads enqueue on the one in-order queue of the device, so a wait may
// also wait for other threads' work, which costs time, never correctness. Construction and
// destruction are not concurrent-safe: destroy the Runtime only after every thread is done with it.
class Runtime {
 public:
  // selector: "" (then $BRDFCL_DEVICE, then device 0), an index, or a name substring.
  explicit Runtime(const std::string& selector = "");
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  const DeviceInfo& info() const;
  // Programs this Runtime built from binaries in brdfcl's disk cache rather than from source.
  std::size_t programsFromDiskCache() const;
  // The -cl-std option picked from the device's OpenCL C version.
  const std::string& standardOption() const;

  // The device's OpenCL objects, for the library's own modules (host/src/runtime/opencl.hpp).
  struct OpenCL;
  OpenCL& opencl() const { return *cl_; }

 private:
  std::unique_ptr<OpenCL> cl_;
};

}  // namespace brdfcl
