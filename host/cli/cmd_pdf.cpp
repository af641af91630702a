// `brdfcl pdf`: materials JSON + eval's samples file (material,Lx,Ly,Lz,Vx,Vy,Vz) -> the density
// `brdfcl sample` draws each L with (Evaluator::pdf), one `pdf` column, written atomically.
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
struct PdfArgs {
  std::string materials, samples, out, device, lobe = "all";
  ModelArgs model;
  bool strict = false;
};
}  // namespace

void addPdfCommand(CLI::App& app) {
  auto args = std::make_shared<PdfArgs>();
  auto* cmd = app.add_subcommand("pdf", "The density (solid angle of L) with which `brdfcl sample` draws L at V");
  cmd->add_option("--materials", args->materials, "glTF 2.0 JSON (or any JSON with a top-level materials array)")->required();
  cmd->add_option("--samples", args->samples, "eval's samples: CSV material,Lx,Ly,Lz,Vx,Vy,Vz or .npy (N,7); - reads stdin")
      ->required();
  cmd->add_option("--out", args->out, "output CSV with one column pdf, or .npy (N,1) float32; - writes CSV to stdout")
      ->required();
  addModelOptions(cmd, args->model);
  cmd->add_option("--lobe", args->lobe, "all|diffuse|specular|sheen|clearcoat: one lobe's sampler (default all)");
  cmd->add_flag("--strict", args->strict, "unknown keys and extensions in the materials file are errors, not warnings");
  cmd->add_option("--device", args->device, "device index or name substring (default $BRDFCL_DEVICE, then 0)");
  cmd->callback([args] {
    checkResultsPath("--out", args->out);
    checkDistinctFiles({{"--materials", args->materials, false}, {"--samples", args->samples, false}, {"--out", args->out, true}});
    EvalOptions o = modelOptions(args->model);
    o.lobe = parseLobe(args->lobe);
    const auto materials = readUserMaterials(args->materials, args->strict);
    const Samples samples = readSamples(args->samples, materials.size(), false);
    Runtime rt(args->device);
    Evaluator ev(rt, o);
    writeTable(args->out, {"pdf"}, ev.pdf(materials, samples));
  });
}

}  // namespace brdfcl::cli
