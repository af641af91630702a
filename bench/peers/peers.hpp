// Hand-written CPU peers of the batch kernel, for side-by-side throughput ratios: the same BRDF
// source compiled as C++ into a plain scalar loop and an OpenMP-SIMD loop over both cores, and a
// STREAM-triad memory bound.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "kernels/common/material_layout.h"

namespace brdfcl::peers {

// What the kernel reads and writes, as SoaBatch lays it out.
struct Input {
  const float* dir[6];  // Lx Ly Lz Vx Vy Vz
  const std::uint32_t* material;
  const brdfcl_material* materials;
  const float* sheenE;
  int sheenESize;
  float* out[3];
  std::size_t count;
};

enum class Flavor { Scalar, OpenMPSimd };

// The benchmark workloads of brdfcl bench: "sheen", "specular", "clearcoat", "all".
// Throws std::invalid_argument for another name.
void run(Flavor flavor, const std::string& workload, const Input& in);

// STREAM triad a = b + s c over `floats` floats per array on all cores; returns bytes/s
// counted as STREAM does (3 arrays x 4 bytes per element), best of `repeats`.
double streamTriadBytesPerSecond(std::size_t floats, int repeats);

// Threads the OpenMP peer and the triad run on (every core unless OMP_NUM_THREADS says otherwise).
int threads();

}  // namespace brdfcl::peers
