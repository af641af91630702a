// `brdfcl bench --op sample`: the resident sampling batch it times (SampleBatch) writes the rows
// Evaluator::sample writes, the command reports the sampler's figures in JSON, with --pairs too
// (the Mitsuba peer's views), and its option errors are one line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "process.hpp"
#include "support.hpp"
#include "brdfcl/evaluator.hpp"
#include "host/src/eval/sample_batch.hpp"
#include "host/src/eval/workload.hpp"

using namespace brdfcl;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;
using brdfcl::test::runtime;

namespace {

RunResult cli(const ScratchDir& dir, std::vector<std::string> args) {
  args.insert(args.begin(), BRDFCL_CLI_PATH);
  brdfcl::test::ProcessOptions o;
  o.cwd = dir.dir();
  return brdfcl::test::runProcess(std::move(args), dir.dir(), o);
}

}  // namespace

TEST(BenchSample, ResidentBatchWritesTheRowsOfEvaluatorSample) {
  for (const std::string lobe : {"specular", "all"}) {
    const bench::Workload w = bench::makeWorkload(lobe, 1, 8);
    const std::size_t n = 3000;
    std::vector<float> view(3 * n), u(3 * n);
    std::vector<std::uint32_t> index(n);
    for (std::size_t i = 0; i < n; ++i) {
      const float z = 0.02f + 0.97f * float(i % 97) / 96.0f, phi = 0.71f * float(i), s = std::sqrt(1 - z * z);
      view[3 * i] = s * std::cos(phi), view[3 * i + 1] = s * std::sin(phi), view[3 * i + 2] = z;
      index[i] = std::uint32_t(i % 8);
    }
    Evaluator::drawUniforms(9, 0, n, u.data());
    Evaluator ev(runtime(), w.options);
    SampleBatch b(runtime(), ev, w.materials, view, index, u);
    b.run();
    b.run();  // a second launch over the same resident rows writes the same
    const std::vector<float> got = b.read();
    const std::vector<float> want = ev.sample(w.materials, index, view, u);
    ASSERT_EQ(got.size(), want.size());
    EXPECT_EQ(got, want) << lobe;
    EXPECT_GE(b.lastKernelSeconds(), 0.0);
  }
}

TEST(BenchSample, ReportsTheSamplerInJson) {
  ScratchDir dir("benchsample");
  for (const std::string lobe : {"specular", "all"}) {
    const RunResult r = cli(dir, {"bench", "--op", "sample", "--lobe", lobe, "--n", "4096", "--runs", "1", "--json"});
    ASSERT_EQ(r.status, 0) << r.describe();
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["op"], "sample");
    EXPECT_EQ(j["lobe"], lobe);
    EXPECT_EQ(j["n"], 4096);
    EXPECT_GT(j["samples_per_second"].get<double>(), 0.0);
    // GGX alone loses the directions reflected below the horizon; the mixture far fewer.
    const double kept = j["kept_fraction"].get<double>();
    EXPECT_GT(kept, lobe == "all" ? 0.9 : 0.6) << lobe;
    EXPECT_LE(kept, 1.0);
    EXPECT_TRUE(j.contains("material0"));
  }
}

TEST(BenchSample, TakesTheViewsOfAPairsFile) {
  ScratchDir dir("benchsamplepairs");
  const std::size_t n = 512;
  std::vector<float> planes(6 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d) {
      const float z = 0.1f + 0.8f * float(i) / float(n), phi = 0.3f * float(i) + float(d), s = std::sqrt(1 - z * z);
      planes[(3 * d) * n + i] = s * std::cos(phi);
      planes[(3 * d + 1) * n + i] = s * std::sin(phi);
      planes[(3 * d + 2) * n + i] = z;
    }
  brdfcl::test::writeFile(dir.path("pairs.f32"),
                          std::string(reinterpret_cast<const char*>(planes.data()), planes.size() * sizeof(float)));
  const RunResult r = cli(dir, {"bench", "--op", "sample", "--lobe", "specular", "--materials", "1", "--pairs",
                                "pairs.f32", "--runs", "1", "--json"});
  ASSERT_EQ(r.status, 0) << r.describe();
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["n"], n);
  EXPECT_EQ(j["materials"], 1);
}

TEST(BenchSample, BadOptionsAreOneLineErrors) {
  ScratchDir dir("benchsamplebad");
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{"bench", "--op", "trace"}, "brdfcl: --op 'trace' is not a benchmark operation; use eval or sample"},
      {{"bench", "--op", "sample", "--profile", "khronos"}, "brdfcl: --op sample times the spec's sampler; drop --profile"},
      {{"bench", "--op", "sample", "--pairs", "p.f32", "--sheen-e-out", "e.f32"},
       "brdfcl: --sheen-e-out goes with --op eval; drop it"},
  };
  brdfcl::test::writeFile(dir.path("p.f32"), std::string(24, '\0'));
  {
    // Refused before the rows are allocated: 2^23 is above every device's launch (at most 2^22 rows).
    const RunResult r = cli(dir, {"bench", "--op", "sample", "--n", "8388608", "--runs", "1"});
    EXPECT_EQ(r.status, 2) << r.describe();
    ASSERT_EQ(r.errorLines().size(), 1u) << r.describe();
    EXPECT_EQ(r.errorLines()[0].rfind("brdfcl: --op sample: 8388608 rows are more than one launch of the sampler takes on this device (", 0), 0u)
        << r.err;
  }
  for (const auto& c : cases) {
    const RunResult r = cli(dir, c.args);
    EXPECT_EQ(r.status, 2) << r.describe();
    const auto lines = r.errorLines();
    ASSERT_EQ(lines.size(), 1u) << r.describe();
    EXPECT_EQ(lines[0], c.message);
  }
}
