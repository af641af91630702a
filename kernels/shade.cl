/* Deferred shading of a G-buffer: per pixel, decode the material once (common/material_pack.h),
   add every punctual light through the batch evaluator's own layers (brdf_sheened, then
   layer_clearcoat on the clearcoat normal), then split-sum image-based light (times the glTF
   occlusion) and the clearcoat-darkened emission. Masked-out pixels show the environment. The view
   is the G-buffer's V where it has one, else the camera's (pinhole or orthographic). */
#define BRDFCL_W 1
#include "brdf/material.h"
#include "common/material_pack.h"
#include "common/environment.h"
#include "common/gbuffer_pixel.h"

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

static inline vec3w to_lanes(float3 v) { vec3w o = {v.x, v.y, v.z}; return o; }

__kernel void shade(__global const float* restrict gb, int width, int height, brdfcl_camera cam,
                    __global const brdfcl_light* restrict lights, int light_count,
                    __global const float* restrict background, __global const float* restrict ggx_chain,
                    __global const float* restrict charlie_chain, __global const float* restrict irradiance,
                    int env_w, int env_h, int prefilter_levels, int irr_w, int irr_h, float env_rotation,
                    __global const float* restrict dfg, int dfg_size, __global const float* restrict sheen_e,
                    int sheen_e_size, __global const float* restrict fresnel_lambert, int fl_size,
                    int split_sum, __global float* restrict out) {
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const int np = width * height, i = y * width + x;
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
    result = env_chain(background, env_w, env_h, 1, -normalize(Vg), env_rotation, 0.0f);
  } else if (GB(GB_MASK) < 0.5f && ortho) {
    result = env_chain(background, env_w, env_h, 1, forward, env_rotation, 0.0f);
  } else if (GB(GB_MASK) < 0.5f) {
    float sx = (2.0f * ((float)x + 0.5f) / (float)width - 1.0f) * cam.tan_half_fov * cam.aspect;
    float sy = (1.0f - 2.0f * ((float)y + 0.5f) / (float)height) * cam.tan_half_fov;
    float3 d = normalize(forward + sx * (float3)(cam.right[0], cam.right[1], cam.right[2]) +
                         sy * (float3)(cam.up[0], cam.up[1], cam.up[2]));
    result = env_chain(background, env_w, env_h, 1, d, env_rotation, 0.0f);
  } else {
    gbuffer_pixel px = gbuffer_pixel_decode(gb, np, i, Vg, eye, forward, ortho);
    float3 P = px.P, N = px.N, T = px.T, B = px.B, Nc = px.Nc, Tc = px.Tc, Bc = px.Bc, V = px.V;
    brdfcl_material_params q = px.q;
    brdfcl_material packed = brdfcl_pack_material(q);
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
      rgbw f = brdf_sheened(m, to_lanes(frame_local(L, T, B, N)), Vl, sheen_e, sheen_e_size);
      f = layer_clearcoat(f, m.clearcoat, m.clearcoat_alpha, to_lanes(frame_local(L, Tc, Bc, Nc)), Vc);
      result += (float3)(f.r, f.g, f.b) * NdotL * radiance;
    }

    float ncv = max(dot(Nc, V), 1e-4f);
    float coat = q.clearcoat * (0.04f + 0.96f * pow5w(1.0f - ncv));
    /* Under --ibl exact the image-based light comes from kernels/ibl_exact.cl instead. */
    float3 ibl = (float3)(0.0f);
    if (split_sum) {
      /* Image-based light: split sum with the DFG table (F0 A + B); the dielectric's diffuse is
         weighted by 1 - (0.04 + 0.96 C(N.V)), C the Fresnel-weighted Lambert albedo, so the pair
         reproduces Appendix B's directional albedo; sheen uses view-only albedo scaling (000). */
      float nv = max(NdotV, 1e-4f), rough = q.roughness;
      float3 R = 2.0f * dot(N, V) * N - V;
      if (q.anisotropy_strength > 0.0f) {
        /* 002 "Image-based lighting": bent normal towards the anisotropic direction. */
        float3 Ta = normalize(cos(q.anisotropy_rotation) * T + sin(q.anisotropy_rotation) * B);
        float3 Ba = cross(N, Ta);
        float3 bent = normalize(cross(cross(Ba, V), Ba));
        float a = 1.0f - q.anisotropy_strength * (1.0f - rough);
        a = a * a;
        a = a * a;
        bent = normalize(mix(bent, N, a));
        R = normalize(mix(2.0f * dot(bent, V) * bent - V, bent, rough * rough));
      }
      float lod = rough * (float)(prefilter_levels - 1);
      float3 spec = env_chain(ggx_chain, env_w, env_h, prefilter_levels, R, env_rotation, lod);
      float3 irr = env_chain(irradiance, irr_w, irr_h, 1, N, env_rotation, 0.0f);
      /* The DFG table is isotropic: an anisotropic lobe is looked up at the RMS of its two alphas,
         the best single match to its directional albedo against the reference (within 2.5% up to
         strength 0.6, 10% at strength 1); its radiance is still read at the base roughness (002). */
      float dfg_rough = q.anisotropy_strength > 0.0f
                            ? sqrt(sqrt(0.5f * (packed.alpha_t * packed.alpha_t + packed.alpha * packed.alpha)))
                            : rough;
      float2 ab = lut2(dfg, dfg_size, nv, dfg_rough);
      float C = lut1(fresnel_lambert, fl_size, nv);
      float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
      float3 dielectric = irr * base * (0.96f * (1.0f - C)) + spec * (0.04f * ab.x + ab.y);
      float3 metal = spec * (base * ab.x + ab.y);
      ibl = mix(dielectric, metal, q.metallic);
      float sheen_max = brdfcl_max3(q.sheen_color);
      if (sheen_max > 0.0f) {
        sheen_albedo_row row = E_SheenAlbedoRow(sheen_e_size, q.sheen_roughness);
        float e = E_SheenAlbedo(sheen_e, sheen_e_size, row, nv);
        float3 sheen_light = env_chain(charlie_chain, env_w, env_h, prefilter_levels, R, env_rotation,
                                       q.sheen_roughness * (float)(prefilter_levels - 1));
        ibl = (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]) * sheen_light * e + (1.0f - sheen_max * e) * ibl;
      }
      if (q.clearcoat > 0.0f) {
        float3 Rc = 2.0f * dot(Nc, V) * Nc - V;
        float2 abc = lut2(dfg, dfg_size, ncv, q.clearcoat_roughness);
        float3 coat_light = env_chain(ggx_chain, env_w, env_h, prefilter_levels, Rc, env_rotation,
                                      q.clearcoat_roughness * (float)(prefilter_levels - 1));
        ibl = (1.0f - coat) * ibl + coat * coat_light * (abc.x + abc.y);
      }
    }
    /* glTF occlusion dims indirect light only: punctual lights and emission are not touched. */
    result += ibl * clamp(GB(GB_OCCLUSION), 0.0f, 1.0f);
    /* 004 "Emission": the coat darkens what is below it. */
    result += (float3)(GB(GB_EMISSIVE_R), GB(GB_EMISSIVE_G), GB(GB_EMISSIVE_B)) * (1.0f - coat);
  }
  out[i] = result.x;
  out[np + i] = result.y;
  out[2 * np + i] = result.z;
#undef GB
}
