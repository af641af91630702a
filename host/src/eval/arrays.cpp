// evaluateArrays / evaluateGridArrays (brdfcl/arrays.hpp): float32 rows go to the row kernels
// where they lie, normalized and checked on the device (Evaluator::evaluateRows); float64 rows are
// checked and normalized a chunk at a time into a SoaBatch's planes (or a grid chunk), on several
// threads. Both use the samples readers' arithmetic (io/directions.hpp): the bits of `brdfcl eval`.
#include "brdfcl/arrays.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "io/directions.hpp"
#include "io/messages.hpp"
#include "io/rows.hpp"

namespace brdfcl {

namespace {

constexpr std::size_t kDefaultChunk = std::size_t(1) << 20;  // StreamOptions::kDefaultChunk, as the CLI

// Row i of a direction array, widened to double as the NPY reader widens each element.
inline void loadRow(const DirectionArray& a, std::size_t i, double* d) {
  if (a.type == DirectionArray::Type::Float32) {
    const float* p = static_cast<const float*>(a.data) + 3 * i;
    d[0] = p[0], d[1] = p[1], d[2] = p[2];
  } else {
    const double* p = static_cast<const double*>(a.data) + 3 * i;
    d[0] = p[0], d[1] = p[1], d[2] = p[2];
  }
}

// The first problem of one worker's rows (the readers' wording, row numbers 0-based).
struct RowError {
  std::size_t row = 0;
  std::string message;
};

// Where normalized rows go: six planes (step 1, a SoaBatch) or two interleaved arrays (step 3,
// Lx = L, Ly = L + 1 ...), and the material indices when they are checked.
struct Dest {
  float* L[3];
  float* V[3];
  std::size_t step = 1;
  std::uint32_t* index = nullptr;
};

// Rows [row, row + n) of one direction array into dest's three outputs from `at`: the vectorized
// run; returns the rows it left undone.
std::size_t fastDirections(const DirectionArray& a, std::size_t row, std::size_t n, float* const* out, std::size_t step,
                           std::size_t at) {
  if (a.type == DirectionArray::Type::Float32) {
    const float* p = static_cast<const float*>(a.data) + 3 * row;
    return step == 1 ? detail::normalizeToPlanes(p, 3, n, out[0] + at, out[1] + at, out[2] + at)
                     : detail::normalizeToRows(p, 3, n, out[0] + 3 * at);
  }
  const double* p = static_cast<const double*>(a.data) + 3 * row;
  return step == 1 ? detail::normalizeToPlanes(p, 3, n, out[0] + at, out[1] + at, out[2] + at)
                   : detail::normalizeToRows(p, 3, n, out[0] + 3 * at);
}

// Checks and normalizes rows [first, first + count) into dest (positions relative to first),
// on several threads, a block at a time: the vectorized runs first, and only a block where they
// leave a row undone goes row by row, to word the problem or rescale an extreme vector (the
// same bits either way); throws the lowest row's problem.
void normalizeRows(const ArraySamples& s, std::size_t first, std::size_t count, std::size_t materialCount,
                   const Dest& dest) {
  static const char* const kNames[6] = {"Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  constexpr std::size_t kBlock = 4096;
  const std::size_t workers = detail::workerCount(count * 48);
  std::vector<RowError> errors(workers);
  auto slowRow = [&](std::size_t k, RowError& error) {
    const std::size_t row = first + k;
    double d[6];
    loadRow(s.L, row, d);
    loadRow(s.V, row, d + 3);
    auto fail = [&](std::string m) {
      error.row = row;
      error.message = std::move(m);
      return false;
    };
    if (dest.index && s.material) {
      const std::int64_t m = s.material[row];
      if (m < 0) return fail(fmt::format("material index {} is not a non-negative integer", m));
      if (std::uint64_t(m) >= materialCount)
        return fail(fmt::format("material index {} out of range ({} {})", m, materialCount,
                                materialCount == 1 ? "material" : "materials"));
    }
    for (int c = 0; c < 6; ++c)
      if (!std::isfinite(d[c]))
        return fail(std::string("field '") + kNames[c] + "' is not finite: " + detail::formatNumber(d[c]));
    float L[3], V[3];
    if (!normalizeDirection(d, L)) return fail("L has zero length");
    if (!normalizeDirection(d + 3, V)) return fail("V has zero length");
    for (int c = 0; c < 3; ++c) {
      dest.L[c][k * dest.step] = L[c];
      dest.V[c][k * dest.step] = V[c];
    }
    if (dest.index) dest.index[k] = s.material ? std::uint32_t(s.material[row]) : 0u;
    return true;
  };
  detail::parallelFor(workers, [&](std::size_t w) {
    const std::size_t begin = count * w / workers, end = count * (w + 1) / workers;
    for (std::size_t b = begin; b < end; b += kBlock) {
      const std::size_t n = std::min(kBlock, end - b);
      std::size_t undone = fastDirections(s.L, first + b, n, dest.L, dest.step, b) +
                           fastDirections(s.V, first + b, n, dest.V, dest.step, b);
      if (dest.index) {
        std::uint32_t* index = dest.index + b;
        if (s.material) {
          const std::int64_t* m = s.material + first + b;
          const std::int64_t limit = std::int64_t(std::min<std::size_t>(materialCount, INT64_MAX));
          for (std::size_t i = 0; i < n; ++i) {
            index[i] = std::uint32_t(m[i]);
            undone += (m[i] >= 0 && m[i] < limit) ? 0 : 1;
          }
        } else {
          std::fill(index, index + n, 0u);
        }
      }
      if (undone == 0) continue;
      for (std::size_t k = b; k < b + n; ++k)
        if (!slowRow(k, errors[w])) return;
    }
  });
  for (const auto& e : errors)  // workers hold ascending ranges: the first error is the lowest row
    if (!e.message.empty()) throw Error(fmt::format("row {}: {}", e.row, e.message));
}

void checkArrays(const ArraySamples& s) {
  if (s.count > 0 && (!s.L.data || !s.V.data)) throw Error("internal: direction arrays without data", 3);
}

bool bothFloat32(const ArraySamples& s) {
  return s.L.type == DirectionArray::Type::Float32 && s.V.type == DirectionArray::Type::Float32;
}

// The device found row `bad` wanting: the host check of that one row words the problem.
void throwBadRow(const ArraySamples& s, std::size_t bad, std::size_t materialCount, bool withIndex) {
  float L[3], V[3];
  std::uint32_t index = 0;
  normalizeRows(s, bad, 1, materialCount, Dest{{L, L + 1, L + 2}, {V, V + 1, V + 2}, 3, withIndex ? &index : nullptr});
  throw Error(fmt::format("internal: row {} reported as bad by the device", bad), 3);
}

}  // namespace

void evaluateArrays(Evaluator& evaluator, const std::vector<MaterialParams>& materials, const ArraySamples& s,
                    float* rgb, std::size_t chunk) {
  checkArrays(s);
  if (materials.empty()) throw Error("no materials to evaluate");
  if (!s.material && materials.size() != 1)
    throw Error(fmt::format("{} materials but no material index; give one index per sample", materials.size()));
  if (bothFloat32(s)) {
    const Evaluator::Rows rows{static_cast<const float*>(s.L.data), static_cast<const float*>(s.V.data), s.material,
                               s.count, chunk};
    const std::size_t bad = evaluator.evaluateRows(materials, rows, rgb, true);
    if (bad < s.count) throwBadRow(s, bad, materials.size(), true);
    return;
  }
  if (chunk == 0) chunk = kDefaultChunk;
  // Two batches in turn: the host checks and normalizes chunk k + 1 into one while the device
  // evaluates chunk k in the other, so neither waits for the other to wake up.
  const std::size_t capacity = std::min(std::max<std::size_t>(std::min(chunk, s.count), 1), evaluator.launchLimit());
  SoaBatch first(evaluator, materials, capacity, SoaBatch::Scratch{});
  std::unique_ptr<SoaBatch> second;
  if (s.count > first.capacity()) second = std::make_unique<SoaBatch>(evaluator, materials, capacity, SoaBatch::Scratch{});
  SoaBatch* batches[2] = {&first, second.get()};
  const std::size_t cap = first.capacity();
  auto fill = [&](SoaBatch& batch, std::size_t begin) {
    const std::size_t count = std::min(cap, s.count - begin);
    float* planes[6];
    for (int k = 0; k < 6; ++k) planes[k] = batch.direction(k);
    std::uint32_t* index = batch.materialIndex();
    // Clear what a previous, longer run left behind past `count` (padding lanes give f = 0).
    if (count < cap) {
      for (auto* p : planes) std::fill(p + count, p + cap, 0.0f);
      std::fill(index + count, index + cap, 0u);
    }
    normalizeRows(s, begin, count, materials.size(),
                  Dest{{planes[0], planes[1], planes[2]}, {planes[3], planes[4], planes[5]}, 1, index});
    batch.setCount(count);
  };
  if (s.count == 0) return;
  fill(first, 0);
  first.start();
  for (std::size_t begin = 0, k = 0; begin < s.count; begin += cap, ++k) {
    SoaBatch& current = *batches[k % 2];
    const std::size_t next = begin + cap;
    if (next < s.count) fill(*batches[(k + 1) % 2], next);  // a bad row throws; the destructors wait
    current.finish();
    if (next < s.count) batches[(k + 1) % 2]->start();
    const std::size_t count = current.count();
    const float* r[3] = {current.result(0), current.result(1), current.result(2)};
    float* out = rgb + 3 * begin;
    for (std::size_t i = 0; i < count; ++i) {
      out[3 * i] = r[0][i];
      out[3 * i + 1] = r[1][i];
      out[3 * i + 2] = r[2][i];
    }
  }
}

void evaluateGridArrays(Evaluator& evaluator, const std::vector<MaterialParams>& materials, const ArraySamples& s,
                        float* rgb, std::size_t chunk) {
  checkArrays(s);
  if (materials.empty()) throw Error("no materials to evaluate");
  const std::size_t n = s.count, nm = materials.size();
  if (bothFloat32(s)) {
    const Evaluator::Rows rows{static_cast<const float*>(s.L.data), static_cast<const float*>(s.V.data), nullptr, n, chunk};
    const std::size_t bad = evaluator.evaluateGridRows(materials, rows, rgb, true, 0, nm);
    if (bad < n) throwBadRow(s, bad, nm, false);
    return;
  }
  if (chunk == 0) chunk = kDefaultChunk;
  Samples dirs;
  for (std::size_t first = 0; first < n; first += chunk) {
    const std::size_t count = std::min(chunk, n - first);
    dirs.L.resize(3 * count);
    dirs.V.resize(3 * count);
    float* L = dirs.L.data();
    float* V = dirs.V.data();
    normalizeRows(s, first, count, nm, Dest{{L, L + 1, L + 2}, {V, V + 1, V + 2}, 3, nullptr});
    // Every material's rows of this chunk of directions: bit-identical to the whole grid's.
    const std::vector<float> part = evaluator.evaluateGrid(materials, dirs);
    for (std::size_t m = 0; m < nm; ++m)
      std::copy(part.begin() + std::ptrdiff_t(3 * m * count), part.begin() + std::ptrdiff_t(3 * (m + 1) * count),
                rgb + 3 * (m * n + first));
  }
}

}  // namespace brdfcl
