// The OpenCL objects behind a brdfcl::Runtime (brdfcl/runtime.hpp), private to the library: the
// device, one context and in-order queue, and a program cache keyed by (build options, source).
// Every failing OpenCL call throws brdfcl::Error naming the call and its error code.
#pragma once
#include <atomic>
#include <CL/opencl.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>
#include <vector>

#include "brdfcl/runtime.hpp"

namespace brdfcl {

struct StagingSet;  // eval/staging.cpp

// Name of an OpenCL error code, e.g. "CL_OUT_OF_RESOURCES".
const char* clErrorName(int code);

// Throws brdfcl::Error for a cl::Error caught from the C++ bindings: "OpenCL call clXxx failed:
// CL_NAME (code)", with the build log for a cl::BuildError. `what` says what brdfcl was doing.
[[noreturn]] void rethrowOpenCL(const std::string& what);

// Thread safety. One Runtime may be shared by any number of threads, each evaluating through
// its own (or a shared) Evaluator: program() guards its cache with a mutex (concurrent first
// requests for one variant wait for a single build); device(), context(), info() and
// standardOption() are fixed after construction. queue() is one in-order cl::CommandQueue that
// every thread enqueues on; OpenCL makes enqueueing thread-safe, but a cl::Kernel's arguments
// are not, so every brdfcl launch path creates its own cl::Kernel (SoaBatch per batch,
// evaluateGrid() and bakeSheenAlbedo() per call) and callers using queue() directly must do the
// same. A blocking read or finish() on the shared queue may also wait for other threads' work,
// which costs time, never correctness.
struct Runtime::OpenCL {
  explicit OpenCL(const std::string& selector);

  const cl::Device& device() const { return device_; }
  const cl::Context& context() const { return context_; }
  cl::CommandQueue& queue() { return queue_; }

  // The arithmetic a program is built for. Exact: correctly rounded float division and sqrt
  // where the device offers them (every kernel but the batch kernels). Batch (eval.cl): on a GPU,
  // the device's own division and sqrt and its special-function unit's exp2, log2 and rsqrt
  // (fastmath.h, BRDFCL_NATIVE_MATH), several times cheaper on NVIDIA than the correctly rounded
  // ones and the polynomials; only the row kernels' direction normalization (rows.h) must match
  // the host readers to the bit, and on a GPU with doubles it is done in double
  // (BRDFCL_ROWS_FP64). CPUs build Batch as Exact: their division is correctly rounded anyway.
  enum class Arithmetic { Exact, Batch };
  // Builds (or returns from the cache) the program for an embedded kernel file, e.g. "eval.cl",
  // with its #include "..." lines resolved from kernels/. `defines` are extra -D options.
  cl::Program program(const std::string& kernelFile, const std::string& defines = "",
                      Arithmetic arithmetic = Arithmetic::Exact);
  // The build options program() adds for `arithmetic` on this device. BRDFCL_BATCH_MATH=exact|fast
  // builds Batch as Exact or as on a GPU whatever the device, for tests and tuning, and
  // BRDFCL_BUILD_OPTIONS is appended to every program's options, for tuning.
  std::string mathOptions(Arithmetic arithmetic) const;
  // The same for a caller's own source text (a test's probe kernel, say), its #include "..."
  // lines resolved from the embedded kernels/ as program() does; `tag` names it in build errors.
  cl::Program programFromSource(const std::string& tag, const std::string& source, const std::string& defines = "");
  // Builds (or returns from the memory or disk cache) a source whose includes are expanded.
  cl::Program buildExpanded(const std::string& tag, const std::string& source, const std::string& defines,
                            Arithmetic arithmetic);

  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  DeviceInfo info_;
  std::string clStd_;
  std::string mathOptions_;  // -cl-fp32-correctly-rounded-divide-sqrt where the device offers it
  bool fp64_ = false;  // the device has doubles (cl_khr_fp64)
  std::mutex cacheMutex_;
  std::map<std::pair<std::string, std::string>, cl::Program> cache_;  // (options, source) -> program
  std::atomic<std::size_t> fromDisk_{0};
  // Idle pinned staging of the row paths (eval/staging.hpp), kept for the next call. Declared
  // last, so it goes before the queue and context its buffers belong to.
  std::mutex stagingMutex_;
  std::vector<std::shared_ptr<StagingSet>> staging_;
};

// How the batch kernels (eval.cl) lay work on a device: samples per work-item (BRDFCL_W) and
// work-items per work-group. CPUs: 16 lanes a work-item, 512 a group (the compiler does not
// vectorize across work-items through pow/exp, so the lanes are the vectors; docs/performance.md).
// GPUs and everything else: 1 lane, 128 work-items (a GPU's SIMD runs across work-items).
// $BRDFCL_LANES = 1, 4, 8 or 16 forces the lane width on any device, for tests and tuning;
// another value throws "BRDFCL_LANES=<v> is not supported; use 1, 4, 8 or 16".
struct LaneShape {
  int lanes = 16;
  std::size_t groupSize = 512;  // before the kernel's own limits (groupSizeFor)
};
LaneShape laneShape(const DeviceInfo& device);

// The work-group size to launch `kernel` with: shape.groupSize, at most the kernel's limit on
// the device, and on GPUs a multiple of the kernel's preferred work-group size multiple.
std::size_t groupSizeFor(const LaneShape& shape, const cl::Kernel& kernel, const cl::Device& device);

// The full source of an embedded kernel file with its includes expanded (for tests and tools).
std::string kernelSource(const std::string& kernelFile);

}  // namespace brdfcl
