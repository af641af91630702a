/* Lookup of the baked sheen albedo table E(mu, r): mu = N.V (or N.L) along x, r = sheenRoughness
   along y. Nodes sit at mu = s^2, r = t^2 for uniform s, t (dense where E is steep: grazing
   angles, low roughness); bilinear in (s, t). The coordinate arithmetic runs on whole lanes; only
   the four texel reads are per lane, and one row position serves both N.V and N.L. Along one row
   the host has already blended for a material's r, a lookup reads two texels. */
#ifndef BRDFCL_SHEEN_ALBEDO_H
#define BRDFCL_SHEEN_ALBEDO_H

#include "common/lanes.h"

/* Where sheenRoughness r falls between two table rows. */
typedef struct { intw row; realw f; } sheen_albedo_row;

BRDF_FN sheen_albedo_row E_SheenAlbedoRow(int size, realw r) {
  realw y = sqrt(clamp(r, 0.0f, 1.0f)) * (float)(size - 1);
  intw y0 = min(CONVERT_INTW(y), size - 2);
  sheen_albedo_row out = {y0 * size, y - CONVERT_REALW(y0)};
  return out;
}

/* Where mu = N.V (or N.L) falls between two table columns. */
typedef struct { intw column; realw f; } sheen_albedo_column;

BRDF_FN sheen_albedo_column E_SheenAlbedoColumn(int size, realw mu) {
  realw x = sqrt(clamp(mu, 0.0f, 1.0f)) * (float)(size - 1);
  intw x0 = min(CONVERT_INTW(x), size - 2);
  sheen_albedo_column out = {x0, x - CONVERT_REALW(x0)};
  return out;
}

BRDF_FN realw E_SheenAlbedo(__global const float* table, int size, sheen_albedo_row row, realw mu) {
  sheen_albedo_column c = E_SheenAlbedoColumn(size, mu);
  intw i00 = row.row + c.column;
  realw t00 = GATHERW(table, i00), t01 = GATHERW(table + 1, i00);
  realw t10 = GATHERW(table + size, i00), t11 = GATHERW(table + size + 1, i00);
  return mix(mix(t00, t01, c.f), mix(t10, t11, c.f), row.f);
}

/* The same E along one row of `size` values at table[row], already blended between the table's
   two rows (SheenAlbedoTable::rowAt on the host): the blends in the other order, so E agrees with
   E_SheenAlbedo to float rounding. */
BRDF_FN realw E_SheenAlbedoAlong(__global const float* table, int size, intw row, realw mu) {
  sheen_albedo_column c = E_SheenAlbedoColumn(size, mu);
  intw i0 = row + c.column;
  return mix(GATHERW(table, i0), GATHERW(table + 1, i0), c.f);
}

#endif
