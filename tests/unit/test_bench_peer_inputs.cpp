// What `brdfcl bench --pairs` gives an outside peer of the same maths (bench/peers/drjit_peer.py):
// the material index of each pair (--indices), the sheen E table the kernel reads (--sheen-e-out)
// and every material in its JSON, and the one-line errors of those options.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "support.hpp"
#include "brdfcl/evaluator.hpp"
#include "host/src/eval/workload.hpp"

using namespace brdfcl;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::runtime;

namespace {

template <class T>
std::string bytesOf(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

// n in-domain pairs as six float32 planes (L.xyz, V.xyz), the layout of a --pairs file.
std::vector<float> pairPlanes(std::size_t n) {
  std::vector<float> p(6 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d) {
      const float z = 0.05f + 0.9f * float((i * 7 + 3 * d) % n) / float(n), phi = 0.37f * float(i) + 2.1f * float(d);
      const float s = std::sqrt(1.0f - z * z);
      p[(3 * d) * n + i] = s * std::cos(phi);
      p[(3 * d + 1) * n + i] = s * std::sin(phi);
      p[(3 * d + 2) * n + i] = z;
    }
  return p;
}

RunResult cli(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), BRDFCL_CLI_PATH);
  brdfcl::test::ProcessOptions o;
  o.timeout = std::chrono::seconds(180);
  return brdfcl::test::runProcess(std::move(args), dir.dir(), o);
}

void expectUserError(const RunResult& r, const std::string& message) {
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.err, "brdfcl: " + message + "\n");
}

}  // namespace

// The kernel gathers the materials the given indices name: its f equals Evaluator::evaluate's
// on the same pairs and indices (which the bench's own random indices would not give).
TEST(BenchPeerInputs, GivenIndicesPickTheKernelsMaterials) {
  const std::size_t n = 512, k = 4;
  bench::Bench b(runtime(), "all", n, 1, k);
  const std::vector<float> planes = pairPlanes(n);
  std::vector<std::uint32_t> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = std::uint32_t((i / 3 + i % 5) % k);
  b.setDirections(planes);
  b.setMaterialIndices(index);
  b.runKernel();
  Samples s;
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) s.L.push_back(planes[c * n + i]);
    for (int c = 0; c < 3; ++c) s.V.push_back(planes[(3 + c) * n + i]);
    s.material.push_back(index[i]);
  }
  Evaluator ev(runtime(), b.workload().options);
  const std::vector<float> want = ev.evaluate(b.workload().materials, s);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float got = b.batch().result(c)[i], w = want[3 * i + c];
      ASSERT_NEAR(got, w, 1e-4 * std::fabs(w) + 1e-6) << "pair " << i << ", channel " << c << ", material " << index[i];
    }
  EXPECT_THROW(b.setMaterialIndices(std::vector<std::uint32_t>(n, std::uint32_t(k))), Error);
  EXPECT_THROW(b.setMaterialIndices(std::vector<std::uint32_t>(n - 1, 0)), Error);
}

// --sheen-e-out writes the table the evaluator reads, and with --indices the JSON lists every material.
TEST(BenchPeerInputs, TheCliWritesTheSheenTableAndEveryMaterial) {
  ScratchDir dir("peer-inputs");
  const std::size_t n = 64, k = 3;
  brdfcl::test::writeFile(dir.path("pairs.f32"), bytesOf(pairPlanes(n)));
  std::vector<std::uint32_t> index(n);
  for (std::size_t i = 0; i < n; ++i) index[i] = std::uint32_t(i % k);
  brdfcl::test::writeFile(dir.path("index.u32"), bytesOf(index));
  const RunResult r = cli(dir, {"bench", "--lobe", "all", "--materials", std::to_string(k), "--pairs", dir.path("pairs.f32"),
                                "--indices", dir.path("index.u32"), "--sheen-e-out", dir.path("e.f32"), "--runs", "1",
                                "--json"});
  ASSERT_EQ(r.status, 0) << r.describe();
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("materials"), k);  // the count, as without --indices
  ASSERT_EQ(j.at("material_params").size(), k);
  EXPECT_EQ(j.at("material_params")[0], j.at("material0"));
  EXPECT_NE(j.at("material_params")[1], j.at("material_params")[0]);
  // Without --indices the run has no peer to feed: material0 alone.
  const RunResult plain = cli(dir, {"bench", "--lobe", "all", "--materials", std::to_string(k), "--pairs",
                                    dir.path("pairs.f32"), "--runs", "1", "--json"});
  ASSERT_EQ(plain.status, 0) << plain.describe();
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("material_params"));

  const std::string e = brdfcl::test::slurp(dir.path("e.f32"));
  Evaluator ev(runtime(), EvalOptions{});
  const SheenAlbedoTable& table = ev.sheenAlbedo();
  ASSERT_EQ(e.size(), table.values.size() * sizeof(float));
  std::vector<float> values(table.values.size());
  std::memcpy(values.data(), e.data(), e.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    ASSERT_NEAR(values[i], table.values[i], 1e-6) << "texel " << i;
}

TEST(BenchPeerInputs, BadIndicesAndTableOptionsAreOneLineErrors) {
  ScratchDir dir("peer-inputs-bad");
  const std::string pairs = dir.path("pairs.f32"), idx = dir.path("index.u32");
  brdfcl::test::writeFile(pairs, bytesOf(pairPlanes(4)));
  expectUserError(cli(dir, {"bench", "--indices", idx, "--runs", "1"}),
                  "--indices gives the material of each pair of --pairs; give --pairs FILE too");
  expectUserError(cli(dir, {"bench", "--sheen-e-out", dir.path("e.f32"), "--runs", "1"}),
                  "--sheen-e-out goes with --pairs, the outside peer's run; give --pairs FILE too");
  expectUserError(cli(dir, {"bench", "--pairs", pairs, "--indices", idx, "--runs", "1"}),
                  "--indices '" + idx + "': cannot read: No such file or directory");
  brdfcl::test::writeFile(idx, bytesOf(std::vector<std::uint32_t>{0, 0, 0}));
  expectUserError(cli(dir, {"bench", "--pairs", pairs, "--indices", idx, "--runs", "1"}),
                  "--indices '" + idx + "' holds 12 bytes; expected 4 uint32 material indices, one per pair of --pairs");
  brdfcl::test::writeFile(idx, bytesOf(std::vector<std::uint32_t>{0, 1, 2, 1}));
  expectUserError(cli(dir, {"bench", "--pairs", pairs, "--indices", idx, "--materials", "2", "--runs", "1"}),
                  "--indices '" + idx + "': pair 2 has material index 2, not below --materials 2");
  expectUserError(cli(dir, {"bench", "--pairs", pairs, "--sheen-e-out", pairs, "--runs", "1"}),
                  "--sheen-e-out '" + pairs + "' is the same file as --pairs '" + pairs + "'; write the output elsewhere");
  expectUserError(cli(dir, {"bench", "--pairs", pairs, "--sheen-e-out", dir.dir(), "--runs", "1"}),
                  "--sheen-e-out '" + dir.dir() + "': cannot write: it is a directory; name a file inside it");
  EXPECT_EQ(brdfcl::test::slurp(pairs), bytesOf(pairPlanes(4)));  // the input survives the refusal
}
