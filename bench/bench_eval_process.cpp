// `brdfcl eval` timed as a whole process, file to file, beside the batch kernel on the very same
// samples and materials in the same run: a float32 NPY of N rows in the page
// cache to a fresh NPY, and the same rows as CSV to CSV.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "brdfcl/runtime.hpp"
#include "tests/unit/process.hpp"
#include "host/src/eval/workload.hpp"
#include "host/src/io/output.hpp"

namespace fs = std::filesystem;

namespace {

// One workload's batch (kept for the kernel row) and its samples written out as the CLI reads them.
struct Files {
  brdfcl::test::ScratchDir dir{"bench-eval-process"};
  std::unique_ptr<brdfcl::Runtime> rt = std::make_unique<brdfcl::Runtime>();
  std::unique_ptr<brdfcl::bench::Bench> batch;
  std::string materials, samples;
  int outputs = 0;

  Files(std::size_t n, bool csv) {
    batch = std::make_unique<brdfcl::bench::Bench>(*rt, "all", n);
    materials = dir.path("materials.json");
    std::ofstream m(materials);
    m << "{\"materials\": [";
    const auto& ms = batch->workload().materials;
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const auto& p = ms[i];
      m << (i ? ",\n" : "\n")
        << fmt::format(
               R"({{"pbrMetallicRoughness": {{"baseColorFactor": [{:.9g}, {:.9g}, {:.9g}, 1], "metallicFactor": {:.9g}, )"
               R"("roughnessFactor": {:.9g}}}, "extensions": {{"KHR_materials_sheen": {{"sheenColorFactor": [{:.9g}, {:.9g}, {:.9g}], )"
               R"("sheenRoughnessFactor": {:.9g}}}, "KHR_materials_clearcoat": {{"clearcoatFactor": {:.9g}, )"
               R"("clearcoatRoughnessFactor": {:.9g}}}, "KHR_materials_anisotropy": {{"anisotropyStrength": {:.9g}, )"
               R"("anisotropyRotation": {:.9g}}}}}}})",
               p.baseColor[0], p.baseColor[1], p.baseColor[2], p.metallic, p.roughness, p.sheenColor[0],
               p.sheenColor[1], p.sheenColor[2], p.sheenRoughness, p.clearcoat, p.clearcoatRoughness,
               p.anisotropyStrength, p.anisotropyRotation);
    }
    m << "]}\n";
    samples = dir.path(csv ? "samples.csv" : "samples.npy");
    const auto& b = batch->batch();
    std::ofstream f(samples, std::ios::binary);
    if (csv) {
      f << "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
      char line[200];
      for (std::size_t i = 0; i < n; ++i) {
        const int len = std::snprintf(line, sizeof line, "%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", b.materialIndexPlane()[i],
                                      b.directionPlane(0)[i], b.directionPlane(1)[i], b.directionPlane(2)[i],
                                      b.directionPlane(3)[i], b.directionPlane(4)[i], b.directionPlane(5)[i]);
        f.write(line, len);
      }
    } else {
      f << brdfcl::detail::npyHeader(std::size_t(n), 7);
      std::vector<float> rows(7 * (std::size_t(1) << 16));
      for (std::size_t first = 0; first < n; first += rows.size() / 7) {
        const std::size_t count = std::min(rows.size() / 7, n - first);
        for (std::size_t i = 0; i < count; ++i) {
          rows[7 * i] = float(b.materialIndexPlane()[first + i]);
          for (int k = 0; k < 6; ++k) rows[7 * i + 1 + std::size_t(k)] = b.directionPlane(k)[first + i];
        }
        f.write(reinterpret_cast<const char*>(rows.data()), std::streamsize(28 * count));
      }
    }
  }
};

Files& files(std::size_t n, bool csv) {
  static std::unique_ptr<Files> current;
  static std::size_t currentN = 0;
  static bool currentCsv = false;
  if (!current || currentN != n || currentCsv != csv) {
    current.reset();
    current = std::make_unique<Files>(n, csv);
    currentN = n;
    currentCsv = csv;
  }
  return *current;
}

// The kernel on the batch the files were written from.
void BM_EvalProcessKernel(benchmark::State& state, bool csv) {
  auto& f = files(std::size_t(state.range(0)), csv);
  f.batch->runKernel();
  for (auto _ : state) f.batch->runKernel();
  state.SetItemsProcessed(std::int64_t(state.iterations()) * state.range(0));
}

// The whole process, into a path that does not exist yet (a user's first write: replacing an
// existing file would add the filesystem's cost of freeing it). The untimed first run reads the
// samples into the page cache and fills PoCL's and brdfcl's caches.
void BM_EvalProcess(benchmark::State& state, bool csv) {
  auto& f = files(std::size_t(state.range(0)), csv);
  const std::string ext = csv ? ".csv" : ".npy";
  const auto once = [&] {
    const std::string out = f.dir.path("out-" + std::to_string(f.outputs++) + ext);
    const auto r = brdfcl::test::runProcess(
        {BRDFCL_CLI_PATH, "eval", "--materials", f.materials, "--samples", f.samples, "--out", out}, f.dir.dir());
    if (r.status != 0) state.SkipWithError(("brdfcl eval failed: " + r.err).c_str());
    return out;
  };
  fs::remove(once());
  for (auto _ : state) {
    const std::string out = once();
    state.PauseTiming();
    fs::remove(out);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * state.range(0));
}

const bool registered = [] {
  // NPY at 8M (start-up weighs in) and 64M (amortized); CSV at 8M.
  for (const auto& [name, csv, n] : {std::tuple{"npy", false, std::int64_t(1) << 23}, {"npy", false, std::int64_t(1) << 26},
                                     {"csv", true, std::int64_t(1) << 23}}) {
    benchmark::RegisterBenchmark(fmt::format("BM_EvalProcess/{}/kernel", name).c_str(), BM_EvalProcessKernel, csv)
        ->Arg(n)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(fmt::format("BM_EvalProcess/{}/process", name).c_str(), BM_EvalProcess, csv)
        ->Arg(n)
        ->Iterations(3)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
