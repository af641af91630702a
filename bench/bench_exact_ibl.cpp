// --ibl exact throughput: the exact image-based-light integrator (kernels/ibl_exact.cl) on the
// 256x256 built-in spheres G-buffer at 64 samples per pixel, in covered pixel-samples per second
// (the punctual lights and the background pass are included in the time, not in the count).
#include <benchmark/benchmark.h>

#include <cstdint>

#include "brdfcl/render.hpp"

using namespace brdfcl;

namespace {

Runtime& runtime() {
  static Runtime rt;
  return rt;
}

void BM_ExactIbl(benchmark::State& state) {
  const int side = 256, samples = int(state.range(0));
  const Scene scene = spheresScene();
  const GBuffer g = renderSpheresGBuffer(runtime(), scene, side, side);
  Shader shader(runtime(), scene);
  ShadeOptions o;
  o.ibl = IblMode::Exact;
  o.iblSamples = samples;
  ShadeStats stats;
  shader.shade(g, o, &stats);  // warm: kernels built, light and CDFs prepared
  for (auto _ : state) benchmark::DoNotOptimize(shader.shade(g, o));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(stats.coveredPixels) * samples);
  state.counters["covered_pixels"] = double(stats.coveredPixels);
}

BENCHMARK(BM_ExactIbl)->Arg(64)->ArgName("samples")->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
