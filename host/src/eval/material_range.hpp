// The check every grid entry point (Evaluator, MultiEvaluator, the grid rows) makes of the
// materials [first, first + count) it is asked for: a caller's slip, so an internal error.
#pragma once
#include <cstddef>

#include <fmt/format.h>

#include "brdfcl/error.hpp"

namespace brdfcl {

inline void checkMaterialRange(std::size_t first, std::size_t count, std::size_t materials) {
  if (first > materials || count > materials - first)
    throw Error(fmt::format("internal: materials [{}, {}) of {}", first, first + count, materials), 3);
}

}  // namespace brdfcl
