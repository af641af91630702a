// A batch of sampling rows resident on the device, launched again and again without copies: the
// throughput path of `brdfcl bench --op sample`, timed as the eval kernel's SoaBatch is. Internal
// to the library and the benchmarks (the public entry is Evaluator::sample).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "brdfcl/evaluator.hpp"

namespace brdfcl {

class SampleBatch {
 public:
  // n rows: view (3 floats a row, unit, N.V > 0), material (one index a row, or empty: material 0)
  // and u (3 floats a row in [0, 1)), checked as Evaluator::sample checks them, then uploaded once.
  // `evaluator` runs on `rt`.
  SampleBatch(Runtime& rt, Evaluator& evaluator, const std::vector<MaterialParams>& materials, const std::vector<float>& view,
              const std::vector<std::uint32_t>& material, const std::vector<float>& u);
  ~SampleBatch();
  SampleBatch(const SampleBatch&) = delete;
  SampleBatch& operator=(const SampleBatch&) = delete;
  std::size_t size() const;
  // One launch over every row, waited for; the rows (7 floats each) stay on the device.
  void run();
  // The last run's launch alone, from its profiling event (seconds).
  double lastKernelSeconds() const;
  // The rows of the last run (Lx Ly Lz pdf wr wg wb), read back.
  std::vector<float> read() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace brdfcl
