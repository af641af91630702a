// Chunked, double-buffered evaluation of sample files (see brdfcl/stream.hpp): one thread reads
// the next chunk and another writes the previous results while this one drives the device.
#include "brdfcl/stream.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <future>
#include <stdexcept>
#include <string>

#include "devices/device_set.hpp"
#include "brdfcl/error.hpp"

namespace brdfcl {

namespace {

// One evaluation: directions (owned, or shared by the blocks of an in-memory grid) and the
// materials they meet: every material by index (batch) or the block [m0, m0 + mc) (grid).
struct Work {
  Samples samples;
  SampleStream::RawRows raw;  // instead of samples, where the device checks and normalizes rows
  const Samples* shared = nullptr;
  std::size_t m0 = 0, mc = 0;
  const Samples& directions() const { return shared ? *shared : samples; }
};

// How one chunk is evaluated: `batch` for samples, `grid` for the grid's material block, and
// `rows` (where set) for a file's raw rows: it returns the first bad row, or rows.count.
struct Evaluate {
  std::function<void(const Samples&, float*)> batch;
  std::function<std::vector<float>(const Samples&, std::size_t, std::size_t)> grid;
  std::function<std::size_t(const SampleStream::RawRows&, float*)> rows;
};

StreamStats stream(const std::vector<MaterialParams>& materials, SampleStream& samples, ResultWriter& out,
                   const StreamOptions& options, const std::function<Evaluate()>& prepare) {
  const std::size_t chunk = options.chunk;
  if (chunk < 1 || chunk > StreamOptions::kMaxChunk)
    throw Error("chunk of " + std::to_string(chunk) + " samples is out of range; use 1 to " +
                std::to_string(StreamOptions::kMaxChunk));
  if (materials.empty()) throw Error("no materials to evaluate");
  // Grid: the block of materials [mBegin, nm) this call evaluates.
  const std::size_t mBegin = options.grid ? std::min(options.firstMaterial, materials.size()) : 0;
  const std::size_t nm = options.grid ? mBegin + std::min(options.materialCount, materials.size() - mBegin)
                                      : materials.size();
  StreamStats stats;

  const Evaluate evaluate = prepare();
  // A float32 NPY goes to the device as the file holds it: no host pass over its rows.
  const bool raw = !options.grid && evaluate.rows && samples.hasRawRows();

  // What to evaluate next, filled on the reader thread; false when nothing is left.
  std::function<bool(Work&)> produce;
  Samples allDirections;  // an in-memory grid's directions
  std::size_t material = mBegin;
  if (raw) {
    produce = [&](Work& w) { return samples.nextRows(chunk, w.raw); };
  } else if (!options.grid) {
    produce = [&](Work& w) {
      w.m0 = 0;
      w.mc = nm;
      return samples.next(chunk, w.samples);
    };
  } else {
    Samples probe;
    samples.next(chunk, allDirections);
    if (!samples.next(chunk, probe)) {
      // Every direction fits in one chunk: blocks of materials whose output fits one chunk.
      const std::size_t block = std::max<std::size_t>(1, chunk / allDirections.size());
      produce = [&, block](Work& w) {
        if (material == nm) return false;
        w.shared = &allDirections;
        w.m0 = material;
        w.mc = std::min(block, nm - material);
        material += w.mc;
        return true;
      };
    } else {
      // Output is material-major, so the directions are read once per material.
      allDirections = Samples{};
      samples.rewind();
      produce = [&](Work& w) {
        while (material < nm) {
          if (samples.next(chunk, w.samples)) {
            w.m0 = material;
            w.mc = 1;
            return true;
          }
          if (++material < nm) samples.rewind();
        }
        return false;
      };
    }
  }

  // Two slots each: while slot k is evaluated, slot k+1 is read and the results of slot k-1
  // are written. Futures of std::async wait in their destructors, so an exception here never
  // leaves a thread touching a slot.
  // Deferred futures run at get(): the same code then reads, evaluates and writes in turn.
  const auto policy = options.overlap ? std::launch::async : std::launch::deferred;
  Work work[2];
  std::vector<float> rgb[2];
  // A file's raw rows' results, written by the device before they are read, each at the address
  // that makes the writer's appendInPlace write them without a copy: congruent to its offset in
  // the file modulo kInPlaceHeadroom, after that many bytes of headroom.
  ChunkVector<float> rawRgb[2];
  constexpr std::size_t kHead = ResultWriter::kInPlaceHeadroom;
  std::size_t fileOffset = out.appendOffset();
  std::future<bool> reading = std::async(policy, produce, std::ref(work[0]));
  std::future<void> writing;
  for (std::size_t k = 0;; ++k) {
    Work& w = work[k % 2];
    if (!reading.get()) break;
    reading = std::async(policy, produce, std::ref(work[(k + 1) % 2]));

    const Samples& dirs = w.directions();
    std::vector<float>& result = rgb[k % 2];
    std::size_t read = dirs.size();
    float* rows = nullptr;  // the results to write
    std::size_t count = 0;
    if (raw) {
      read = w.raw.count;
      ChunkVector<float>& f = rawRgb[k % 2];
      f.resize((2 * kHead + 12 * read) / sizeof(float));
      const std::size_t misalign = (fileOffset - reinterpret_cast<std::uintptr_t>(f.data())) % kHead;
      float* at = f.data() + (kHead + misalign) / sizeof(float);  // offsets are whole floats
      const std::size_t bad = evaluate.rows(w.raw, at);
      if (bad < read) samples.throwRowError(w.raw, bad);
      rows = at;
      count = read;
      fileOffset += 12 * read;
    } else {
      if (!options.grid) {
        result.resize(3 * dirs.size());
        evaluate.batch(dirs, result.data());
      } else {
        result = evaluate.grid(dirs, w.m0, w.mc);
      }
      rows = result.data();
      count = result.size() / 3;
    }
    if (!options.grid || w.m0 == mBegin) stats.samples += read;
    stats.rows += count;
    ++stats.chunks;

    if (writing.valid()) writing.get();  // frees slot (k + 1) % 2 for the next round
    writing = std::async(policy, [&out, rows, count, raw] {
      if (raw)
        out.appendInPlace(rows, count);
      else
        out.append(rows, count);
    });
  }
  if (writing.valid()) writing.get();
  return stats;
}

}  // namespace

StreamStats evaluateStream(Evaluator& evaluator, const std::vector<MaterialParams>& materials,
                           SampleStream& samples, ResultWriter& out, const StreamOptions& options) {
  return stream(materials, samples, out, options, [&] {
    return Evaluate{[&](const Samples& dirs, float* rgb) { evaluator.evaluate(materials, dirs, rgb); },
                    [&](const Samples& dirs, std::size_t m0, std::size_t mc) {
                      return evaluator.evaluateGrid(materials, dirs, m0, mc);
                    },
                    [&](const SampleStream::RawRows& rows, float* rgb) {
                      return evaluator.evaluateTableRows(materials, rows.data.data(), rows.count, rgb);
                    }};
  });
}

StreamStats evaluateStream(MultiEvaluator& evaluator, const std::vector<MaterialParams>& materials,
                           SampleStream& samples, ResultWriter& out, const StreamOptions& options) {
  std::shared_ptr<MultiEvaluator::Batches> batches;
  return stream(materials, samples, out, options, [&] {
    if (!options.grid) batches = std::make_shared<MultiEvaluator::Batches>(evaluator, materials);
    return Evaluate{[&](const Samples& dirs, float* rgb) { batches->evaluate(dirs, rgb); },
                    [&](const Samples& dirs, std::size_t m0, std::size_t mc) {
                      return evaluator.evaluateGrid(materials, dirs, m0, mc);
                    },
                    {}};
  });
}

}  // namespace brdfcl
