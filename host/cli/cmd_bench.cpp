// `brdfcl bench`: throughput of the batch kernel on N random in-domain samples over K random
// materials (256 by default), median of several runs after a warm-up, with the side-by-side ratios
// to the C++ peers (scalar loop, OpenMP-SIMD loop) and to the STREAM-triad memory bound, in one process;
// with --op sample, of the importance sampler (kernels/sample.cl) on resident rows.
#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "commands.hpp"
#include "host/src/eval/sample_batch.hpp"
#include "host/src/eval/workload.hpp"
#include "peers_module.hpp"

namespace brdfcl::cli {

namespace {
using Clock = std::chrono::steady_clock;

template <class F>
double medianSeconds(int runs, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = Clock::now();
    f();
    t.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

struct BenchArgs {
  std::string op = "eval", lobe = "all", device, profile = "spec";
  std::size_t n = std::size_t(1) << 22;
  std::size_t materials = bench::kDefaultMaterials;
  std::string pairs, indices, sheenEOut;
  int runs = 7;
  bool json = false;
};

// Six little-endian float32 planes of n values each (L.xyz, V.xyz): the file an outside peer
// (bench/peers/mitsuba_peer.py) writes so that both sides evaluate the very same pairs.
std::vector<float> readPairs(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() < 0) throw Error(fmt::format("--pairs '{}': cannot read: {}", path, std::strerror(errno)));
  const auto bytes = std::size_t(in.tellg());
  if (bytes == 0 || bytes % 24 != 0 || bytes / 24 > (std::size_t(1) << 28))
    throw Error(fmt::format("--pairs '{}' holds {} bytes; expected six float32 planes of 1 to 268435456 values", path, bytes));
  std::vector<float> planes(bytes / 4);
  in.seekg(0);
  in.read(reinterpret_cast<char*>(planes.data()), std::streamsize(bytes));
  if (!in) throw Error(fmt::format("--pairs '{}': cannot read: {}", path, std::strerror(errno)));
  return planes;
}

// One little-endian uint32 material index per pair of the --pairs file, each below --materials:
// an outside peer (bench/peers/drjit_peer.py) then gathers the very materials the kernel gathers.
std::vector<std::uint32_t> readIndices(const std::string& path, std::size_t n, std::size_t materials) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() < 0) throw Error(fmt::format("--indices '{}': cannot read: {}", path, std::strerror(errno)));
  const auto bytes = std::size_t(in.tellg());
  if (bytes != 4 * n)
    throw Error(fmt::format("--indices '{}' holds {} bytes; expected {} uint32 material indices, one per pair of --pairs",
                            path, bytes, n));
  std::vector<std::uint32_t> index(n);
  in.seekg(0);
  in.read(reinterpret_cast<char*>(index.data()), std::streamsize(bytes));
  if (!in) throw Error(fmt::format("--indices '{}': cannot read: {}", path, std::strerror(errno)));
  for (std::size_t i = 0; i < n; ++i)
    if (index[i] >= materials)
      throw Error(fmt::format("--indices '{}': pair {} has material index {}, not below --materials {}", path, i,
                              index[i], materials));
  return index;
}

nlohmann::json materialJson(const MaterialParams& m) {
  return {{"base_color", {m.baseColor[0], m.baseColor[1], m.baseColor[2]}},
          {"metallic", m.metallic},
          {"roughness", m.roughness},
          {"sheen_color", {m.sheenColor[0], m.sheenColor[1], m.sheenColor[2]}},
          {"sheen_roughness", m.sheenRoughness},
          {"clearcoat", m.clearcoat},
          {"clearcoat_roughness", m.clearcoatRoughness},
          {"anisotropy_strength", m.anisotropyStrength},
          {"anisotropy_rotation", m.anisotropyRotation}};
}
// --profile P: the engine profile and spec timed side by side, interleaved.
void benchProfile(const BenchArgs& a, Profile profile) {
  Runtime rt(a.device);
  bench::Bench spec(rt, a.lobe, a.n, 1, a.materials);
  bench::Bench engine(rt, a.lobe, a.n, 1, a.materials, profile);
  spec.runKernel();  // warm-up and program builds
  engine.runKernel();
  // Interleaved runs: both sides see the same machine state, so the ratio is what counts.
  std::vector<double> ts, te;
  for (int r = 0; r < a.runs; ++r) {
    ts.push_back(medianSeconds(1, [&] { spec.runKernel(); }));
    te.push_back(medianSeconds(1, [&] { engine.runKernel(); }));
  }
  std::sort(ts.begin(), ts.end());
  std::sort(te.begin(), te.end());
  const double sSpec = double(a.n) / ts[ts.size() / 2], sEngine = double(a.n) / te[te.size() / 2];
  if (a.json) {
    const nlohmann::json j = {{"profile", a.profile},
                              {"lobe", a.lobe},
                              {"n", a.n},
                              {"materials", a.materials},
                              {"runs", a.runs},
                              {"device", rt.info().name},
                              {"spec_samples_per_second", sSpec},
                              {"profile_samples_per_second", sEngine},
                              {"profile_over_spec", sEngine / sSpec}};
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    fmt::print("brdfcl bench: lobe {}, {} samples over {} materials, median of {} interleaved runs, on {}\n",
               a.lobe, a.n, a.materials, a.runs, rt.info().name);
    fmt::print("  {:<28}{:>12.1f} Msamples/s\n", "--profile spec", sSpec / 1e6);
    fmt::print("  {:<28}{:>12.1f} Msamples/s   {:.2f}x spec's speed\n", "--profile " + a.profile,
               sEngine / 1e6, sEngine / sSpec);
  }
}

// The kernel's figures in --json, as both kernel reports give them (the keys print sorted).
nlohmann::json kernelJson(const BenchArgs& a, Runtime& rt, double kernel, double launch, double firstRun) {
  return {{"samples_per_second", double(a.n) / kernel},
          {"n", a.n},
          {"lobe", a.lobe},
          {"materials", a.materials},
          {"device", rt.info().name},
          {"runs", a.runs},
          {"kernel_seconds_median", kernel},
          {"first_run_seconds", firstRun},
          {"launch_seconds_median", launch},
          {"launch_samples_per_second", double(a.n) / launch}};
}

// --pairs FILE: the kernel alone on the outside peer's pairs; it times its own side and needs the
// kernel's figure and the material.
void reportPairs(const BenchArgs& a, Runtime& rt, const bench::Bench& b, double kernel, double launch, double firstRun) {
  const double sps = double(a.n) / kernel;
  if (a.json) {
    nlohmann::json j = kernelJson(a, rt, kernel, launch, firstRun);
    j["material0"] = materialJson(b.workload().materials[0]);
    // With --indices, every material, so that the outside peer evaluates the same ones by the same
    // indices (without, the list would only lengthen the output: material0 describes K = 1).
    if (!a.indices.empty()) {
      nlohmann::json& all = j["material_params"] = nlohmann::json::array();
      for (const auto& m : b.workload().materials) all.push_back(materialJson(m));
    }
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    fmt::print("brdfcl bench: lobe {}, {} pairs from '{}' over {} materials, median of {} runs, on {}\n",
               a.lobe, a.n, a.pairs, a.materials, a.runs, rt.info().name);
    fmt::print("  {:<28}{:>12.1f} Msamples/s\n", "OpenCL kernel", sps / 1e6);
    fmt::print("  {:<28}{:>12.1f} Msamples/s\n", "launch alone (device time)", double(a.n) / launch / 1e6);
  }
}

// --op sample: the sampler over n rows resident on the device (views random above the horizon, or
// those of --pairs; u from the counter-based generator with seed 1), wall time of a launch and its
// device time. --lobe specular samples the anisotropic GGX lobe alone; all, the layered mixture.
void benchSample(BenchArgs& a) {
  std::vector<float> pairs;
  std::vector<std::uint32_t> indices;
  if (!a.pairs.empty()) {
    pairs = readPairs(a.pairs);
    a.n = pairs.size() / 6;
    if (!a.indices.empty()) indices = readIndices(a.indices, a.n, a.materials);
  }
  const auto t0 = Clock::now();
  Runtime rt(a.device);
  const bench::Workload w = bench::makeWorkload(a.lobe, 1, a.materials);
  Evaluator ev(rt, w.options);
  // Before the rows are allocated: the batch is one launch, as the evaluation kernel's is.
  if (a.n > ev.launchLimit())
    throw Error(fmt::format("--op sample: {} rows are more than one launch of the sampler takes on this device ({} at "
                            "most); lower --n or use a smaller --pairs file",
                            a.n, ev.launchLimit()));
  std::vector<float> view(3 * a.n), u(3 * a.n);
  std::vector<std::uint32_t> index(a.n);
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  const auto next = [&state] {  // xorshift64*: views and indices, independent of the u stream
    state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
    return state * 0x2545f4914f6cdd1dull;
  };
  const auto unit = [&next] { return float(next() >> 40) * (1.0f / 16777216.0f); };
  for (std::size_t i = 0; i < a.n; ++i) {
    if (!pairs.empty()) {
      for (int k = 0; k < 3; ++k) view[3 * i + k] = pairs[(3 + k) * a.n + i];
    } else {
      const float z = 0.01f + 0.99f * unit(), phi = 6.2831853f * unit(), s = std::sqrt(1.0f - z * z);
      view[3 * i] = s * std::cos(phi), view[3 * i + 1] = s * std::sin(phi), view[3 * i + 2] = z;
    }
    index[i] = indices.empty() ? std::uint32_t(next() % a.materials) : indices[i];
  }
  Evaluator::drawUniforms(1, 0, a.n, u.data());
  SampleBatch b(rt, ev, w.materials, view, index, u);
  b.run();  // warm-up; also builds (or loads from PoCL's cache) the program
  const double firstRun = std::chrono::duration<double>(Clock::now() - t0).count();
  std::vector<double> launches;
  const double kernel = medianSeconds(a.runs, [&] {
    b.run();
    launches.push_back(b.lastKernelSeconds());
  });
  std::sort(launches.begin(), launches.end());
  const double launch = launches[launches.size() / 2];
  const std::vector<float> rows = b.read();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < a.n; ++i) kept += rows[7 * i + 3] > 0.0f;
  const double keptFraction = double(kept) / double(a.n);
  if (a.json) {
    nlohmann::json j = kernelJson(a, rt, kernel, launch, firstRun);
    j["op"] = "sample";
    j["kept_fraction"] = keptFraction;
    j["material0"] = materialJson(w.materials[0]);
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  fmt::print("brdfcl bench --op sample: lobe {}, {} rows over {} materials, median of {} runs, on {}\n", a.lobe, a.n,
             a.materials, a.runs, rt.info().name);
  fmt::print("  {:<28}{:>12.1f} Msamples/s\n", "OpenCL kernel", double(a.n) / kernel / 1e6);
  fmt::print("  {:<28}{:>12.1f} Msamples/s   (device time of the launch)\n", "launch alone", double(a.n) / launch / 1e6);
  fmt::print("  directions kept (above the horizon): {:.2f} %\n", 100 * keptFraction);
  fmt::print("  first run (device open, program build or cache load, warm-up): {:.3f} s\n", firstRun);
}

// The kernel, and unless --pairs, its ratios to the C++ peers, the memory bound and a small eval.
void benchKernel(BenchArgs& a) {
  std::vector<float> pairs;
  std::vector<std::uint32_t> indices;
  if (!a.pairs.empty()) {
    pairs = readPairs(a.pairs);  // before the clock: file I/O is no part of the kernel's time
    a.n = pairs.size() / 6;
    if (!a.indices.empty()) indices = readIndices(a.indices, a.n, a.materials);
  }
  // The peers' module, when the run compares with them, before any work: a build without it fails at once.
  const peers::ModuleTable* peerModule = pairs.empty() ? &peersModule() : nullptr;
  const auto t0 = Clock::now();
  Runtime rt(a.device);
  bench::Bench b(rt, a.lobe, a.n, 1, a.materials);
  if (!pairs.empty()) b.setDirections(pairs);
  if (!indices.empty()) b.setMaterialIndices(indices);
  b.runKernel();  // warm-up; also builds (or loads from PoCL's cache) the program
  const double firstRun = std::chrono::duration<double>(Clock::now() - t0).count();
  // The launch alone, from its profiling event: on a GPU the run also copies the result back
  // to the host, which can take longer than the kernel.
  std::vector<double> launches;
  const double kernel = medianSeconds(a.runs, [&] {
    b.runKernel();
    launches.push_back(b.batch().lastKernelSeconds());
  });
  std::sort(launches.begin(), launches.end());
  const double launch = launches[launches.size() / 2];
  if (!pairs.empty()) {
    if (!a.sheenEOut.empty()) {
      // The table the kernel read, for an outside peer of the same maths (bench/peers/drjit_peer.py).
      const SheenAlbedoTable& e = b.evaluator().sheenAlbedo();
      writeOutput(a.sheenEOut, e.values.data(), e.values.size() * sizeof(float));
    }
    reportPairs(a, rt, b, kernel, launch, firstRun);
    return;
  }
  const auto runPeer = [&](bool simd) {
    if (!peerModule->run(simd, b.workload().name.c_str(), &b.peerInput()))
      throw std::logic_error("the C++ peers have no workload '" + b.workload().name + "'");
  };
  runPeer(true);
  const double simd = medianSeconds(a.runs, [&] { runPeer(true); });
  const double simdDeviation = b.peerDeviation();
  const double scalar = medianSeconds(std::min(a.runs, 3), [&] { runPeer(false); });
  const double triad = peerModule->streamTriadBytesPerSecond(std::size_t(1) << 25, 5);

  // End to end through the public API for a small batch: what a second `eval` of 1K pays.
  const auto w = bench::makeWorkload(a.lobe, 1, a.materials);
  Samples small;
  for (int i = 0; i < 1024; ++i) {
    const float z = 0.05f + 0.9f * float(i) / 1024.0f, s = std::sqrt(1 - z * z);
    small.L.insert(small.L.end(), {s, 0.0f, z});
    small.V.insert(small.V.end(), {-s * 0.6f, s * 0.8f, z});
    small.material.push_back(std::uint32_t(std::size_t(i) % a.materials));
  }
  Evaluator ev(rt, w.options);
  ev.evaluate(w.materials, small);
  const double e2e1k = medianSeconds(a.runs, [&] { ev.evaluate(w.materials, small); });

  const double n = double(a.n);
  const double sps = n / kernel, spsSimd = n / simd, spsScalar = n / scalar;
  const double bound = triad / bench::kBytesPerSample;
  if (a.json) {
    nlohmann::json j = kernelJson(a, rt, kernel, launch, firstRun);
    j["eval_1024_seconds"] = e2e1k;
    j["bytes_per_sample"] = bench::kBytesPerSample;
    j["peers"] = {{"scalar_cpp_samples_per_second", spsScalar},
                  {"openmp_simd_samples_per_second", spsSimd},
                  {"openmp_simd_max_rel_deviation", simdDeviation},
                  {"stream_triad_bytes_per_second", triad},
                  {"memory_bound_samples_per_second", bound}};
    j["ratios"] = {{"vs_scalar_cpp", sps / spsScalar}, {"vs_openmp_simd", sps / spsSimd}, {"of_memory_bound", sps / bound}};
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  fmt::print("brdfcl bench: lobe {}, {} samples over {} materials, median of {} runs, on {}\n", a.lobe,
             a.n, a.materials, a.runs, rt.info().name);
  fmt::print("  {:<28}{:>12.1f} Msamples/s\n", "OpenCL kernel", sps / 1e6);
  fmt::print("  {:<28}{:>12.1f} Msamples/s   (device time of the launch, without copies)\n", "launch alone",
             n / launch / 1e6);
  fmt::print("  {:<28}{:>12.1f} Msamples/s   kernel is {:.2f}x\n", "scalar C++ loop", spsScalar / 1e6, sps / spsScalar);
  fmt::print("  {:<28}{:>12.1f} Msamples/s   kernel is {:.2f}x\n", fmt::format("OpenMP-SIMD loop ({} threads)", peerModule->threads()), spsSimd / 1e6,
             sps / spsSimd);
  fmt::print("  {:<28}{:>12.1f} Msamples/s   kernel is {:.0f}% of it ({:.1f} GB/s triad, {:.0f} B/sample)\n",
             "memory bound", bound / 1e6, 100 * sps / bound, triad / 1e9, bench::kBytesPerSample);
  fmt::print("  first run (device open, program build or cache load, warm-up): {:.3f} s\n", firstRun);
  fmt::print("  1,024 samples end to end through Evaluator::evaluate (warm): {:.2f} ms\n", e2e1k * 1e3);
}
}  // namespace

void addBenchCommand(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd = app.add_subcommand("bench", "Measure samples/s of the kernel and its ratios to CPU peers");
  cmd->add_option("--op", args->op,
                  "eval (default): f of the batch kernel; sample: the importance sampler (Lx Ly Lz pdf w rows), "
                  "--lobe specular its anisotropic GGX lobe alone, all the layered mixture");
  cmd->add_option("--lobe", args->lobe, "sheen|specular|clearcoat|all (default all)");
  cmd->add_option("--n", args->n, "samples per run (default 4194304)");
  cmd->add_option("--materials", args->materials, "number of random materials, 1 to 1048576 (default 256)");
  cmd->add_option("--pairs", args->pairs,
                  "raw file of 6 float32 planes (L.xyz, V.xyz) to evaluate instead of random pairs; "
                  "times the kernel only (no peers) and sets --n from the file");
  cmd->add_option("--indices", args->indices,
                  "with --pairs: raw file of one uint32 material index per pair (each below --materials) "
                  "instead of random indices; --json then lists every material");
  cmd->add_option("--sheen-e-out", args->sheenEOut,
                  "with --pairs: also write the sheen albedo table E the kernel reads, raw float32, "
                  "320 x 320 row-major (rows: sheenRoughness t^2, columns: N.V s^2, s and t uniform on [0, 1])");
  cmd->add_option("--runs", args->runs, "timed runs after the warm-up; the median is reported (default 7)");
  cmd->add_option("--device", args->device, "device index or name substring (default $BRDFCL_DEVICE, then 0)");
  cmd->add_option("--profile", args->profile,
                  "khronos|threejs|filament|babylon|materialx: time that engine profile and spec side by side, "
                  "interleaved, on the same pairs and materials (docs/profiles.md)");
  cmd->add_flag("--json", args->json, "print one JSON object on stdout");
  cmd->callback([args] {
    const Profile profile = parseProfile(args->profile);
    if (args->op != "eval" && args->op != "sample")
      throw Error(fmt::format("--op '{}' is not a benchmark operation; use eval or sample", args->op));
    if (args->n == 0 || args->n > (std::size_t(1) << 28))
      throw Error(fmt::format("--n {} is out of range; use 1 to 268435456", args->n));
    if (args->runs < 1 || args->runs > 1000) throw Error(fmt::format("--runs {} is out of range; use 1 to 1000", args->runs));
    if (args->materials == 0 || args->materials > (std::size_t(1) << 20))
      throw Error(fmt::format("--materials {} is out of range; use 1 to 1048576", args->materials));
    if (!args->indices.empty() && args->pairs.empty())
      throw Error("--indices gives the material of each pair of --pairs; give --pairs FILE too");
    if (!args->sheenEOut.empty()) {
      if (args->pairs.empty()) throw Error("--sheen-e-out goes with --pairs, the outside peer's run; give --pairs FILE too");
      checkOutputPath("--sheen-e-out", args->sheenEOut);
      checkDistinctFiles({{"--pairs", args->pairs}, {"--indices", args->indices}, {"--sheen-e-out", args->sheenEOut, true}});
    }
    if (args->op == "sample") {
      if (profile != Profile::Spec) throw Error("--op sample times the spec's sampler; drop --profile");
      if (!args->sheenEOut.empty()) throw Error("--sheen-e-out goes with --op eval; drop it");
      benchSample(*args);
      return;
    }
    if (profile != Profile::Spec) {
      if (!args->pairs.empty()) throw Error("--pairs and --profile are separate measurements; give one");
      benchProfile(*args, profile);
      return;
    }
    benchKernel(*args);
  });
}

}  // namespace brdfcl::cli
