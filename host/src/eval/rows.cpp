// Evaluator::evaluateRows / evaluateTableRows / evaluateGridRows: the caller's rows handed to the
// row kernels (eval_rows, eval_table_rows, eval_grid_rows in kernels/eval.cl) where they lie, a
// launch at a time. The device normalizes and checks the rows; only the lowest bad row comes back.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "eval/batch.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {

constexpr std::uintptr_t kPage = 4096;
constexpr cl_uint kNoBadRow = UINT32_MAX;

std::size_t roundUp(std::size_t n, std::size_t m) { return (n + m - 1) / m * m; }

// A buffer over caller memory [p, p + bytes) and the element offset of p in it. On a CPU device
// the buffer starts at p's page boundary: page-aligned host memory is what CPU runtimes use in
// place rather than copy. Other devices get p itself and copy the bytes in (and out) as they must.
struct Wrapped {
  cl::Buffer buffer;
  cl_uint at = 0;
};

template <class... A>
void setArgs(cl::Kernel& kernel, const A&... args) {
  cl_uint i = 0;
  (kernel.setArg(i++, args), ...);
}

// Rows a launch takes: every row buffer within the device's largest allocation, and the
// kernel's 32-bit row numbers within range.
std::size_t rowsPerLaunch(const Evaluator& ev, const DeviceInfo& info, std::size_t asked, std::size_t rowBytes) {
  const std::size_t limit =
      std::max<std::size_t>(16, std::min<std::size_t>(ev.launchLimit(), info.maxAlloc / rowBytes) / 16 * 16);
  return asked ? std::min(asked, limit) : limit;
}

// One evaluation's launches of a row kernel: the caller's memory wrapped and kept alive until
// the device is done with it, one bad-row slot a launch, and a drain that waits for the device
// on every way out (an error included) before that memory may be reused or freed.
class RowLaunches {
 public:
  // The kernel `name` (whole groups of lanes) and `name`_tail (the partial group at the end).
  RowLaunches(Runtime& rt, const cl::Program& program, const std::string& name, const LaneShape& shape)
      : ctx_(rt.opencl().context()), q_(rt.opencl().queue()), cpu_(rt.info().type == "CPU"), kernel_(program, name.c_str()),
        tail_(program, (name + "_tail").c_str()), lanes_(std::size_t(shape.lanes)),
        local_(groupSizeFor(shape, kernel_, rt.opencl().device())) {}
  ~RowLaunches() {
    try {
      q_.finish();
    } catch (...) {
    }
  }
  RowLaunches(const RowLaunches&) = delete;
  RowLaunches& operator=(const RowLaunches&) = delete;

  // The arguments of the next launch, for both entry points.
  template <class... A>
  void args(const A&... a) {
    setArgs(kernel_, a...);
    setArgs(tail_, a...);
  }

  Wrapped in(const void* p, std::size_t bytes, std::size_t element) {
    return wrap(p, bytes, element, CL_MEM_READ_ONLY);
  }
  Wrapped out(float* p, std::size_t rows) { return wrap(p, 12 * rows, 4, CL_MEM_WRITE_ONLY); }
  // A slot the launch lowers to its first bad row (relative to `firstRow`).
  cl::Buffer badRowSlot(std::size_t firstRow) {
    cl_uint init = kNoBadRow;
    bad_.emplace_back(firstRow, cl::Buffer(ctx_, cl_mem_flags(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR),
                                           std::size_t(4), &init));
    return bad_.back().second;
  }
  // Runs the kernel (arguments set) over `rows` rows, for `materials` materials (0: a 1-D launch),
  // and makes the device's writes to `result` visible to the host (free on CPU devices).
  void launch(std::size_t rows, std::size_t materials, const Wrapped& result, std::size_t resultRows) {
    const std::size_t groups = rows / lanes_;
    const auto range = [&](std::size_t n) { return materials ? cl::NDRange(n, materials) : cl::NDRange(n); };
    if (groups > 0) {
      const bool grouped = groups >= 8 * local_;
      const cl::NDRange local = !grouped ? cl::NullRange : materials ? cl::NDRange(local_, 1) : cl::NDRange(local_);
      q_.enqueueNDRangeKernel(kernel_, cl::NullRange, range(grouped ? roundUp(groups, local_) : groups), local);
    }
    if (rows % lanes_) q_.enqueueNDRangeKernel(tail_, cl::NullRange, range(1), cl::NullRange);
    const std::size_t bytes = 12 * resultRows + 4 * result.at;
    void* p = q_.enqueueMapBuffer(result.buffer, CL_FALSE, CL_MAP_READ, 0, bytes);
    q_.enqueueUnmapMemObject(result.buffer, p);
  }
  // The lowest bad row of every launch, or `none`; waits for the launches.
  std::size_t lowestBadRow(std::size_t none) {
    std::size_t lowest = none;
    for (auto& [first, slot] : bad_) {
      cl_uint row = kNoBadRow;
      q_.enqueueReadBuffer(slot, CL_TRUE, 0, 4, &row);
      if (row != kNoBadRow) lowest = std::min(lowest, first + row);
    }
    q_.finish();
    return lowest;
  }

 private:
  Wrapped wrap(const void* p, std::size_t bytes, std::size_t element, cl_mem_flags flags) {
    const auto addr = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t base = cpu_ ? addr & ~(kPage - 1) : addr;
    Wrapped w;
    w.at = cl_uint((addr - base) / element);
    w.buffer = cl::Buffer(ctx_, flags | CL_MEM_USE_HOST_PTR, bytes + (addr - base), reinterpret_cast<void*>(base));
    keep_.push_back(w.buffer);
    return w;
  }

  const cl::Context& ctx_;
  cl::CommandQueue& q_;
  bool cpu_;
  cl::Kernel kernel_, tail_;
  std::size_t lanes_, local_;
  std::vector<cl::Buffer> keep_;
  std::vector<std::pair<std::size_t, cl::Buffer>> bad_;  // (first row of the launch, its slot)
};

cl_uint count32(std::size_t n) { return cl_uint(std::min<std::size_t>(n, UINT32_MAX)); }

}  // namespace

std::size_t Evaluator::evaluateRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                                    bool normalize) {
  if (rows.count == 0) return 0;
  if (!rows.L || !rows.V || !rgb) throw Error("internal: rows without data", 3);
  if (rows.index && rows.index32) throw Error("internal: rows with two kinds of index", 3);
  Batch b = prepare(materials);
  const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), rows.launch, 12);
  try {
    RowLaunches run(rt_, b.program, "eval_rows", b.shape);
    for (std::size_t first = 0; first < rows.count; first += chunk) {
      const std::size_t n = std::min(chunk, rows.count - first);
      const Wrapped L = run.in(rows.L + 3 * first, 12 * n, 4), V = run.in(rows.V + 3 * first, 12 * n, 4);
      const Wrapped index = rows.index     ? run.in(rows.index + first, 8 * n, 8)
                            : rows.index32 ? run.in(rows.index32 + first, 4 * n, 4)
                                           : Wrapped{};
      const Wrapped out = run.out(rgb + 3 * first, n);
      run.args(L.buffer, L.at, V.buffer, V.at, index.buffer, index.at, cl_int(rows.index != nullptr),
              count32(materials.size()), cl_uint(n), cl_int(normalize), b.materials, b.tableBuffer, b.tableSize,
              out.buffer, out.at, run.badRowSlot(first));
      run.launch(n, 0, out, n);
    }
    return run.lowestBadRow(rows.count);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating rows");
  }
}

std::size_t Evaluator::evaluateTableRows(const std::vector<MaterialParams>& materials, const float* rows,
                                         std::size_t count, float* rgb, std::size_t launch) {
  if (count == 0) return 0;
  if (!rows || !rgb) throw Error("internal: table rows without data", 3);
  Batch b = prepare(materials);
  const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), launch, 28);
  try {
    RowLaunches run(rt_, b.program, "eval_table_rows", b.shape);
    for (std::size_t first = 0; first < count; first += chunk) {
      const std::size_t n = std::min(chunk, count - first);
      const Wrapped in = run.in(rows + 7 * first, 28 * n, 4), out = run.out(rgb + 3 * first, n);
      run.args(in.buffer, in.at, count32(materials.size()), cl_uint(n), b.materials, b.tableBuffer,
              b.tableSize, out.buffer, out.at, run.badRowSlot(first));
      run.launch(n, 0, out, n);
    }
    return run.lowestBadRow(count);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating sample rows");
  }
}

std::size_t Evaluator::evaluateGridRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                                        bool normalize, std::size_t firstMaterial, std::size_t materialCount) {
  if (firstMaterial > materials.size() || materialCount > materials.size() - firstMaterial)
    throw Error(fmt::format("internal: materials [{}, {}) of {}", firstMaterial, firstMaterial + materialCount,
                            materials.size()), 3);
  const std::size_t n = rows.count, nm = materialCount;
  if (n == 0 || nm == 0) return n;
  if (!rows.L || !rows.V || !rgb) throw Error("internal: rows without data", 3);
  Batch b = prepare(materials);
  const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), rows.launch, 12);
  try {
    RowLaunches run(rt_, b.program, "eval_grid_rows", b.shape);
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      const Wrapped L = run.in(rows.L + 3 * first, 12 * count, 4), V = run.in(rows.V + 3 * first, 12 * count, 4);
      // Materials in groups whose stretch of the output, (mc - 1) * n + count rows, fits a launch.
      const std::size_t perLaunch = std::max<std::size_t>(1, chunk > count ? (chunk - count) / n + 1 : 1);
      for (std::size_t m0 = 0; m0 < nm; m0 += perLaunch) {
        const std::size_t mc = std::min(perLaunch, nm - m0), outRows = (mc - 1) * n + count;
        const Wrapped out = run.out(rgb + 3 * (m0 * n + first), outRows);
        run.args(L.buffer, L.at, V.buffer, V.at, cl_uint(count), cl_int(normalize), b.materials,
                cl_uint(firstMaterial + m0), b.tableBuffer, b.tableSize, out.buffer, out.at, cl_ulong(n),
                run.badRowSlot(first));
        run.launch(count, mc, out, outRows);
      }
    }
    return run.lowestBadRow(n);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating the material x direction grid");
  }
}

}  // namespace brdfcl
