// The row paths against the bus, side by side in one run on one workload: the batch kernel alone
// (its profiling event), rows in pageable host memory in place (BRDFCL_STAGING=0) and through
// pinned, double-buffered staging (=1), rows kept in device memory (DeviceArray), and the copy
// bound: the same bytes through the same staging with no kernel.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "brdfcl/device_array.hpp"
#include "brdfcl/runtime.hpp"
#include "host/src/eval/staging.hpp"
#include "host/src/eval/workload.hpp"

namespace {

using brdfcl::DeviceArray;

// The workload's pairs as a caller holds them: (N, 3) float32 rows and int64 indices (numpy's),
// and the same rows in device memory.
struct Rows {
  std::unique_ptr<brdfcl::Runtime> rt = std::make_unique<brdfcl::Runtime>();
  std::unique_ptr<brdfcl::bench::Bench> batch;
  std::vector<float> L, V, rgb;
  std::vector<std::int64_t> index;
  std::unique_ptr<DeviceArray> dL, dV, dIndex, dRgb;

  Rows(const std::string& lobe, std::size_t n) {
    batch = std::make_unique<brdfcl::bench::Bench>(*rt, lobe, n);
    const auto& b = batch->batch();
    L.resize(3 * n);
    V.resize(3 * n);
    rgb.resize(3 * n);
    index.resize(n);
    std::vector<std::uint32_t> index32(n);
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) {
        L[3 * i + std::size_t(k)] = b.directionPlane(k)[i];
        V[3 * i + std::size_t(k)] = b.directionPlane(3 + k)[i];
      }
      index[i] = b.materialIndexPlane()[i];
      index32[i] = b.materialIndexPlane()[i];
    }
    dL = std::make_unique<DeviceArray>(*rt, DeviceArray::Type::Float32, 3 * n);
    dV = std::make_unique<DeviceArray>(*rt, DeviceArray::Type::Float32, 3 * n);
    dIndex = std::make_unique<DeviceArray>(*rt, DeviceArray::Type::UInt32, n);
    dRgb = std::make_unique<DeviceArray>(*rt, DeviceArray::Type::Float32, 3 * n);
    dL->upload(L.data(), L.size());
    dV->upload(V.data(), V.size());
    dIndex->upload(index32.data(), n);
  }
};

Rows& rows(const std::string& lobe, std::size_t n) {
  static std::unique_ptr<Rows> current;
  static std::string currentLobe;
  static std::size_t currentN = 0;
  if (!current || currentLobe != lobe || currentN != n) {
    current.reset();
    current = std::make_unique<Rows>(lobe, n);
    currentLobe = lobe;
    currentN = n;
  }
  return *current;
}

enum class Path { Kernel, InPlace, Staged, Device, CopyBound };

void BM_Transfer(benchmark::State& state, std::string lobe, Path path) {
  const std::size_t n = std::size_t(state.range(0));
  Rows& r = rows(lobe, n);
  auto& ev = r.batch->evaluator();
  const auto& materials = r.batch->workload().materials;
  brdfcl::Evaluator::Rows in;
  in.L = r.L.data();
  in.V = r.V.data();
  in.index = r.index.data();
  in.count = n;
  const char* staging = path == Path::Staged ? "1" : "0";
  ::setenv("BRDFCL_STAGING", staging, 1);
  const auto once = [&] {
    switch (path) {
      case Path::Kernel:
        r.batch->runKernel();
        return r.batch->batch().lastKernelSeconds();
      case Path::InPlace:
      case Path::Staged:
        ev.evaluateRows(materials, in, r.rgb.data(), true);
        return 0.0;
      case Path::Device:
        ev.evaluate(materials, *r.dL, *r.dV, r.dIndex.get(), *r.dRgb, true);
        return 0.0;
      case Path::CopyBound: {
        brdfcl::Staging st(*r.rt);
        for (std::size_t first = 0; first < n; first += brdfcl::kStagedRows) {
          const std::size_t c = std::min(brdfcl::kStagedRows, n - first);
          st.begin();
          st.in(0, r.L.data() + 3 * first, 12 * c);
          st.in(1, r.V.data() + 3 * first, 12 * c);
          st.in(2, r.index.data() + first, 8 * c);
          float* to = r.rgb.data() + 3 * first;
          st.out(12 * c, [to, c](const void* p) { std::memcpy(to, p, 12 * c); });
          st.end();
        }
        st.drain();
        return 0.0;
      }
    }
    return 0.0;
  };
  once();
  for (auto _ : state) {
    const double kernel = once();
    if (path == Path::Kernel) state.SetIterationTime(kernel);
  }
  ::unsetenv("BRDFCL_STAGING");
  state.SetItemsProcessed(std::int64_t(state.iterations()) * state.range(0));
  // Bytes the rows move over the bus: L and V (24), an int64 index (8), rgb (12).
  state.SetBytesProcessed(std::int64_t(state.iterations()) * state.range(0) * 44);
}

const bool registered = [] {
  const std::int64_t n = std::getenv("BRDFCL_TRANSFER_N") ? std::atoll(std::getenv("BRDFCL_TRANSFER_N")) : 1 << 24;
  for (const std::string lobe : {"all", "specular"})
    for (const auto& [name, path] : {std::pair{"kernel", Path::Kernel}, {"inplace", Path::InPlace}, {"staged", Path::Staged},
                                     {"device", Path::Device}, {"copy-bound", Path::CopyBound}}) {
      auto* b = benchmark::RegisterBenchmark(("BM_Transfer/" + lobe + "/" + name).c_str(), BM_Transfer, lobe, path)
                    ->Arg(n)
                    ->Unit(benchmark::kMillisecond);
      if (path == Path::Kernel)
        b->UseManualTime();
      else
        b->UseRealTime();
    }
  return true;
}();

}  // namespace
