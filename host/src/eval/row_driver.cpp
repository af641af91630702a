// RowDriver (row_driver.hpp): the launches of the row kernels over the caller's rows, in place,
// copied, staged through pinned memory (staging.hpp) or in device buffers.
#include "eval/row_driver.hpp"

#include <algorithm>

namespace brdfcl {

namespace {

constexpr std::uintptr_t kPage = 4096;
constexpr cl_uint kNoBadRow = UINT32_MAX;

std::size_t roundUp(std::size_t n, std::size_t m) { return (n + m - 1) / m * m; }

}  // namespace

void launchWholeAndTail(cl::CommandQueue& q, cl::Kernel& whole, cl::Kernel& tail, std::size_t rows, std::size_t lanes,
                        std::size_t local, std::size_t materials, cl::Event* wholeDone, cl::Event* tailDone) {
  const std::size_t groups = rows / lanes;
  const auto range = [&](std::size_t n) { return materials ? cl::NDRange(n, materials) : cl::NDRange(n); };
  if (groups > 0) {
    // Large launches use the work-group size; small ones leave the choice to the runtime rather
    // than pad a mostly empty group.
    const bool grouped = local > 0 && groups >= 8 * local;
    const cl::NDRange size = !grouped ? cl::NullRange : materials ? cl::NDRange(local, 1) : cl::NDRange(local);
    q.enqueueNDRangeKernel(whole, cl::NullRange, range(grouped ? roundUp(groups, local) : groups), size, nullptr,
                           wholeDone);
  }
  if (rows % lanes) q.enqueueNDRangeKernel(tail, cl::NullRange, range(1), cl::NullRange, nullptr, tailDone);
}

cl::Buffer deviceCopy(const cl::Context& ctx, const void* p, std::size_t bytes) {
  static const std::uint32_t zero = 0;
  return cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes ? bytes : sizeof zero,
                    const_cast<void*>(bytes ? p : &zero));
}

RowDriver::RowDriver(Runtime& rt, const cl::Program& program, const std::string& name, const LaneShape& shape,
                     Rows rows)
    : ctx_(rt.opencl().context()), q_(rt.opencl().queue()), info_(rt.info()), rows_(rows),
      kernel_(program, name.c_str()), tail_(program, (name + "_tail").c_str()), lanes_(std::size_t(shape.lanes)),
      local_(shape.groupSize ? groupSizeFor(shape, kernel_, rt.opencl().device()) : 0) {
  if (rows != Rows::Device && stagesRows(rt)) stage_ = std::make_unique<Staging>(rt);
}

RowDriver::~RowDriver() {
  try {
    q_.finish();
  } catch (...) {
  }
}

std::size_t RowDriver::rowsPerLaunch(std::size_t launchLimit, std::size_t asked, std::size_t rowBytes,
                                     std::size_t granule) const {
  std::size_t limit =
      std::max<std::size_t>(granule, std::min<std::size_t>(launchLimit, info_.maxAlloc / rowBytes) / granule * granule);
  if (stage_) limit = std::min(limit, kStagedRows);
  return asked ? std::min(asked, limit) : limit;
}

void RowDriver::begin() {
  if (stage_) stage_->begin();
  input_ = 0;
  resultBytes_ = 0;
}

Wrapped RowDriver::in(const void* p, std::size_t bytes, std::size_t element) {
  if (stage_) return Wrapped{stage_->in(input_++, p, bytes), 0};
  if (rows_ == Rows::Copied) return Wrapped{deviceCopy(ctx_, p, bytes), 0};
  return wrap(const_cast<void*>(p), bytes, element, CL_MEM_READ_ONLY);
}

Wrapped RowDriver::out(void* p, std::size_t bytes) {
  if (stage_) return Wrapped{stage_->out(bytes, [p, bytes](const void* s) { copySpans({{p, s, bytes}}); }), 0};
  if (rows_ == Rows::Copied) {
    result_ = Wrapped{cl::Buffer(ctx_, CL_MEM_WRITE_ONLY, bytes), 0};
    resultHost_ = p;
    resultBytes_ = bytes;
    return result_;
  }
  result_ = wrap(p, bytes, 4, CL_MEM_WRITE_ONLY);
  resultBytes_ = bytes + 4 * result_.at;
  return result_;
}

std::pair<Wrapped, std::size_t> RowDriver::outGrid(float* p, std::size_t materials, std::size_t rows,
                                                   std::size_t stride) {
  if (!stage_) return {out(p, 12 * ((materials - 1) * stride + rows)), stride};
  const auto deliver = [=](const void* s) {
    std::vector<CopySpan> spans;
    for (std::size_t m = 0; m < materials; ++m)
      spans.push_back({p + 3 * m * stride, static_cast<const float*>(s) + 3 * m * rows, 12 * rows});
    copySpans(spans);
  };
  return {Wrapped{stage_->out(12 * materials * rows, deliver), 0}, rows};
}

cl::Buffer RowDriver::badRowSlot(std::size_t firstRow) {
  cl_uint init = kNoBadRow;
  bad_.emplace_back(firstRow,
                    cl::Buffer(ctx_, cl_mem_flags(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR), std::size_t(4), &init));
  return bad_.back().second;
}

void RowDriver::launch(std::size_t rows, std::size_t materials, cl::Event* wholeDone, cl::Event* tailDone) {
  launchWholeAndTail(stage_ ? stage_->queue() : q_, kernel_, tail_, rows, lanes_, local_, materials, wholeDone,
                     tailDone);
  if (stage_) {
    stage_->end();
    return;
  }
  if (!resultBytes_) return;
  if (rows_ == Rows::Copied) {
    q_.enqueueReadBuffer(result_.buffer, CL_TRUE, 0, resultBytes_, resultHost_);
    result_ = Wrapped{};  // read: free it before the next launch allocates its own
    return;
  }
  // A read map/unmap makes the device's writes visible to the host (free on a CPU device).
  void* p = q_.enqueueMapBuffer(result_.buffer, CL_FALSE, CL_MAP_READ, 0, resultBytes_);
  q_.enqueueUnmapMemObject(result_.buffer, p);
}

void RowDriver::finish() {
  if (stage_) stage_->drain();
  q_.finish();
}

std::size_t RowDriver::lowestBadRow(std::size_t none) {
  if (stage_) stage_->drain();
  std::size_t lowest = none;
  for (auto& [first, slot] : bad_) {
    cl_uint row = kNoBadRow;
    q_.enqueueReadBuffer(slot, CL_TRUE, 0, 4, &row);
    if (row != kNoBadRow) lowest = std::min(lowest, first + row);
  }
  q_.finish();
  return lowest;
}

// A buffer over caller memory [p, p + bytes) and the element offset of p in it. On a CPU device
// the buffer starts at p's page boundary: page-aligned host memory is what CPU runtimes use in
// place rather than copy. Other devices get p itself and copy the bytes in (and out) as they must.
Wrapped RowDriver::wrap(void* p, std::size_t bytes, std::size_t element, cl_mem_flags flags) {
  const auto addr = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t base = info_.type == "CPU" ? addr & ~(kPage - 1) : addr;
  Wrapped w;
  w.at = cl_uint((addr - base) / element);
  w.buffer = cl::Buffer(ctx_, flags | CL_MEM_USE_HOST_PTR, bytes + (addr - base), reinterpret_cast<void*>(base));
  keep_.push_back(w.buffer);
  return w;
}

}  // namespace brdfcl
