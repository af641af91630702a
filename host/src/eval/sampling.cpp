// Evaluator::sample / pdf: rows checked on the host, then handed to kernels/sample.cl (sample_rows,
// pdf_rows) a launch at a time by eval/row_driver.hpp (copied, or staged on GPUs); the device-resident
// SampleBatch of the benchmarks; and the counter-based uniforms of `brdfcl sample --count --seed`.
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
#include "eval/row_driver.hpp"
#include "eval/sample_batch.hpp"
#include "eval/splitmix64.hpp"
#include "model/pack.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

namespace {

const char* finiteWord(float v) { return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"; }

void checkDirection(const float* d, std::size_t row, const char* name) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(d[k]))
      throw Error(fmt::format("row {}: {}{} is not finite: {}", row, name, "xyz"[k], finiteWord(d[k])));
}

void checkIndex(const std::uint32_t* material, std::size_t row, std::size_t count) {
  if (material && material[row] >= count)
    throw Error(fmt::format("row {}: material index {} out of range ({} materials)", row, material[row], count));
}

// The rows sample() takes: finite views, indices in range, uniforms in [0, 1).
void checkSampleRows(const float* view, const std::uint32_t* material, const float* u, std::size_t n,
                     std::size_t materialCount) {
  for (std::size_t i = 0; i < n; ++i) {
    checkDirection(view + 3 * i, i, "V");
    checkIndex(material, i, materialCount);
    for (int k = 0; k < 3; ++k)
      if (!(u[3 * i + k] >= 0.0f && u[3 * i + k] < 1.0f))
        throw Error(fmt::format("row {}: u{} must be in [0, 1), got {}", i, k + 1, u[3 * i + k]));
  }
}

// What the sampling kernels read: the program for the batch's options and features, the packed
// materials, f's tables and the sheen albedo table the lobe probabilities look up.
struct SamplingBatch {
  cl::Program program;
  cl::Buffer materials, table, albedo;
  int tableSize = 2, albedoSize = 2;
  int lanes = 1;  // rows a work-item (BRDFCL_W)
};

// sample_rows' arguments (and its tail's): rows of V, index (null: material 0) and U in, `result` out.
void setSampleArgs(RowDriver& run, const cl::Buffer& V, const cl::Buffer& index, const cl::Buffer& U,
                   std::size_t n, const SamplingBatch& s, const cl::Buffer& result) {
  run.args(V, index, U, cl_uint(n), s.materials, s.table, s.tableSize, s.albedo, s.albedoSize, result);
}

}  // namespace

void Evaluator::drawUniforms(std::uint64_t seed, std::uint64_t firstRow, std::size_t rows, float* u) {
  for (std::size_t i = 0; i < 3 * rows; ++i) {
    detail::SplitMix64 g{seed + (3 * firstRow + i) * 0x9e3779b97f4a7c15ull};
    u[i] = g.uniformFloat();
  }
}

namespace {
// The kernels of sample.cl a program holds (BRDFCL_SAMPLER_KERNELS): sampling and the pdf each
// build their own, so a process loads and the device parses only the one it launches.
constexpr unsigned kSampleKernels = 1, kPdfKernels = 2;

// The sheen albedo table is the evaluator's where a material has sheen (or the draft), else a 2x2 dummy.
SamplingBatch makeSamplingBatch(Runtime& rt, Evaluator& ev, const std::vector<MaterialParams>& materials,
                                const std::vector<brdfcl_material>& packed, const std::vector<float>& table,
                                int tableSize, unsigned kernels) {
  const EvalOptions& options = ev.options();
  const FeatureSet features = featuresOf(materials, options.profile);
  const SheenAlbedoTable* albedo = features.sheen || features.draft ? &ev.sheenAlbedo() : nullptr;
  SamplingBatch s;
  s.tableSize = tableSize;
  const std::vector<float> dummy(4, 0.0f);
  const std::vector<float>& e = albedo ? albedo->values : dummy;
  s.albedoSize = albedo ? int(albedo->width) : 2;
  try {
    s.lanes = laneShape(rt.info()).lanes;
    s.program = rt.opencl().program("sample.cl", materialDefines(options, features) +
                                                     fmt::format(" -DBRDFCL_W={}", s.lanes) +
                                                     (materials.size() == 1 ? " -DBRDFCL_ONE_MATERIAL=1" : "") +
                                                     fmt::format(" -DBRDFCL_SAMPLER_KERNELS={}", kernels));
    const auto& ctx = rt.opencl().context();
    s.materials = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, packed.size() * sizeof(brdfcl_material),
                             const_cast<brdfcl_material*>(packed.data()));
    s.table = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, table.size() * 4, const_cast<float*>(table.data()));
    s.albedo = cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, e.size() * 4, const_cast<float*>(e.data()));
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing the samplers");
  }
  return s;
}

// The sampling kernel `name` over host rows, copied where they are not staged.
RowDriver rowDriver(Runtime& rt, const SamplingBatch& s, const char* name) {
  return RowDriver(rt, s.program, name, LaneShape{s.lanes, 0}, RowDriver::Rows::Copied);
}
}  // namespace

void Evaluator::sample(const std::vector<MaterialParams>& materials, const std::uint32_t* material, const float* view,
                       const float* u, std::size_t count, float* out) {
  Batch b = prepare(materials, Kernels::None);
  checkSampleRows(view, material, u, count, materials.size());
  if (count == 0) return;
  const SamplingBatch s = makeSamplingBatch(rt_, *this, materials, b.packed, b.table, b.tableSize, kSampleKernels);
  try {
    RowDriver run = rowDriver(rt_, s, "sample_rows");
    run.run(count, run.rowsPerLaunch(launchLimit(), 0, 28, 1), {{view, 12}, {u, 12}, {material, 4}}, out, 28,
            [&](std::size_t, std::size_t n, const std::vector<Wrapped>& in, const Wrapped& result) {
              setSampleArgs(run, in[0].buffer, in[2].buffer, in[1].buffer, n, s, result.buffer);
            });
    run.finish();
  } catch (const cl::Error&) {
    rethrowOpenCL("sampling directions");
  }
}

std::vector<float> Evaluator::sample(const std::vector<MaterialParams>& materials,
                                     const std::vector<std::uint32_t>& material, const std::vector<float>& view,
                                     const std::vector<float>& u) {
  const std::size_t n = view.size() / 3;
  if (view.size() % 3 || u.size() != 3 * n || (!material.empty() && material.size() != n))
    throw Error(fmt::format("internal: {} view floats, {} uniforms, {} indices", view.size(), u.size(), material.size()), 3);
  std::vector<float> out(7 * n);
  sample(materials, material.empty() ? nullptr : material.data(), view.data(), u.data(), n, out.data());
  return out;
}

void Evaluator::pdf(const std::vector<MaterialParams>& materials, const Samples& samples, float* pdf) {
  Batch b = prepare(materials, Kernels::None);
  const std::size_t count = samples.size();
  const std::uint32_t* material = samples.material.empty() ? nullptr : samples.material.data();
  if (material && samples.material.size() != count)
    throw Error(fmt::format("internal: {} material indices for {} samples", samples.material.size(), count), 3);
  for (std::size_t i = 0; i < count; ++i) {
    checkDirection(samples.L.data() + 3 * i, i, "L");
    checkDirection(samples.V.data() + 3 * i, i, "V");
    checkIndex(material, i, materials.size());
  }
  if (count == 0) return;
  const SamplingBatch s = makeSamplingBatch(rt_, *this, materials, b.packed, b.table, b.tableSize, kPdfKernels);
  try {
    RowDriver run = rowDriver(rt_, s, "pdf_rows");
    run.run(count, run.rowsPerLaunch(launchLimit(), 0, 12, 1),
            {{samples.L.data(), 12}, {samples.V.data(), 12}, {material, 4}}, pdf, 4,
            [&](std::size_t, std::size_t n, const std::vector<Wrapped>& in, const Wrapped& result) {
              run.args(in[0].buffer, in[1].buffer, in[2].buffer, cl_uint(n), s.materials, s.albedo, s.albedoSize,
                       result.buffer);
            });
    run.finish();
  } catch (const cl::Error&) {
    rethrowOpenCL("evaluating sampling densities");
  }
}

std::vector<float> Evaluator::pdf(const std::vector<MaterialParams>& materials, const Samples& samples) {
  std::vector<float> out(samples.size());
  pdf(materials, samples, out.data());
  return out;
}

struct SampleBatch::State {
  Runtime* rt = nullptr;
  SamplingBatch s;
  std::size_t n = 0;
  cl::Buffer view, index, u, result;
  std::unique_ptr<RowDriver> run;  // after the buffers its kernels use: it goes first
  cl::Event launch, tailLaunch;
};

SampleBatch::SampleBatch(Runtime& rt, Evaluator& ev, const std::vector<MaterialParams>& materials,
                         const std::vector<float>& view, const std::vector<std::uint32_t>& material,
                         const std::vector<float>& u)
    : s_(std::make_unique<State>()) {
  const std::size_t n = view.size() / 3;
  if (view.size() % 3 || u.size() != 3 * n || (!material.empty() && material.size() != n) || n == 0)
    throw Error(fmt::format("internal: {} view floats, {} uniforms, {} indices", view.size(), u.size(), material.size()), 3);
  // The packed materials and f's tables, as a batch of the evaluator holds them (checked there).
  const SoaBatch b(ev, materials, 16);
  checkSampleRows(view.data(), material.empty() ? nullptr : material.data(), u.data(), n, materials.size());
  if (n > ev.launchLimit())
    throw Error(fmt::format("internal: {} sampling rows exceed one launch ({} at most on this device)", n, ev.launchLimit()), 3);
  s_->rt = &rt;
  s_->n = n;
  s_->s = makeSamplingBatch(rt, ev, materials, b.packedMaterials(), b.sheenAlbedoValues(), b.sheenAlbedoSize(),
                             kSampleKernels);
  try {
    const auto& ctx = rt.opencl().context();
    s_->view = deviceCopy(ctx, view.data(), 4 * view.size());
    s_->u = deviceCopy(ctx, u.data(), 4 * u.size());
    s_->index = deviceCopy(ctx, material.data(), 4 * material.size());
    s_->result = cl::Buffer(ctx, CL_MEM_READ_WRITE, 28 * n);
    s_->run = std::make_unique<RowDriver>(rt, s_->s.program, "sample_rows", LaneShape{s_->s.lanes, 0},
                                          RowDriver::Rows::Device);
    setSampleArgs(*s_->run, s_->view, material.empty() ? cl::Buffer() : s_->index, s_->u, n, s_->s, s_->result);
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing the sampling batch");
  }
}

SampleBatch::~SampleBatch() = default;

std::size_t SampleBatch::size() const { return s_->n; }

void SampleBatch::run() {
  try {
    s_->launch = cl::Event();
    s_->tailLaunch = cl::Event();
    s_->run->launch(s_->n, 0, &s_->launch, &s_->tailLaunch);
    s_->run->finish();
  } catch (const cl::Error&) {
    rethrowOpenCL("sampling directions");
  }
}

double SampleBatch::lastKernelSeconds() const {
  // The whole groups' launch and the tail's, either of which may be absent.
  try {
    double seconds = 0;
    for (const cl::Event* e : {&s_->launch, &s_->tailLaunch}) {
      if ((*e)() == nullptr) continue;
      seconds += double(e->getProfilingInfo<CL_PROFILING_COMMAND_END>() - e->getProfilingInfo<CL_PROFILING_COMMAND_START>()) * 1e-9;
    }
    return seconds;
  } catch (const cl::Error&) {
    rethrowOpenCL("reading the kernel's profiling times");
  }
}

std::vector<float> SampleBatch::read() const {
  std::vector<float> out(7 * s_->n);
  try {
    s_->rt->opencl().queue().enqueueReadBuffer(s_->result, CL_TRUE, 0, 28 * s_->n, out.data());
  } catch (const cl::Error&) {
    rethrowOpenCL("reading the sampled rows");
  }
  return out;
}

}  // namespace brdfcl
