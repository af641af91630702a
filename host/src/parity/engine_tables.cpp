// three.js's DFG table as floats: the RG16F texel bits carried over in threejs_dfg_lut.inc,
// widened with the IEEE 754 binary16 rules (normals, subnormals; the table has no inf or NaN).
#include "parity/engine_tables.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>

#include "kernels/common/material_layout.h"

namespace brdfcl {
namespace {

constexpr std::uint16_t kBits[] = {
#include "parity/threejs_dfg_lut.inc"
};
static_assert(std::size(kBits) == 2 * BRDFCL_DFG_SIZE * BRDFCL_DFG_SIZE, "16x16 texels of (A, B)");

float halfToFloat(std::uint16_t h) {
  const int exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
  const float sign = (h & 0x8000) ? -1.0f : 1.0f;
  if (exponent == 0) return sign * std::ldexp(float(mantissa), -24);
  return sign * std::ldexp(float(mantissa | 0x400), exponent - 25);
}

}  // namespace

const std::vector<float>& threejsDfgTable() {
  static const std::vector<float> table = [] {
    std::vector<float> t;
    for (std::uint16_t b : kBits) t.push_back(halfToFloat(b));
    return t;
  }();
  return table;
}

}  // namespace brdfcl
