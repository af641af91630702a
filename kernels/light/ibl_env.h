/* The image-based light's inputs as the shading kernel hands them over, one struct for the spec's
   split sum (light/split_sum.h) and the engine profiles' (brdf/profiles/ibl.h), and the geometry
   at the pixel both read. Shading kernels only (BRDFCL_W == 1). */
#ifndef BRDFCL_LIGHT_IBL_ENV_H
#define BRDFCL_LIGHT_IBL_ENV_H

#include "common/environment.h"

/* The prefiltered chains (GGX and Charlie, roughness linear in the level), the irradiance map
   (radiance a white Lambertian reflects), brdfcl's GGX DFG table (A, B at N.V, perceptual
   roughness), the anisotropic DFG table (aniso_dfg.cl), the Fresnel-weighted Lambert albedo C(N.V),
   and the profile's tables: the sheen E table, then for engine profiles three.js's DFG, then for
   khronos the Sample Renderer's sheen albedo texture. The kernel builds it from its arguments:
   OpenCL kernel arguments cannot be structs holding pointers. */
typedef struct {
  __global const float* ggx;
  __global const float* charlie;
  __global const float* irradiance;
  int env_w, env_h, charlie_w, charlie_h, levels, irr_w, irr_h;
  float rotation;
  __global const float* dfg;
  int dfg_size;
  __global const float* tables;
  int e_size;
  __global const float* aniso_dfg;
  __global const float* fresnel_lambert;
  int fl_size;
} ibl_env;

/* The geometry at the pixel: unit N, V, the clearcoat normal, and the anisotropy direction
   (Ta, with Ba = N x Ta; read only when the strength is above 0). */
typedef struct {
  float3 N, V, Nc, Ta, Ba;
} ibl_frame;

#endif
