// Each evaluation path builds a program of eval.cl's kernels that it launches and no others (the
// sampler and the pdf none of them, and only their own of sample.cl's), the disk cache serves each
// path its own, and the paths agree to the bit.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "host/src/io/disk_cache.hpp"
#include "host/src/runtime/opencl.hpp"
#include "npy.hpp"
#include "process.hpp"
#include "scratch_cache_home.hpp"
#include "support.hpp"

using namespace brdfcl;
using brdfcl::test::ScratchCacheHome;
namespace fs = std::filesystem;

namespace {

const char* const kNoBinaries = "the device hands out no program binaries, so brdfcl caches none";

// Materials without sheen, so no path needs the sheen albedo table (whose bake would store a
// program of its own); clearcoat and anisotropy keep most of the model in the programs.
std::vector<MaterialParams> materials() {
  MaterialParams a, b;
  a.baseColor = {0.8f, 0.3f, 0.2f};
  a.roughness = 0.4f;
  a.clearcoat = 0.7f;
  a.clearcoatRoughness = 0.2f;
  b.baseColor = {0.5f, 0.5f, 0.6f};
  b.metallic = 0.6f;
  b.roughness = 0.25f;
  b.anisotropyStrength = 0.5f;
  b.anisotropyRotation = 1.1f;
  return {a, b};
}

// The kernels of every program stored in the cache at `dir`, a set a program.
std::vector<std::set<std::string>> storedPrograms(const fs::path& dir) {
  std::vector<std::set<std::string>> out;
  Runtime& rt = test::runtime();
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("program_", 0) != 0) continue;
    const std::string payload = detail::loadCachedPayload(name);
    if (payload.empty()) {
      ADD_FAILURE() << name << " is no valid cache entry";
      continue;
    }
    cl::Program::Binaries binaries{std::vector<unsigned char>(payload.begin(), payload.end())};
    const std::vector<cl::Device> devices{rt.opencl().device()};
    cl::Program program(rt.opencl().context(), devices, binaries);
    program.build(devices);
    std::set<std::string> kernels;
    std::istringstream names(program.getInfo<CL_PROGRAM_KERNEL_NAMES>());
    for (std::string k; std::getline(names, k, ';');) {
      while (!k.empty() && k.back() == '\0') k.pop_back();
      if (!k.empty()) kernels.insert(k);
    }
    out.push_back(std::move(kernels));
  }
  return out;
}

// A path of evaluation, run once on a fresh Runtime (and so a fresh program cache in memory).
struct Path {
  const char* name;
  std::set<std::string> kernels;  // what its program must hold
  std::vector<float> (*run)(Runtime& rt, const Samples& s);
};

std::vector<float> viaBatch(Runtime& rt, const Samples& s) {
  Evaluator ev(rt, EvalOptions{});
  SoaBatch batch(ev, materials(), s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      batch.direction(c)[i] = s.L[3 * i + std::size_t(c)];
      batch.direction(3 + c)[i] = s.V[3 * i + std::size_t(c)];
    }
    batch.materialIndex()[i] = s.material[i];
  }
  batch.setCount(s.size());
  batch.run();
  std::vector<float> rgb(3 * s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + std::size_t(c)] = batch.result(c)[i];
  return rgb;
}

std::vector<float> viaRows(Runtime& rt, const Samples& s) { return Evaluator(rt, EvalOptions{}).evaluate(materials(), s); }

// The file's layout, (count, 7) float rows: evaluated as NPY samples are.
std::vector<float> viaTable(Runtime& rt, const Samples& s) {
  std::vector<float> rows;
  for (std::size_t i = 0; i < s.size(); ++i) {
    rows.push_back(float(s.material[i]));
    rows.insert(rows.end(), s.L.begin() + std::ptrdiff_t(3 * i), s.L.begin() + std::ptrdiff_t(3 * i + 3));
    rows.insert(rows.end(), s.V.begin() + std::ptrdiff_t(3 * i), s.V.begin() + std::ptrdiff_t(3 * i + 3));
  }
  std::vector<float> rgb(3 * s.size());
  EXPECT_EQ(Evaluator(rt, EvalOptions{}).evaluateTableRows(materials(), rows.data(), s.size(), rgb.data()), s.size());
  return rgb;
}

// Each sample's own material's row of the grid.
std::vector<float> viaGrid(Runtime& rt, const Samples& s) {
  const std::vector<float> grid = Evaluator(rt, EvalOptions{}).evaluateGrid(materials(), s);
  std::vector<float> rgb(3 * s.size());
  for (std::size_t i = 0; i < s.size(); ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + std::size_t(c)] = grid[3 * (s.material[i] * s.size() + i) + std::size_t(c)];
  return rgb;
}

const std::vector<Path>& paths() {
  static const std::vector<Path> p = {
      {"batch", {"eval_samples"}, viaBatch},
      {"rows", {"eval_rows", "eval_rows_tail"}, viaRows},
      {"table", {"eval_table_rows", "eval_table_rows_tail"}, viaTable},
      {"grid", {"eval_grid_rows", "eval_grid_rows_tail"}, viaGrid},
  };
  return p;
}

// Unit directions in a count with a partial group at the end.
Samples samples() {
  std::mt19937_64 rng(test::seed() + 41);
  return test::randomSamples(rng, 1000 + 7, materials().size());
}

}  // namespace

// The program a path stores holds that path's entry points and none of the others'.
TEST(ProgramSets, EachPathStoresAProgramOfItsOwnKernels) {
  const Samples s = samples();
  for (const auto& path : paths()) {
    SCOPED_TRACE(path.name);
    test::ScratchDir dir(std::string("program-set-") + path.name);
    ScratchCacheHome home(dir);
    {
      Runtime rt;
      path.run(rt, s);
    }
    const auto stored = storedPrograms(dir.path("brdfcl"));
    if (stored.empty()) GTEST_SKIP() << kNoBinaries;
    ASSERT_EQ(stored.size(), 1u);
    EXPECT_EQ(stored[0], path.kernels);
  }
}

// Sampling and its pdf launch only sample.cl's kernels, each its own: no program of eval.cl is
// built for them, and neither loads the other's.
TEST(ProgramSets, SamplingAndPdfBuildOnlyTheirOwnKernels) {
  test::ScratchDir dir("program-set-sample");
  ScratchCacheHome home(dir);
  {
    Runtime rt;
    Evaluator ev(rt, EvalOptions{});
    const std::vector<float> view = {0.0f, 0.6f, 0.8f, 0.3f, 0.0f, 0.9f};
    const std::vector<float> u = {0.1f, 0.2f, 0.3f, 0.7f, 0.8f, 0.9f};
    EXPECT_EQ(ev.sample(materials(), {0, 1}, view, u).size(), 14u);
    Samples pairs;
    pairs.L = {0.0f, 0.0f, 1.0f, 0.6f, 0.0f, 0.8f};
    pairs.V = view;
    pairs.material = {0, 1};
    EXPECT_EQ(ev.pdf(materials(), pairs).size(), 2u);
  }
  const auto stored = storedPrograms(dir.path("brdfcl"));
  if (stored.empty()) GTEST_SKIP() << kNoBinaries;
  const std::set<std::set<std::string>> want = {{"sample_rows", "sample_rows_tail"}, {"pdf_rows", "pdf_rows_tail"}};
  EXPECT_EQ(std::set<std::set<std::string>>(stored.begin(), stored.end()), want);
  EXPECT_EQ(stored.size(), 2u);
}

// A second process's Runtime takes each path's program from the disk cache, builds nothing, and
// computes the same bits; every path computes the same bits as every other.
TEST(ProgramSets, TheCacheServesEachPathAndThePathsAgree) {
  const Samples s = samples();
  test::ScratchDir dir("program-set-warm");
  ScratchCacheHome home(dir);
  std::vector<std::vector<float>> cold;
  {
    Runtime rt;
    for (const auto& path : paths()) cold.push_back(path.run(rt, s));
    EXPECT_EQ(rt.programsFromDiskCache(), 0u);
  }
  const std::size_t stored = storedPrograms(dir.path("brdfcl")).size();
  if (stored == 0) GTEST_SKIP() << kNoBinaries;
  EXPECT_EQ(stored, paths().size());
  for (std::size_t k = 0; k < paths().size(); ++k) {
    SCOPED_TRACE(paths()[k].name);
    Runtime rt;
    const std::vector<float> warm = paths()[k].run(rt, s);
    EXPECT_EQ(rt.programsFromDiskCache(), 1u);
    ASSERT_EQ(warm.size(), cold[0].size());
    EXPECT_EQ(std::memcmp(warm.data(), cold[k].data(), warm.size() * sizeof(float)), 0);
    if (std::string(paths()[k].name) != "table")
      EXPECT_EQ(std::memcmp(warm.data(), cold[0].data(), warm.size() * sizeof(float)), 0) << "against the batch path";
  }
  // The table path normalizes as the readers do: it agrees with the rows path normalizing.
  Runtime rt;
  Evaluator::Rows rows{s.L.data(), s.V.data(), nullptr, s.size()};
  rows.index32 = s.material.data();
  std::vector<float> normalized(3 * s.size());
  EXPECT_EQ(Evaluator(rt, EvalOptions{}).evaluateRows(materials(), rows, normalized.data(), true), s.size());
  EXPECT_EQ(std::memcmp(normalized.data(), cold[2].data(), normalized.size() * sizeof(float)), 0);
}

// `brdfcl eval` of an NPY file builds the table kernels alone.
TEST(ProgramSets, NpyEvalStoresTheTableProgramAlone) {
  test::ScratchDir dir("program-set-cli");
  test::runtime();
  const Samples s = samples();
  std::vector<double> values;
  for (std::size_t i = 0; i < s.size(); ++i) {
    values.push_back(s.material[i]);
    for (int c = 0; c < 3; ++c) values.push_back(s.L[3 * i + std::size_t(c)]);
    for (int c = 0; c < 3; ++c) values.push_back(s.V[3 * i + std::size_t(c)]);
  }
  test::writeFile(dir.path("s.npy"), test::npyArray(values, 7, true));
  test::writeFile(dir.path("m.json"),
                  R"({"materials": [{"pbrMetallicRoughness": {"roughnessFactor": 0.4}, "extensions": )"
                  R"({"KHR_materials_clearcoat": {"clearcoatFactor": 0.7}}}, {"pbrMetallicRoughness": )"
                  R"({"metallicFactor": 0.6, "roughnessFactor": 0.25}}]})");
  test::ProcessOptions o;
  o.env = {{"XDG_CACHE_HOME", dir.dir()}, {"TMPDIR", dir.dir()}};
  if (const std::string pocl = test::poclCacheDir(); !pocl.empty()) o.env["POCL_CACHE_DIR"] = pocl;
  o.cwd = dir.dir();
  o.timeout = std::chrono::seconds(120);
  const test::RunResult r =
      test::runProcess({BRDFCL_CLI_PATH, "eval", "--materials", "m.json", "--samples", "s.npy", "--out", "o.npy"},
                       dir.dir(), o);
  ASSERT_EQ(r.status, 0) << r.describe();
  ScratchCacheHome home(dir);
  const auto stored = storedPrograms(dir.path("brdfcl"));
  if (stored.empty()) GTEST_SKIP() << kNoBinaries;
  ASSERT_EQ(stored.size(), 1u);
  EXPECT_EQ(stored[0], (std::set<std::string>{"eval_table_rows", "eval_table_rows_tail"}));
}
