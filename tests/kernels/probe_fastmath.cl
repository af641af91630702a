/* Test probe: evaluates the inlinable math of common/fastmath.h on the device, BRDFCL_W inputs a
   work-item, one output plane a function, so tests/unit/test_fastmath.cpp can measure its error
   against double at one lane and at the kernels' 16 (where AVX-512 estimates replace divisions). */
#include "common/fastmath.h"

__kernel void probe_fastmath(__global const float* restrict x, __global float* restrict out, uint n) {
  uint g = get_global_id(0);
  if ((g + 1) * BRDFCL_W > n) return;
  realw v = VLOADW(g, x);
  VSTOREW(brdf_exp2(v), g, out + 0 * n);
  VSTOREW(brdf_log2(v), g, out + 1 * n);
  VSTOREW(brdf_exp(v), g, out + 2 * n);
  VSTOREW(brdf_log1p(v), g, out + 3 * n);
  VSTOREW(brdf_log2_1p(v), g, out + 4 * n);
  VSTOREW(brdf_rcp(v), g, out + 5 * n);
  VSTOREW(brdf_rsqrt(v), g, out + 6 * n);
  VSTOREW(brdf_exp2_nonpositive(v), g, out + 7 * n);
  VSTOREW(brdf_exp_bounded(v), g, out + 8 * n);
}
