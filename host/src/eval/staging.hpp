// Rows moved between the caller's pageable memory and device memory through pinned staging
// buffers, a chunk at a time on two queues, so that one chunk's copies overlap the other's kernel.
// The row paths use it on devices that do not read host memory in place (GPUs).
#pragma once
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "runtime/opencl.hpp"

namespace brdfcl {

// Whether the row paths stage rows through pinned memory on this runtime: on every device that
// is not a CPU (a CPU reads the caller's pages in place). $BRDFCL_STAGING=1 or 0 forces the
// choice on any device, for tests and measurements; another value throws
// "BRDFCL_STAGING=<v> is not supported; use 0 or 1".
bool stagesRows(const Runtime& rt);

// Rows a staged launch takes at most: a few MiB a buffer, small enough that the first copy in and
// the last copy out (which nothing overlaps) are a small part of a large call, large enough that
// a launch's fixed cost is too.
constexpr std::size_t kStagedRows = std::size_t(1) << 20;

// Copies between the caller's memory and pinned memory: (destination, source, bytes) spans,
// split across up to 8 threads when they are large. One thread copies pageable memory at about
// 10 GB/s, below the rate of a PCIe 4 or 5 link.
struct CopySpan {
  void* to;
  const void* from;
  std::size_t bytes;
};
void copySpans(const std::vector<CopySpan>& spans);

// Jobs run in turn on two slots, each with its own in-order queue, pinned host buffers
// (CL_MEM_ALLOC_HOST_PTR, mapped once) and device buffers. A job is begin(), in() for each input,
// out(), the caller's kernel launch on queue(), then end(); its results reach the caller (the
// `deliver` function, a host copy out of pinned memory) when its slot comes round again or at
// drain(). The slots' memory is kept in the Runtime for the next call: pinning costs far more
// than copying through pinned pages.
class Staging {
 public:
  explicit Staging(Runtime& rt);
  ~Staging();  // waits for the device, delivers nothing more, and returns the slots to the Runtime
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;

  // Starts the next job on the next slot, once that slot's last job is done and delivered.
  void begin();
  // Input `k` of this job: `bytes` of `data` to be copied into the slot's pinned buffer k and
  // uploaded to its device buffer k (returned; at least 4 bytes even for none). The copies of
  // all inputs run together, in out().
  cl::Buffer in(int k, const void* data, std::size_t bytes);
  // Copies the job's inputs and enqueues their uploads, then returns the job's output buffer of
  // `bytes`; once downloaded, `deliver` gets its pinned copy.
  cl::Buffer out(std::size_t bytes, std::function<void(const void*)> deliver);
  // The queue the job's launches go on.
  cl::CommandQueue& queue();
  // Enqueues the download and lets the job run.
  void end();
  // Waits for every job and delivers the results not yet delivered.
  void drain();

  struct Slot;

 private:
  Runtime::OpenCL& cl_;
  std::shared_ptr<StagingSet> set_;
  int current_ = -1;
  std::size_t outBytes_ = 0;
  std::vector<std::pair<int, CopySpan>> pending_;  // inputs not yet copied: (k, span)
};

}  // namespace brdfcl
