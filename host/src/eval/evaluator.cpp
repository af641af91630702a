// Batch evaluation on the device. Materials are packed once per batch; samples travel as SoA
// planes in page-aligned host memory the device uses in place (SoaBatch); batches larger than a
// chunk (or than the device's largest allocation) run chunk by chunk through one SoaBatch.
#include "brdfcl/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <unordered_map>
#include <utility>

#include <sys/mman.h>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "eval/batch.hpp"
#include "eval/material_range.hpp"
#include "model/pack.hpp"
#include "model/engine_tables.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {
constexpr std::size_t kLanes = SoaBatch::kLanes;
constexpr std::size_t kMaxChunk = std::size_t(1) << 22;
constexpr std::size_t kPage = 4096, kHugePage = std::size_t(2) << 20;
// Idle plane sets an Evaluator keeps for its scratch batches (one per concurrent caller, typically).
constexpr std::size_t kPoolSets = 4;

std::size_t roundUp(std::size_t n, std::size_t m) { return (n + m - 1) / m * m; }

// Samples per launch: bounded by a fixed chunk and by the device's largest allocation.
std::size_t chunkSize(const Runtime& rt, std::size_t bytesPerSample) {
  std::size_t byAlloc = std::size_t(rt.info().maxAlloc) / bytesPerSample;
  return std::max(kLanes, std::min(kMaxChunk, byAlloc) / kLanes * kLanes);
}

template <class T>
T* allocPages(std::size_t count) {
  // A count whose byte size does not fit size_t can never be allocated; checking first also
  // keeps count * sizeof(T) from wrapping round to a small allocation.
  const bool representable = count <= (SIZE_MAX - kHugePage) / sizeof(T);
  const std::size_t bytes = representable ? roundUp(std::max<std::size_t>(count * sizeof(T), 1), kPage) : 0;
  // Planes of several MiB sit on 2 MiB boundaries and ask for transparent huge pages (where the
  // kernel grants them on request): one fault per 2 MiB instead of 512 on first touch.
  const bool huge = bytes >= 2 * kHugePage;
  void* p = representable ? std::aligned_alloc(huge ? kHugePage : kPage, huge ? roundUp(bytes, kHugePage) : bytes) : nullptr;
  if (!p)
    throw Error(ErrorKind::Memory, fmt::format("out of host memory allocating {:.0f} MiB for a batch",
                            std::ceil(double(count) * sizeof(T) / double(1 << 20))));
  if (huge) ::madvise(p, roundUp(bytes, kHugePage), MADV_HUGEPAGE);  // advice only: failure is harmless
  std::memset(p, 0, bytes);  // zero directions lie below the horizon: padding lanes give f = 0
  return static_cast<T*>(p);
}

// NaN or an infinity in a direction would come back as NaN f: the file readers reject them,
// and so does the library for directions built in memory.
// A branch-free scan of the exponent bits first (it vectorizes; the readers' samples always
// pass it), then the row-by-row search for the message only when something is not finite.
bool allFinite(const std::vector<float>& v) {
  std::uint32_t any = 0;
  for (const float x : v) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, 4);
    any |= std::uint32_t((bits & 0x7f800000u) == 0x7f800000u);
  }
  return any == 0;
}

// "sample 7: Vz is not finite: inf" for the first non-finite component of sample i, if any.
void checkSample(const Samples& s, std::size_t i) {
  static const char* const kNames[6] = {"Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  for (int k = 0; k < 6; ++k) {
    const float v = k < 3 ? s.L[3 * i + k] : s.V[3 * i + k - 3];
    if (!std::isfinite(v))
      throw Error(fmt::format("sample {}: {} is not finite: {}", i, kNames[k], std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"));
  }
}

void checkDirections(const Samples& s) {
  if (allFinite(s.L) && allFinite(s.V)) return;
  for (std::size_t i = 0; i < s.size(); ++i) checkSample(s, i);
}

}  // namespace

Evaluator::Evaluator(Runtime& rt, EvalOptions options) : rt_(rt), options_(options) { checkProfileOptions(options); }

// Host planes (Lx Ly Lz Vx Vy Vz r g b, then the material index), `floats` each, and the
// buffers that hand them to the device in place; the buffers go before the memory they wrap.
struct Evaluator::Planes {
  std::size_t floats = 0;
  float* host[9] = {};
  std::uint32_t* index = nullptr;
  cl::Buffer buffers[9], indexBuffer;

  Planes(const cl::Context& ctx, std::size_t n) : floats(n) {
    try {
      for (auto*& p : host) p = allocPages<float>(n);
      index = allocPages<std::uint32_t>(n);
    } catch (...) {
      release();
      throw;
    }
    try {
      for (int k = 0; k < 9; ++k)
        buffers[k] = cl::Buffer(ctx, (k < 6 ? CL_MEM_READ_ONLY : CL_MEM_WRITE_ONLY) | CL_MEM_USE_HOST_PTR, n * 4, host[k]);
      indexBuffer = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, n * 4, index);
    } catch (const cl::Error&) {
      release();
      rethrowOpenCL("allocating a sample batch");
    }
  }
  ~Planes() { release(); }
  Planes(const Planes&) = delete;
  Planes& operator=(const Planes&) = delete;

 private:
  void release() {
    for (auto& b : buffers) b = cl::Buffer();
    indexBuffer = cl::Buffer();
    for (auto*& p : host) std::free(std::exchange(p, nullptr));
    std::free(std::exchange(index, nullptr));
  }
};

Evaluator::~Evaluator() = default;

std::unique_ptr<Evaluator::Planes> Evaluator::takePlanes(std::size_t floats) {
  std::lock_guard<std::mutex> lock(poolMutex_);
  for (auto it = pool_.begin(); it != pool_.end(); ++it)
    if ((*it)->floats == floats) {
      auto planes = std::move(*it);
      pool_.erase(it);
      return planes;
    }
  return nullptr;
}

void Evaluator::givePlanes(std::unique_ptr<Planes> planes) {
  std::lock_guard<std::mutex> lock(poolMutex_);
  if (pool_.size() == kPoolSets) pool_.erase(pool_.begin());  // the least recently returned goes
  pool_.push_back(std::move(planes));
}

// Baked on first use; the lock makes concurrent first calls bake once and see the finished
// table (a failed bake leaves table_ empty and the next call tries again). table_ is never
// replaced afterwards, so the returned reference stays valid for the Evaluator's lifetime.
const SheenAlbedoTable& Evaluator::sheenAlbedo() {
  std::lock_guard<std::mutex> lock(tableMutex_);
  if (!table_)
    table_ = std::make_unique<SheenAlbedoTable>(cachedSheenAlbedo(rt_, sheenTableOptions(options_).sheenDistribution,
                                                                  sheenTableOptions(options_).sheenVisibility));
  return *table_;
}

Evaluator::Batch Evaluator::prepare(const std::vector<MaterialParams>& materials, Kernels kernels) {
  if (materials.empty()) throw Error("no materials to evaluate");
  for (std::size_t i = 0; i < materials.size(); ++i) checkMaterial(materials[i], i);
  const auto features = featuresOf(materials, options_.profile);
  Batch b;
  for (const auto& m : materials) b.packed.push_back(packMaterial(m, options_.profile));
  // Under the spec profile each material reads its own row of E, blended here once for its
  // sheenRoughness and placed after the table (kernels/brdf/material.h, BRDFCL_E_ROW): a lookup
  // is then two texel reads and one blend instead of four and three. Materials of one
  // sheenRoughness share a row; past kMaxSheenRows materials the kernel blends the table's rows.
  // The samplers (Kernels::None) build programs of their own, which read the table.
  const bool eRow = kernels != Kernels::None && options_.profile == Profile::Spec &&
                    features.needsSheenAlbedo(options_) && materials.size() <= kMaxSheenRows;
  if (features.needsSheenAlbedo(options_)) {
    const SheenAlbedoTable& table = sheenAlbedo();
    b.table = table.values;
    b.tableSize = int(table.width);
    if (eRow) {
      std::unordered_map<std::uint32_t, std::uint32_t> rowAt;  // sheen_roughness's bits -> row
      for (brdfcl_material& p : b.packed) {
        std::uint32_t bits;
        std::memcpy(&bits, &p.sheen_roughness, sizeof bits);
        const auto [at, fresh] = rowAt.try_emplace(bits, std::uint32_t(b.table.size()));
        if (fresh) {
          const std::vector<float> row = table.rowAt(p.sheen_roughness);
          b.table.insert(b.table.end(), row.begin(), row.end());
        }
        p.sheen_e_row = at->second;
      }
    }
  }
  // Engine profiles read three.js's DFG table right after the E table, khronos the Sample
  // Renderer's sheen albedo texture after that, babylon its BRDF texture (docs/profiles.md "Tables").
  if (options_.profile != Profile::Spec) {
    const auto& dfg = threejsDfgTable();
    b.table.insert(b.table.end(), dfg.begin(), dfg.end());
  }
  if (options_.profile == Profile::Khronos && features.ratifiedSheen) {
    const auto& lut = khronosSheenETable();
    b.table.insert(b.table.end(), lut.begin(), lut.end());
  }
  if (options_.profile == Profile::Babylon) {
    const auto& lut = babylonBrdfTable();
    b.table.insert(b.table.end(), lut.begin(), lut.end());
  }
  b.shape = laneShape(rt_.info());
  if (kernels == Kernels::None) return b;
  try {
    // One material: every lane reads the same record (no gathers); indices are still checked.
    b.program = rt_.opencl().program("eval.cl", materialDefines(options_, features) + fmt::format(" -DBRDFCL_W={}", b.shape.lanes) +
                                           (materials.size() == 1 ? " -DBRDFCL_ONE_MATERIAL=1" : "") +
                                           (eRow ? " -DBRDFCL_E_ROW=1" : "") +
                                           fmt::format(" -DBRDFCL_KERNELS={}", unsigned(kernels)),
                                       Runtime::OpenCL::Arithmetic::Batch);
    const auto& ctx = rt_.opencl().context();
    b.materials = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, b.packed.size() * sizeof(brdfcl_material),
                             b.packed.data());
    b.tableBuffer = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, b.table.size() * 4, b.table.data());
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing a batch");
  }
  return b;
}

struct SoaBatch::Device {
  Evaluator::Batch batch;
  cl::Kernel kernel;
  std::size_t local = 1;  // work-group size used when a launch is large enough
  cl::Event done;         // the last command start() enqueued
  cl::Event launch;       // the launch itself
};

SoaBatch::SoaBatch(Evaluator& evaluator, const std::vector<MaterialParams>& materials, std::size_t capacity)
    : SoaBatch(evaluator, materials, capacity, false) {}

SoaBatch::SoaBatch(Evaluator& evaluator, const std::vector<MaterialParams>& materials, std::size_t capacity, Scratch)
    : SoaBatch(evaluator, materials, capacity, true) {}

SoaBatch::SoaBatch(Evaluator& evaluator, const std::vector<MaterialParams>& materials, std::size_t capacity, bool pooled)
    : ev_(evaluator), pooled_(pooled), capacity_(roundUp(std::max<std::size_t>(capacity, 1), kLanes)), count_(capacity) {
  if (capacity > SIZE_MAX / 2)  // rounding up would wrap round: no such batch fits in memory
    throw Error(ErrorKind::Memory, fmt::format("out of host memory allocating {:.0f} MiB for a batch", double(capacity) * 4 / double(1 << 20)));
  device_ = std::make_unique<Device>();
  device_->batch = ev_.prepare(materials, Evaluator::Kernels::Samples);
  packed_ = device_->batch.packed;
  tableValues_ = device_->batch.table;
  tableSize_ = device_->batch.tableSize;
  try {
    auto& d = *device_;
    d.kernel = cl::Kernel(d.batch.program, "eval_samples");
    d.local = groupSizeFor(d.batch.shape, d.kernel, ev_.rt_.opencl().device());
  } catch (const cl::Error&) {
    rethrowOpenCL("creating the batch kernel");
  }
  // Planes are padded (with zeros: f = 0) to whole work-groups, so a launch rounded up to the
  // work-group size never reads past them. Pooled planes of the same size were padded alike,
  // and no batch writes past its capacity, so their padding is still zero.
  allocated_ = roundUp(capacity_, kLanes * device_->local);
  if (pooled_) set_ = ev_.takePlanes(allocated_);
  if (!set_) set_ = std::make_unique<Evaluator::Planes>(ev_.rt_.opencl().context(), allocated_);
  for (int k = 0; k < 9; ++k) planes_[k] = set_->host[k];
  index_ = set_->index;
  try {
    auto& d = *device_;
    int arg = 0;
    for (int k = 0; k < 6; ++k) d.kernel.setArg(arg++, set_->buffers[k]);
    d.kernel.setArg(arg++, set_->indexBuffer);
    d.kernel.setArg(arg++, d.batch.materials);
    d.kernel.setArg(arg++, d.batch.tableBuffer);
    d.kernel.setArg(arg++, d.batch.tableSize);
    for (int k = 6; k < 9; ++k) d.kernel.setArg(arg++, set_->buffers[k]);
  } catch (const cl::Error&) {
    release();
    rethrowOpenCL("allocating a sample batch");
  }
}

SoaBatch::~SoaBatch() {
  try {
    finish();  // the device must be done with the planes before they are freed or pooled
  } catch (...) {
  }
  release();
}

void SoaBatch::release() {
  device_.reset();  // the kernel lets go of the buffers first
  for (auto*& p : planes_) p = nullptr;
  index_ = nullptr;
  if (set_ && pooled_) ev_.givePlanes(std::move(set_));
  set_.reset();
}

void SoaBatch::setCount(std::size_t count) {
  if (count > capacity_)
    throw Error(fmt::format("internal: batch of {} samples exceeds its capacity {}", count, capacity_), 3);
  count_ = count;
}

float* SoaBatch::direction(int k) {
  inputsChanged_ = true;
  return planes_[k];
}

std::uint32_t* SoaBatch::materialIndex() {
  inputsChanged_ = true;
  return index_;
}

const float* SoaBatch::result(int c) const { return planes_[6 + c]; }

void SoaBatch::run() {
  start();
  finish();
}

// Everything is enqueued without blocking (the queue is in order), so the host may fill another
// batch while this one runs; finish() waits for the last command.
void SoaBatch::start() {
  if (count_ == 0) return;
  auto& q = ev_.rt_.opencl().queue();
  auto& d = *device_;
  try {
    if (inputsChanged_) {
      // A write map/unmap hands the host's writes to a device that caches USE_HOST_PTR memory
      // (a GPU); on a CPU device both calls are free.
      for (int k = 0; k < 7; ++k) {
        cl::Buffer& b = k < 6 ? set_->buffers[k] : set_->indexBuffer;
        void* p = q.enqueueMapBuffer(b, CL_FALSE, CL_MAP_WRITE, 0, allocated_ * 4);
        q.enqueueUnmapMemObject(b, p);
      }
      inputsChanged_ = false;
    }
    // Large launches use the measured work-group size (the padding costs at most 1/8); small ones
    // leave the choice to the runtime rather than evaluate a mostly empty group.
    const std::size_t lanes = std::size_t(d.batch.shape.lanes);
    std::size_t global = roundUp(count_, kLanes) / lanes;
    const bool grouped = global >= 8 * d.local && roundUp(global, d.local) * lanes <= allocated_;
    if (grouped) global = roundUp(global, d.local);
    q.enqueueNDRangeKernel(d.kernel, cl::NullRange, cl::NDRange(global), grouped ? cl::NDRange(d.local) : cl::NullRange,
                           nullptr, &d.launch);
    for (int k = 6; k < 9; ++k) {
      void* p = q.enqueueMapBuffer(set_->buffers[k], CL_FALSE, CL_MAP_READ, 0, allocated_ * 4);
      q.enqueueUnmapMemObject(set_->buffers[k], p, nullptr, k == 8 ? &d.done : nullptr);
    }
    q.flush();
    running_ = true;
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating samples");
  }
}

void SoaBatch::finish() {
  if (!running_) return;
  running_ = false;
  try {
    device_->done.wait();
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating samples");
  }
}

double SoaBatch::lastKernelSeconds() const {
  if (!device_ || device_->launch() == nullptr) return 0;
  const cl::Event& launch = device_->launch;
  try {
    const auto begin = launch.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const auto end = launch.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    return double(end - begin) * 1e-9;
  } catch (const cl::Error&) {
    rethrowOpenCL("reading the kernel's profiling times");
  }
}

std::size_t Evaluator::launchLimit() const { return chunkSize(rt_, 4); }

std::vector<float> Evaluator::evaluate(const std::vector<MaterialParams>& materials, const Samples& samples) {
  const std::size_t n = samples.size();
  std::vector<float> rgb(3 * n);
  evaluate(materials, samples, rgb.data());
  return rgb;
}

std::vector<float> Evaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples) {
  return evaluateGrid(materials, samples, 0, materials.size());
}

std::vector<float> Evaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples,
                                           std::size_t firstMaterial, std::size_t materialCount) {
  checkMaterialRange(firstMaterial, materialCount, materials.size());
  std::vector<float> rgb(3 * samples.size() * materialCount);
  evaluateGrid(materials, samples, firstMaterial, materialCount, rgb.data());
  return rgb;
}

void Evaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples, float* rgb) {
  evaluateGrid(materials, samples, 0, materials.size(), rgb);
}

// The row kernel over the samples' own arrays, which checks them on the device: the host words
// the first bad row (checkSample) only when there is one.
void Evaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples,
                             std::size_t firstMaterial, std::size_t materialCount, float* rgb) {
  const std::size_t n = samples.size();
  if (n == 0 || materialCount == 0) {
    checkDirections(samples);
    return;
  }
  const std::size_t bad =
      evaluateGridRows(materials, Rows{samples.L.data(), samples.V.data(), nullptr, n}, rgb, false, firstMaterial,
                       materialCount);
  if (bad < n) {
    checkSample(samples, bad);
    throw Error(fmt::format("internal: sample {} reported as not finite", bad), 3);
  }
}

// The row kernel on the samples' own arrays: no planes, and the indices and directions are
// checked on the device; the host words the first bad sample only when there is one.
void Evaluator::evaluate(const std::vector<MaterialParams>& materials, const Samples& samples, float* rgb) {
  const std::size_t n = samples.size();
  if (samples.material.size() != n)
    throw Error(fmt::format("internal: {} material indices for {} samples", samples.material.size(), n), 3);
  if (n == 0) return;
  Rows rows{samples.L.data(), samples.V.data(), nullptr, n};
  rows.index32 = samples.material.data();
  const std::size_t bad = evaluateRows(materials, rows, rgb, false);
  if (bad == n) return;
  if (samples.material[bad] >= materials.size())
    throw Error(fmt::format("sample {}: material index {} out of range ({} materials)", bad, samples.material[bad],
                            materials.size()));
  checkSample(samples, bad);
  throw Error(fmt::format("internal: sample {} reported as bad", bad), 3);
}

}  // namespace brdfcl
