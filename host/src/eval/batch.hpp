// What every launch of an evaluation shares (Evaluator::prepare): the program specialised to the
// materials' feature set, the packed materials and the sheen albedo table. Internal to the
// evaluator's translation units (evaluator.cpp, rows.cpp).
#pragma once
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

// The sheen albedo table is a 2x2 dummy when no material needs it.
struct Evaluator::Batch {
  LaneShape shape;  // the device's lane width and work-group size (runtime.hpp)
  cl::Program program;
  std::vector<brdfcl_material> packed;
  std::vector<float> table = std::vector<float>(4, 0.0f);
  int tableSize = 2;
  cl::Buffer materials, tableBuffer;
};

}  // namespace brdfcl
