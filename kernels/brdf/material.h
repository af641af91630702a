/* The layered glTF material: base (Appendix B) with anisotropy, sheen (ratified or draft) with
   albedo scaling, clearcoat on top. Lobes are built from terms.h, the material from lobes.
   Options and the feature set of a batch are compile-time defines, so unused layers cost nothing. */
#ifndef BRDFCL_MATERIAL_H
#define BRDFCL_MATERIAL_H

#include "common/material_layout.h"
#include "common/lanes.h"
#include "brdf/terms.h"
#include "brdf/sheen_albedo.h"

#ifndef BRDFCL_SHEEN_VIS
#define BRDFCL_SHEEN_VIS BRDFCL_SHEEN_VIS_CHARLIE
#endif
#ifndef BRDFCL_SHEEN_DIST
#define BRDFCL_SHEEN_DIST BRDFCL_SHEEN_DIST_CHARLIE
#endif
#ifndef BRDFCL_SCALING
#define BRDFCL_SCALING BRDFCL_SCALING_MIN
#endif
#ifndef BRDFCL_LOBE
#define BRDFCL_LOBE BRDFCL_LOBE_ALL
#endif
/* Whose BRDF: the specs (below) or an engine's (brdf/profiles/, docs/profiles.md). */
#ifndef BRDFCL_PROFILE
#define BRDFCL_PROFILE BRDFCL_PROFILE_SPEC
#endif
/* Feature set of the batch: a layer no material uses is compiled out. */
#ifndef BRDFCL_HAS_SHEEN
#define BRDFCL_HAS_SHEEN 1
#endif
#ifndef BRDFCL_HAS_DRAFT
#define BRDFCL_HAS_DRAFT 1
#endif
#ifndef BRDFCL_HAS_CLEARCOAT
#define BRDFCL_HAS_CLEARCOAT 1
#endif
#ifndef BRDFCL_HAS_ANISOTROPY
#define BRDFCL_HAS_ANISOTROPY 1
#endif

/* Below this cosine, denominators of V terms are evaluated at this cosine: keeps f finite at
   N.L or N.V -> 0+ (documented clamp; f = 0 at N.L <= 0 or N.V <= 0 anyway). */
#define BRDFCL_MIN_COS 1.0e-4f

/* The float fields a lane reads, as (lane name, field of brdfcl_material). */
#define BRDFCL_MATERIAL_LANES(X)                                                      \
  X(base_r, base_color[0]) X(base_g, base_color[1]) X(base_b, base_color[2])          \
  X(metallic, metallic) X(alpha, alpha) X(alpha_t, alpha_t)                           \
  X(aniso_cos, aniso_cos) X(aniso_sin, aniso_sin)                                     \
  X(sheen_r, sheen_color[0]) X(sheen_g, sheen_color[1]) X(sheen_b, sheen_color[2])    \
  X(sheen_max, sheen_max) X(sheen_alpha, sheen_alpha)                                 \
  X(sheen_roughness, sheen_roughness) X(sheen_weight, sheen_weight)                   \
  X(clearcoat, clearcoat) X(clearcoat_alpha, clearcoat_alpha)                       \
  BRDFCL_PROFILE_LANES(X)

/* The fields only engine profiles read: spec's gathers stay as they were. */
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC
#define BRDFCL_PROFILE_LANES(X)
#else
#define BRDFCL_PROFILE_LANES(X) \
  X(roughness, roughness) X(ior_f0, ior_f0) X(aniso_strength, aniso_strength) X(clearcoat_roughness, clearcoat_roughness)
#endif

#define BRDFCL_DECLARE_LANE(name, field) realw name;
typedef struct {
  BRDFCL_MATERIAL_LANES(BRDFCL_DECLARE_LANE)
  realw draft;     /* 1 for the experimental draft's sheen, else 0 */
  realw aniso_ext; /* 1 where BRDFCL_MAT_ANISOTROPY is set (khronos, filament), else 0 */
} material_lanes;

/* All lanes share one material (grid evaluation, shading): splat. OpenCL C 1.2 has no generic
   address space, hence a global and a private entry point over one body. */
#define BRDFCL_SPLAT_LANE(name, field) out.name = (realw)(m->field);
#define BRDFCL_SPLAT_BODY                                                    \
  material_lanes out;                                                        \
  BRDFCL_MATERIAL_LANES(BRDFCL_SPLAT_LANE)                                   \
  out.draft = (realw)((m->flags & BRDFCL_MAT_DRAFT_SHEEN) ? 1.0f : 0.0f);     \
  out.aniso_ext = (realw)((m->flags & BRDFCL_MAT_ANISOTROPY) ? 1.0f : 0.0f);  \
  return out;
BRDF_FN material_lanes material_splat(__global const brdfcl_material* m) { BRDFCL_SPLAT_BODY }
#ifdef __OPENCL_VERSION__
BRDF_FN material_lanes material_splat_private(const brdfcl_material* m) { BRDFCL_SPLAT_BODY }
#endif

/* Each lane has its own material index: one vector gather per field, records being
   sizeof(brdfcl_material) / 4 floats apart. */
#if BRDFCL_W == 1
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  return material_splat(materials + index);
}
#else
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  intw at = AS_INTW(index) * (int)(sizeof(brdfcl_material) / 4);
  material_lanes out;
#define BRDFCL_GATHER_LANE(name, field) out.name = GATHERW((__global const float*)&materials->field, at);
  BRDFCL_MATERIAL_LANES(BRDFCL_GATHER_LANE)
  intw flags = AS_INTW(GATHERW((__global const float*)&materials->flags, at));
  out.draft = select((realw)(0.0f), (realw)(1.0f), (flags & (int)BRDFCL_MAT_DRAFT_SHEEN) != 0);
  out.aniso_ext = select((realw)(0.0f), (realw)(1.0f), (flags & (int)BRDFCL_MAT_ANISOTROPY) != 0);
  return out;
}
#endif

/* White sheen lobe D * V for the batch's options; 000 "Sheen distribution", "Sheen visibility". */
BRDF_FN realw sheen_dv(realw hxy2, realw hn2, realw NdotL, realw NdotV, realw alpha) {
#if BRDFCL_SHEEN_DIST == BRDFCL_SHEEN_DIST_ASHIKHMIN
  realw D = D_Ashikhmin(hxy2, hn2, alpha);
#else
  realw D = D_Charlie(hxy2, hn2, alpha);
#endif
#if BRDFCL_SHEEN_VIS == BRDFCL_SHEEN_VIS_ASHIKHMIN
  realw V = V_Ashikhmin(NdotL, NdotV);
#else
  realw V = V_Charlie(NdotL, NdotV, alpha);
#endif
  return D * V;
}

/* Half-vector components with the degenerate L = -V case mapped to H = N. */
BRDF_FN vec3w half_vector(vec3w L, vec3w V) {
  vec3w h = {L.x + V.x, L.y + V.y, L.z + V.z};
  realw h2 = h.x * h.x + h.y * h.y + h.z * h.z;
  /* L = -V with both within ~1e-15 of the horizon: |L + V|^2 underflows and H is undefined.
     Taking H = N there keeps f finite (documented clamp; such pairs sit far outside the domain). */
  intw degenerate = h2 < 1.0e-30f;
  /* Nearly opposite L and V: the D terms square |h|^2 twice, which underflows to 0/0 (NaN f, e.g.
     at grazing L, V mirrored about N with N.L = N.V = 1e-12). Every consumer of h is homogeneous
     of degree 0 in it, so an exact power-of-two rescale (2^40) changes nothing else. */
  realw scale = select((realw)(1.0f), (realw)(1099511627776.0f), h2 < 1.0e-12f);
  h.x = select(h.x * scale, (realw)(0.0f), degenerate);
  h.y = select(h.y * scale, (realw)(0.0f), degenerate);
  h.z = select(h.z * scale, (realw)(1.0f), degenerate);
  return h;
}

/* Base and sheen layers (everything below the clearcoat), f in 1/sr without the cosine. L, V:
   unit vectors in the shading frame (N = +Z); not yet zeroed below the horizon. `sheen_e`: E
   table for the batch's sheen options (unused without scaling). */
BRDF_FN rgbw brdf_sheened(const material_lanes m, vec3w L, vec3w V, __global const float* sheen_e,
                          int sheen_e_size) {
  realw NdotL = max(L.z, BRDFCL_MIN_COS), NdotV = max(V.z, BRDFCL_MIN_COS);

  vec3w h = half_vector(L, V);
  realw hxy2 = h.x * h.x + h.y * h.y, hn2 = h.z * h.z, h2 = hxy2 + hn2;
  realw inv_h = rsqrt(h2);
  /* 1 - V.H = |V - H|^2 / 2 for unit vectors: no cancellation as H -> V. */
  realw dx = V.x - h.x * inv_h, dy = V.y - h.y * inv_h, dz = V.z - h.z * inv_h;
  realw w = pow5w(0.5f * (dx * dx + dy * dy + dz * dz));

  rgbw result = rgbw_splat(0.0f);

  /* Base layer: glTF 2.0 Appendix B, specular D and V replaced by 002's anisotropic forms. */
#if BRDFCL_LOBE == BRDFCL_LOBE_ALL || BRDFCL_LOBE == BRDFCL_LOBE_DIFFUSE || BRDFCL_LOBE == BRDFCL_LOBE_SPECULAR
  rgbw base;
  {
#if BRDFCL_LOBE != BRDFCL_LOBE_DIFFUSE
#if BRDFCL_HAS_ANISOTROPY
    /* T' = (cos r, sin r, 0), B' = N x T' = (-sin r, cos r, 0). */
    realw c = m.aniso_cos, s = m.aniso_sin;
    realw ht = h.x * c + h.y * s, hb = h.y * c - h.x * s;
    realw TdotV = V.x * c + V.y * s, BdotV = V.y * c - V.x * s;
    realw TdotL = L.x * c + L.y * s, BdotL = L.y * c - L.x * s;
    realw spec = D_GGX_Anisotropic(ht, hb, h.z, h2, m.alpha_t, m.alpha) *
                 V_GGX_Anisotropic(NdotL, NdotV, TdotV, BdotV, TdotL, BdotL, m.alpha_t, m.alpha);
#else
    realw spec = D_GGX(hxy2, hn2, m.alpha) * V_SmithGGXCorrelated(NdotL, NdotV, m.alpha);
#endif
#endif
    realw F = F_Schlick(0.04f, w);
    realw dielectric_w = 1.0f - m.metallic;
    base = rgbw_splat(0.0f);
#if BRDFCL_LOBE != BRDFCL_LOBE_SPECULAR
    realw kd = dielectric_w * (1.0f - F) * M_1_PI_F;
    base.r += kd * m.base_r;
    base.g += kd * m.base_g;
    base.b += kd * m.base_b;
#endif
#if BRDFCL_LOBE != BRDFCL_LOBE_DIFFUSE
    realw ks = dielectric_w * F;
    base.r += (ks + m.metallic * F_Schlick(m.base_r, w)) * spec;
    base.g += (ks + m.metallic * F_Schlick(m.base_g, w)) * spec;
    base.b += (ks + m.metallic * F_Schlick(m.base_b, w)) * spec;
#endif
  }
#if BRDFCL_HAS_SHEEN && BRDFCL_SCALING != BRDFCL_SCALING_NONE
  /* Conty & Kulla albedo scaling; 000 "Albedo-scaling technique". Draft lanes have sheen_max 0. */
  sheen_albedo_row row = E_SheenAlbedoRow(sheen_e_size, m.sheen_roughness);
  realw s_view = 1.0f - m.sheen_max * E_SheenAlbedo(sheen_e, sheen_e_size, row, NdotV);
#if BRDFCL_SCALING == BRDFCL_SCALING_MIN
  realw s_light = 1.0f - m.sheen_max * E_SheenAlbedo(sheen_e, sheen_e_size, row, NdotL);
  base = rgbw_scale(base, min(s_view, s_light));
#else
  base = rgbw_scale(base, s_view);
#endif
#endif
  result = base;
#endif

  /* Sheen layer: 000 (ratified), or 001's additive (1 - reflectance) blend for draft lanes. */
#if BRDFCL_HAS_SHEEN && (BRDFCL_LOBE == BRDFCL_LOBE_ALL || BRDFCL_LOBE == BRDFCL_LOBE_SHEEN)
  {
    realw dv = sheen_dv(hxy2, hn2, NdotL, NdotV, m.sheen_alpha);
#if BRDFCL_HAS_DRAFT && !(BRDFCL_SHEEN_DIST == BRDFCL_SHEEN_DIST_CHARLIE && BRDFCL_SHEEN_VIS == BRDFCL_SHEEN_VIS_ASHIKHMIN)
    /* The draft always uses Charlie D with Ashikhmin V, whatever the ratified options say. */
    realw dv_draft = D_Charlie(hxy2, hn2, m.sheen_alpha) * V_Ashikhmin(NdotL, NdotV);
    dv = select(dv, dv_draft, m.draft > 0.5f);
#endif
    realw k = m.sheen_weight * dv;
    result.r += m.sheen_r * k;
    result.g += m.sheen_g * k;
    result.b += m.sheen_b * k;
  }
#endif

  return result;
}

/* Clearcoat on top: 004 "Layering", Fresnel on Nc.V (energy-conserving simple layering). Lc, Vc
   are L and V in the clearcoat normal's frame (Nc = +Z); in batch evaluation Nc = N. */
BRDF_FN rgbw layer_clearcoat(rgbw below, realw clearcoat, realw clearcoat_alpha, vec3w Lc, vec3w Vc) {
  rgbw result = below;
#if BRDFCL_HAS_CLEARCOAT
  realw Fc = F_Schlick(0.04f, pow5w(1.0f - Vc.z));
  realw coat = clearcoat * Fc;
#if BRDFCL_LOBE == BRDFCL_LOBE_CLEARCOAT
  result = rgbw_splat(0.0f);
#else
  result = rgbw_scale(result, 1.0f - coat);
#endif
#if BRDFCL_LOBE == BRDFCL_LOBE_ALL || BRDFCL_LOBE == BRDFCL_LOBE_CLEARCOAT
  vec3w h = half_vector(Lc, Vc);
  realw NcL = max(Lc.z, BRDFCL_MIN_COS), NcV = max(Vc.z, BRDFCL_MIN_COS);
  realw cc = D_GGX(h.x * h.x + h.y * h.y, h.z * h.z, clearcoat_alpha) * V_SmithGGXCorrelated(NcL, NcV, clearcoat_alpha);
  realw add = coat * cc;
  result.r += add;
  result.g += add;
  result.b += add;
#endif
#endif
  return result;
}

/* Included here, outside the per-engine branches: the kernel loader inlines each header once, at
   its first #include, so that first one must not sit in a branch another profile skips. */
#if BRDFCL_PROFILE != BRDFCL_PROFILE_SPEC
#include "brdf/profiles/engine_terms.h"
#endif
#if BRDFCL_PROFILE == BRDFCL_PROFILE_KHRONOS
#include "brdf/profiles/khronos.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_THREEJS
#include "brdf/profiles/threejs.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_FILAMENT
#include "brdf/profiles/filament.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_BABYLON
#include "brdf/profiles/babylon.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_MATERIALX
#include "brdf/profiles/materialx.h"
#endif

/* Every layer, f in 1/sr without the cosine; not yet zeroed below the horizon. L, V in the
   shading frame, Lc, Vc in the clearcoat normal's (the same in batch evaluation). `sheen_e`: the
   sheen E table; engine profiles find their DFG table right after it. */
BRDF_FN rgbw brdf_layers(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                         __global const float* sheen_e, int sheen_e_size) {
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC
  return layer_clearcoat(brdf_sheened(m, L, V, sheen_e, sheen_e_size), m.clearcoat, m.clearcoat_alpha, Lc, Vc);
#else
  return brdf_profile(m, L, V, Lc, Vc, sheen_e, sheen_e_size);
#endif
}

/* The layered material, f(L, V) in 1/sr without the cosine, 0 when N.L <= 0 or N.V <= 0. */
BRDF_FN rgbw brdf_material(const material_lanes m, vec3w L, vec3w V, __global const float* sheen_e,
                           int sheen_e_size) {
  intw valid = (L.z > 0.0f) & (V.z > 0.0f);
  rgbw result = brdf_layers(m, L, V, L, V, sheen_e, sheen_e_size);
  result.r = keep_or_zero(result.r, valid);
  result.g = keep_or_zero(result.g, valid);
  result.b = keep_or_zero(result.b, valid);
  return result;
}

#endif
