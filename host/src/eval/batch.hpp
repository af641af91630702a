// What every launch of an evaluation shares (Evaluator::prepare): the program specialised to the
// materials' feature set, the packed materials and the sheen albedo table. Internal to the
// evaluator's translation units (evaluator.cpp, rows.cpp).
#pragma once
#include <vector>

#include "brdfcl/evaluator.hpp"
#include "runtime/opencl.hpp"

namespace brdfcl {

// The kernels of eval.cl a batch's program holds, one path's each (the bits of BRDFCL_KERNELS in
// kernels/eval.cl): a process then loads, and the device parses, only what the path launches.
// None builds no program: the samplers need only the packed materials and the tables.
enum class Evaluator::Kernels : unsigned { None = 0, Samples = 1, Rows = 2, Grid = 4, Table = 8 };

// The sheen albedo table is a 2x2 dummy when no material needs it.
struct Evaluator::Batch {
  LaneShape shape;  // the device's lane width and work-group size (runtime.hpp)
  cl::Program program;  // null for Kernels::None
  std::vector<brdfcl_material> packed;
  std::vector<float> table = std::vector<float>(4, 0.0f);
  int tableSize = 2;
  cl::Buffer materials, tableBuffer;
};

}  // namespace brdfcl
