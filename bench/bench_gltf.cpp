// glTF benchmarks on SheenChair (the sample assets: $BRDFCL_ASSETS): the G-buffer trace, the
// warm render at 1 and 4 samples per pixel, and the first render of an asset (loading, texture
// decoding and mip generation included). Rows are skipped with a message when the asset is absent.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "brdfcl/gltf.hpp"
#include "host/src/render/gltf_frame.hpp"
#include "tests/assets_dir.hpp"

using namespace brdfcl;

namespace {

constexpr int kWidth = 1920, kHeight = 1080;

std::string sheenChair() {
  const std::string root = brdfcl::test::assetsDir();
  if (root.empty()) return "";
  const auto p = std::filesystem::path(root) / "SheenChair" / "glTF" / "SheenChair.gltf";
  return std::filesystem::exists(p) ? p.string() : "";
}

Runtime& runtime() {
  static Runtime rt;
  return rt;
}

// Loaded once and shared by the warm rows.
struct Chair {
  gltf::Asset asset;
  std::unique_ptr<gltf::Raycaster> raycaster;
  gltf::View view;
  Scene lighting;
};

Chair* chair(benchmark::State& state) {
  static std::unique_ptr<Chair> c;
  if (c) return c.get();
  const std::string path = sheenChair();
  if (path.empty()) {
    state.SkipWithError("SheenChair not found: set BRDFCL_ASSETS to the shared assets folder");
    return nullptr;
  }
  c = std::make_unique<Chair>();
  c->asset = gltf::load(path);
  c->raycaster = std::make_unique<gltf::Raycaster>(c->asset);
  c->view = gltf::chooseView(c->asset, "", kWidth, kHeight);
  c->lighting = gltf::frameLighting(c->asset, c->view, "gltf", Environment{}, false);
  return c.get();
}

void BM_GltfGbuffer(benchmark::State& state) {
  Chair* c = chair(state);
  if (!c) return;
  for (auto _ : state) benchmark::DoNotOptimize(c->raycaster->trace(c->view, kWidth, kHeight));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kWidth * kHeight);
}

void BM_GltfRender(benchmark::State& state) {
  Chair* c = chair(state);
  if (!c) return;
  const int spp = int(state.range(0));
  Shader shader(runtime(), c->lighting);
  gltf::renderFrame(shader, *c->raycaster, c->view, 64, 36, 1);  // warm: kernels built, light prepared
  for (auto _ : state) benchmark::DoNotOptimize(gltf::renderFrame(shader, *c->raycaster, c->view, kWidth, kHeight, spp));
  state.SetItemsProcessed(std::int64_t(state.iterations()) * kWidth * kHeight * spp);
}

// Everything a first `brdfcl render --spp 1` does after start-up: load, decode textures, build
// mips and the BVH, shade (kernels and environment already prepared by the warm rows' process).
void BM_GltfFirstRender(benchmark::State& state) {
  const std::string path = sheenChair();
  if (path.empty()) {
    state.SkipWithError("SheenChair not found: set BRDFCL_ASSETS to the shared assets folder");
    return;
  }
  for (auto _ : state) {
    const gltf::Asset asset = gltf::load(path);
    const gltf::Raycaster raycaster(asset);
    const gltf::View view = gltf::chooseView(asset, "", kWidth, kHeight);
    Shader shader(runtime(), gltf::frameLighting(asset, view, "gltf", Environment{}, false));
    benchmark::DoNotOptimize(gltf::renderFrame(shader, raycaster, view, kWidth, kHeight, 1));
  }
}

BENCHMARK(BM_GltfGbuffer)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GltfRender)->Arg(1)->Arg(4)->ArgName("spp")->Iterations(4)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GltfFirstRender)->Iterations(3)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
