/* Lookup of the baked sheen albedo table E(mu, r): mu = N.V (or N.L) along x, r = sheenRoughness
   along y. Nodes sit at mu = s^2, r = t^2 for uniform s, t (dense where E is steep: grazing
   angles, low roughness); bilinear in (s, t). */
#ifndef BRDFCL_SHEEN_ALBEDO_H
#define BRDFCL_SHEEN_ALBEDO_H

#include "common/lanes.h"

static inline float sheen_albedo_texel(__global const float* table, int size, float mu, float r) {
  float x = sqrt(clamp(mu, 0.0f, 1.0f)) * (float)(size - 1);
  float y = sqrt(clamp(r, 0.0f, 1.0f)) * (float)(size - 1);
  int x0 = min((int)x, size - 2), y0 = min((int)y, size - 2);
  float fx = x - (float)x0, fy = y - (float)y0;
  __global const float* row0 = table + y0 * size + x0;
  __global const float* row1 = row0 + size;
  float top = mix(row0[0], row0[1], fx);
  float bottom = mix(row1[0], row1[1], fx);
  return mix(top, bottom, fy);
}

/* Per-lane gather: tables are small and lanes index them independently. */
BRDF_FN realw E_SheenAlbedo(__global const float* table, int size, realw mu, realw r) {
#if BRDFCL_W == 1
  return sheen_albedo_texel(table, size, mu, r);
#else
  float mu_a[BRDFCL_W], r_a[BRDFCL_W], e_a[BRDFCL_W];
  VSTOREW(mu, 0, mu_a);
  VSTOREW(r, 0, r_a);
  for (int i = 0; i < BRDFCL_W; ++i) e_a[i] = sheen_albedo_texel(table, size, mu_a[i], r_a[i]);
  return VLOADW(0, e_a);
#endif
}

#endif
