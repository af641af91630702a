/* The spec's image-based light as a split sum (Karis 2013, "Real Shading in Unreal Engine 4"):
   prefiltered radiance times the directional albedo from brdfcl's DFG tables, layered as the
   material is (glTF 2.0 Appendix B base, KHR_materials_anisotropy's bent normal, KHR_materials_sheen
   with view-only albedo scaling, KHR_materials_clearcoat on top). --ibl exact is ibl_exact.cl. */
#ifndef BRDFCL_LIGHT_SPLIT_SUM_H
#define BRDFCL_LIGHT_SPLIT_SUM_H

#include "light/ibl_env.h"
#include "common/material_pack.h"
#include "brdf/sheen_albedo.h"

/* Bilinear look-up of a two-channel size x size table at (N.V, perceptual roughness). */
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

/* The clearcoat's Fresnel weight on Nc.V, clearcoat * F_Schlick(0.04): what the coat takes from
   the light below it, the emission included (KHR_materials_clearcoat "Emission"). */
static inline float split_sum_coat(brdfcl_material_params q, const ibl_frame* f) {
  float ncv = max(dot(f->Nc, f->V), 1e-4f);
  return q.clearcoat * (0.04f + 0.96f * pow5w(1.0f - ncv));
}

/* Reflected image-based radiance at the pixel, before occlusion. The dielectric's diffuse is
   weighted by 1 - (0.04 + 0.96 C(N.V)), C the Fresnel-weighted Lambert albedo, so that the pair
   reproduces Appendix B's directional albedo. */
static inline float3 split_sum_spec(const ibl_env* e, const ibl_frame* f, brdfcl_material_params q) {
  float3 N = f->N, V = f->V, Nc = f->Nc;
  float NdotV = dot(N, V);
  float ncv = max(dot(Nc, V), 1e-4f);
  float coat = split_sum_coat(q, f);
  float nv = max(NdotV, 1e-4f), rough = q.roughness;
  float3 R = 2.0f * dot(N, V) * N - V;
  float psi = 0.0f;
  if (q.anisotropy_strength > 0.0f) {
    /* KHR_materials_anisotropy "Image-based lighting": bent normal towards the anisotropic direction. */
    float3 Ta = f->Ta, Ba = f->Ba;
    /* The albedo is symmetric under Ta -> -Ta and Ba -> -Ba: the table holds [0, pi/2]. */
    psi = atan2(fabs(dot(V, Ba)), fabs(dot(V, Ta)) + 1e-12f);
    float3 bent = normalize(cross(cross(Ba, V), Ba));
    float a = 1.0f - q.anisotropy_strength * (1.0f - rough);
    a = a * a;
    a = a * a;
    bent = normalize(mix(bent, N, a));
    R = normalize(mix(2.0f * dot(bent, V) * bent - V, bent, rough * rough));
  }
  float lod = rough * (float)(e->levels - 1);
  float3 spec = env_chain(e->ggx, e->env_w, e->env_h, BRDFCL_PREFILTER_CAP_W, BRDFCL_PREFILTER_CAP_H, e->levels, R,
                          e->rotation, lod);
  float3 irr = env_chain(e->irradiance, e->irr_w, e->irr_h, e->irr_w, e->irr_h, 1, N, e->rotation, 0.0f);
  /* An anisotropic lobe's albedo depends on both alphas and on the view's azimuth, which no
     isotropic look-up matches (10 % off at strength 1): it has its own table. Its radiance is
     still read at the base roughness about the bent normal (KHR_materials_anisotropy). */
  float2 ab = q.anisotropy_strength > 0.0f ? lut_aniso(e->aniso_dfg, nv, rough, q.anisotropy_strength, psi)
                                           : lut2(e->dfg, e->dfg_size, nv, rough);
  float C = lut1(e->fresnel_lambert, e->fl_size, nv);
  float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
  float3 dielectric = irr * base * (0.96f * (1.0f - C)) + spec * (0.04f * ab.x + ab.y);
  float3 metal = spec * (base * ab.x + ab.y);
  float3 ibl = mix(dielectric, metal, q.metallic);
  /* KHR_materials_sheen: Charlie-prefiltered radiance times E, the base scaled by 1 - max(color) E. */
  float sheen_max = brdfcl_max3(q.sheen_color);
  if (sheen_max > 0.0f) {
    sheen_albedo_row row = E_SheenAlbedoRow(e->e_size, q.sheen_roughness);
    float E = E_SheenAlbedo(e->tables, e->e_size, row, nv);
    float3 sheen_light = env_chain(e->charlie, e->charlie_w, e->charlie_h, e->charlie_w, e->charlie_h, e->levels, R,
                                   e->rotation, q.sheen_roughness * (float)(e->levels - 1));
    ibl = (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]) * sheen_light * E + (1.0f - sheen_max * E) * ibl;
  }
  if (q.clearcoat > 0.0f) {
    float3 Rc = 2.0f * dot(Nc, V) * Nc - V;
    float2 abc = lut2(e->dfg, e->dfg_size, ncv, q.clearcoat_roughness);
    float3 coat_light = env_chain(e->ggx, e->env_w, e->env_h, BRDFCL_PREFILTER_CAP_W, BRDFCL_PREFILTER_CAP_H, e->levels,
                                  Rc, e->rotation, q.clearcoat_roughness * (float)(e->levels - 1));
    ibl = (1.0f - coat) * ibl + coat * coat_light * (abc.x + abc.y);
  }
  return ibl;
}

#endif
