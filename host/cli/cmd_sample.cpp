// `brdfcl sample`: materials JSON + views (with the caller's uniforms, or --count K --seed S for
// counter-based ones) -> Lx,Ly,Lz,pdf,wr,wg,wb per sample from Evaluator::sample, written
// atomically as CSV or NPY.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/sampling_io.hpp"
#include "commands.hpp"
#include "model_options.hpp"

namespace brdfcl::cli {

namespace {
struct SampleArgs {
  std::string materials, views, out, device, lobe = "all";
  ModelArgs model;
  long long count = 0, chunk = 1 << 20;
  std::uint64_t seed = 0;
  bool strict = false;
};
}  // namespace

void addSampleCommand(CLI::App& app) {
  auto args = std::make_shared<SampleArgs>();
  auto* cmd = app.add_subcommand("sample", "Importance-sample L for views: L, the mixture pdf and w = f cos / pdf");
  cmd->add_option("--materials", args->materials, "glTF 2.0 JSON (or any JSON with a top-level materials array)")->required();
  cmd->add_option("--views", args->views,
                  "CSV with columns material,Vx,Vy,Vz,u1,u2,u3 (u's optional with --count), or .npy (N,7)/(N,4); - reads stdin")
      ->required();
  cmd->add_option("--out", args->out, "output CSV Lx,Ly,Lz,pdf,wr,wg,wb or .npy (N,7) float32; - writes CSV to stdout")
      ->required();
  addModelOptions(cmd, args->model);
  cmd->add_option("--lobe", args->lobe, "all|diffuse|specular|sheen|clearcoat: sample and weigh one lobe (default all)");
  cmd->add_option("--count", args->count, "samples per view from the counter-based generator (views without u columns)");
  cmd->add_option("--seed", args->seed, "seed of the counter-based generator (default 0)");
  cmd->add_option("--chunk", args->chunk, "samples per device launch (default 1048576); the output does not depend on it");
  cmd->add_flag("--strict", args->strict, "unknown keys and extensions in the materials file are errors, not warnings");
  cmd->add_option("--device", args->device, "device index or name substring (default $BRDFCL_DEVICE, then 0)");
  cmd->callback([args] {
    checkResultsPath("--out", args->out);
    checkDistinctFiles({{"--materials", args->materials, false}, {"--views", args->views, false}, {"--out", args->out, true}});
    EvalOptions o = modelOptions(args->model);
    o.lobe = parseLobe(args->lobe);
    if (args->chunk < 1 || args->chunk > (1LL << 26))
      throw Error("--chunk " + std::to_string(args->chunk) + " is out of range; use 1 to " + std::to_string(1LL << 26));
    if (args->count < 0 || args->count > (1LL << 32))
      throw Error("--count " + std::to_string(args->count) + " is out of range; use 1 to 4294967296");
    const auto materials = readUserMaterials(args->materials, args->strict);
    const SampleViews views = readSampleViews(args->views, materials.size());
    const bool drawn = views.u.empty();
    if (drawn && args->count == 0)
      throw Error("--views '" + args->views + "' has no u1,u2,u3 columns; add them, or pass --count K (and --seed S)");
    if (!drawn && args->count != 0)
      throw Error("--count draws the uniforms, but --views '" + args->views + "' has u1,u2,u3 columns; give one or the other");
    const std::size_t per = drawn ? std::size_t(args->count) : 1, rows = views.size() * per;
    Runtime rt(args->device);
    Evaluator ev(rt, o);
    std::vector<float> out(7 * rows), V, u;
    std::vector<std::uint32_t> index;
    for (std::size_t first = 0; first < rows; first += std::size_t(args->chunk)) {
      const std::size_t n = std::min(std::size_t(args->chunk), rows - first);
      V.resize(3 * n);
      index.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t view = (first + i) / per;
        std::copy_n(&views.V[3 * view], 3, &V[3 * i]);
        index[i] = views.material.empty() ? 0 : views.material[view];
      }
      if (drawn) {
        u.resize(3 * n);
        Evaluator::drawUniforms(args->seed, first, n, u.data());
      } else {
        u.assign(views.u.begin() + std::ptrdiff_t(3 * first), views.u.begin() + std::ptrdiff_t(3 * (first + n)));
      }
      ev.sample(materials, index.data(), V.data(), u.data(), n, &out[7 * first]);
    }
    writeTable(args->out, {"Lx", "Ly", "Lz", "pdf", "wr", "wg", "wb"}, out);
  });
}

}  // namespace brdfcl::cli
