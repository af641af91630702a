/* Batch BRDF evaluation. Directions arrive as SoA planes (Lx Ly Lz Vx Vy Vz) and results leave
   as planes (r g b). Each work-item handles BRDFCL_W consecutive samples, so the host pads every
   plane to a multiple of BRDFCL_W. */
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

/* One material per sample, gathered by index. Every plane is its own buffer, so callers can
   hand over their arrays in place and a plane stays under the device's largest allocation. */
__kernel void eval_samples(__global const float* restrict Lx, __global const float* restrict Ly,
                           __global const float* restrict Lz, __global const float* restrict Vx,
                           __global const float* restrict Vy, __global const float* restrict Vz,
                           __global const uint* restrict material_index,
                           __global const brdfcl_material* restrict materials,
                           __global const float* restrict sheen_e, int sheen_e_size,
                           __global float* restrict out_r, __global float* restrict out_g,
                           __global float* restrict out_b) {
  uint i = get_global_id(0);
  vec3w L = {VLOADW(i, Lx), VLOADW(i, Ly), VLOADW(i, Lz)};
  vec3w V = {VLOADW(i, Vx), VLOADW(i, Vy), VLOADW(i, Vz)};
  material_lanes m = material_gather(materials, VLOADW(i, material_index));
  rgbw f = brdf_material(m, L, V, sheen_e, sheen_e_size);
  VSTOREW(f.r, i, out_r);
  VSTOREW(f.g, i, out_g);
  VSTOREW(f.b, i, out_b);
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
