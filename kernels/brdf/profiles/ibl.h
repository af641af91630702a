/* Image-based light as each engine profile approximates it (docs/profiles.md "Image-based
   light"): the engine's combination of prefiltered radiance, irradiance and DFG terms, read from
   brdfcl's own prefiltered chains at the roughness the engine intends. Shading kernels only
   (BRDFCL_W == 1); included by shade.cl when BRDFCL_PROFILE != BRDFCL_PROFILE_SPEC. */
#ifndef BRDFCL_PROFILE_IBL_H
#define BRDFCL_PROFILE_IBL_H

#include "light/ibl_env.h"
#include "common/material_pack.h"
#include "brdf/profiles/engine_terms.h"

static inline float3 ibl_radiance(const ibl_env* e, float3 R, float roughness) {
  return env_chain(e->ggx, e->env_w, e->env_h, BRDFCL_PREFILTER_CAP_W, BRDFCL_PREFILTER_CAP_H, e->levels, normalize(R),
                   e->rotation, clamp(roughness, 0.0f, 1.0f) * (float)(e->levels - 1));
}

static inline float3 ibl_charlie_radiance(const ibl_env* e, float3 R, float roughness) {
  return env_chain(e->charlie, e->charlie_w, e->charlie_h, e->charlie_w, e->charlie_h, e->levels, normalize(R), e->rotation,
                   clamp(roughness, 0.0f, 1.0f) * (float)(e->levels - 1));
}

static inline float3 ibl_irradiance(const ibl_env* e, float3 N) {
  return env_chain(e->irradiance, e->irr_w, e->irr_h, e->irr_w, e->irr_h, 1, N, e->rotation, 0.0f);
}

/* brdfcl's DFG table: (A, B) with directional albedo F0 A + B. */
static inline float2 ibl_dfg(const ibl_env* e, float nv, float r) {
  float x = clamp(nv, 0.0f, 1.0f) * (float)(e->dfg_size - 1), y = clamp(r, 0.0f, 1.0f) * (float)(e->dfg_size - 1);
  int x0 = min((int)x, e->dfg_size - 2), y0 = min((int)y, e->dfg_size - 2);
  float fx = x - (float)x0, fy = y - (float)y0;
  __global const float* p = e->dfg + 2 * (y0 * e->dfg_size + x0);
  float2 a = mix(vload2(0, p), vload2(1, p), fx);
  float2 b = mix(vload2(e->dfg_size, p), vload2(e->dfg_size + 1, p), fx);
  return mix(a, b, fy);
}

static inline float ibl_sheen_e(const ibl_env* e, float mu, float r) {
  return E_SheenAlbedo(e->tables, e->e_size, E_SheenAlbedoRow(e->e_size, r), mu);
}

static inline float3 reflect_v(float3 V, float3 n) { return 2.0f * dot(n, V) * n - V; }
static inline float pow4f(float x) { x *= x; return x * x; }
static inline float s5f(float x) { return pow5w(1.0f - clamp(x, 0.0f, 1.0f)); }

/* KHR_materials_anisotropy "Image-based lighting" bent normal, as the spec (and three.js, Babylon) write it. */
static inline float3 bent_normal_spec(const ibl_frame* f, float s, float r) {
  float3 bn = normalize(cross(cross(f->Ba, f->V), f->Ba));
  return normalize(mix(bn, f->N, pow4f(1.0f - s * (1.0f - r))));
}

#if BRDFCL_PROFILE == BRDFCL_PROFILE_KHRONOS
/* Sample Renderer ibl.glsl@4e170c47: Fdez-Aguera's roughness-dependent Fresnel with multiple
   scattering; Charlie-prefiltered sheen times E with view-only scaling by the renderer's
   lut_sheen_E.png; the coat's radiance with no DFG factor; an unnormalized bent normal without
   the R-mix step. */
static inline float3 F_ibl_khronos(float3 F0, float r, float nv, float2 ab) {
  float3 kS = F0 + (max((float3)(1.0f - r), F0) - F0) * s5f(nv);
  float3 FssEss = kS * ab.x + ab.y;
  float Ems = 1.0f - (ab.x + ab.y);
  float3 Favg = F0 + (1.0f - F0) / 21.0f;
  return FssEss + Ems * FssEss * Favg / (1.0f - Favg * Ems);
}

static inline float3 profile_ibl(const ibl_env* e, const ibl_frame* f, brdfcl_material_params q,
                                 const brdfcl_material* p, float* emission_weight) {
  /* clampedDot: N.V and the coat's N.V clamped to [0, 1], no floor */
  float nv = clamp(dot(f->N, f->V), 0.0f, 1.0f), r = clamp(q.roughness, 0.0f, 1.0f);
  float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
  float3 n = f->N;
  if (q.anisotropy_strength > 0.0f) {
    float3 aN = cross(cross(f->Ba, f->V), f->Ba); /* |aN| = sin of the angle (Ba, V): not normalized, as written */
    n = normalize(mix(aN, f->N, pow4f(1.0f - q.anisotropy_strength * (1.0f - r))));
  }
  float3 Ls = ibl_radiance(e, reflect_v(f->V, n), r);
  float2 ab = ibl_dfg(e, nv, r);
  float3 metal = F_ibl_khronos(base, r, nv, ab) * Ls;
  float3 Fd = F_ibl_khronos((float3)(p->ior_f0), r, nv, ab);
  float3 col = mix(mix(ibl_irradiance(e, f->N) * base, Ls, Fd), metal, q.metallic);
  float sheen_max = brdfcl_max3(q.sheen_color);
  if (sheen_max > 0.0f) {
    /* The Charlie lobe's albedo from brdfcl's E at the E table's floor (docs/profiles.md "Tables";
       the renderer bakes its u_CharlieLUT at run time); the base's scaling from the renderer's
       lut_sheen_E.png, after the E and DFG tables. */
    float E = ibl_sheen_e(e, max(nv, 1e-4f), q.sheen_roughness);
    float E_lut = E_SheenKhronos(e->tables + e->e_size * e->e_size + 2 * BRDFCL_DFG_SIZE * BRDFCL_DFG_SIZE, nv,
                                 q.sheen_roughness);
    float3 c = (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]);
    col = ibl_charlie_radiance(e, reflect_v(f->V, f->N), q.sheen_roughness) * c * E + col * (1.0f - sheen_max * E_lut);
  }
  float ncv = clamp(dot(f->Nc, f->V), 0.0f, 1.0f);
  float coat = q.clearcoat * (p->ior_f0 + (1.0f - p->ior_f0) * s5f(ncv));
  col = mix(col, ibl_radiance(e, reflect_v(f->V, f->Nc), q.clearcoat_roughness), coat);
  *emission_weight = 1.0f - coat;
  return col;
}

#elif BRDFCL_PROFILE == BRDFCL_PROFILE_THREEJS
/* PhysicalLightingModel (TSL) indirect: Fdez-Aguera multiscatter from its DFG table at
   (roughness, N.V), computed for the dielectric f0 and for the base colour and mixed by metalness
   (the multiscatter term is not linear in f0, so this is not the multiscatter of the blended f0),
   the radiance read about mix(R, N, roughness^2), sheen from the irradiance times its analytic
   albedo and above the coat, the coat with 0.04 A + B; N.V clamped to [0, 1], as the engine does. */
static inline void ms_threejs(float3 Fr, float2 ab, float3* single, float3* multi) {
  float3 FssEss = Fr * ab.x + ab.y;
  float Ess = ab.x + ab.y, Ems = 1.0f - Ess;
  float3 Favg = Fr + (1.0f - Fr) * 0.047619f;
  float3 Fms = FssEss * Favg / (1.0f - Ems * Favg);
  *single = FssEss;
  *multi = Fms * Ems;
}

static inline float2 dfg_threejs(const ibl_env* e, float r, float nv) {
  float A, B;
  DFG_ThreeJs(e->tables + e->e_size * e->e_size, r, nv, &A, &B);
  return (float2)(A, B);
}

static inline float3 radiance_threejs(const ibl_env* e, float3 V, float3 n, float r) {
  return ibl_radiance(e, normalize(mix(reflect_v(V, n), n, r * r)), r);
}

static inline float3 profile_ibl(const ibl_env* e, const ibl_frame* f, brdfcl_material_params q,
                                 const brdfcl_material* p, float* emission_weight) {
  float nv = clamp(dot(f->N, f->V), 0.0f, 1.0f), r = p->roughness;
  float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
  float3 n = q.anisotropy_strength > 0.0f ? bent_normal_spec(f, q.anisotropy_strength, r) : f->N;
  float3 irr = ibl_irradiance(e, f->N);
  float2 ab = dfg_threejs(e, r, nv);
  float3 ss_d, ms_d, ss_m, ms_m;
  ms_threejs((float3)(p->ior_f0), ab, &ss_d, &ms_d);
  ms_threejs(base, ab, &ss_m, &ms_m);
  float3 ss = mix(ss_d, ss_m, q.metallic), ms = mix(ms_d, ms_m, q.metallic);
  float3 col = radiance_threejs(e, f->V, n, r) * ss + ms * irr + (1.0f - q.metallic) * base * (1.0f - (ss_d + ms_d)) * irr;
  float sheen_max = brdfcl_max3(q.sheen_color);
  float Es = sheen_max > 0.0f ? E_SheenThreeJs(nv, p->sheen_roughness) : 0.0f;
  col *= 1.0f - sheen_max * Es;
  float ncv = clamp(dot(f->Nc, f->V), 0.0f, 1.0f), rc = sqrt(p->clearcoat_alpha);
  float Fcc = F_SchlickSG(0.04f, 1.0f, Fs_SphericalGaussian(ncv));
  float2 abc = dfg_threejs(e, rc, ncv);
  col = col * (1.0f - q.clearcoat * Fcc) + q.clearcoat * radiance_threejs(e, f->V, f->Nc, rc) * (0.04f * abc.x + abc.y);
  col += irr * (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]) * Es;
  *emission_weight = 1.0f - q.clearcoat * Fcc;
  return col;
}

#elif BRDFCL_PROFILE == BRDFCL_PROFILE_FILAMENT
/* surface_light_indirect.fs@1de6d8a5: E = f0 A + B with energy compensation, diffuse x (1 - E),
   radiance about the dominant direction mix(R, n, alpha^2), sheen from the GGX chain times DFG.z
   with view-only scaling, the coat's radiance times its Fresnel on N.V, Kulla's bent normal. */
static inline float3 profile_ibl(const ibl_env* e, const ibl_frame* f, brdfcl_material_params q,
                                 const brdfcl_material* p, float* emission_weight) {
  float nv = max(dot(f->N, f->V), 1e-4f), r = p->roughness, alpha = r * r;
  float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
  float3 n = f->N;
  if (q.anisotropy_strength > 0.0f) {
    float3 aN = cross(cross(f->Ba, f->V), f->Ba);
    n = normalize(mix(f->N, aN, q.anisotropy_strength * clamp(5.0f * r, 0.0f, 1.0f)));
  }
  float3 R = mix(reflect_v(f->V, n), n, alpha * alpha);
  float2 ab = ibl_dfg(e, nv, r);
  float3 f0 = mix((float3)(p->ior_f0), base, q.metallic);
  float3 E = f0 * ab.x + ab.y;
  float3 Fr = E * ibl_radiance(e, R, r) * (1.0f + f0 * (1.0f / (ab.x + ab.y) - 1.0f));
  float3 Fd = (1.0f - q.metallic) * base * ibl_irradiance(e, f->N) * (1.0f - E);
  float sheen_max = brdfcl_max3(q.sheen_color);
  if (sheen_max > 0.0f) {
    float rs = p->sheen_roughness, Es = ibl_sheen_e(e, nv, rs);
    Fd *= 1.0f - sheen_max * Es;
    Fr *= 1.0f - sheen_max * Es;
    Fr += (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]) * Es * ibl_radiance(e, reflect_v(f->V, f->N), rs);
  }
  float ncv = max(dot(f->Nc, f->V), 1e-4f);
  float Fc = q.clearcoat * F_Schlick90(0.04f, 1.0f, s5f(ncv));
  Fd *= 1.0f - Fc;
  Fr *= 1.0f - Fc;
  Fr += ibl_radiance(e, reflect_v(f->V, f->Nc), sqrt(p->clearcoat_alpha)) * Fc;
  *emission_weight = 1.0f - Fc;
  return Fd + Fr;
}

#elif BRDFCL_PROFILE == BRDFCL_PROFILE_BABYLON
/* PBR blocks (pbrBlockReflection, pbrBlockReflectance, pbrBlockSheen, pbrBlockClearcoat,
   pbrBlockFinalLitComponents) under the glTF loader's defines: the base radiance, read at
   sqrt(alpha_G), mixed towards the irradiance by alpha_G (MIX_IBL_RADIANCE_WITH_IRRADIANCE), times
   f0 A + B and the multiscatter factor; the irradiance times the legacy surface albedo
   b (1 - f0_ior)(1 - m), not times 1 - reflectance; sheen from the GGX chain at sqrt(alpha_G,s)
   times c E with view-only scaling; the coat's radiance times cc (0.04 A + B), everything below
   times 1 - cc F(N_c.V). N.V is |N.V| + 1e-7 (absEps); reflection and irradiance about the
   anisotropic bent normal, with no mix towards it. (A, B) and E are Babylon's BRDF texture:
   A = .y - .x, B = .x, E = .b. */
static inline float3 babylon_brdf(const ibl_env* e, float nv, float r) {
  __global const float* lut = e->tables + e->e_size * e->e_size + 2 * BRDFCL_DFG_SIZE * BRDFCL_DFG_SIZE;
  return (float3)(BRDF_Babylon(lut, nv, r, 0), BRDF_Babylon(lut, nv, r, 1), BRDF_Babylon(lut, nv, r, 2));
}

static inline float3 profile_ibl(const ibl_env* e, const ibl_frame* f, brdfcl_material_params q,
                                 const brdfcl_material* p, float* emission_weight) {
  float nv = fabs(dot(f->N, f->V)) + 1e-7f, r = q.roughness, alpha_g = r * r + 0.0005f;
  float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
  float3 n = q.anisotropy_strength > 0.0f ? bent_normal_spec(f, q.anisotropy_strength, r) : f->N;
  float3 irr = ibl_irradiance(e, n);
  float3 t = babylon_brdf(e, nv, r);
  float2 ab = (float2)(t.y - t.x, t.x);
  float3 f0 = mix((float3)(p->ior_f0), base, q.metallic);
  float3 refl = f0 * ab.x + ab.y;
  float3 Ls = mix(ibl_radiance(e, reflect_v(f->V, n), sqrt(alpha_g)), irr, alpha_g);
  float3 spec = Ls * refl * (1.0f + f0 * (1.0f / (ab.x + ab.y) - 1.0f));
  float3 diffuse = irr * (1.0f - q.metallic) * (1.0f - p->ior_f0) * base;
  float3 sheen = (float3)(0.0f);
  float sheen_max = brdfcl_max3(q.sheen_color);
  if (sheen_max > 0.0f) {
    float Es = babylon_brdf(e, nv, q.sheen_roughness).z;
    spec *= 1.0f - sheen_max * Es;
    diffuse *= 1.0f - sheen_max * Es;
    sheen = (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]) * Es *
            ibl_radiance(e, reflect_v(f->V, n), sqrt(p->sheen_alpha));
  }
  float ncv = fabs(dot(f->Nc, f->V)) + 1e-7f;
  float Fc = q.clearcoat * F_Schlick90(0.04f, 1.0f, s5f(ncv));
  float3 tc = babylon_brdf(e, ncv, q.clearcoat_roughness);
  float2 abc = (float2)(tc.y - tc.x, tc.x);
  float3 coat = q.clearcoat * (0.04f * abc.x + abc.y) * ibl_radiance(e, reflect_v(f->V, f->Nc), sqrt(p->clearcoat_alpha));
  *emission_weight = 1.0f - Fc;
  return (diffuse + spec + sheen) * (1.0f - Fc) + coat;
}

#elif BRDFCL_PROFILE == BRDFCL_PROFILE_MATERIALX
/* gltf_pbr indirect (CLOSURE_TYPE_INDIRECT, docs/profiles.md): each BSDF's response is its radiance
   times its analytic-fit albedo and the same energy compensation as the direct light (tinted by the
   average Fresnel F0 + (F90 - F0)/21), layered by the same throughputs; sheen from the irradiance
   times E; a weight below M_FLOAT_EPS leaves a BSDF out; no bent normal; emission above the coat. */
static inline float3 profile_ibl(const ibl_env* e, const ibl_frame* f, brdfcl_material_params q,
                                 const brdfcl_material* p, float* emission_weight) {
  float nv = clamp(dot(f->N, f->V), 1e-8f, 1.0f), avg = sqrt(p->alpha_t * p->alpha);
  float3 base = (float3)(q.base_color[0], q.base_color[1], q.base_color[2]);
  float3 Ls = ibl_radiance(e, reflect_v(f->V, f->N), sqrt(avg));
  float3 irr = ibl_irradiance(e, f->N);
  float A, B;
  DFG_MaterialXFit(nv, avg, &A, &B);
  float E = A + B, f0 = p->ior_f0;
  float comp_d = comp_MaterialX(f0, 1.0f, E);
  float3 comp_m = 1.0f + (base + (1.0f - base) * (1.0f / 21.0f)) * (1.0f - E) / E;
  float t_d = 1.0f - (f0 * A + B) * comp_d;
  float3 col = (1.0f - q.metallic) * (Ls * (f0 * A + B) * comp_d + t_d * base * irr) + q.metallic * Ls * (base * A + B) * comp_m;
  float sheen_max = brdfcl_max3(q.sheen_color);
  if (sheen_max >= 1e-8f) {
    float Es = E_SheenMaterialX(nv, p->sheen_alpha);
    col = irr * (float3)(q.sheen_color[0], q.sheen_color[1], q.sheen_color[2]) * Es + (1.0f - sheen_max * Es) * col;
  }
  if (q.clearcoat >= 1e-8f) {
    float ncv = clamp(dot(f->Nc, f->V), 1e-8f, 1.0f), Ac, Bc;
    DFG_MaterialXFit(ncv, p->clearcoat_alpha, &Ac, &Bc);
    float comp_c = comp_MaterialX(0.04f, 1.0f, Ac + Bc); /* F_diel(1, 1.5) = 0.04 */
    float coat = q.clearcoat * (0.04f * Ac + Bc) * comp_c;
    col = coat * ibl_radiance(e, reflect_v(f->V, f->Nc), sqrt(p->clearcoat_alpha)) + (1.0f - coat) * col;
  }
  *emission_weight = 1.0f;
  return col;
}
#endif

#endif
