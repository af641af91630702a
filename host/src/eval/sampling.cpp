// Evaluator::sample / pdf: rows checked on the host, then handed to kernels/sample.cl (sample_rows,
// pdf_rows) a launch at a time; and the counter-based uniforms of `brdfcl sample --count --seed`.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "eval/batch.hpp"
#include "eval/sample_batch.hpp"
#include "eval/splitmix64.hpp"
#include "eval/staging.hpp"
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

// What the sampling kernels read: the program for the batch's options and features, the packed
// materials, f's tables and the sheen albedo table the lobe probabilities look up.
struct SamplingBatch {
  cl::Program program;
  cl::Buffer materials, table, albedo;
  int tableSize = 2, albedoSize = 2;
  int lanes = 1;  // rows a work-item (BRDFCL_W)
};

// One launch of rows: the whole groups of `lanes` rows (a work-item each), then the partial group.
void launchRows(cl::CommandQueue& q, cl::Kernel& whole, cl::Kernel& tail, std::size_t n, int lanes,
                cl::Event* wholeDone = nullptr, cl::Event* tailDone = nullptr) {
  const std::size_t groups = n / std::size_t(lanes);
  if (groups > 0) q.enqueueNDRangeKernel(whole, cl::NullRange, cl::NDRange(groups), cl::NullRange, nullptr, wholeDone);
  if (n % std::size_t(lanes)) q.enqueueNDRangeKernel(tail, cl::NullRange, cl::NDRange(1), cl::NullRange, nullptr, tailDone);
}

}  // namespace

void Evaluator::drawUniforms(std::uint64_t seed, std::uint64_t firstRow, std::size_t rows, float* u) {
  for (std::size_t i = 0; i < 3 * rows; ++i) {
    detail::SplitMix64 g{seed + (3 * firstRow + i) * 0x9e3779b97f4a7c15ull};
    u[i] = g.uniformFloat();
  }
}

namespace {
SamplingBatch makeSamplingBatch(Runtime& rt, const EvalOptions& options, const std::vector<MaterialParams>& materials,
                                const std::vector<brdfcl_material>& packed, const std::vector<float>& table,
                                int tableSize, const SheenAlbedoTable* albedo) {
  SamplingBatch s;
  s.tableSize = tableSize;
  const std::vector<float> dummy(4, 0.0f);
  const std::vector<float>& e = albedo ? albedo->values : dummy;
  s.albedoSize = albedo ? int(albedo->width) : 2;
  try {
    s.lanes = laneShape(rt.info()).lanes;
    s.program = rt.opencl().program("sample.cl", materialDefines(options, featuresOf(materials, options.profile)) +
                                                     fmt::format(" -DBRDFCL_W={}", s.lanes) +
                                                     (materials.size() == 1 ? " -DBRDFCL_ONE_MATERIAL=1" : ""));
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

// A read-only device copy of n elements of T (a 1-element dummy for none).
template <class T>
cl::Buffer input(const cl::Context& ctx, const T* p, std::size_t n) {
  static const T zero[1] = {};
  return cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, std::max<std::size_t>(n, 1) * sizeof(T),
                    const_cast<T*>(p ? p : zero));
}
}  // namespace

void Evaluator::sample(const std::vector<MaterialParams>& materials, const std::uint32_t* material, const float* view,
                       const float* u, std::size_t count, float* out) {
  Batch b = prepare(materials);
  for (std::size_t i = 0; i < count; ++i) {
    checkDirection(view + 3 * i, i, "V");
    checkIndex(material, i, materials.size());
    for (int k = 0; k < 3; ++k)
      if (!(u[3 * i + k] >= 0.0f && u[3 * i + k] < 1.0f))
        throw Error(fmt::format("row {}: u{} must be in [0, 1), got {}", i, k + 1, u[3 * i + k]));
  }
  if (count == 0) return;
  const FeatureSet features = featuresOf(materials, options_.profile);
  const SamplingBatch s = makeSamplingBatch(rt_, options_, materials, b.packed, b.table, b.tableSize,
                                            features.sheen || features.draft ? &sheenAlbedo() : nullptr);
  const bool staged = stagesRows(rt_);
  const std::size_t chunk = std::max<std::size_t>(
      1, std::min({launchLimit(), std::size_t(rt_.info().maxAlloc) / 28, staged ? kStagedRows : SIZE_MAX}));
  try {
    cl::Kernel kernel(s.program, "sample_rows"), tail(s.program, "sample_rows_tail");
    const auto setArgs = [&](const cl::Buffer& V, const cl::Buffer& index, const cl::Buffer& U, std::size_t n,
                             const cl::Buffer& result) {
      for (cl::Kernel* k : {&kernel, &tail}) {
        int arg = 0;
        k->setArg(arg++, V);
        if (material)
          k->setArg(arg++, index);
        else
          k->setArg(arg++, sizeof(cl_mem), nullptr);
        k->setArg(arg++, U);
        k->setArg(arg++, cl_uint(n));
        k->setArg(arg++, s.materials);
        k->setArg(arg++, s.table);
        k->setArg(arg++, s.tableSize);
        k->setArg(arg++, s.albedo);
        k->setArg(arg++, s.albedoSize);
        k->setArg(arg++, result);
      }
    };
    if (staged) {
      // Pinned, double-buffered copies (eval/staging.hpp): one chunk's copies overlap the other's launch.
      Staging st(rt_);
      for (std::size_t first = 0; first < count; first += chunk) {
        const std::size_t n = std::min(chunk, count - first);
        st.begin();
        const cl::Buffer V = st.in(0, view + 3 * first, 12 * n);
        const cl::Buffer U = st.in(1, u + 3 * first, 12 * n);
        const cl::Buffer index = material ? st.in(2, material + first, 4 * n) : cl::Buffer();
        float* to = out + 7 * first;
        setArgs(V, index, U, n, st.out(28 * n, [to, n](const void* p) { copySpans({{to, p, 28 * n}}); }));
        launchRows(st.queue(), kernel, tail, n, s.lanes);
        st.end();
      }
      st.drain();
      return;
    }
    auto& q = rt_.opencl().queue();
    const auto& ctx = rt_.opencl().context();
    for (std::size_t first = 0; first < count; first += chunk) {
      const std::size_t n = std::min(chunk, count - first);
      cl::Buffer V = input(ctx, view + 3 * first, 3 * n), U = input(ctx, u + 3 * first, 3 * n);
      cl::Buffer index = input(ctx, material ? material + first : nullptr, material ? n : 0);
      cl::Buffer result(ctx, CL_MEM_WRITE_ONLY, 28 * n);
      setArgs(V, index, U, n, result);
      launchRows(q, kernel, tail, n, s.lanes);
      q.enqueueReadBuffer(result, CL_TRUE, 0, 28 * n, out + 7 * first);
    }
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
  Batch b = prepare(materials);
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
  const FeatureSet features = featuresOf(materials, options_.profile);
  const SamplingBatch s = makeSamplingBatch(rt_, options_, materials, b.packed, b.table, b.tableSize,
                                            features.sheen || features.draft ? &sheenAlbedo() : nullptr);
  const bool staged = stagesRows(rt_);
  const std::size_t chunk = std::max<std::size_t>(
      1, std::min({launchLimit(), std::size_t(rt_.info().maxAlloc) / 12, staged ? kStagedRows : SIZE_MAX}));
  try {
    cl::Kernel kernel(s.program, "pdf_rows"), tail(s.program, "pdf_rows_tail");
    const auto setArgs = [&](const cl::Buffer& L, const cl::Buffer& V, const cl::Buffer& index, std::size_t n,
                             const cl::Buffer& result) {
      for (cl::Kernel* k : {&kernel, &tail}) {
        int arg = 0;
        k->setArg(arg++, L);
        k->setArg(arg++, V);
        if (material)
          k->setArg(arg++, index);
        else
          k->setArg(arg++, sizeof(cl_mem), nullptr);
        k->setArg(arg++, cl_uint(n));
        k->setArg(arg++, s.materials);
        k->setArg(arg++, s.albedo);
        k->setArg(arg++, s.albedoSize);
        k->setArg(arg++, result);
      }
    };
    if (staged) {
      Staging st(rt_);
      for (std::size_t first = 0; first < count; first += chunk) {
        const std::size_t n = std::min(chunk, count - first);
        st.begin();
        const cl::Buffer L = st.in(0, samples.L.data() + 3 * first, 12 * n);
        const cl::Buffer V = st.in(1, samples.V.data() + 3 * first, 12 * n);
        const cl::Buffer index = material ? st.in(2, material + first, 4 * n) : cl::Buffer();
        float* to = pdf + first;
        setArgs(L, V, index, n, st.out(4 * n, [to, n](const void* p) { copySpans({{to, p, 4 * n}}); }));
        launchRows(st.queue(), kernel, tail, n, s.lanes);
        st.end();
      }
      st.drain();
      return;
    }
    auto& q = rt_.opencl().queue();
    const auto& ctx = rt_.opencl().context();
    for (std::size_t first = 0; first < count; first += chunk) {
      const std::size_t n = std::min(chunk, count - first);
      cl::Buffer L = input(ctx, samples.L.data() + 3 * first, 3 * n), V = input(ctx, samples.V.data() + 3 * first, 3 * n);
      cl::Buffer index = input(ctx, material ? material + first : nullptr, material ? n : 0);
      cl::Buffer result(ctx, CL_MEM_WRITE_ONLY, 4 * n);
      setArgs(L, V, index, n, result);
      launchRows(q, kernel, tail, n, s.lanes);
      q.enqueueReadBuffer(result, CL_TRUE, 0, 4 * n, pdf + first);
    }
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
  cl::Kernel kernel, tail;
  cl::Buffer view, index, u, result;
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
  for (std::size_t i = 0; i < n; ++i) {
    checkDirection(view.data() + 3 * i, i, "V");
    checkIndex(material.empty() ? nullptr : material.data(), i, materials.size());
    for (int k = 0; k < 3; ++k)
      if (!(u[3 * i + k] >= 0.0f && u[3 * i + k] < 1.0f))
        throw Error(fmt::format("row {}: u{} must be in [0, 1), got {}", i, k + 1, u[3 * i + k]));
  }
  if (n > ev.launchLimit())
    throw Error(fmt::format("internal: {} sampling rows exceed one launch ({} at most on this device)", n, ev.launchLimit()), 3);
  const FeatureSet features = featuresOf(materials, ev.options().profile);
  s_->rt = &rt;
  s_->n = n;
  s_->s = makeSamplingBatch(rt, ev.options(), materials, b.packedMaterials(), b.sheenAlbedoValues(),
                            b.sheenAlbedoSize(), features.sheen || features.draft ? &ev.sheenAlbedo() : nullptr);
  try {
    const auto& ctx = rt.opencl().context();
    s_->view = input(ctx, view.data(), view.size());
    s_->u = input(ctx, u.data(), u.size());
    s_->index = input(ctx, material.empty() ? nullptr : material.data(), material.size());
    s_->result = cl::Buffer(ctx, CL_MEM_READ_WRITE, 28 * n);
    s_->kernel = cl::Kernel(s_->s.program, "sample_rows");
    s_->tail = cl::Kernel(s_->s.program, "sample_rows_tail");
    for (cl::Kernel* k : {&s_->kernel, &s_->tail}) {
      int arg = 0;
      k->setArg(arg++, s_->view);
      if (!material.empty())
        k->setArg(arg++, s_->index);
      else
        k->setArg(arg++, sizeof(cl_mem), nullptr);
      k->setArg(arg++, s_->u);
      k->setArg(arg++, cl_uint(n));
      k->setArg(arg++, s_->s.materials);
      k->setArg(arg++, s_->s.table);
      k->setArg(arg++, s_->s.tableSize);
      k->setArg(arg++, s_->s.albedo);
      k->setArg(arg++, s_->s.albedoSize);
      k->setArg(arg++, s_->result);
    }
  } catch (const cl::Error&) {
    rethrowOpenCL("preparing the sampling batch");
  }
}

SampleBatch::~SampleBatch() = default;

std::size_t SampleBatch::size() const { return s_->n; }

void SampleBatch::run() {
  try {
    auto& q = s_->rt->opencl().queue();
    s_->launch = cl::Event();
    s_->tailLaunch = cl::Event();
    launchRows(q, s_->kernel, s_->tail, s_->n, s_->s.lanes, &s_->launch, &s_->tailLaunch);
    q.finish();
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
