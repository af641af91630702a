// `brdfcl eval`: materials JSON + samples CSV/NPY -> f(L, V) per sample (or per material x
// direction with --grid), streamed in chunks of --chunk samples and written atomically as CSV/NPY.
#include <cstdio>
#include <string>

#include "brdfcl/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/stream.hpp"
#include "commands.hpp"
#include "model_options.hpp"

namespace brdfcl::cli {

namespace {
struct EvalArgs {
  std::string materials, samples, out, device;
  ModelArgs model;
  std::string lobe = "all";
  bool grid = false, strict = false;
  long long chunk = static_cast<long long>(StreamOptions::kDefaultChunk);
};

// --device all or a list (0,2): every chunk split across the devices (brdfcl/device_set.hpp).
void evaluateOnDevices(const std::string& devices, const EvalOptions& o, const std::vector<MaterialParams>& materials,
                       SampleStream& samples, const std::string& outPath, const StreamOptions& so) {
  DeviceSet set(devices);
  MultiEvaluator evaluator(set, o);
  ResultWriter out(outPath);
  evaluateStream(evaluator, materials, samples, out, so);
  out.commit();
}
}  // namespace

void addEvalCommand(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* cmd = app.add_subcommand("eval", "Evaluate f(L, V) of glTF materials for a batch of direction pairs");
  cmd->add_option("--materials", args->materials, "glTF 2.0 JSON (or any JSON with a top-level materials array)")
      ->required();
  cmd->add_option("--samples", args->samples, "CSV with columns material,Lx,Ly,Lz,Vx,Vy,Vz in any order, or .npy (N,7); - reads stdin (CSV, or NPY by its magic)")->required();
  cmd->add_option("--out", args->out, "output CSV r,g,b or .npy (N,3) float32; - writes CSV to stdout")->required();
  addModelOptions(cmd, args->model);
  cmd->add_option("--lobe", args->lobe, "all|diffuse|specular|sheen|clearcoat (default all; every profile defines its lobes, README)");
  cmd->add_flag("--grid", args->grid, "every material x every direction pair, material-major");
  cmd->add_flag("--strict", args->strict,
                "unknown keys and extensions in the materials file are errors, not warnings");
  cmd->add_option("--chunk", args->chunk,
                  "samples per chunk (default " + std::to_string(StreamOptions::kDefaultChunk) +
                      "); memory stays bounded by a few chunks whatever the file size");
  cmd->add_option("--device", args->device,
                  "device index or name substring (default $BRDFCL_DEVICE, then 0), or all, or a list such as 0,2 "
                  "to split the work across devices");
  cmd->callback([args] {
    checkResultsPath("--out", args->out);
    EvalOptions o = modelOptions(args->model);
    o.lobe = parseLobe(args->lobe);
    if (args->chunk < 1 || args->chunk > static_cast<long long>(StreamOptions::kMaxChunk))
      throw Error("--chunk " + std::to_string(args->chunk) + " is out of range; use 1 to " +
                  std::to_string(StreamOptions::kMaxChunk));
    auto materials = readUserMaterials(args->materials, args->strict);
    // The header is checked before the device is set up; rows are checked as they stream.
    SampleStream samples(args->samples, args->grid ? 0 : materials.size(), args->grid);
    StreamOptions so;
    so.chunk = static_cast<std::size_t>(args->chunk);
    so.grid = args->grid;
    if (isDeviceList(args->device)) return evaluateOnDevices(args->device, o, materials, samples, args->out, so);
    Runtime rt(args->device);
    Evaluator evaluator(rt, o);
    ResultWriter out(args->out);
    evaluateStream(evaluator, materials, samples, out, so);
    out.commit();
  });
}

}  // namespace brdfcl::cli
