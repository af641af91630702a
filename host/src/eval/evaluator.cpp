// Batch evaluation on the device. Materials are packed once per batch; samples travel as SoA
// planes in page-aligned host memory the device uses in place (SoaBatch); batches larger than a
// chunk (or than the device's largest allocation) run chunk by chunk through one SoaBatch.
#include "brdfcl/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "model/pack.hpp"
#include "parity/engine_tables.hpp"

namespace brdfcl {

namespace {
constexpr std::size_t kLanes = SoaBatch::kLanes;
constexpr std::size_t kMaxChunk = std::size_t(1) << 22;
constexpr std::size_t kPage = 4096;

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
  const bool representable = count <= (SIZE_MAX - kPage) / sizeof(T);
  const std::size_t bytes = representable ? roundUp(std::max<std::size_t>(count * sizeof(T), 1), kPage) : 0;
  void* p = representable ? std::aligned_alloc(kPage, bytes) : nullptr;
  if (!p)
    throw Error(fmt::format("out of host memory allocating {:.0f} MiB for a batch",
                            std::ceil(double(count) * sizeof(T) / double(1 << 20))));
  std::memset(p, 0, bytes);  // zero directions lie below the horizon: padding lanes give f = 0
  return static_cast<T*>(p);
}

// NaN or an infinity in a direction would come back as NaN f: the file readers reject them,
// and so does the library for directions built in memory.
void checkDirections(const Samples& s) {
  static const char* const kNames[6] = {"Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int k = 0; k < 6; ++k) {
      const float v = k < 3 ? s.L[3 * i + k] : s.V[3 * i + k - 3];
      if (!std::isfinite(v))
        throw Error(fmt::format("sample {}: {} is not finite: {}", i, kNames[k], std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"));
    }
}

// Lays samples [first, first + count) out as the 6 planes the kernels read.
void fillDirectionPlanes(const Samples& s, std::size_t first, std::size_t count, std::size_t stride, float* planes) {
  for (std::size_t i = 0; i < count; ++i) {
    const float* L = &s.L[3 * (first + i)];
    const float* V = &s.V[3 * (first + i)];
    for (int c = 0; c < 3; ++c) {
      planes[c * stride + i] = L[c];
      planes[(3 + c) * stride + i] = V[c];
    }
  }
}
}  // namespace

Evaluator::Evaluator(Runtime& rt, EvalOptions options) : rt_(rt), options_(options) { checkProfileOptions(options); }

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

// What every launch of a batch shares: the program specialised to its feature set, the packed
// materials and the sheen albedo table (a 2x2 dummy when no material needs it).
struct Evaluator::Batch {
  LaneShape shape;  // the device's lane width and work-group size (runtime.hpp)
  cl::Program program;
  std::vector<brdfcl_material> packed;
  std::vector<float> table = std::vector<float>(4, 0.0f);
  int tableSize = 2;
  cl::Buffer materials, tableBuffer;
};

Evaluator::Batch Evaluator::prepare(const std::vector<MaterialParams>& materials) {
  if (materials.empty()) throw Error("no materials to evaluate");
  for (std::size_t i = 0; i < materials.size(); ++i) checkMaterial(materials[i], i);
  const auto features = featuresOf(materials);
  Batch b;
  for (const auto& m : materials) b.packed.push_back(packMaterial(m, options_.profile));
  if (features.needsSheenAlbedo(options_)) {
    const SheenAlbedoTable& table = sheenAlbedo();
    b.table = table.values;
    b.tableSize = int(table.width);
  }
  // Engine profiles read three.js's DFG table right after the E table (docs/profiles.md).
  if (options_.profile != Profile::Spec) {
    const auto& dfg = threejsDfgTable();
    b.table.insert(b.table.end(), dfg.begin(), dfg.end());
  }
  b.shape = laneShape(rt_.info());
  try {
    b.program = rt_.program("eval.cl", materialDefines(options_, features) + fmt::format(" -DBRDFCL_W={}", b.shape.lanes));
    const auto& ctx = rt_.context();
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
  cl::Buffer planes[9], index;
  cl::Kernel kernel;
  std::size_t local = 1;  // work-group size used when a launch is large enough
};

SoaBatch::SoaBatch(Evaluator& evaluator, const std::vector<MaterialParams>& materials, std::size_t capacity)
    : ev_(evaluator), capacity_(roundUp(std::max<std::size_t>(capacity, 1), kLanes)), count_(capacity) {
  if (capacity > SIZE_MAX / 2)  // rounding up would wrap round: no such batch fits in memory
    throw Error(fmt::format("out of host memory allocating {:.0f} MiB for a batch", double(capacity) * 4 / double(1 << 20)));
  device_ = std::make_unique<Device>();
  device_->batch = ev_.prepare(materials);
  packed_ = device_->batch.packed;
  tableValues_ = device_->batch.table;
  tableSize_ = device_->batch.tableSize;
  try {
    auto& d = *device_;
    d.kernel = cl::Kernel(d.batch.program, "eval_samples");
    d.local = groupSizeFor(d.batch.shape, d.kernel, ev_.rt_.device());
  } catch (const cl::Error&) {
    rethrowOpenCL("creating the batch kernel");
  }
  // Planes are padded (with zeros: f = 0) to whole work-groups, so a launch rounded up to the
  // work-group size never reads past them. A constructor that throws runs no destructor, so a
  // failure part-way frees what was already allocated.
  allocated_ = roundUp(capacity_, kLanes * device_->local);
  try {
    for (auto& p : planes_) p = allocPages<float>(allocated_);
    index_ = allocPages<std::uint32_t>(allocated_);
  } catch (...) {
    release();
    throw;
  }
  try {
    const auto& ctx = ev_.rt_.context();
    auto& d = *device_;
    for (int k = 0; k < 9; ++k)
      d.planes[k] = cl::Buffer(ctx, (k < 6 ? CL_MEM_READ_ONLY : CL_MEM_WRITE_ONLY) | CL_MEM_USE_HOST_PTR,
                               allocated_ * 4, planes_[k]);
    d.index = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, allocated_ * 4, index_);
    int arg = 0;
    for (int k = 0; k < 6; ++k) d.kernel.setArg(arg++, d.planes[k]);
    d.kernel.setArg(arg++, d.index);
    d.kernel.setArg(arg++, d.batch.materials);
    d.kernel.setArg(arg++, d.batch.tableBuffer);
    d.kernel.setArg(arg++, d.batch.tableSize);
    for (int k = 6; k < 9; ++k) d.kernel.setArg(arg++, d.planes[k]);
  } catch (const cl::Error&) {
    release();
    rethrowOpenCL("allocating a sample batch");
  }
}

SoaBatch::~SoaBatch() { release(); }

void SoaBatch::release() {
  device_.reset();  // release the buffers before the memory they wrap
  for (auto*& p : planes_) {
    std::free(p);
    p = nullptr;
  }
  std::free(index_);
  index_ = nullptr;
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
  if (count_ == 0) return;
  auto& q = ev_.rt_.queue();
  auto& d = *device_;
  try {
    if (inputsChanged_) {
      // A write map/unmap hands the host's writes to a device that caches USE_HOST_PTR memory
      // (a GPU); on a CPU device both calls are free.
      for (int k = 0; k < 7; ++k) {
        cl::Buffer& b = k < 6 ? d.planes[k] : d.index;
        void* p = q.enqueueMapBuffer(b, CL_TRUE, CL_MAP_WRITE, 0, allocated_ * 4);
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
    q.enqueueNDRangeKernel(d.kernel, cl::NullRange, cl::NDRange(global), grouped ? cl::NDRange(d.local) : cl::NullRange);
    for (int k = 6; k < 9; ++k) {
      void* p = q.enqueueMapBuffer(d.planes[k], CL_TRUE, CL_MAP_READ, 0, allocated_ * 4);
      q.enqueueUnmapMemObject(d.planes[k], p);
    }
    q.finish();
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating samples");
  }
}

std::size_t Evaluator::launchLimit() const { return chunkSize(rt_, 4); }

std::vector<float> Evaluator::evaluate(const std::vector<MaterialParams>& materials, const Samples& samples) {
  const std::size_t n = samples.size();
  std::vector<float> rgb(3 * n);
  if (n == 0) return rgb;
  SoaBatch batch(*this, materials, std::min(roundUp(n, kLanes), launchLimit()));
  batch.evaluate(samples, rgb.data());
  return rgb;
}

void SoaBatch::evaluate(const Samples& samples, float* rgb) {
  const std::size_t n = samples.size();
  if (samples.material.size() != n)
    throw Error(fmt::format("internal: {} material indices for {} samples", samples.material.size(), n), 3);
  for (std::size_t i = 0; i < n; ++i)
    if (samples.material[i] >= packed_.size())
      throw Error(fmt::format("sample {}: material index {} out of range ({} materials)", i, samples.material[i],
                              packed_.size()));
  checkDirections(samples);
  const std::size_t chunk = capacity();
  for (std::size_t first = 0; first < n; first += chunk) {
    const std::size_t count = std::min(chunk, n - first);
    float* planes[6];
    for (int k = 0; k < 6; ++k) planes[k] = direction(k);
    std::uint32_t* index = materialIndex();
    // Clear what a previous, longer run left behind past `count` (padding lanes give f = 0).
    if (count < chunk) {
      for (auto* p : planes) std::fill(p + count, p + chunk, 0.0f);
      std::fill(index + count, index + chunk, 0u);
    }
    for (std::size_t i = 0; i < count; ++i) {
      for (int c = 0; c < 3; ++c) {
        planes[c][i] = samples.L[3 * (first + i) + c];
        planes[3 + c][i] = samples.V[3 * (first + i) + c];
      }
      index[i] = samples.material[first + i];
    }
    setCount(count);
    run();
    for (int c = 0; c < 3; ++c) {
      const float* plane = result(c);
      for (std::size_t i = 0; i < count; ++i) rgb[3 * (first + i) + c] = plane[i];
    }
  }
}

std::vector<float> Evaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples) {
  return evaluateGrid(materials, samples, 0, materials.size());
}

std::vector<float> Evaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples,
                                           std::size_t firstMaterial, std::size_t materialCount) {
  if (firstMaterial > materials.size() || materialCount > materials.size() - firstMaterial)
    throw Error(fmt::format("internal: materials [{}, {}) of {}", firstMaterial, firstMaterial + materialCount,
                            materials.size()), 3);
  const std::size_t n = samples.size(), nm = materialCount;
  checkDirections(samples);
  std::vector<float> rgb(3 * n * nm);
  if (n == 0 || nm == 0) return rgb;

  try {
    Batch b = prepare(materials);
    cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_uint, cl::Buffer, int, cl::Buffer> kernel(b.program,
                                                                                                  "eval_grid");
    const auto& ctx = rt_.context();
    // Directions in chunks; within a chunk, materials in groups whose output fits one launch.
    const std::size_t chunk = std::min(roundUp(n, kLanes), chunkSize(rt_, 6 * 4));
    const std::size_t outLimit = chunkSize(rt_, 3 * 4);
    const std::size_t materialsPerLaunch = std::max<std::size_t>(1, std::min(nm, outLimit / chunk));
    cl::Buffer bDirs(ctx, CL_MEM_READ_ONLY, 6 * chunk * 4);
    cl::Buffer bOut(ctx, CL_MEM_WRITE_ONLY, 3 * chunk * materialsPerLaunch * 4);
    std::vector<float> planes(6 * chunk), out(3 * chunk * materialsPerLaunch);
    auto& q = rt_.queue();
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      const std::size_t stride = roundUp(count, kLanes);
      std::fill(planes.begin(), planes.end(), 0.0f);
      fillDirectionPlanes(samples, first, count, stride, planes.data());
      q.enqueueWriteBuffer(bDirs, CL_FALSE, 0, 6 * stride * 4, planes.data());
      for (std::size_t m0 = 0; m0 < nm; m0 += materialsPerLaunch) {
        const std::size_t mc = std::min(materialsPerLaunch, nm - m0);
        kernel(cl::EnqueueArgs(q, cl::NDRange(stride / std::size_t(b.shape.lanes), mc)), bDirs, cl_uint(stride), b.materials,
               cl_uint(firstMaterial + m0), b.tableBuffer, b.tableSize, bOut);
        const std::size_t plane = stride * mc;
        q.enqueueReadBuffer(bOut, CL_TRUE, 0, 3 * plane * 4, out.data());
        for (std::size_t m = 0; m < mc; ++m)
          for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < 3; ++c) rgb[3 * ((m0 + m) * n + first + i) + c] = out[c * plane + m * stride + i];
      }
    }
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating the material x direction grid");
  }
  return rgb;
}

}  // namespace brdfcl
