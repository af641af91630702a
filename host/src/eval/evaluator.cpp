// Batch evaluation on the device: materials are packed once, directions go to the device as
// SoA planes padded to the kernel's lane width, and batches are split to respect the device's
// maximum allocation.
#include "brdfcl/evaluator.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "model/pack.hpp"

namespace brdfcl {

namespace {
constexpr std::size_t kLanes = 16;  // BRDFCL_W of the batch kernels
constexpr std::size_t kMaxChunk = std::size_t(1) << 22;

std::size_t roundUp(std::size_t n, std::size_t m) { return (n + m - 1) / m * m; }

// Samples per launch: bounded by a fixed chunk and by the device's largest allocation.
std::size_t chunkSize(const Runtime& rt, std::size_t bytesPerSample) {
  std::size_t byAlloc = std::size_t(rt.info().maxAlloc) / bytesPerSample;
  return std::max(kLanes, std::min(kMaxChunk, byAlloc) / kLanes * kLanes);
}

std::vector<brdfcl_material> packAll(const std::vector<MaterialParams>& materials) {
  std::vector<brdfcl_material> packed;
  packed.reserve(materials.size());
  for (const auto& m : materials) packed.push_back(packMaterial(m));
  return packed;
}

// Lays samples [first, first + count) out as the 6 planes the kernels read.
void fillDirectionPlanes(const Samples& s, std::size_t first, std::size_t count, std::size_t stride,
                         std::vector<float>& planes) {
  planes.assign(6 * stride, 0.0f);  // zero padding: L = V = 0 lies below the horizon, f = 0
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

Evaluator::Evaluator(Runtime& rt, EvalOptions options) : rt_(rt), options_(options) {}

// What every launch of a batch shares: the program specialised to its feature set, the packed
// materials and the sheen albedo table (a 2x2 dummy when no material needs it).
struct Evaluator::Batch {
  cl::Program program;
  cl::Buffer materials, table;
  int tableSize = 2;
};

Evaluator::Batch Evaluator::prepare(const std::vector<MaterialParams>& materials) {
  const auto features = featuresOf(materials);
  const auto packed = packAll(materials);
  Batch b;
  std::vector<float> table(4, 0.0f);
  if (features.needsSheenAlbedo(options_)) {
    table = sheenAlbedo().values;
    b.tableSize = int(table_->width);
  }
  b.program = rt_.program("eval.cl", materialDefines(options_, features) + " -DBRDFCL_W=16");
  const auto& ctx = rt_.context();
  b.materials = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, packed.size() * sizeof(brdfcl_material),
                           const_cast<brdfcl_material*>(packed.data()));
  b.table = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, table.size() * 4, table.data());
  return b;
}

const SheenAlbedoTable& Evaluator::sheenAlbedo() {
  if (!table_)
    table_ = std::make_unique<SheenAlbedoTable>(
        cachedSheenAlbedo(rt_, options_.sheenDistribution, options_.sheenVisibility));
  return *table_;
}

std::vector<float> Evaluator::evaluate(const std::vector<MaterialParams>& materials, const Samples& samples) {
  const std::size_t n = samples.size();
  if (samples.material.size() != n)
    throw Error(fmt::format("internal: {} material indices for {} samples", samples.material.size(), n), 3);
  for (std::size_t i = 0; i < n; ++i)
    if (samples.material[i] >= materials.size())
      throw Error(fmt::format("sample {}: material index {} out of range ({} materials)", i, samples.material[i],
                              materials.size()));
  std::vector<float> rgb(3 * n);
  if (n == 0) return rgb;

  try {
    Batch b = prepare(materials);
    cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl::Buffer, cl::Buffer, int, cl::Buffer> kernel(b.program, "eval_samples");
    const auto& ctx = rt_.context();

    const std::size_t chunk = std::min(roundUp(n, kLanes), chunkSize(rt_, 6 * 4));
    cl::Buffer bDirs(ctx, CL_MEM_READ_ONLY, 6 * chunk * 4);
    cl::Buffer bIndex(ctx, CL_MEM_READ_ONLY, chunk * 4);
    cl::Buffer bOut(ctx, CL_MEM_WRITE_ONLY, 3 * chunk * 4);
    std::vector<float> planes, out(3 * chunk);
    std::vector<std::uint32_t> index(chunk);
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      const std::size_t stride = roundUp(count, kLanes);
      fillDirectionPlanes(samples, first, count, stride, planes);
      std::fill(index.begin(), index.end(), 0u);
      std::copy_n(samples.material.begin() + first, count, index.begin());
      auto& q = rt_.queue();
      q.enqueueWriteBuffer(bDirs, CL_FALSE, 0, 6 * stride * 4, planes.data());
      q.enqueueWriteBuffer(bIndex, CL_FALSE, 0, stride * 4, index.data());
      kernel(cl::EnqueueArgs(q, cl::NDRange(stride / kLanes)), bDirs, cl_uint(stride), bIndex, b.materials, b.table,
             b.tableSize, bOut);
      q.enqueueReadBuffer(bOut, CL_TRUE, 0, 3 * stride * 4, out.data());
      for (std::size_t i = 0; i < count; ++i)
        for (int c = 0; c < 3; ++c) rgb[3 * (first + i) + c] = out[c * stride + i];
    }
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating samples");
  }
  return rgb;
}

std::vector<float> Evaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples) {
  const std::size_t n = samples.size(), nm = materials.size();
  std::vector<float> rgb(3 * n * nm);
  if (n == 0 || nm == 0) return rgb;

  try {
    Batch b = prepare(materials);
    cl::KernelFunctor<cl::Buffer, cl_uint, cl::Buffer, cl_uint, cl::Buffer, int, cl::Buffer> kernel(b.program, "eval_grid");
    const auto& ctx = rt_.context();

    // Directions in chunks; within a chunk, materials in groups whose output fits one launch.
    const std::size_t chunk = std::min(roundUp(n, kLanes), chunkSize(rt_, 6 * 4));
    const std::size_t outLimit = chunkSize(rt_, 3 * 4);
    const std::size_t materialsPerLaunch = std::max<std::size_t>(1, std::min(nm, outLimit / chunk));
    cl::Buffer bDirs(ctx, CL_MEM_READ_ONLY, 6 * chunk * 4);
    cl::Buffer bOut(ctx, CL_MEM_WRITE_ONLY, 3 * chunk * materialsPerLaunch * 4);
    std::vector<float> planes, out(3 * chunk * materialsPerLaunch);
    auto& q = rt_.queue();
    for (std::size_t first = 0; first < n; first += chunk) {
      const std::size_t count = std::min(chunk, n - first);
      const std::size_t stride = roundUp(count, kLanes);
      fillDirectionPlanes(samples, first, count, stride, planes);
      q.enqueueWriteBuffer(bDirs, CL_FALSE, 0, 6 * stride * 4, planes.data());
      for (std::size_t m0 = 0; m0 < nm; m0 += materialsPerLaunch) {
        const std::size_t mc = std::min(materialsPerLaunch, nm - m0);
        kernel(cl::EnqueueArgs(q, cl::NDRange(stride / kLanes, mc)), bDirs, cl_uint(stride), b.materials,
               cl_uint(m0), b.table, b.tableSize, bOut);
        const std::size_t plane = stride * mc;
        q.enqueueReadBuffer(bOut, CL_TRUE, 0, 3 * plane * 4, out.data());
        for (std::size_t m = 0; m < mc; ++m)
          for (std::size_t i = 0; i < count; ++i)
            for (int c = 0; c < 3; ++c)
              rgb[3 * ((m0 + m) * n + first + i) + c] = out[c * plane + m * stride + i];
      }
    }
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating the material x direction grid");
  }
  return rgb;
}

}  // namespace brdfcl
