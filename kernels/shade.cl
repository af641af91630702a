/* Deferred shading of a G-buffer: per pixel, decode the material once (common/material_pack.h),
   add every punctual light (light/punctual.h) through the batch evaluator's own layers
   (brdf_layers, the clearcoat on its own normal), then split-sum image-based light times the glTF
   occlusion (light/split_sum.h; an engine profile's own under -DBRDFCL_PROFILE) and the
   clearcoat-darkened emission. Masked-out pixels show the environment. The view is the G-buffer's
   V where it has one, else the camera's (pinhole or orthographic). */
#define BRDFCL_W 1
#include "brdf/material.h"
#include "common/material_pack.h"
#include "common/environment.h"
#include "common/gbuffer_pixel.h"
#include "light/punctual.h"
#include "light/split_sum.h"
#if BRDFCL_PROFILE != BRDFCL_PROFILE_SPEC
#include "brdf/profiles/ibl.h"
#endif

static inline vec3w to_lanes(float3 v) { vec3w o = {v.x, v.y, v.z}; return o; }

/* One launch shades the band of rows [y0, y0 + band_h): gb and out hold the band's planes only. */
__kernel void shade(__global const float* restrict gb, int width, int height, int y0, int band_h, brdfcl_camera cam,
                    __global const brdfcl_light* restrict lights, int light_count,
                    __global const float* restrict background, __global const float* restrict ggx_chain,
                    __global const float* restrict charlie_chain, __global const float* restrict irradiance,
                    int env_w, int env_h, int charlie_w, int charlie_h, int prefilter_levels, int irr_w, int irr_h,
                    float env_rotation,
                    __global const float* restrict dfg, int dfg_size, __global const float* restrict aniso_dfg,
                    __global const float* restrict sheen_e,
                    int sheen_e_size, __global const float* restrict fresnel_lambert, int fl_size,
                    int split_sum, __global float* restrict out) {
  int x = get_global_id(0), y = y0 + (int)get_global_id(1);
  if (x >= width || y >= height || y >= y0 + band_h) return;
  const int np = width * band_h, i = (y - y0) * width + x;
#define GB(k) gb[(k) * np + i]
  const float3 eye = (float3)(cam.position[0], cam.position[1], cam.position[2]);
  const float3 forward = (float3)(cam.forward[0], cam.forward[1], cam.forward[2]);
  const bool ortho = cam.orthographic > 0.5f;
  /* The G-buffer's own view direction, when it has one, replaces the camera's (orthographic
     and other cameras a pinhole cannot express; docs/gbuffer.md). */
  const float3 Vg = (float3)(GB(GB_VX), GB(GB_VY), GB(GB_VZ));
  const bool has_v = dot(Vg, Vg) > 0.0f;
  float3 result;
  if (GB(GB_MASK) < 0.5f && has_v) {
    result = env_chain(background, env_w, env_h, env_w, env_h, 1, -normalize(Vg), env_rotation, 0.0f);
  } else if (GB(GB_MASK) < 0.5f && ortho) {
    result = env_chain(background, env_w, env_h, env_w, env_h, 1, forward, env_rotation, 0.0f);
  } else if (GB(GB_MASK) < 0.5f) {
    float sx = (2.0f * ((float)x + 0.5f) / (float)width - 1.0f) * cam.tan_half_fov * cam.aspect;
    float sy = (1.0f - 2.0f * ((float)y + 0.5f) / (float)height) * cam.tan_half_fov;
    float3 d = normalize(forward + sx * (float3)(cam.right[0], cam.right[1], cam.right[2]) +
                         sy * (float3)(cam.up[0], cam.up[1], cam.up[2]));
    result = env_chain(background, env_w, env_h, env_w, env_h, 1, d, env_rotation, 0.0f);
  } else {
    gbuffer_pixel px = gbuffer_pixel_decode(gb, np, i, Vg, eye, forward, ortho);
    float3 P = px.P, N = px.N, T = px.T, B = px.B, Nc = px.Nc, Tc = px.Tc, Bc = px.Bc, V = px.V;
    brdfcl_material_params q = px.q;
    brdfcl_material packed = brdfcl_pack_material_profile(q, BRDFCL_PROFILE);
    material_lanes m = material_splat_private(&packed);

    vec3w Vl = to_lanes(frame_local(V, T, B, N)), Vc = to_lanes(frame_local(V, Tc, Bc, Nc));
    float NdotV = dot(N, V);
    result = (float3)(0.0f);

    /* Punctual lights (light/punctual.h): f (N.L) times the light's radiance at P. */
    for (int k = 0; k < light_count; ++k) {
      float3 L;
      float3 radiance = punctual_radiance(lights + k, P, &L);
      float NdotL = dot(N, L);
      if (NdotL <= 0.0f || NdotV <= 0.0f) continue;
      rgbw f = brdf_layers(m, to_lanes(frame_local(L, T, B, N)), Vl, to_lanes(frame_local(L, Tc, Bc, Nc)), Vc, sheen_e,
                           sheen_e_size);
      result += (float3)(f.r, f.g, f.b) * NdotL * radiance;
    }

    /* Image-based light by split sum: the spec's (light/split_sum.h) or the engine's
       (brdf/profiles/ibl.h). Under --ibl exact it comes from ibl_exact.cl instead, for the spec
       only: the host refuses exact with a profile. */
    ibl_env e = {ggx_chain, charlie_chain, irradiance, env_w, env_h, charlie_w, charlie_h, prefilter_levels, irr_w, irr_h,
                 env_rotation, dfg, dfg_size, sheen_e, sheen_e_size, aniso_dfg, fresnel_lambert, fl_size};
    float3 Ta = normalize(cos(q.anisotropy_rotation) * T + sin(q.anisotropy_rotation) * B);
    ibl_frame frame = {N, V, Nc, Ta, cross(N, Ta)};
    float3 ibl = (float3)(0.0f);
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC
    float emission_weight = 1.0f - split_sum_coat(q, &frame);
    if (split_sum) ibl = split_sum_spec(&e, &frame, q);
#else
    /* The engine's coat sets the emission weight. */
    float emission_weight = 1.0f;
    if (split_sum) ibl = profile_ibl(&e, &frame, q, &packed, &emission_weight);
#endif
    /* glTF occlusion dims indirect light only: punctual lights and emission are not touched. */
    result += ibl * clamp(GB(GB_OCCLUSION), 0.0f, 1.0f);
    /* KHR_materials_clearcoat "Emission": the coat darkens what is below it. */
    result += (float3)(GB(GB_EMISSIVE_R), GB(GB_EMISSIVE_G), GB(GB_EMISSIVE_B)) * emission_weight;
#if BRDFCL_PROFILE == BRDFCL_PROFILE_BABYLON
    /* pbrBlockFinalColorComposition clamps the composed colour at 0: the sheen's albedo scaling
       1 - max3(c) E turns negative where E > 1 at grazing N.V. */
    result = max(result, (float3)(0.0f));
#endif
  }
  out[i] = result.x;
  out[np + i] = result.y;
  out[2 * np + i] = result.z;
#undef GB
}
