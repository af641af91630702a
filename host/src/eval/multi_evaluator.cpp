// MultiEvaluator: Evaluator's batch and grid evaluation with each batch split across the
// devices of a DeviceSet (samples by range; grid rows by material, or directions for one row).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "devices/device_set.hpp"
#include "brdfcl/error.hpp"
#include "eval/material_range.hpp"

namespace brdfcl {

namespace {
constexpr std::size_t kGrain = SoaBatch::kLanes;

// The checks Evaluator makes, made here on the whole batch so that a message names the sample's
// index in the caller's batch, not in one device's range.
void checkSamples(const Samples& s, std::size_t materialCount, bool indexes) {
  static const char* const kNames[6] = {"Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (indexes && s.material[i] >= materialCount)
      throw Error(fmt::format("sample {}: material index {} out of range ({} materials)", i, s.material[i], materialCount));
    for (int k = 0; k < 6; ++k) {
      const float v = k < 3 ? s.L[3 * i + k] : s.V[3 * i + k - 3];
      if (!std::isfinite(v))
        throw Error(fmt::format("sample {}: {} is not finite: {}", i, kNames[k], std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"));
    }
  }
}

Samples slice(const Samples& s, std::size_t first, std::size_t count) {
  Samples out;
  if (!s.material.empty()) out.material.assign(s.material.begin() + first, s.material.begin() + first + count);
  out.L.assign(s.L.begin() + 3 * first, s.L.begin() + 3 * (first + count));
  out.V.assign(s.V.begin() + 3 * first, s.V.begin() + 3 * (first + count));
  return out;
}

// Samples [first, first + count) of a checked batch on one device, read and written in place by
// the row kernel (no slice, no result copy).
void evaluateRange(Evaluator& ev, const std::vector<MaterialParams>& materials, const Samples& s, std::size_t first,
                   std::size_t count, float* rgb) {
  Evaluator::Rows rows{s.L.data() + 3 * first, s.V.data() + 3 * first, nullptr, count};
  rows.index32 = s.material.data() + first;
  if (ev.evaluateRows(materials, rows, rgb + 3 * first, false) != count)
    throw Error(fmt::format("internal: a checked sample in [{}, {}) reported as bad", first, first + count), 3);
}
}  // namespace

MultiEvaluator::MultiEvaluator(DeviceSet& devices, EvalOptions options) : devices_(devices), options_(options) {
  for (std::size_t k = 0; k < devices.size(); ++k)
    evaluators_.push_back(std::make_unique<Evaluator>(devices.runtime(k), options));
}

MultiEvaluator::~MultiEvaluator() = default;

std::vector<float> MultiEvaluator::evaluate(const std::vector<MaterialParams>& materials, const Samples& samples) {
  if (samples.material.size() != samples.size())
    throw Error(fmt::format("internal: {} material indices for {} samples", samples.material.size(), samples.size()), 3);
  if (materials.empty()) throw Error("no materials to evaluate");
  checkSamples(samples, materials.size(), true);
  std::vector<float> rgb(3 * samples.size());
  devices_.run(samples.size(), kGrain, [&](std::size_t k, std::size_t first, std::size_t count) {
    evaluateRange(*evaluators_[k], materials, samples, first, count, rgb.data());
  });
  // An empty batch runs nothing, but its materials are still checked, as Evaluator does.
  if (samples.size() == 0) evaluators_[0]->evaluate(materials, samples);
  return rgb;
}

std::vector<float> MultiEvaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples) {
  return evaluateGrid(materials, samples, 0, materials.size());
}

std::vector<float> MultiEvaluator::evaluateGrid(const std::vector<MaterialParams>& materials, const Samples& samples,
                                                std::size_t firstMaterial, std::size_t materialCount) {
  checkMaterialRange(firstMaterial, materialCount, materials.size());
  checkSamples(samples, materials.size(), false);
  const std::size_t n = samples.size();
  std::vector<float> rgb(3 * n * materialCount);
  if (n == 0 || materialCount == 0 || devices_.size() == 1)
    return evaluators_[0]->evaluateGrid(materials, samples, firstMaterial, materialCount);
  if (materialCount >= devices_.size()) {
    // Whole rows per device: each row is bit-identical to that row of the whole grid.
    devices_.run(materialCount, 1, [&](std::size_t k, std::size_t first, std::size_t count) {
      evaluators_[k]->evaluateGrid(materials, samples, firstMaterial + first, count, rgb.data() + 3 * n * first);
    });
  } else {
    // Fewer rows than devices (a direction file read once per material): split the directions.
    devices_.run(n, kGrain, [&](std::size_t k, std::size_t first, std::size_t count) {
      const auto part = evaluators_[k]->evaluateGrid(materials, slice(samples, first, count), firstMaterial, materialCount);
      for (std::size_t m = 0; m < materialCount; ++m)
        std::copy(part.begin() + std::ptrdiff_t(3 * m * count), part.begin() + std::ptrdiff_t(3 * (m + 1) * count),
                  rgb.begin() + std::ptrdiff_t(3 * (m * n + first)));
    });
  }
  return rgb;
}

MultiEvaluator::Batches::Batches(MultiEvaluator& multi, const std::vector<MaterialParams>& materials)
    : multi_(multi), materials_(materials) {
  // Checks the materials and builds every device's program now, as a batch of one sample does.
  for (auto& ev : multi.evaluators_) SoaBatch(*ev, materials, 1);
}

MultiEvaluator::Batches::~Batches() = default;

void MultiEvaluator::Batches::evaluate(const Samples& samples, float* rgb) {
  checkSamples(samples, materials_.size(), true);
  multi_.devices_.run(samples.size(), kGrain, [&](std::size_t k, std::size_t first, std::size_t count) {
    evaluateRange(*multi_.evaluators_[k], materials_, samples, first, count, rgb);
  });
}

}  // namespace brdfcl
