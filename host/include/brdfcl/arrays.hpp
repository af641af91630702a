// f(L, V) of directions held in memory (numpy arrays of the Python module, any caller's buffers):
// checked and normalized exactly as the samples readers do it, a chunk at a time, so memory stays
// bounded and the results equal `brdfcl eval` on the same numbers bit for bit.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "brdfcl/material.hpp"

namespace brdfcl {

// N rows of 3 components each, row-major and contiguous (x y z x y z ...), in float32 or float64:
// the two element types a samples .npy may hold. Only read, never copied whole.
struct DirectionArray {
  enum class Type { Float32, Float64 };
  const void* data = nullptr;
  Type type = Type::Float32;
};

// The samples of one evaluation: `count` rows of L (towards the light) and V (towards the
// viewer) in the shading frame N = +Z, T = +X, B = +Y, and for evaluateArrays one material index
// per row (nullptr means every row uses material 0; only allowed with exactly one material).
struct ArraySamples {
  DirectionArray L, V;
  const std::int64_t* material = nullptr;
  std::size_t count = 0;
};

// Each row is checked and normalized as readSamples does it (normalizeDirection); a bad row
// throws brdfcl::Error with 0-based row numbers, as numpy indexes them:
//   "row 12: field 'Lx' is not finite: nan"
//   "row 12: V has zero length"
//   "row 3: material index 5 out of range (2 materials)" / "row 3: material index -1 is not a
//   non-negative integer".
// Materials are checked as Evaluator::evaluate checks them. `rgb` receives 3 floats per row.
// Rows are evaluated through one SoaBatch of at most `chunk` samples (0: the evaluator's launch
// limit), so the extra memory is that batch's planes whatever `count` is.
void evaluateArrays(Evaluator& evaluator, const std::vector<MaterialParams>& materials, const ArraySamples& samples,
                    float* rgb, std::size_t chunk = 0);

// Every material x every direction, material-major: rgb holds materials.size() x count x 3
// floats, the bits `brdfcl eval --grid` writes for the same numbers. samples.material is ignored. Directions go to the device
// `chunk` at a time (0: 1 << 20, the CLI's default chunk).
void evaluateGridArrays(Evaluator& evaluator, const std::vector<MaterialParams>& materials,
                        const ArraySamples& samples, float* rgb, std::size_t chunk = 0);

}  // namespace brdfcl
