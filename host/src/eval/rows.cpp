// Evaluator::evaluateRows / evaluateGridRows: the caller's (N, 3) rows handed to the row kernels
// (eval_rows, eval_grid_rows in kernels/eval.cl) where they lie, a launch at a time. The device
// normalizes and checks the rows; only the lowest bad row comes back, for the caller to word.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "eval/batch.hpp"

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

Wrapped wrap(const cl::Context& ctx, bool cpu, const void* p, std::size_t bytes, std::size_t element,
             cl_mem_flags flags) {
  const auto addr = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t base = cpu ? addr & ~(kPage - 1) : addr;
  Wrapped w;
  w.at = cl_uint((addr - base) / element);
  w.buffer = cl::Buffer(ctx, flags | CL_MEM_USE_HOST_PTR, bytes + (addr - base), reinterpret_cast<void*>(base));
  return w;
}

// What one evaluation's launches need kept alive until the device is done with them, and the
// drain that waits for that on every way out (an error included), before the caller's memory
// may be reused or freed.
struct Launches {
  cl::CommandQueue& q;
  std::vector<cl::Buffer> keep;
  std::vector<std::pair<std::size_t, cl::Buffer>> badRows;  // (first row of the launch, its slot)
  ~Launches() {
    try {
      q.finish();
    } catch (...) {
    }
  }
  cl::Buffer badRowSlot(const cl::Context& ctx, std::size_t firstRow) {
    cl_uint init = kNoBadRow;
    badRows.emplace_back(firstRow, cl::Buffer(ctx, cl_mem_flags(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR), std::size_t(4), &init));
    return badRows.back().second;
  }
  // The lowest bad row of every launch (blocking: the launches are done after it), or `none`.
  std::size_t lowestBadRow(std::size_t none) {
    std::size_t lowest = none;
    for (auto& [first, slot] : badRows) {
      cl_uint row = kNoBadRow;
      q.enqueueReadBuffer(slot, CL_TRUE, 0, 4, &row);
      if (row != kNoBadRow) lowest = std::min(lowest, first + row);
    }
    q.finish();
    return lowest;
  }
  // The host sees the device's writes to `out` (free on CPU devices, a copy back elsewhere).
  void publish(const cl::Buffer& out, std::size_t bytes) {
    void* p = q.enqueueMapBuffer(out, CL_FALSE, CL_MAP_READ, 0, bytes);
    q.enqueueUnmapMemObject(out, p);
  }
};

// Global size of a launch over `groups` lane groups: whole work-groups of `local` when large.
std::pair<cl::NDRange, cl::NDRange> rowsRange(std::size_t groups, std::size_t local, std::size_t materials = 0) {
  const bool grouped = groups >= 8 * local;
  const std::size_t global = grouped ? roundUp(groups, local) : groups;
  if (materials == 0) return {cl::NDRange(global), grouped ? cl::NDRange(local) : cl::NullRange};
  return {cl::NDRange(global, materials), grouped ? cl::NDRange(local, 1) : cl::NullRange};
}

// Rows a launch takes: every row buffer within the device's largest allocation, and the
// kernel's 32-bit row numbers within range.
std::size_t rowsPerLaunch(const Evaluator& ev, const DeviceInfo& info, std::size_t asked, std::size_t rowBytes = 12) {
  const std::size_t limit =
      std::max<std::size_t>(16, std::min<std::size_t>(ev.launchLimit(), info.maxAlloc / rowBytes) / 16 * 16);
  return asked ? std::min(asked, limit) : limit;
}

}  // namespace

std::size_t Evaluator::evaluateRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                                    bool normalize) {
  if (rows.count == 0) return 0;
  if (!rows.L || !rows.V || !rgb) throw Error("internal: rows without data", 3);
  if (rows.index && rows.index32) throw Error("internal: rows with two kinds of index", 3);
  Batch b = prepare(materials);
  const auto& ctx = rt_.context();
  const bool cpu = rt_.info().type == "CPU";
  const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), rows.launch);
  try {
    cl::Kernel kernel(b.program, "eval_rows");
    const std::size_t local = groupSizeFor(b.shape, kernel, rt_.device());
    Launches run{rt_.queue(), {}, {}};
    for (std::size_t first = 0; first < rows.count; first += chunk) {
      const std::size_t count = std::min(chunk, rows.count - first);
      const Wrapped L = wrap(ctx, cpu, rows.L + 3 * first, 12 * count, 4, CL_MEM_READ_ONLY);
      const Wrapped V = wrap(ctx, cpu, rows.V + 3 * first, 12 * count, 4, CL_MEM_READ_ONLY);
      const Wrapped index = rows.index     ? wrap(ctx, cpu, rows.index + first, 8 * count, 8, CL_MEM_READ_ONLY)
                            : rows.index32 ? wrap(ctx, cpu, rows.index32 + first, 4 * count, 4, CL_MEM_READ_ONLY)
                                           : Wrapped{};
      const Wrapped out = wrap(ctx, cpu, rgb + 3 * first, 12 * count, 4, CL_MEM_WRITE_ONLY);
      int arg = 0;
      kernel.setArg(arg++, L.buffer);
      kernel.setArg(arg++, L.at);
      kernel.setArg(arg++, V.buffer);
      kernel.setArg(arg++, V.at);
      kernel.setArg(arg++, index.buffer);
      kernel.setArg(arg++, index.at);
      kernel.setArg(arg++, cl_int(rows.index != nullptr));
      kernel.setArg(arg++, cl_uint(std::min<std::size_t>(materials.size(), UINT32_MAX)));
      kernel.setArg(arg++, cl_uint(count));
      kernel.setArg(arg++, cl_int(normalize));
      kernel.setArg(arg++, b.materials);
      kernel.setArg(arg++, b.tableBuffer);
      kernel.setArg(arg++, b.tableSize);
      kernel.setArg(arg++, out.buffer);
      kernel.setArg(arg++, out.at);
      kernel.setArg(arg++, run.badRowSlot(ctx, first));
      const auto [global, group] = rowsRange((count + b.shape.lanes - 1) / b.shape.lanes, local);
      run.q.enqueueNDRangeKernel(kernel, cl::NullRange, global, group);
      run.publish(out.buffer, 12 * count + 4 * out.at);
      for (const auto* w : {&L, &V, &index, &out}) run.keep.push_back(w->buffer);
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
  const auto& ctx = rt_.context();
  const bool cpu = rt_.info().type == "CPU";
  const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), launch, 28);
  try {
    cl::Kernel kernel(b.program, "eval_table_rows");
    const std::size_t local = groupSizeFor(b.shape, kernel, rt_.device());
    Launches run{rt_.queue(), {}, {}};
    for (std::size_t first = 0; first < count; first += chunk) {
      const std::size_t n = std::min(chunk, count - first);
      const Wrapped in = wrap(ctx, cpu, rows + 7 * first, 28 * n, 4, CL_MEM_READ_ONLY);
      const Wrapped out = wrap(ctx, cpu, rgb + 3 * first, 12 * n, 4, CL_MEM_WRITE_ONLY);
      int arg = 0;
      kernel.setArg(arg++, in.buffer);
      kernel.setArg(arg++, in.at);
      kernel.setArg(arg++, cl_uint(std::min<std::size_t>(materials.size(), UINT32_MAX)));
      kernel.setArg(arg++, cl_uint(n));
      kernel.setArg(arg++, b.materials);
      kernel.setArg(arg++, b.tableBuffer);
      kernel.setArg(arg++, b.tableSize);
      kernel.setArg(arg++, out.buffer);
      kernel.setArg(arg++, out.at);
      kernel.setArg(arg++, run.badRowSlot(ctx, first));
      const auto [global, group] = rowsRange((n + b.shape.lanes - 1) / b.shape.lanes, local);
      run.q.enqueueNDRangeKernel(kernel, cl::NullRange, global, group);
      run.publish(out.buffer, 12 * n + 4 * out.at);
      run.keep.push_back(in.buffer);
      run.keep.push_back(out.buffer);
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
  const auto& ctx = rt_.context();
  const bool cpu = rt_.info().type == "CPU";
  const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), rows.launch);
  try {
    cl::Kernel kernel(b.program, "eval_grid_rows");
    const std::size_t local = groupSizeFor(b.shape, kernel, rt_.device());
    Launches run{rt_.queue(), {}, {}};
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      const Wrapped L = wrap(ctx, cpu, rows.L + 3 * first, 12 * count, 4, CL_MEM_READ_ONLY);
      const Wrapped V = wrap(ctx, cpu, rows.V + 3 * first, 12 * count, 4, CL_MEM_READ_ONLY);
      run.keep.push_back(L.buffer);
      run.keep.push_back(V.buffer);
      // Materials in groups whose stretch of the output, (mc - 1) * n + count rows, fits a launch.
      const std::size_t perLaunch = std::max<std::size_t>(1, chunk > count ? (chunk - count) / n + 1 : 1);
      for (std::size_t m0 = 0; m0 < nm; m0 += perLaunch) {
        const std::size_t mc = std::min(perLaunch, nm - m0);
        const std::size_t outRows = (mc - 1) * n + count;
        const Wrapped out = wrap(ctx, cpu, rgb + 3 * (m0 * n + first), 12 * outRows, 4, CL_MEM_WRITE_ONLY);
        int arg = 0;
        kernel.setArg(arg++, L.buffer);
        kernel.setArg(arg++, L.at);
        kernel.setArg(arg++, V.buffer);
        kernel.setArg(arg++, V.at);
        kernel.setArg(arg++, cl_uint(count));
        kernel.setArg(arg++, cl_int(normalize));
        kernel.setArg(arg++, b.materials);
        kernel.setArg(arg++, cl_uint(firstMaterial + m0));
        kernel.setArg(arg++, b.tableBuffer);
        kernel.setArg(arg++, b.tableSize);
        kernel.setArg(arg++, out.buffer);
        kernel.setArg(arg++, out.at);
        kernel.setArg(arg++, cl_ulong(n));
        kernel.setArg(arg++, run.badRowSlot(ctx, first));
        const auto [global, group] = rowsRange((count + b.shape.lanes - 1) / b.shape.lanes, local, mc);
        run.q.enqueueNDRangeKernel(kernel, cl::NullRange, global, group);
        run.publish(out.buffer, 12 * outRows + 4 * out.at);
        run.keep.push_back(out.buffer);
      }
    }
    return run.lowestBadRow(n);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating the material x direction grid");
  }
}

}  // namespace brdfcl
