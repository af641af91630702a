/* Batch BRDF evaluation. Directions arrive as SoA planes (Lx Ly Lz Vx Vy Vz, `stride` floats
   apart) and results leave as planes (r g b). Each work-item handles BRDFCL_W consecutive samples,
   so the host pads every plane to a multiple of BRDFCL_W. */
#include "brdf/material.h"

BRDF_FN void load_directions(__global const float* dirs, uint stride, uint i, vec3w* L, vec3w* V) {
  L->x = VLOADW(i, dirs);
  L->y = VLOADW(i, dirs + stride);
  L->z = VLOADW(i, dirs + 2 * stride);
  V->x = VLOADW(i, dirs + 3 * stride);
  V->y = VLOADW(i, dirs + 4 * stride);
  V->z = VLOADW(i, dirs + 5 * stride);
}

BRDF_FN void store_rgb(rgbw f, __global float* out, ulong stride, uint i) {
  VSTOREW(f.r, i, out);
  VSTOREW(f.g, i, out + stride);
  VSTOREW(f.b, i, out + 2 * stride);
}

/* One material per sample, gathered by index. */
__kernel void eval_samples(__global const float* restrict dirs, uint stride,
                           __global const uint* restrict material_index,
                           __global const brdfcl_material* restrict materials,
                           __global const float* restrict sheen_e, int sheen_e_size,
                           __global float* restrict out) {
  uint i = get_global_id(0);
  vec3w L, V;
  load_directions(dirs, stride, i, &L, &V);
  material_lanes m = material_gather(materials, VLOADW(i, material_index));
  store_rgb(brdf_material(m, L, V, sheen_e, sheen_e_size), out, stride, i);
}

/* Every material (global id 1, from `first_material`) x every direction pair (global id 0);
   output material-major, each material's block `stride` samples long. */
__kernel void eval_grid(__global const float* restrict dirs, uint stride,
                        __global const brdfcl_material* restrict materials, uint first_material,
                        __global const float* restrict sheen_e, int sheen_e_size,
                        __global float* restrict out) {
  uint i = get_global_id(0);
  ulong material = get_global_id(1);
  ulong plane = (ulong)stride * get_global_size(1);
  vec3w L, V;
  load_directions(dirs, stride, i, &L, &V);
  material_lanes m = material_splat(materials + first_material + material);
  store_rgb(brdf_material(m, L, V, sheen_e, sheen_e_size), out + material * stride, plane, i);
}
