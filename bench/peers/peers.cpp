// Dispatch to the per-workload peer loops, and the STREAM triad.
#include "peers.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <stdexcept>

namespace brdfcl::peers {

#define BRDFCL_PEER(flavor, workload) void peer_##flavor##_##workload(const Input&);
#define BRDFCL_PEERS(workload) BRDFCL_PEER(scalar, workload) BRDFCL_PEER(simd, workload)
BRDFCL_PEERS(sheen)
BRDFCL_PEERS(specular)
BRDFCL_PEERS(clearcoat)
BRDFCL_PEERS(all)

void run(Flavor flavor, const std::string& workload, const Input& in) {
  const bool simd = flavor == Flavor::OpenMPSimd;
  if (workload == "sheen") return simd ? peer_simd_sheen(in) : peer_scalar_sheen(in);
  if (workload == "specular") return simd ? peer_simd_specular(in) : peer_scalar_specular(in);
  if (workload == "clearcoat") return simd ? peer_simd_clearcoat(in) : peer_scalar_clearcoat(in);
  if (workload == "all") return simd ? peer_simd_all(in) : peer_scalar_all(in);
  throw std::invalid_argument("unknown peer workload '" + workload + "'");
}

double streamTriadBytesPerSecond(std::size_t floats, int repeats) {
  auto alloc = [&] { return std::unique_ptr<float[]>(new float[floats]); };
  auto a = alloc(), b = alloc(), c = alloc();
  const long n = long(floats);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) a[i] = 0.0f, b[i] = 1.0f, c[i] = 2.0f;  // first touch on the threads that use it
  double best = 1e30;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const float s = 3.0f;
    float *pa = a.get(), *pb = b.get(), *pc = c.get();
#pragma omp parallel for simd schedule(static)
    for (long i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return 3.0 * 4.0 * double(floats) / best;
}

int threads() { return omp_get_max_threads(); }

}  // namespace brdfcl::peers
