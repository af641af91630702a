// Evaluator::evaluateRows / evaluateTableRows / evaluateGridRows: the caller's rows handed to the
// row kernels (eval_rows, eval_table_rows, eval_grid_rows in kernels/eval.cl) where they lie, a
// launch at a time. The device normalizes and checks the rows; only the lowest bad row comes back.
// CPU devices read and write the caller's pages in place; other devices get the rows through
// pinned staging, double buffered (eval/staging.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "eval/batch.hpp"
#include "eval/device_array.hpp"
#include "eval/staging.hpp"
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
std::size_t rowsPerLaunch(const Evaluator& ev, const DeviceInfo& info, std::size_t asked, std::size_t rowBytes,
                          bool staged) {
  std::size_t limit =
      std::max<std::size_t>(16, std::min<std::size_t>(ev.launchLimit(), info.maxAlloc / rowBytes) / 16 * 16);
  if (staged) limit = std::min(limit, kStagedRows);
  return asked ? std::min(asked, limit) : limit;
}

// One evaluation's launches of a row kernel: the caller's memory wrapped and kept alive until
// the device is done with it, one bad-row slot a launch, and a drain that waits for the device
// on every way out (an error included) before that memory may be reused or freed.
class RowLaunches {
 public:
  // The kernel `name` (whole groups of lanes) and `name`_tail (the partial group at the end).
  // `host`: the rows are in host memory (false: in device buffers, never staged).
  RowLaunches(Runtime& rt, const cl::Program& program, const std::string& name, const LaneShape& shape,
              bool host = true)
      : ctx_(rt.opencl().context()), q_(rt.opencl().queue()), cpu_(rt.info().type == "CPU"), kernel_(program, name.c_str()),
        tail_(program, (name + "_tail").c_str()), lanes_(std::size_t(shape.lanes)),
        local_(groupSizeFor(shape, kernel_, rt.opencl().device())) {
    if (host && stagesRows(rt)) stage_ = std::make_unique<Staging>(rt);
  }
  ~RowLaunches() {
    try {
      q_.finish();
    } catch (...) {
    }
  }

  bool staged() const { return stage_ != nullptr; }

  // Starts a launch: with staging, on the next slot once its last results are delivered.
  void begin() {
    if (stage_) stage_->begin();
    input_ = 0;
  }
  RowLaunches(const RowLaunches&) = delete;
  RowLaunches& operator=(const RowLaunches&) = delete;

  // The arguments of the next launch, for both entry points.
  template <class... A>
  void args(const A&... a) {
    setArgs(kernel_, a...);
    setArgs(tail_, a...);
  }

  // The launch's next input: the caller's memory, or its staged copy.
  Wrapped in(const void* p, std::size_t bytes, std::size_t element) {
    if (stage_) return Wrapped{stage_->in(input_++, p, bytes), 0};
    return wrap(p, bytes, element, CL_MEM_READ_ONLY);
  }
  // Where the launch writes `rows` rows that belong at p.
  Wrapped out(float* p, std::size_t rows) {
    if (stage_)
      return Wrapped{stage_->out(12 * rows, [p, rows](const void* s) { copySpans({{p, s, 12 * rows}}); }), 0};
    return wrap(p, 12 * rows, 4, CL_MEM_WRITE_ONLY);
  }
  // Where a grid launch writes `materials` stretches of `rows` rows that belong `stride` rows
  // apart from p on, and the stride the launch writes them with (a staged launch packs them).
  std::pair<Wrapped, std::size_t> outGrid(float* p, std::size_t materials, std::size_t rows, std::size_t stride) {
    if (!stage_) return {wrap(p, 12 * ((materials - 1) * stride + rows), 4, CL_MEM_WRITE_ONLY), stride};
    const auto deliver = [=](const void* s) {
      std::vector<CopySpan> spans;
      for (std::size_t m = 0; m < materials; ++m)
        spans.push_back({p + 3 * m * stride, static_cast<const float*>(s) + 3 * m * rows, 12 * rows});
      copySpans(spans);
    };
    return {Wrapped{stage_->out(12 * materials * rows, deliver), 0}, rows};
  }
  // A slot the launch lowers to its first bad row (relative to `firstRow`).
  cl::Buffer badRowSlot(std::size_t firstRow) {
    cl_uint init = kNoBadRow;
    bad_.emplace_back(firstRow, cl::Buffer(ctx_, cl_mem_flags(CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR),
                                           std::size_t(4), &init));
    return bad_.back().second;
  }
  // Runs the kernel (arguments set) over `rows` rows, for `materials` materials (0: a 1-D launch),
  // and makes the device's writes to `result` visible to the host (free on CPU devices; nothing
  // for results left on the device, `result` null).
  void launch(std::size_t rows, std::size_t materials, const Wrapped* result, std::size_t resultRows) {
    cl::CommandQueue& q = stage_ ? stage_->queue() : q_;
    const std::size_t groups = rows / lanes_;
    const auto range = [&](std::size_t n) { return materials ? cl::NDRange(n, materials) : cl::NDRange(n); };
    if (groups > 0) {
      const bool grouped = groups >= 8 * local_;
      const cl::NDRange local = !grouped ? cl::NullRange : materials ? cl::NDRange(local_, 1) : cl::NDRange(local_);
      q.enqueueNDRangeKernel(kernel_, cl::NullRange, range(grouped ? roundUp(groups, local_) : groups), local);
    }
    if (rows % lanes_) q.enqueueNDRangeKernel(tail_, cl::NullRange, range(1), cl::NullRange);
    if (stage_) {
      stage_->end();
      return;
    }
    if (!result) return;
    const std::size_t bytes = 12 * resultRows + 4 * result->at;
    void* p = q_.enqueueMapBuffer(result->buffer, CL_FALSE, CL_MAP_READ, 0, bytes);
    q_.enqueueUnmapMemObject(result->buffer, p);
  }
  // The lowest bad row of every launch, or `none`; waits for the launches.
  std::size_t lowestBadRow(std::size_t none) {
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
  std::unique_ptr<Staging> stage_;  // declared last: it waits for its queues before the kernels go
  int input_ = 0;
};

cl_uint count32(std::size_t n) { return cl_uint(std::min<std::size_t>(n, UINT32_MAX)); }

// A device array's check against what evaluate() takes for it.
void checkArray(const Runtime& rt, const DeviceArray& a, const char* name, DeviceArray::Type type, std::size_t size,
                std::size_t rows) {
  if (!a.belongsTo(rt))
    throw Error(fmt::format("device array {} belongs to another Runtime; create it on the evaluator's Runtime", name));
  if (a.type() != type)
    throw Error(fmt::format("device array {} must be {}", name, type == DeviceArray::Type::Float32 ? "float32" : "uint32"));
  if (a.size() != size)
    throw Error(fmt::format("device array {} holds {} elements; {} rows need {}", name, a.size(), rows, size));
}

// The message for bad row `i` of device-resident rows, worded as evaluate() words it.
[[noreturn]] void throwDeviceRowError(const DeviceArray& L, const DeviceArray& V, const DeviceArray* material,
                                      std::size_t materialCount, std::size_t i) {
  std::uint32_t index = 0;
  if (material) material->download(&index, 1, i);
  if (index >= materialCount)
    throw Error(fmt::format("sample {}: material index {} out of range ({} materials)", i, index, materialCount));
  float d[6];
  L.download(d, 3, 3 * i);
  V.download(d + 3, 3, 3 * i);
  static const char* const kNames[6] = {"Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  for (int k = 0; k < 6; ++k)
    if (!std::isfinite(d[k]))
      throw Error(fmt::format("sample {}: {} is not finite: {}", i, kNames[k], std::isnan(d[k]) ? "nan" : d[k] > 0 ? "inf" : "-inf"));
  throw Error(fmt::format("sample {}: {} is zero", i, d[0] == 0 && d[1] == 0 && d[2] == 0 ? "L" : "V"));
}

}  // namespace

std::size_t Evaluator::evaluateRows(const std::vector<MaterialParams>& materials, const Rows& rows, float* rgb,
                                    bool normalize) {
  if (rows.count == 0) return 0;
  if (!rows.L || !rows.V || !rgb) throw Error("internal: rows without data", 3);
  if (rows.index && rows.index32) throw Error("internal: rows with two kinds of index", 3);
  Batch b = prepare(materials);
  try {
    RowLaunches run(rt_, b.program, "eval_rows", b.shape);
    const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), rows.launch, 12, run.staged());
    for (std::size_t first = 0; first < rows.count; first += chunk) {
      const std::size_t n = std::min(chunk, rows.count - first);
      run.begin();
      const Wrapped L = run.in(rows.L + 3 * first, 12 * n, 4), V = run.in(rows.V + 3 * first, 12 * n, 4);
      const Wrapped index = rows.index     ? run.in(rows.index + first, 8 * n, 8)
                            : rows.index32 ? run.in(rows.index32 + first, 4 * n, 4)
                                           : Wrapped{};
      const Wrapped out = run.out(rgb + 3 * first, n);
      run.args(L.buffer, L.at, V.buffer, V.at, index.buffer, index.at, cl_int(rows.index != nullptr),
              count32(materials.size()), cl_uint(n), cl_int(normalize), b.materials, b.tableBuffer, b.tableSize,
              out.buffer, out.at, run.badRowSlot(first));
      run.launch(n, 0, &out, n);
    }
    return run.lowestBadRow(rows.count);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating rows");
  }
}

void Evaluator::evaluate(const std::vector<MaterialParams>& materials, const DeviceArray& L, const DeviceArray& V,
                         const DeviceArray* material, DeviceArray& rgb, bool normalize) {
  using T = DeviceArray::Type;
  if (L.size() % 3)
    throw Error(fmt::format("device array L holds {} elements; give 3 floats a row", L.size()));
  const std::size_t n = L.size() / 3;
  if (n > UINT32_MAX / 3) throw Error(fmt::format("device arrays of {} rows are too long; use at most {} rows a call", n, UINT32_MAX / 3));
  checkArray(rt_, L, "L", T::Float32, 3 * n, n);
  checkArray(rt_, V, "V", T::Float32, 3 * n, n);
  if (material) checkArray(rt_, *material, "material", T::UInt32, n, n);
  checkArray(rt_, rgb, "rgb", T::Float32, 3 * n, n);
  if (&rgb.impl() == &L.impl() || &rgb.impl() == &V.impl())
    throw Error("device array rgb must not be L or V; give the results their own array");
  Batch b = prepare(materials);
  if (n == 0) return;
  std::size_t bad = n;
  try {
    RowLaunches run(rt_, b.program, "eval_rows", b.shape, false);
    const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), 0, 12, false);
    const cl::Buffer none;
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      run.begin();
      run.args(L.impl().buffer, cl_uint(3 * first), V.impl().buffer, cl_uint(3 * first),
               material ? material->impl().buffer : none, cl_uint(material ? first : 0), cl_int(0),
               count32(materials.size()), cl_uint(count), cl_int(normalize), b.materials, b.tableBuffer, b.tableSize,
               rgb.impl().buffer, cl_uint(3 * first), run.badRowSlot(first));
      run.launch(count, 0, nullptr, count);
    }
    bad = run.lowestBadRow(n);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating device rows");
  }
  if (bad < n) throwDeviceRowError(L, V, material, materials.size(), bad);
}

std::size_t Evaluator::evaluateTableRows(const std::vector<MaterialParams>& materials, const float* rows,
                                         std::size_t count, float* rgb, std::size_t launch) {
  if (count == 0) return 0;
  if (!rows || !rgb) throw Error("internal: table rows without data", 3);
  Batch b = prepare(materials);
  try {
    RowLaunches run(rt_, b.program, "eval_table_rows", b.shape);
    const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), launch, 28, run.staged());
    for (std::size_t first = 0; first < count; first += chunk) {
      const std::size_t n = std::min(chunk, count - first);
      run.begin();
      const Wrapped in = run.in(rows + 7 * first, 28 * n, 4), out = run.out(rgb + 3 * first, n);
      run.args(in.buffer, in.at, count32(materials.size()), cl_uint(n), b.materials, b.tableBuffer,
              b.tableSize, out.buffer, out.at, run.badRowSlot(first));
      run.launch(n, 0, &out, n);
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
  try {
    RowLaunches run(rt_, b.program, "eval_grid_rows", b.shape);
    const std::size_t chunk = rowsPerLaunch(*this, rt_.info(), rows.launch, 12, run.staged());
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      // Materials in groups whose stretch of the output, (mc - 1) * n + count rows (mc * count
      // staged), fits a launch.
      const std::size_t perLaunch = run.staged() ? std::max<std::size_t>(1, chunk / count)
                                                 : std::max<std::size_t>(1, chunk > count ? (chunk - count) / n + 1 : 1);
      for (std::size_t m0 = 0; m0 < nm; m0 += perLaunch) {
        const std::size_t mc = std::min(perLaunch, nm - m0);
        // Staged, every launch takes its own copy of the directions (the slots alternate).
        run.begin();
        const Wrapped L = run.in(rows.L + 3 * first, 12 * count, 4), V = run.in(rows.V + 3 * first, 12 * count, 4);
        const auto [out, stride] = run.outGrid(rgb + 3 * (m0 * n + first), mc, count, n);
        run.args(L.buffer, L.at, V.buffer, V.at, cl_uint(count), cl_int(normalize), b.materials,
                cl_uint(firstMaterial + m0), b.tableBuffer, b.tableSize, out.buffer, out.at, cl_ulong(stride),
                run.badRowSlot(first));
        run.launch(count, mc, &out, (mc - 1) * stride + count);
      }
    }
    return run.lowestBadRow(n);
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating the material x direction grid");
  }
}

}  // namespace brdfcl
