// Evaluation of sample files of any size: chunks are read, evaluated and written in turn, with
// the next chunk read and the previous one written while the device evaluates, so memory stays
// bounded by a few chunks and the output equals a one-shot run byte for byte.
#pragma once
#include <cstddef>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/io.hpp"

namespace brdfcl {

struct StreamOptions {
  static constexpr std::size_t kDefaultChunk = std::size_t(1) << 20;  // ~0.2 GiB in flight
  static constexpr std::size_t kMaxChunk = std::size_t(1) << 28;
  std::size_t chunk = kDefaultChunk;  // samples (grid: directions and output rows) per chunk
  bool grid = false;                  // every material x every direction, material-major
  // Grid only: evaluate materials [firstMaterial, firstMaterial + materialCount) of the list
  // (an mpirun rank's block); the kernels are still built for the whole list, so each row's
  // bytes are those of the whole grid.
  std::size_t firstMaterial = 0;
  std::size_t materialCount = static_cast<std::size_t>(-1);
  // Read the next chunk and write the previous one on their own threads while the device
  // evaluates (the default); false runs the three steps one after another on the calling thread,
  // which the benchmark BM_EvalFile measures against. The bytes written are the same.
  bool overlap = true;
};

struct StreamStats {
  std::size_t samples = 0;  // rows read from the file (each pass of a grid counted once)
  std::size_t rows = 0;     // rows written
  std::size_t chunks = 0;   // evaluations run
};

// Reads `samples` to the end, evaluates every chunk with `evaluator`, and appends the results to
// `out` in file order; the caller commits `out`. In grid mode, a direction file that fits in
// one chunk is read once and evaluated for blocks of materials; a larger one is read once per
// material. Throws the first error (a bad row, an OpenCL failure, a full disk); `out` is then
// left uncommitted, so no partial file appears. `chunk` must be 1 to kMaxChunk.
StreamStats evaluateStream(Evaluator& evaluator, const std::vector<MaterialParams>& materials,
                           SampleStream& samples, ResultWriter& out, const StreamOptions& options = {});

class MultiEvaluator;

// The same over several devices (device_set.hpp): each chunk is split across them, and the
// bytes written equal a single-device run's on devices of one kind.
StreamStats evaluateStream(MultiEvaluator& evaluator, const std::vector<MaterialParams>& materials,
                           SampleStream& samples, ResultWriter& out, const StreamOptions& options = {});

}  // namespace brdfcl
