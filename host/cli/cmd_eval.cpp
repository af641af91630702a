// `brdfcl eval`: materials JSON + samples CSV/NPY -> f(L, V) per sample (or per material x
// direction with --grid), streamed in chunks of --chunk samples and written atomically as CSV/NPY.
// Under mpirun, each rank evaluates a contiguous share of the rows (of the materials with --grid)
// and the ranks write the one output file together.
#include <sys/stat.h>

#include <cstdio>
#include <memory>
#include <string>

#include "host/src/devices/device_set.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/evaluator.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/stream.hpp"
#include "commands.hpp"
#include "host/src/io/output.hpp"
#include "host/src/mpi/session.hpp"
#include "host/src/mpi/shared_output.hpp"
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

// --device all or a list (0,2): every chunk split across the devices (devices/device_set.hpp).
void evaluateOnDevices(const std::string& devices, const EvalOptions& o, const std::vector<MaterialParams>& materials,
                       SampleStream& samples, const std::string& outPath, const StreamOptions& so) {
  DeviceSet set(devices);
  MultiEvaluator evaluator(set, o);
  ResultWriter out(outPath);
  evaluateStream(evaluator, materials, samples, out, so);
  out.commit();
}

// The run of one rank of an mpirun job: the same checks, reads and kernels as one process, on
// this rank's share, into a local part file that writeShared puts at its place in --out. Every
// step that can fail on one rank runs inside together(), so all ranks stop at the same point.
void evalAcrossRanks(const EvalArgs& args, const EvalOptions& o) {
  mpi::Session& session = mpi::Session::get();
  std::vector<MaterialParams> materials;
  std::unique_ptr<SampleStream> samples;
  std::string part;
  struct RemovePart {
    std::string& path;
    ~RemovePart() {
      if (!path.empty()) detail::removeTemporary(path);
    }
  } removePart{part};
  std::uint64_t rows = 0, bytes = 0;
  const std::string format = detail::outputExtension(args.out, detail::resolveOutput(args.out));
  session.together([&] {
    mpi::checkSharedOutput("--out", args.out);
    if (args.samples == "-")  // mpirun gives stdin to rank 0 only
      throw Error("--samples -: under mpirun only rank 0 can read stdin; give the samples as a file every rank can read");
    materials = readUserMaterials(args.materials, args.strict);
    samples = std::make_unique<SampleStream>(args.samples, args.grid ? 0 : materials.size(), args.grid);
  });
  session.together([&] {
    StreamOptions so;
    so.chunk = static_cast<std::size_t>(args.chunk);
    so.grid = args.grid;
    // Rows of the file (materials with --grid) in contiguous shares, in rank order. With none
    // at all, every rank reads the whole input and meets the one-process error.
    bool work = true;
    if (args.grid && !materials.empty()) {
      const mpi::Share share = mpi::shareOf(materials.size(), session.rank(), session.size());
      so.firstMaterial = share.begin;
      so.materialCount = share.count();
      work = share.count() > 0;
    } else if (!args.grid) {
      const std::size_t total = samples->countRows();
      const mpi::Share share = mpi::shareOf(total, session.rank(), session.size());
      if (total > 0 && share.count() > 0) samples->selectRows(share.begin, share.count());
      work = total == 0 || share.count() > 0;
    }
    if (!work) return;
    Runtime rt(mpi::deviceSelector(args.device));
    Evaluator evaluator(rt, o);
    part = detail::createSpool(args.out);
    ResultWriter out(part, format, false);
    rows = evaluateStream(evaluator, materials, *samples, out, so).rows;
    out.commit();
    struct stat st {};
    if (::stat(part.c_str(), &st) != 0) throw Error("cannot read this rank's part of '" + args.out + "'");
    bytes = static_cast<std::uint64_t>(st.st_size);
  });
  std::uint64_t total = 0;
  session.exclusivePrefixSum(rows, &total);
  const std::string header = format == ".npy" ? detail::npyHeader(total, 3) : "r,g,b\n";
  mpi::writeShared(args.out, header, part, bytes);
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
  cmd->add_option("--lobe", args->lobe, "all|diffuse|specular|sheen|clearcoat (default all; every profile defines its lobes, docs/model.md)");
  cmd->add_flag("--grid", args->grid, "every material x every direction pair, material-major");
  cmd->add_flag("--strict", args->strict,
                "unknown keys and extensions in the materials file are errors, not warnings");
  cmd->add_option("--chunk", args->chunk,
                  "samples per chunk (default " + std::to_string(StreamOptions::kDefaultChunk) +
                      "); memory stays bounded by a few chunks whatever the file size");
  cmd->add_option("--device", args->device,
                  "device index or name substring (default $BRDFCL_DEVICE, then 0; under mpirun the node-local rank "
                  "modulo the device count), or all, or a list such as 0,2 to split the work across devices");
  cmd->callback([args] {
    checkResultsPath("--out", args->out);
    checkDistinctFiles({{"--materials", args->materials, false}, {"--samples", args->samples, false}, {"--out", args->out, true}});
    EvalOptions o = modelOptions(args->model);
    o.lobe = parseLobe(args->lobe);
    if (args->chunk < 1 || args->chunk > static_cast<long long>(StreamOptions::kMaxChunk))
      throw Error("--chunk " + std::to_string(args->chunk) + " is out of range; use 1 to " +
                  std::to_string(StreamOptions::kMaxChunk));
    if (mpi::Session::get().parallel()) {
      evalAcrossRanks(*args, o);
      return;
    }
    auto materials = readUserMaterials(args->materials, args->strict);
    // The header is checked before the device is set up; rows are checked as they stream.
    SampleStream samples(args->samples, args->grid ? 0 : materials.size(), args->grid);
    StreamOptions so;
    so.chunk = static_cast<std::size_t>(args->chunk);
    so.grid = args->grid;
    if (isDeviceList(args->device)) return evaluateOnDevices(args->device, o, materials, samples, args->out, so);
    // The first chunk is read while the device opens, which takes one core for tens of ms.
    if (!so.grid) samples.readAhead(so.chunk);
    Runtime rt(args->device);
    Evaluator evaluator(rt, o);
    ResultWriter out(args->out);
    evaluateStream(evaluator, materials, samples, out, so);
    out.commit();
  });
}

}  // namespace brdfcl::cli
