// Concurrent evaluation on one Runtime: N threads x M batches (per-sample, grid and SoaBatch
// launches with varying options) must give bit-for-bit the results of the same batches run one
// after another, whether each thread has its own Evaluator or all share one. See the thread
// safety notes in brdfcl/runtime.hpp and brdfcl/evaluator.hpp.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <exception>
#include <random>
#include <thread>
#include <vector>

#include "support.hpp"

namespace brdfcl::test {
namespace {

constexpr int kThreads = 4;
constexpr int kBatchesPerThread = 6;
constexpr std::size_t kSamples = 5000;
constexpr std::size_t kMaterials = 32;
constexpr std::size_t kGridDirections = 160;  // x 32 materials = 5,120 results

const std::vector<EvalOptions>& optionSets() {
  static const std::vector<EvalOptions> sets = {
      {SheenVisibility::Charlie, SheenDistribution::Charlie, SheenScaling::Min, Lobe::All},
      {SheenVisibility::Ashikhmin, SheenDistribution::Ashikhmin, SheenScaling::View, Lobe::All},
      {SheenVisibility::Charlie, SheenDistribution::Charlie, SheenScaling::None, Lobe::Specular},
  };
  return sets;
}

enum class Kind { Samples, Grid, Soa };

struct Job {
  Kind kind;
  std::size_t options;  // index into optionSets()
  std::vector<MaterialParams> materials;
  Samples samples;
};

// Job j's inputs depend on j alone, so serial and threaded runs see the same batches.
Job makeJob(int j) {
  std::mt19937_64 rng(seed() * 1000003ull + std::uint64_t(j));
  Job job;
  job.kind = Kind(j % 3);
  job.options = std::size_t(j / 3) % optionSets().size();
  for (std::size_t m = 0; m < kMaterials; ++m) job.materials.push_back(randomMaterial(rng));
  job.samples = randomSamples(rng, job.kind == Kind::Grid ? kGridDirections : kSamples + std::size_t(j) * 37,
                              job.kind == Kind::Grid ? 0 : kMaterials);
  return job;
}

// Fills a SoaBatch in two halves and runs it twice, as the throughput path's users do.
std::vector<float> runSoa(Evaluator& ev, const Job& job) {
  const Samples& s = job.samples;
  const std::size_t n = s.size();
  SoaBatch batch(ev, job.materials, n);
  std::vector<float> rgb(3 * n);
  const std::size_t half = n / 2;
  for (const auto& [first, count] : {std::pair{std::size_t(0), half}, std::pair{half, n - half}}) {
    float* planes[6];
    for (int k = 0; k < 6; ++k) planes[k] = batch.direction(k);
    std::uint32_t* index = batch.materialIndex();
    for (std::size_t i = 0; i < batch.capacity(); ++i) {
      for (int c = 0; c < 3; ++c) {
        planes[c][i] = i < count ? s.L[3 * (first + i) + c] : 0.0f;
        planes[3 + c][i] = i < count ? s.V[3 * (first + i) + c] : 0.0f;
      }
      index[i] = i < count ? s.material[first + i] : 0u;
    }
    batch.setCount(count);
    batch.run();
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < count; ++i) rgb[3 * (first + i) + c] = batch.result(c)[i];
  }
  return rgb;
}

std::vector<float> runJob(Evaluator& ev, const Job& job) {
  switch (job.kind) {
    case Kind::Samples: return ev.evaluate(job.materials, job.samples);
    case Kind::Grid: return ev.evaluateGrid(job.materials, job.samples);
    case Kind::Soa: return runSoa(ev, job);
  }
  return {};
}

// First difference as a readable message, or "" when the two are bit-for-bit equal.
std::string compareBits(const std::vector<float>& got, const std::vector<float>& want) {
  if (got.size() != want.size())
    return "size " + std::to_string(got.size()) + " != " + std::to_string(want.size());
  if (std::memcmp(got.data(), want.data(), got.size() * sizeof(float)) == 0) return "";
  for (std::size_t i = 0; i < got.size(); ++i)
    if (std::memcmp(&got[i], &want[i], sizeof(float)) != 0) {
      std::ostringstream o;
      o.precision(9);
      o << "value " << i << ": " << got[i] << " vs serial " << want[i];
      return o.str();
    }
  return "";
}

// Runs body(t) on kThreads threads released together; rethrows the first exception.
template <class Body>
void runThreads(Body&& body) {
  std::atomic<int> ready{0};
  std::vector<std::exception_ptr> errors(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      ready.fetch_add(1);
      while (ready.load() < kThreads) std::this_thread::yield();
      try {
        body(t);
      } catch (...) {
        errors[t] = std::current_exception();
      }
    });
  for (auto& th : threads) th.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
}

struct Fixture {
  std::vector<Job> jobs;
  std::vector<std::vector<float>> serial;
};

// All jobs run serially once (this also builds every program variant and the sheen tables).
const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture x;
    for (int j = 0; j < kThreads * kBatchesPerThread; ++j) {
      x.jobs.push_back(makeJob(j));
      Evaluator ev(runtime(), optionSets()[x.jobs.back().options]);
      x.serial.push_back(runJob(ev, x.jobs.back()));
    }
    return x;
  }();
  return f;
}

void expectMatchesSerial(const std::vector<std::vector<float>>& results) {
  const auto& f = fixture();
  for (std::size_t j = 0; j < f.jobs.size(); ++j) {
    SCOPED_TRACE("job " + std::to_string(j) + " (kind " + std::to_string(int(f.jobs[j].kind)) + ", " +
                 describeOptions(optionSets()[f.jobs[j].options]) + "), seed " + std::to_string(seed()));
    EXPECT_EQ(compareBits(results[j], f.serial[j]), "");
  }
}

TEST(Threads, SerialRunIsDeterministic) {
  const auto& f = fixture();
  std::vector<std::vector<float>> again;
  for (const auto& job : f.jobs) {
    Evaluator ev(runtime(), optionSets()[job.options]);
    again.push_back(runJob(ev, job));
  }
  expectMatchesSerial(again);
}

// Thread t runs jobs t, t + kThreads, ...: each thread mixes kinds and options.
TEST(Threads, OwnEvaluatorPerThreadMatchesSerial) {
  const auto& f = fixture();
  std::vector<std::vector<float>> results(f.jobs.size());
  runThreads([&](int t) {
    for (std::size_t j = std::size_t(t); j < f.jobs.size(); j += kThreads) {
      Evaluator ev(runtime(), optionSets()[f.jobs[j].options]);
      results[j] = runJob(ev, f.jobs[j]);
    }
  });
  expectMatchesSerial(results);
}

// One Evaluator per option set, shared by every thread, created fresh so that the threads race
// for the lazy sheen table as well.
TEST(Threads, SharedEvaluatorMatchesSerial) {
  const auto& f = fixture();
  std::vector<std::unique_ptr<Evaluator>> shared;
  for (const auto& o : optionSets()) shared.push_back(std::make_unique<Evaluator>(runtime(), o));
  std::vector<std::vector<float>> results(f.jobs.size());
  std::vector<const SheenAlbedoTable*> tables(kThreads);
  runThreads([&](int t) {
    tables[t] = &shared[std::size_t(t) % shared.size()]->sheenAlbedo();
    for (std::size_t j = std::size_t(t); j < f.jobs.size(); j += kThreads)
      results[j] = runJob(*shared[f.jobs[j].options], f.jobs[j]);
  });
  expectMatchesSerial(results);
  for (int t = 0; t < kThreads; ++t)
    EXPECT_EQ(tables[t], &shared[std::size_t(t) % shared.size()]->sheenAlbedo()) << "table baked twice";
}

// A fresh Runtime and Evaluator: every thread's first call races for the same program build
// and the same lazily loaded sheen table.
TEST(Threads, FreshRuntimeConcurrentFirstUse) {
  const auto& f = fixture();
  Runtime rt;
  Evaluator ev(rt, optionSets()[0]);
  std::vector<std::size_t> mine;
  for (std::size_t j = 0; j < f.jobs.size(); ++j)
    if (f.jobs[j].options == 0 && f.jobs[j].kind == Kind::Samples) mine.push_back(j);
  ASSERT_FALSE(mine.empty());
  std::vector<std::vector<float>> results(kThreads);
  runThreads([&](int t) { results[t] = runJob(ev, f.jobs[mine[std::size_t(t) % mine.size()]]); });
  for (int t = 0; t < kThreads; ++t) {
    SCOPED_TRACE("thread " + std::to_string(t) + ", seed " + std::to_string(seed()));
    EXPECT_EQ(compareBits(results[t], f.serial[mine[std::size_t(t) % mine.size()]]), "");
  }
}

}  // namespace
}  // namespace brdfcl::test
