/* Test probe: the samplers of brdf/sampling.h at the build's lane width (BRDFCL_W, 16 by default),
   each against its own pdf: per lane, N.L / pdf(L) of a sampled L, whose mean is the cosine
   integral pi when sampler and pdf agree (tests/unit/test_exact_ibl.cpp). */
#include "brdf/sampling.h"

__kernel void probe_sampling(__global const float* restrict u1s, __global const float* restrict u2s, float vx, float vy,
                             float vz, float ax, float ay, int technique, __global float* restrict out) {
  const int i = get_global_id(0);
  realw u1 = VLOADW(i, u1s), u2 = VLOADW(i, u2s);
  vec3w V = {(realw)(vx), (realw)(vy), (realw)(vz)};
  vec3w L;
  realw pdf;
  if (technique == 0) {
    L = reflect_about(V, SampleGGXVNDF(V, (realw)(ax), (realw)(ay), u1, u2));
    pdf = PdfGGXVNDFReflect(L, V, (realw)(ax), (realw)(ay));
  } else if (technique == 1) {
    L = SampleCosineHemisphere(u1, u2);
    pdf = PdfCosineHemisphere(L);
  } else {
    L = SampleUniformHemisphere(u1, u2);
    pdf = PdfUniformHemisphere(L);
  }
  VSTOREW(keep_or_zero(L.z / pdf, (L.z > 0.0f) & (pdf > 0.0f)), i, out);
}
