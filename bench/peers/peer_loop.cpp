// One peer loop: compiled once per (workload, flavour) by CMake with the workload's -D options
// (the same defines the kernel gets) and the flavour's compiler flags. PEER_FN names the entry.
#include "kernels/common/host_compat.h"
#define BRDFCL_W 1
#include "kernels/brdf/material.h"
#include "peers.hpp"

namespace brdfcl::peers {

// The loop body lives in its own always-inline function: GCC lowers `omp simd` before inlining,
// and struct-typed locals written in the loop itself become per-lane arrays that block
// vectorization, while the callee's locals are scalarized after inlining.
static inline __attribute__((always_inline)) void evalOne(const float* const* dir, const std::uint32_t* index,
                                                          const brdfcl_material* materials, const float* sheenE,
                                                          int sheenESize, float* const* out, long i) {
  const vec3w L = {dir[0][i], dir[1][i], dir[2][i]}, V = {dir[3][i], dir[4][i], dir[5][i]};
  const rgbw f = brdf_material(material_gather(materials, index[i]), L, V, sheenE, sheenESize);
  out[0][i] = f.r;
  out[1][i] = f.g;
  out[2][i] = f.b;
}

void PEER_FN(const Input& in) {
  const long n = long(in.count);
  // The plane pointers are declared inside the parallel region: as shared variables they would be
  // re-read from memory every iteration (the stores could alias them) and block vectorization.
#ifdef PEER_OPENMP_SIMD
#pragma omp parallel
#endif
  {
    const float* dir[6] = {in.dir[0], in.dir[1], in.dir[2], in.dir[3], in.dir[4], in.dir[5]};
    float* out[3] = {in.out[0], in.out[1], in.out[2]};
    const std::uint32_t* index = in.material;
    const brdfcl_material* materials = in.materials;
    const float* sheenE = in.sheenE;
    const int sheenESize = in.sheenESize;
#ifdef PEER_OPENMP_SIMD
#pragma omp for simd schedule(static)
#endif
    for (long i = 0; i < n; ++i) evalOne(dir, index, materials, sheenE, sheenESize, out, i);
  }
}

}  // namespace brdfcl::peers
