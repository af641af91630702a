// Hand-written CPU peers of the batch kernel, for side-by-side throughput ratios: the same BRDF
// source compiled as C++ into a plain scalar loop and an OpenMP-SIMD loop over both cores, and a
// STREAM-triad memory bound.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "host/src/eval/peer_input.hpp"

namespace brdfcl::peers {

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
