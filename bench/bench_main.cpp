// build/bin/brdfcl-bench: Google Benchmark over the batch kernel and its peers on the same
// arrays in the same run (scalar C++ loop, OpenMP-SIMD loop, STREAM-triad memory bound), plus
// grid evaluation, file-to-file streaming (overlapped vs serial) and the sheen albedo bake. Every
// Eval/peer row reports items/s and bytes/s at 40 bytes a sample, so ratios can be read off one JSON file.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include "brdfcl/arrays.hpp"
#include "brdfcl/render.hpp"
#include "brdfcl/stream.hpp"
#include "host/src/eval/workload.hpp"
#include "host/src/io/output.hpp"
#include "peers.hpp"

using namespace brdfcl;

namespace {

Runtime& runtime() {
  static Runtime rt;
  return rt;
}

// One workload at a time: 64M samples are 2.5 GB, so consecutive rows share it.
bench::Bench& benchFor(const std::string& lobe, std::size_t n) {
  static std::unique_ptr<bench::Bench> current;
  if (!current || current->size() != n || current->workload().name != lobe) {
    current.reset();
    current = std::make_unique<bench::Bench>(runtime(), lobe, n);
  }
  return *current;
}

void report(benchmark::State& state, std::size_t n) {
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(n));
  state.SetBytesProcessed(std::int64_t(double(state.iterations()) * double(n) * bench::kBytesPerSample));
}

void BM_Eval(benchmark::State& state, std::string lobe) {
  const std::size_t n = std::size_t(state.range(0));
  auto& b = benchFor(lobe, n);
  b.runKernel();  // warm-up: program build and first touch stay out of the timing
  double launches = 0;
  for (auto _ : state) {
    b.runKernel();
    launches += b.batch().lastKernelSeconds();
  }
  report(state, n);
  // The launch alone (device time): on a GPU each run also copies the result back to the host.
  if (launches > 0) state.counters["launch_items_per_second"] = double(state.iterations()) * double(n) / launches;
}

void BM_Peer(benchmark::State& state, std::string lobe, peers::Flavor flavor) {
  const std::size_t n = std::size_t(state.range(0));
  auto& b = benchFor(lobe, n);
  peers::run(flavor, lobe, b.peerInput());
  for (auto _ : state) peers::run(flavor, lobe, b.peerInput());
  report(state, n);
  b.runKernel();
  state.counters["max_rel_dev_vs_kernel"] = b.peerDeviation();
}

// The memory roofline: STREAM triad bytes/s divided by 40 bytes a sample.
void BM_StreamTriad(benchmark::State& state) {
  const std::size_t floats = std::size_t(state.range(0));
  double bytesPerSecond = 0;
  for (auto _ : state) bytesPerSecond = peers::streamTriadBytesPerSecond(floats, 5);
  state.counters["triad_GBps"] = bytesPerSecond / 1e9;
  state.counters["samples_per_second_bound"] = bytesPerSecond / bench::kBytesPerSample;
}

void BM_EvalGrid(benchmark::State& state) {
  const auto w = bench::makeWorkload("all");
  Evaluator ev(runtime(), w.options);
  Samples s;
  const std::size_t n = std::size_t(state.range(0));
  for (std::size_t i = 0; i < n; ++i) {
    const float t = float(i) / float(n), z = 0.05f + 0.9f * t, r = std::sqrt(1 - z * z);
    s.L.insert(s.L.end(), {r * std::cos(40.0f * t), r * std::sin(40.0f * t), z});
    s.V.insert(s.V.end(), {r * std::cos(7.0f * t), -r * std::sin(7.0f * t), z});
  }
  ev.evaluateGrid(w.materials, s);
  for (auto _ : state) benchmark::DoNotOptimize(ev.evaluateGrid(w.materials, s));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(n * w.materials.size()));
}

// The library's in-memory paths on the kernel's own workload (the same pairs and materials as
// BM_Eval/<lobe>/<n>, `materials` random ones): what the Python module calls. `arrays` is
// evaluateArrays on float32 (N, 3) rows, checked and normalized, into a reused output; `table`
// is Evaluator::evaluateTableRows on the same samples as a float32 NPY's (N, 7) rows;
// `grid` is Evaluator::evaluateGrid of one material into a reused output, `grid-fresh` the same
// returning a fresh vector (whose pages every call faults in); `kernel` runs the
// batch alone, so each row's items/s divided by its kernel row's is the fraction of kernel speed.
enum class InMemory { Kernel, Arrays, Table, Grid, GridFresh };
void BM_InMemory(benchmark::State& state, std::string lobe, InMemory path) {
  const std::size_t n = std::size_t(state.range(0)), materials = std::size_t(state.range(1));
  auto b = std::make_unique<bench::Bench>(runtime(), lobe, n, 1, materials);
  const SoaBatch& batch = b->batch();
  std::vector<float> L(3 * n), V(3 * n), rgb(3 * n);
  std::vector<std::int64_t> index(n);
  Samples s;
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      L[3 * i + c] = batch.directionPlane(c)[i];
      V[3 * i + c] = batch.directionPlane(3 + c)[i];
    }
    index[i] = batch.materialIndexPlane()[i];
  }
  std::vector<float> table(7 * n);  // a samples NPY's rows: material, L, V
  for (std::size_t i = 0; i < n; ++i) {
    table[7 * i] = float(index[i]);
    for (int c = 0; c < 3; ++c) table[7 * i + 1 + c] = L[3 * i + c], table[7 * i + 4 + c] = V[3 * i + c];
  }
  ArraySamples a;
  a.L.data = L.data();
  a.V.data = V.data();
  a.material = materials > 1 ? index.data() : nullptr;
  a.count = n;
  if (path == InMemory::Grid || path == InMemory::GridFresh) s.L = L, s.V = V;
  const auto& mats = b->workload().materials;
  auto once = [&] {
    switch (path) {
      case InMemory::Kernel: b->runKernel(); break;
      case InMemory::Arrays: evaluateArrays(b->evaluator(), mats, a, rgb.data()); break;
      case InMemory::Table: b->evaluator().evaluateTableRows(mats, table.data(), n, rgb.data()); break;
      case InMemory::Grid: b->evaluator().evaluateGrid(mats, s, rgb.data()); break;
      case InMemory::GridFresh: benchmark::DoNotOptimize(b->evaluator().evaluateGrid(mats, s)); break;
    }
  };
  once();
  for (auto _ : state) once();
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(n));
}

// `brdfcl eval` file to file on n samples (all layers): a float32 NPY to an NPY result, with
// reading and writing overlapped with evaluation (the default) or the same steps one after
// another; `csv` is the overlapped run on the same rows as CSV in and out. The input is written
// once per process to the temp directory and the output replaced each run.
enum class FileMode { Overlapped, Serial, Csv };
void BM_EvalFile(benchmark::State& state, FileMode mode) {
  const std::size_t n = std::size_t(state.range(0));
  const auto w = bench::makeWorkload("all");
  const bool csv = mode == FileMode::Csv;
  const std::string dir = (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
  const std::string stem = dir + "/brdfcl-bench-" + std::to_string(::getpid()) + "-";
  const std::string in = stem + std::to_string(n) + (csv ? ".csv" : ".npy");
  const std::string out = stem + (csv ? "out.csv" : "out.npy");
  {
    std::ofstream f(in, std::ios::binary);
    if (csv) {
      f << "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
    } else {
      f << detail::npyHeader(std::size_t(n), 7);
    }
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<float> row(7);
    char text[160];
    for (std::size_t i = 0; i < n; ++i) {
      row = {float(i % w.materials.size()), u(rng), u(rng), 1.5f + u(rng), u(rng), u(rng), 1.5f + u(rng)};
      if (csv) {
        const int len = std::snprintf(text, sizeof text, "%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", int(row[0]), row[1],
                                      row[2], row[3], row[4], row[5], row[6]);
        f.write(text, len);
      } else {
        f.write(reinterpret_cast<const char*>(row.data()), 28);
      }
    }
  }
  Evaluator ev(runtime(), w.options);
  StreamOptions o;
  o.overlap = mode != FileMode::Serial;
  const auto run = [&] {
    SampleStream samples(in, w.materials.size(), false);
    ResultWriter writer(out);
    evaluateStream(ev, w.materials, samples, writer, o);
    writer.commit();
  };
  run();  // program build, E table and page cache stay out of the timing
  for (auto _ : state) run();
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(n));
  if (!csv) state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(n) * (28 + 12));
  std::remove(in.c_str());
  std::remove(out.c_str());
}

void BM_LutBake(benchmark::State& state) {
  const std::size_t size = std::size_t(state.range(0));
  bakeSheenAlbedo(runtime(), SheenDistribution::Charlie, SheenVisibility::Charlie, 8);  // build the program
  for (auto _ : state)
    benchmark::DoNotOptimize(bakeSheenAlbedo(runtime(), SheenDistribution::Charlie, SheenVisibility::Charlie, size));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(size * size));
}

// Deferred shading of the built-in spheres G-buffer (two lights and image-based light).
void BM_Shade(benchmark::State& state) {
  const int side = int(state.range(0));
  const Scene scene = spheresScene();
  const GBuffer g = renderSpheresGBuffer(runtime(), scene, side, side);
  Shader shader(runtime(), scene);
  shader.shade(g);
  for (auto _ : state) benchmark::DoNotOptimize(shader.shade(g));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * side * side);
}

void registerAll() {
  const std::vector<std::int64_t> sizes = {1 << 10, 1 << 14, 1 << 18, 1 << 22, 1 << 26};
  for (const auto& lobe : bench::workloadNames()) {
    for (auto n : sizes) {
      benchmark::RegisterBenchmark(("BM_Eval/" + lobe).c_str(), BM_Eval, lobe)->Arg(n)->UseRealTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("BM_SimdPeer/" + lobe).c_str(), BM_Peer, lobe, peers::Flavor::OpenMPSimd)
          ->Arg(n)->UseRealTime()->Unit(benchmark::kMillisecond);
      if (n <= (1 << 22))  // a single-threaded scalar loop over 64M samples takes many seconds
        benchmark::RegisterBenchmark(("BM_ScalarPeer/" + lobe).c_str(), BM_Peer, lobe, peers::Flavor::Scalar)
            ->Arg(n)->UseRealTime()->Unit(benchmark::kMillisecond);
    }
  }
  // Interleaved, so that each library row sits next to its kernel row in one run.
  for (const auto& [lobe, materials] : std::vector<std::pair<std::string, int>>{{"all", 256}, {"all", 1}, {"specular", 1}}) {
    for (auto [name, path] : {std::pair{"kernel", InMemory::Kernel}, std::pair{"arrays", InMemory::Arrays},
                              std::pair{"table", InMemory::Table},
                              std::pair{"grid", InMemory::Grid}, std::pair{"grid-fresh", InMemory::GridFresh}}) {
      if ((path == InMemory::Grid || path == InMemory::GridFresh) && materials != 1) continue;
      benchmark::RegisterBenchmark(("BM_InMemory/" + lobe + "/" + name).c_str(), BM_InMemory, lobe, path)
          ->Args({1 << 22, materials})->ArgNames({"n", "materials"})->UseRealTime()->Unit(benchmark::kMillisecond);
    }
  }
  // The table rows beside the planes kernel at a samples file's 8M rows (docs/performance.md).
  for (auto [name, path] : {std::pair{"kernel", InMemory::Kernel}, std::pair{"table", InMemory::Table}})
    benchmark::RegisterBenchmark((std::string("BM_InMemory/all/") + name).c_str(), BM_InMemory, std::string("all"), path)
        ->Args({1 << 23, 256})->ArgNames({"n", "materials"})->UseRealTime()->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_StreamTriad", BM_StreamTriad)->Arg(1 << 25)->Iterations(1)->UseRealTime();
  benchmark::RegisterBenchmark("BM_EvalGrid", BM_EvalGrid)->Arg(1 << 14)->UseRealTime()->Unit(benchmark::kMillisecond);
  // Next to the kernel alone on the same workload (all layers, 256 materials), in one run.
  benchmark::RegisterBenchmark("BM_EvalFile/kernel", BM_Eval, std::string("all"))->Arg(1 << 23)->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  for (auto [name, mode] : {std::pair{"overlapped", FileMode::Overlapped}, std::pair{"serial", FileMode::Serial},
                            std::pair{"csv", FileMode::Csv}})
    benchmark::RegisterBenchmark((std::string("BM_EvalFile/") + name).c_str(), BM_EvalFile, mode)
        ->Arg(1 << 23)->UseRealTime()->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_Shade", BM_Shade)->Arg(512)->UseRealTime()->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_LutBake", BM_LutBake)->Arg(64)->UseRealTime()->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
