/* Test probe: evaluates the inlinable math of common/fastmath.h on the device, one input a
   work-item, so tests/unit/test_fastmath.cpp can measure its error against double. */
#include "common/fastmath.h"

__kernel void probe_fastmath(__global const float* restrict x, __global float* restrict out, uint n) {
  uint i = get_global_id(0);
  if (i >= n) return;
  out[4 * i + 0] = brdf_exp2(x[i]);
  out[4 * i + 1] = brdf_log2(x[i]);
  out[4 * i + 2] = brdf_exp(x[i]);
  out[4 * i + 3] = brdf_log1p(x[i]);
}
