// The engine tables as floats: three.js's RG16F texel bits (threejs_dfg_lut.inc) widened with
// the IEEE 754 binary16 rules (normals, subnormals; the table has no inf or NaN), and the Sample
// Renderer's 8-bit sheen albedo texels (khronos_sheen_e_lut.inc, zlib) as unorm8 / 255, and
// Babylon's decoded BRDF texels (babylon_brdf_lut.inc, zlib, half-float bits) widened the same way.
#include "model/engine_tables.hpp"

#include <cmath>
#include <cstdint>
#include <iterator>
#include <stdexcept>

#include <zlib.h>

#include "kernels/common/material_layout.h"

namespace brdfcl {
namespace {

constexpr std::uint16_t kBits[] = {
#include "model/threejs_dfg_lut.inc"
};
static_assert(std::size(kBits) == 2 * BRDFCL_DFG_SIZE * BRDFCL_DFG_SIZE, "16x16 texels of (A, B)");

constexpr unsigned char kSheenE[] = {
#include "model/khronos_sheen_e_lut.inc"
};

constexpr unsigned char kBabylonBrdf[] = {
#include "model/babylon_brdf_lut.inc"
};

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

const std::vector<float>& khronosSheenETable() {
  static const std::vector<float> table = [] {
    constexpr uLongf kTexels = uLongf(BRDFCL_KHRONOS_SHEEN_E_SIZE) * BRDFCL_KHRONOS_SHEEN_E_SIZE;
    std::vector<unsigned char> texels(kTexels);
    uLongf n = kTexels;
    // The data is compiled in: a failure here is a broken build, not bad input.
    if (uncompress(texels.data(), &n, kSheenE, uLong(std::size(kSheenE))) != Z_OK || n != kTexels)
      throw std::logic_error("khronos_sheen_e_lut.inc does not inflate to 1024x1024 texels");
    std::vector<float> t(kTexels);
    for (uLongf i = 0; i < kTexels; ++i) t[i] = float(texels[i]) / 255.0f;
    return t;
  }();
  return table;
}

const std::vector<float>& babylonBrdfTable() {
  static const std::vector<float> table = [] {
    constexpr std::size_t kValues = std::size_t(3) * BRDFCL_BABYLON_BRDF_SIZE * BRDFCL_BABYLON_BRDF_SIZE;
    std::vector<unsigned char> bytes(2 * kValues);
    uLongf n = uLongf(bytes.size());
    // The data is compiled in: a failure here is a broken build, not bad input.
    if (uncompress(bytes.data(), &n, kBabylonBrdf, uLong(std::size(kBabylonBrdf))) != Z_OK || n != bytes.size())
      throw std::logic_error("babylon_brdf_lut.inc does not inflate to 256x256 texels of 3 half floats");
    std::vector<float> t(kValues);
    for (std::size_t i = 0; i < kValues; ++i)
      t[i] = halfToFloat(std::uint16_t(bytes[2 * i] | (bytes[2 * i + 1] << 8)));
    return t;
  }();
  return table;
}

}  // namespace brdfcl
