// Start-up of the CLI as a user meets it, whole processes timed: a warm 64x64 spheres render, a
// warm shade of a 256x256 G-buffer, and the first use of an environment (the spheres sky, and a
// 1k .hdr from the shared assets) with brdfcl's disk cache empty and PoCL's kernel cache kept.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "host/src/io/output.hpp"
#include "tests/assets_dir.hpp"
#include "tests/unit/process.hpp"

namespace fs = std::filesystem;

namespace {

// A scratch directory for every row, and the PoCL cache the child keeps when XDG_CACHE_HOME moves.
struct Scratch {
  brdfcl::test::ScratchDir dir{"bench-startup"};
  std::map<std::string, std::string> warm, cold;
  Scratch() {
    const std::string pocl = brdfcl::test::poclCacheDir();
    warm["XDG_CACHE_HOME"] = dir.path("warm-cache");
    if (!pocl.empty()) warm["POCL_CACHE_DIR"] = cold["POCL_CACHE_DIR"] = pocl;
  }
};

Scratch& scratch() {
  static Scratch s;
  return s;
}

void run(benchmark::State& state, const std::vector<std::string>& args, const std::map<std::string, std::string>& env) {
  std::vector<std::string> argv{BRDFCL_CLI_PATH};
  argv.insert(argv.end(), args.begin(), args.end());
  brdfcl::test::ProcessOptions o;
  o.env = env;
  o.cwd = scratch().dir.dir();
  const auto r = brdfcl::test::runProcess(argv, scratch().dir.dir(), o);
  if (r.status != 0) state.SkipWithError(("brdfcl failed: " + r.err).c_str());
}

// Every iteration timed whole; the first, untimed run fills the cache the warm rows read.
void warmRow(benchmark::State& state, const std::vector<std::string>& args) {
  run(state, args, scratch().warm);
  for (auto _ : state) run(state, args, scratch().warm);
}

// A warm `eval` of 1,024 samples from a float32 NPY: the latency floor of one CLI call.
void BM_StartupEval1kWarm(benchmark::State& state) {
  const std::string samples = scratch().dir.path("s1k.npy"), materials = scratch().dir.path("m1k.json");
  {
    std::ofstream m(materials);
    m << R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 0.5}, "extensions": )"
         R"({"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.4}}}]})";
    std::ofstream f(samples, std::ios::binary);
    f << brdfcl::detail::npyHeader(1024, 7);
    for (int i = 0; i < 1024; ++i) {
      const float row[7] = {0, 0.6f, 0, 0.8f, 0, 0.6f * float(i % 7) / 7, 0.8f};
      f.write(reinterpret_cast<const char*>(row), sizeof row);
    }
  }
  int k = 0;
  const auto args = [&] { return std::vector<std::string>{"eval", "--materials", materials, "--samples", samples, "--out", "e" + std::to_string(k++) + ".npy"}; };
  run(state, args(), scratch().warm);
  for (auto _ : state) run(state, args(), scratch().warm);
}

void BM_StartupRenderSpheres64Warm(benchmark::State& state) {
  warmRow(state, {"render", "--size", "64x64", "--out", "r.png"});
}

void BM_StartupShade256Warm(benchmark::State& state) {
  run(state, {"gbuffer", "--size", "256x256", "--out", "g.exr"}, scratch().warm);
  const std::string scene = scratch().dir.path("s.json");
  std::ofstream(scene) << R"({"lights": [{"type": "directional", "direction": [0, 0, -1]}], "environment": "builtin"})";
  warmRow(state, {"shade", "--gbuffer", "g.exr", "--scene", "s.json", "--out", "o.exr"});
}

// Cold: a fresh brdfcl cache per iteration holding only the tables no environment changes (sheen
// E, GGX and anisotropic DFG), so the row times an environment's first use; PoCL's kernels kept.
void coldRow(benchmark::State& state, const std::vector<std::string>& args) {
  int k = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto env = scratch().cold;
    const std::string cache = scratch().dir.path("cold-" + std::to_string(k++));
    fs::create_directories(cache + "/brdfcl");
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(scratch().dir.path("warm-cache/brdfcl"), ec))
      if (e.path().filename().string().rfind("env_", 0) != 0)
        fs::copy_file(e.path(), cache + "/brdfcl/" + e.path().filename().string(), ec);
    env["XDG_CACHE_HOME"] = cache;
    state.ResumeTiming();
    run(state, args, env);
  }
}

void BM_StartupRenderSpheres64Cold(benchmark::State& state) {
  run(state, {"render", "--size", "64x64", "--out", "r.png"}, scratch().warm);  // seeds the tables
  coldRow(state, {"render", "--size", "64x64", "--out", "r.png"});
}

void BM_StartupFirstUseOf1kHdr(benchmark::State& state) {
  const fs::path hdr = fs::path(brdfcl::test::assetsDir()) / "environments" / "polyhaven" / "quarry_01_1k.hdr";
  if (!fs::exists(hdr)) {
    state.SkipWithError(("asset missing: " + hdr.string()).c_str());
    return;
  }
  run(state, {"render", "--size", "64x64", "--out", "r.png"}, scratch().warm);
  coldRow(state, {"render", "--size", "64x64", "--environment", hdr.string(), "--out", "r.png"});
}

}  // namespace

BENCHMARK(BM_StartupEval1kWarm)->Iterations(10)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StartupRenderSpheres64Warm)->Iterations(5)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StartupShade256Warm)->Iterations(5)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StartupRenderSpheres64Cold)->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StartupFirstUseOf1kHdr)->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);
