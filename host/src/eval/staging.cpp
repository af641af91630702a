// Pinned, double-buffered staging of the row paths (staging.hpp): two slots, each an in-order
// queue with pinned host buffers mapped once and device buffers, reused across calls through the
// Runtime's pool.
#include "eval/staging.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "brdfcl/error.hpp"
#include "io/rows.hpp"

namespace brdfcl {

bool stagesRows(const Runtime& rt) {
  if (const char* v = std::getenv("BRDFCL_STAGING"); v && *v) {
    const std::string s = v;
    if (s == "1") return true;
    if (s == "0") return false;
    throw Error("BRDFCL_STAGING=" + s + " is not supported; use 0 or 1");
  }
  return rt.info().type != "CPU";
}

void copySpans(const std::vector<CopySpan>& spans) {
  std::size_t total = 0;
  for (const auto& s : spans) total += s.bytes;
  const std::size_t threads = std::min<std::size_t>(8, total < (std::size_t(4) << 20) ? 1 : detail::workerCount(total));
  // Thread t copies bytes [t * total / threads, (t + 1) * total / threads) of the spans laid end to end.
  const auto part = [&](std::size_t t) {
    const std::size_t begin = t * total / threads, end = (t + 1) * total / threads;
    std::size_t at = 0;
    for (const auto& s : spans) {
      const std::size_t lo = std::max(begin, at), hi = std::min(end, at + s.bytes);
      if (lo < hi)
        std::memcpy(static_cast<char*>(s.to) + (lo - at), static_cast<const char*>(s.from) + (lo - at), hi - lo);
      at += s.bytes;
    }
  };
  if (threads == 1)
    part(0);
  else
    detail::parallelFor(threads, part);
}

namespace {

// A pinned host buffer (CL_MEM_ALLOC_HOST_PTR: page-locked where the driver can DMA from it)
// mapped for the host once, for as long as it lives.
struct Pinned {
  cl::Buffer buffer;
  void* host = nullptr;
  std::size_t bytes = 0;
};

void release(cl::CommandQueue& q, Pinned& p) {
  if (p.host) q.enqueueUnmapMemObject(p.buffer, p.host);
  p = Pinned{};
}

// Buffer sizes: powers of two from 4 KiB, so that a caller whose calls grow reallocates a few
// times only, and a full launch (1M rows of 4, 8, 12 or 28 bytes) wastes little or nothing.
std::size_t sizeFor(std::size_t bytes) {
  std::size_t size = 4096;
  while (size < bytes) size *= 2;
  return size;
}

// At least `bytes` of pinned memory. The slot is idle, so the old buffer may go.
void reserve(const cl::Context& ctx, cl::CommandQueue& q, Pinned& p, std::size_t bytes) {
  if (p.bytes >= bytes) return;
  release(q, p);
  const std::size_t size = sizeFor(bytes);
  p.buffer = cl::Buffer(ctx, CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, size);
  p.host = q.enqueueMapBuffer(p.buffer, CL_TRUE, CL_MAP_READ | CL_MAP_WRITE, 0, size);
  p.bytes = size;
}

struct DeviceBuffer {
  cl::Buffer buffer;
  std::size_t bytes = 0;
};

void reserve(const cl::Context& ctx, DeviceBuffer& b, std::size_t bytes) {
  if (b.bytes >= bytes) return;
  const std::size_t size = sizeFor(bytes);
  b.buffer = cl::Buffer(ctx, CL_MEM_READ_WRITE, size);
  b.bytes = size;
}

}  // namespace

struct Staging::Slot {
  cl::CommandQueue queue;
  std::vector<Pinned> pinnedIn;
  std::vector<DeviceBuffer> deviceIn;
  Pinned pinnedOut;
  DeviceBuffer deviceOut;
  cl::Event done;  // the download of the slot's last job
  std::function<void(const void*)> deliver;
};

struct StagingSet {
  Staging::Slot slots[2];
  ~StagingSet() {
    for (auto& s : slots) {
      try {
        for (auto& p : s.pinnedIn) release(s.queue, p);
        release(s.queue, s.pinnedOut);
        if (s.queue() != nullptr) s.queue.finish();
      } catch (...) {
      }
    }
  }
};

Staging::Staging(Runtime& rt) : cl_(rt.opencl()) {
  {
    std::lock_guard<std::mutex> lock(cl_.stagingMutex_);
    if (!cl_.staging_.empty()) {
      set_ = std::move(cl_.staging_.back());
      cl_.staging_.pop_back();
    }
  }
  if (!set_) {
    set_ = std::make_shared<StagingSet>();
    try {
      for (auto& s : set_->slots) s.queue = cl::CommandQueue(cl_.context(), cl_.device());
    } catch (const cl::Error&) {
      rethrowOpenCL("creating the staging queues");
    }
  }
}

Staging::~Staging() {
  try {
    for (auto& s : set_->slots) {
      s.queue.finish();
      s.deliver = nullptr;
      s.done = cl::Event();
    }
  } catch (...) {
    return;  // a queue in error keeps its slots out of the pool
  }
  std::lock_guard<std::mutex> lock(cl_.stagingMutex_);
  if (cl_.staging_.size() < 2) cl_.staging_.push_back(std::move(set_));
}

void Staging::begin() {
  pending_.clear();
  current_ = (current_ + 1) % 2;
  Slot& s = set_->slots[current_];
  if (s.done() != nullptr) {
    s.done.wait();
    s.done = cl::Event();
  }
  if (s.deliver) std::exchange(s.deliver, nullptr)(s.pinnedOut.host);
  outBytes_ = 0;
}

cl::Buffer Staging::in(int k, const void* data, std::size_t bytes) {
  Slot& s = set_->slots[current_];
  if (s.pinnedIn.size() <= std::size_t(k)) {
    s.pinnedIn.resize(std::size_t(k) + 1);
    s.deviceIn.resize(std::size_t(k) + 1);
  }
  const std::size_t size = std::max<std::size_t>(bytes, 4);
  reserve(cl_.context(), s.queue, s.pinnedIn[std::size_t(k)], size);
  reserve(cl_.context(), s.deviceIn[std::size_t(k)], size);
  if (bytes) pending_.emplace_back(k, CopySpan{s.pinnedIn[std::size_t(k)].host, data, bytes});
  return s.deviceIn[std::size_t(k)].buffer;
}

cl::Buffer Staging::out(std::size_t bytes, std::function<void(const void*)> deliver) {
  Slot& s = set_->slots[current_];
  std::vector<CopySpan> spans;
  for (const auto& [k, span] : pending_) spans.push_back(span);
  copySpans(spans);
  for (const auto& [k, span] : pending_)
    s.queue.enqueueWriteBuffer(s.deviceIn[std::size_t(k)].buffer, CL_FALSE, 0, span.bytes, span.to);
  pending_.clear();
  const std::size_t size = std::max<std::size_t>(bytes, 4);
  reserve(cl_.context(), s.queue, s.pinnedOut, size);
  reserve(cl_.context(), s.deviceOut, size);
  s.deliver = std::move(deliver);
  outBytes_ = bytes;
  return s.deviceOut.buffer;
}

cl::CommandQueue& Staging::queue() { return set_->slots[current_].queue; }

void Staging::end() {
  Slot& s = set_->slots[current_];
  if (outBytes_) s.queue.enqueueReadBuffer(s.deviceOut.buffer, CL_FALSE, 0, outBytes_, s.pinnedOut.host, nullptr, &s.done);
  s.queue.flush();
}

void Staging::drain() {
  // The older job first: results are delivered in the order the jobs ran.
  for (int i = 1; i <= 2; ++i) {
    Slot& s = set_->slots[(current_ + i) % 2];
    s.queue.finish();
    s.done = cl::Event();
    if (s.deliver) std::exchange(s.deliver, nullptr)(s.pinnedOut.host);
  }
}

}  // namespace brdfcl
