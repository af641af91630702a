/* Deferred shading of a G-buffer: per pixel, decode the material once (common/material_pack.h),
   add every punctual light through the batch evaluator's own layers (brdf_layers, the clearcoat
   on its own normal), then split-sum image-based light (times the glTF occlusion; an engine
   profile's own approximation under -DBRDFCL_PROFILE) and the clearcoat-darkened emission. Masked-out pixels show the environment. The view
   is the G-buffer's V where it has one, else the camera's (pinhole or orthographic). */
#define BRDFCL_W 1
#include "brdf/material.h"
#include "common/material_pack.h"
#include "common/environment.h"
#include "common/gbuffer_pixel.h"
#if BRDFCL_PROFILE != BRDFCL_PROFILE_SPEC
#include "brdf/profiles/ibl.h"
#endif

typedef struct {
  __global const float* chain; int w0, h0, levels;
} env_chain_ref;

static inline float2 lut2(__global const float* lut, int size, float nv, float r) {
  float x = clamp(nv, 0.0f, 1.0f) * (float)(size - 1), y = clamp(r, 0.0f, 1.0f) * (float)(size - 1);
  int x0 = min((int)x, size - 2), y0 = min((int)y, size - 2);
  float fx = x - (float)x0, fy = y - (float)y0;
  __global const float* p = lut + 2 * (y0 * size + x0);
  float2 a = mix(vload2(0, p), vload2(1, p), fx);
  float2 b = mix(vload2(size, p), vload2(size + 1, p), fx);
  return mix(a, b, fy);
}

static inline float lut1(__global const float* lut, int size, float x) {
  float t = clamp(x, 0.0f, 1.0f) * (float)(size - 1);
  int i = min((int)t, size - 2);
  return mix(lut[i], lut[i + 1], t - (float)i);
}

/* Quadrilinear look-up of the anisotropic split-sum table (aniso_dfg.cl) at N.V, perceptual
   roughness, strength and the view's azimuth psi in [0, pi/2] from the anisotropy direction. */
static inline float2 lut_aniso(__global const float* lut, float nv, float r, float s, float psi) {
  const int n[4] = {BRDFCL_ANISO_DFG_NV, BRDFCL_ANISO_DFG_R, BRDFCL_ANISO_DFG_S, BRDFCL_ANISO_DFG_PSI};
  const float u[4] = {nv, r, s, psi * 0.6366197723675814f};
  int i0[4];
  float f[4];
  for (int d = 0; d < 4; ++d) {
    float c = clamp(u[d], 0.0f, 1.0f) * (float)(n[d] - 1);
    i0[d] = min((int)c, n[d] - 2);
    f[d] = c - (float)i0[d];
  }
  float2 acc = (float2)(0.0f);
  for (int corner = 0; corner < 16; ++corner) {
    float w = 1.0f;
    int index = 0;
    for (int d = 3; d >= 0; --d) {
      const int bit = (corner >> d) & 1;
      w *= bit ? f[d] : 1.0f - f[d];
      index = index * n[d] + i0[d] + bit;
    }
    acc += w * vload2(index, lut);
  }
  return acc;
}

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

    /* Punctual lights, KHR_lights_punctual: f (N.L) times the light's radiance at P. */
    for (int k = 0; k < light_count; ++k) {
      __global const brdfcl_light* lt = lights + k;
      float3 L, radiance = (float3)(lt->color[0], lt->color[1], lt->color[2]);
      float3 dir = (float3)(lt->direction[0], lt->direction[1], lt->direction[2]);
      if ((int)lt->type == BRDFCL_LIGHT_DIRECTIONAL) {
        L = -dir;
      } else {
        float3 to = (float3)(lt->position[0], lt->position[1], lt->position[2]) - P;
        float d2 = max(dot(to, to), 1e-12f), d = sqrt(d2);
        L = to / d;
        float window = 1.0f;
        if (lt->range > 0.0f) {
          float r = d / lt->range;
          window = clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
        }
        radiance *= window / d2;
        if ((int)lt->type == BRDFCL_LIGHT_SPOT) {
          float t = clamp(dot(dir, -L) * lt->cone_scale + lt->cone_offset, 0.0f, 1.0f);
          radiance *= t * t;
        }
      }
      float NdotL = dot(N, L);
      if (NdotL <= 0.0f || NdotV <= 0.0f) continue;
      rgbw f = brdf_layers(m, to_lanes(frame_local(L, T, B, N)), Vl, to_lanes(frame_local(L, Tc, Bc, Nc)), Vc, sheen_e,
                           sheen_e_size);
      result += (float3)(f.r, f.g, f.b) * NdotL * radiance;
    }

#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC
    float ncv = max(dot(Nc, V), 1e-4f);
    float coat = q.clearcoat * (0.04f + 0.96f * pow5w(1.0f - ncv));
    float emission_weight = 1.0f - coat;
    /* Under --ibl exact the image-based light comes from kernels/ibl_exact.cl instead. */
    float3 ibl = (float3)(0.0f);
    if (split_sum) {
      /* Image-based light: split sum with the DFG table (F0 A + B); the dielectric's diffuse is
         weighted by 1 - (0.04 + 0.96 C(N.V)), C the Fresnel-weighted Lambert albedo, so the pair
         reproduces Appendix B's directional albedo; sheen uses view-only albedo scaling (000). */
      float nv = max(NdotV, 1e-4f), rough = q.roughness;
      float3 R = 2.0f * dot(N, V) * N - V;
      float psi = 0.0f;
      if (q.anisotropy_strength > 0.0f) {
        /* 002 "Image-based lighting": bent normal towards the anisotropic direction. */
        float3 Ta = normalize(cos(q.anisotropy_rotation) * T + sin(q.anisotropy_rotation) * B);
        float3 Ba = cross(N, Ta);
        /* The albedo is symmetric under Ta -> -Ta and Ba -> -Ba: the table holds [0, pi/2]. */
        psi = atan2(fabs(dot(V, Ba)), fabs(dot(V, Ta)) + 1e-12f);
        float3 bent = normalize(cross(cross(Ba, V), Ba));
        float a = 1.0f - q.anisotropy_strength * (1.0f - rough);
        a = a * a;
        a = a * a;
        bent = normalize(mix(bent, N, a));
        R = normalize(mix(2.0f * dot(bent, V) * bent - V, bent, rough * rough));
      }
      float lod = rough * (float)(prefilter_levels - 1);
      float3 spec = env_chain(ggx_chain, env_w, env_h, BRDFCL_PREFILTER_CAP_W, BRDFCL_PREFILTER_CAP_H, prefilter_levels,
                              R, env_rotation, lod);
      float3 irr = env_chain(irradiance, irr_w, irr_h, irr_w, irr_h, 1, N, env_rotation, 0.0f);
      /* An anisotropic lobe's albedo depends on both alphas and on the view's azimuth, which no
         isotropic look-up matches (10 % off at strength 1): it has its own table. Its radiance is
         still read at the base roughness about the bent normal (002). */
      float2 ab = q.anisotropy_strength > 0.0f ? lut_aniso(aniso_dfg, nv, rough, q.anisotropy_strength, psi)
                                               : lut2(dfg, dfg_size, nv, rough);
      float C = lut1(fresnel_lambert, fl_size, nv);
      float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
      float3 dielectric = irr * base * (0.96f * (1.0f - C)) + spec * (0.04f * ab.x + ab.y);
      float3 metal = spec * (base * ab.x + ab.y);
      ibl = mix(dielectric, metal, q.metallic);
      float sheen_max = brdfcl_max3(q.sheen_color);
      if (sheen_max > 0.0f) {
        sheen_albedo_row row = E_SheenAlbedoRow(sheen_e_size, q.sheen_roughness);
        float e = E_SheenAlbedo(sheen_e, sheen_e_size, row, nv);
        float3 sheen_light = env_chain(charlie_chain, charlie_w, charlie_h, charlie_w, charlie_h, prefilter_levels, R,
                                       env_rotation, q.sheen_roughness * (float)(prefilter_levels - 1));
        ibl = (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]) * sheen_light * e + (1.0f - sheen_max * e) * ibl;
      }
      if (q.clearcoat > 0.0f) {
        float3 Rc = 2.0f * dot(Nc, V) * Nc - V;
        float2 abc = lut2(dfg, dfg_size, ncv, q.clearcoat_roughness);
        float3 coat_light = env_chain(ggx_chain, env_w, env_h, BRDFCL_PREFILTER_CAP_W, BRDFCL_PREFILTER_CAP_H,
                                      prefilter_levels, Rc, env_rotation,
                                      q.clearcoat_roughness * (float)(prefilter_levels - 1));
        ibl = (1.0f - coat) * ibl + coat * coat_light * (abc.x + abc.y);
      }
    }
#else
    /* The engine's own image-based light (brdf/profiles/ibl.h); its coat sets the emission weight.
       (--ibl exact evaluates the spec only: the host refuses it with a profile.) */
    float3 ibl = (float3)(0.0f);
    float emission_weight = 1.0f;
    if (split_sum) {
      profile_ibl_env e = {ggx_chain, charlie_chain, irradiance, env_w, env_h, charlie_w, charlie_h, prefilter_levels,
                           irr_w, irr_h, env_rotation, dfg, dfg_size, sheen_e, sheen_e_size};
      float3 Ta = normalize(cos(q.anisotropy_rotation) * T + sin(q.anisotropy_rotation) * B);
      profile_ibl_frame frame = {N, V, Nc, Ta, cross(N, Ta)};
      ibl = profile_ibl(&e, &frame, q, &packed, &emission_weight);
    }
#endif
    /* glTF occlusion dims indirect light only: punctual lights and emission are not touched. */
    result += ibl * clamp(GB(GB_OCCLUSION), 0.0f, 1.0f);
    /* 004 "Emission": the coat darkens what is below it. */
    result += (float3)(GB(GB_EMISSIVE_R), GB(GB_EMISSIVE_G), GB(GB_EMISSIVE_B)) * emission_weight;
  }
  out[i] = result.x;
  out[np + i] = result.y;
  out[2 * np + i] = result.z;
#undef GB
}
