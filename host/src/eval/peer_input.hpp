// What a C++ peer of the batch kernel (bench/peers) reads and writes: the planes of a SoaBatch
// and output planes of its own. The peers are benchmark code; the library only lays out their input.
#pragma once
#include <cstddef>
#include <cstdint>

#include "kernels/common/material_layout.h"

namespace brdfcl::peers {

struct Input {
  const float* dir[6];  // Lx Ly Lz Vx Vy Vz
  const std::uint32_t* material;
  const brdfcl_material* materials;
  const float* sheenE;
  int sheenESize;
  float* out[3];
  std::size_t count;
};

}  // namespace brdfcl::peers
