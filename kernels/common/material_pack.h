/* glTF material parameters -> brdfcl_material, written once for both sides: the host packs
   batch materials with it (host/src/model/pack.cpp) and the shading kernel packs each G-buffer
   pixel with it. Alphas are squared and clamped here; see docs/model.md "Clamps". */
#ifndef BRDFCL_MATERIAL_PACK_H
#define BRDFCL_MATERIAL_PACK_H

#include "common/material_layout.h"

#ifndef __OPENCL_VERSION__
#include "common/host_compat.h"
#endif

typedef struct brdfcl_material_params {
  float base_color[3], metallic, roughness;
  float sheen_color[3], sheen_roughness;     /* ratified KHR_materials_sheen */
  int draft;                                 /* KHR_materials_sheen's experimental draft: sheen_color = colorFactor * intensityFactor */
  float clearcoat, clearcoat_roughness;
  float anisotropy_strength, anisotropy_rotation;
  int anisotropy;                            /* KHR_materials_anisotropy is present (khronos reads it) */
  float ior;                                 /* KHR_materials_ior; engine profiles only */
} brdfcl_material_params;

static inline float brdfcl_max3(const float* c) { return fmax(c[0], fmax(c[1], c[2])); }

static inline brdfcl_material brdfcl_pack_material(brdfcl_material_params m) {
  brdfcl_material p;
  const float alpha = m.roughness * m.roughness;
  const float s2 = m.anisotropy_strength * m.anisotropy_strength;
  for (int i = 0; i < 3; ++i) {
    p.base_color[i] = m.base_color[i];
    p.sheen_color[i] = m.sheen_color[i];
  }
  p.sheen_e_row = 0u;
  p.reserved = 0.0f;
  p.clearcoat_roughness = m.clearcoat_roughness;
  p.roughness = m.roughness;
  p.ior_f0 = 0.04f;
  p.aniso_strength = m.anisotropy_strength;
  p.metallic = m.metallic;
  p.alpha = fmax(alpha, BRDFCL_MIN_ALPHA);
  p.alpha_t = fmax(alpha * (1.0f - s2) + s2, BRDFCL_MIN_ALPHA); /* KHR_materials_anisotropy: mix(alpha, 1, strength^2) */
  p.aniso_cos = cos(m.anisotropy_rotation);
  p.aniso_sin = sin(m.anisotropy_rotation);
  if (m.draft) {
    /* KHR_materials_sheen's experimental draft: sheen roughness is the material roughness;
       (1 - reflectance) weights the additive lobe, reflectance = max3(mix(0.04, baseColor, metallic)); no albedo scaling. */
    float f0[3];
    for (int i = 0; i < 3; ++i) f0[i] = 0.04f * (1.0f - m.metallic) + m.base_color[i] * m.metallic;
    p.sheen_max = 0.0f;
    p.sheen_alpha = fmax(alpha, BRDFCL_MIN_SHEEN_ALPHA);
    p.sheen_roughness = m.roughness;
    p.sheen_weight = 1.0f - brdfcl_max3(f0);
    p.flags = BRDFCL_MAT_DRAFT_SHEEN | (brdfcl_max3(m.sheen_color) > 0.0f ? BRDFCL_MAT_SHEEN : 0u);
  } else {
    p.sheen_max = brdfcl_max3(m.sheen_color);
    p.sheen_alpha = fmax(m.sheen_roughness * m.sheen_roughness, BRDFCL_MIN_SHEEN_ALPHA);
    p.sheen_roughness = m.sheen_roughness;
    p.sheen_weight = 1.0f;
    p.flags = p.sheen_max > 0.0f ? BRDFCL_MAT_SHEEN : 0u;
  }
  p.clearcoat = m.clearcoat;
  p.clearcoat_alpha = fmax(m.clearcoat_roughness * m.clearcoat_roughness, BRDFCL_MIN_ALPHA);
  return p;
}

static inline float brdfcl_clampf(float x, float lo, float hi) { return fmax(lo, x < hi ? x : hi); }
static inline float brdfcl_mixf(float a, float b, float t) { return a * (1.0f - t) + b * t; }

/* The same parameters decoded as an engine decodes them (docs/profiles.md): its floors and
   clamps instead of brdfcl's, its roughness remaps, its F0 from the IOR. No engine reads the
   draft sheen, so a draft material has none here. */
static inline brdfcl_material brdfcl_pack_material_profile(brdfcl_material_params m, int profile) {
  brdfcl_material p = brdfcl_pack_material(m);
  if (profile == BRDFCL_PROFILE_SPEC) return p;
  if (m.draft) {
    for (int i = 0; i < 3; ++i) p.sheen_color[i] = 0.0f;
    p.sheen_max = 0.0f;
    p.sheen_weight = 1.0f;
    p.sheen_roughness = 0.0f;
    p.flags = 0u;
  }
  const float r = m.roughness, s = m.anisotropy_strength, s2 = s * s;
  const float rs = m.draft ? 0.0f : m.sheen_roughness, rc = m.clearcoat_roughness;
  const float ior = m.ior;
  const float f0_ior = ((ior - 1.0f) / (ior + 1.0f)) * ((ior - 1.0f) / (ior + 1.0f));
  p.ior_f0 = f0_ior;
  p.roughness = r;
  p.sheen_weight = 1.0f;
  if (profile == BRDFCL_PROFILE_KHRONOS) {
    /* The renderer defines MATERIAL_ANISOTROPY when the extension is present, even at strength 0,
       and then takes the anisotropic path (ab floored at 0.001). */
    const float a = r * r;
    if (m.anisotropy) p.flags |= BRDFCL_MAT_ANISOTROPY;
    p.alpha = m.anisotropy ? brdfcl_clampf(a, 0.001f, 1.0f) : a;
    p.alpha_t = brdfcl_mixf(a, 1.0f, s2);
    const float rs1 = fmax(rs, 1e-6f);
    p.sheen_alpha = rs1 * rs1;
    p.sheen_roughness = rs;
    p.clearcoat_alpha = rc * rc;
  } else if (profile == BRDFCL_PROFILE_THREEJS) {
    const float rho = brdfcl_clampf(r, 0.045f, 1.0f), a = rho * rho;
    p.roughness = rho;
    p.alpha = a;
    p.alpha_t = brdfcl_mixf(a, 1.0f, s2);
    const float rhos = brdfcl_clampf(rs, 0.07f, 1.0f); /* MaterialNode SHEEN_ROUGHNESS: clamp(0.07, 1) */
    p.sheen_alpha = rhos * rhos;
    p.sheen_roughness = rhos;
    const float rhoc = brdfcl_clampf(rc, 0.045f, 1.0f);
    p.clearcoat_alpha = rhoc * rhoc;
    p.ior_f0 = f0_ior < 1.0f ? f0_ior : 1.0f;
  } else if (profile == BRDFCL_PROFILE_FILAMENT) {
    if (m.anisotropy) p.flags |= BRDFCL_MAT_ANISOTROPY; /* gltfio's MATERIAL_HAS_ANISOTROPY */
    const float rho = brdfcl_clampf(brdfcl_mixf(r, fmax(r, rc), m.clearcoat), 0.045f, 1.0f), a = rho * rho;
    p.roughness = rho;
    p.alpha_t = fmax(a * (1.0f + s), 0.002025f); /* Kulla 2017, A = strength */
    p.alpha = fmax(a * (1.0f - s), 0.002025f);
    const float rhos = brdfcl_clampf(rs, 0.045f, 1.0f);
    p.sheen_alpha = rhos * rhos;
    p.sheen_roughness = rhos;
    const float rhoc = brdfcl_clampf(rc, 0.045f, 1.0f);
    p.clearcoat_alpha = rhoc * rhoc;
    const float iorf = fmax(ior, 1.0f);
    p.ior_f0 = ((iorf - 1.0f) / (iorf + 1.0f)) * ((iorf - 1.0f) / (iorf + 1.0f));
  } else if (profile == BRDFCL_PROFILE_BABYLON) {
    const float ag = r * r + 0.0005f;
    p.alpha = fmax(ag, 0.0005f);
    p.alpha_t = fmax(brdfcl_mixf(ag, 1.0f, s2), 0.0005f);
    p.sheen_alpha = rs * rs + 0.0005f;
    p.sheen_roughness = rs;
    p.clearcoat_alpha = rc * rc + 0.0005f;
  } else { /* BRDFCL_PROFILE_MATERIALX */
    const float a = r * r;
    p.alpha = brdfcl_clampf(a, 1e-5f, 1.0f);
    p.alpha_t = brdfcl_clampf(brdfcl_mixf(a, 1.0f, s2), 1e-5f, 1.0f);
    p.sheen_alpha = rs * rs;
    p.sheen_roughness = rs;
    p.clearcoat_alpha = brdfcl_clampf(rc * rc, 1e-8f, 1.0f);
  }
  return p;
}

#endif
