/* Bakes the sheen albedo table E(mu, r) = integral over the hemisphere of D V (N.L) dw_L for the
   white sheen lobe of the batch's sheen options, at the nodes mu = s^2, r = t^2 (s, t uniform), by a tensor quadrature rule over (N.L, phi) that
   the host builds (composite Gauss-Legendre, graded towards the grazing peak). One work-item per
   table entry; its lanes run over the phi nodes. */
#include "brdf/material.h"

__kernel void bake_sheen_albedo(int size,
                                __global const float* restrict u_nodes, __global const float* restrict u_weights,
                                int u_count,
                                __global const float* restrict phi_cos, __global const float* restrict phi_sin,
                                __global const float* restrict phi_weights, int phi_count,
                                __global float* restrict out) {
  int ix = get_global_id(0), iy = get_global_id(1);
  /* N.V is clamped as brdf_material clamps it, so the table answers what the lookup asks. */
  float sx = (float)ix / (float)(size - 1), ty = (float)iy / (float)(size - 1);
#ifdef BRDFCL_SHEEN_ALBEDO_UNIFORM
  /* Exported LUTs (kernels/lut.cl) sit on the grid engines sample: uniform in mu and r. */
  float mu = max(sx, BRDFCL_MIN_COS);
  float r = ty;
#else
  float mu = max(sx * sx, BRDFCL_MIN_COS);
  float r = ty * ty;
#endif
  float alpha = max(r * r, BRDFCL_MIN_SHEEN_ALPHA);
  float vx = sqrt(1.0f - mu * mu);

  float total = 0.0f;
  for (int iu = 0; iu < u_count; ++iu) {
    float u = u_nodes[iu];
    float sin_l = sqrt(1.0f - u * u);
    realw acc = (realw)(0.0f);
    for (int ip = 0; ip < phi_count; ip += BRDFCL_W) {
      realw c = VLOADW(0, phi_cos + ip), s = VLOADW(0, phi_sin + ip), pw = VLOADW(0, phi_weights + ip);
      realw hx = sin_l * c + vx, hy = sin_l * s;
      realw hz = (realw)(u + mu);
      realw hxy2 = hx * hx + hy * hy, hn2 = hz * hz;
      acc += pw * sheen_dv(hxy2, hn2, (realw)(u), (realw)(mu), (realw)(alpha));
    }
#if BRDFCL_W == 1
    float row = acc;
#else
    float lanes[BRDFCL_W];
    VSTOREW(acc, 0, lanes);
    float row = 0.0f;
    for (int k = 0; k < BRDFCL_W; ++k) row += lanes[k];
#endif
    total += u_weights[iu] * u * row;
  }
  out[iy * size + ix] = total;
}
