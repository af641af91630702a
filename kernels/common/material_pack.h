/* glTF material parameters -> brdfcl_material, written once for both sides: the host packs
   batch materials with it (host/src/model/pack.cpp) and the shading kernel packs each G-buffer
   pixel with it. Alphas are squared and clamped here; see README.md "Clamps". */
#ifndef BRDFCL_MATERIAL_PACK_H
#define BRDFCL_MATERIAL_PACK_H

#include "common/material_layout.h"

#ifdef __OPENCL_VERSION__
#define BRDFCL_PACK_FN static inline
#define BRDFCL_MAXF fmax
#define BRDFCL_COSF cos
#define BRDFCL_SINF sin
#else
#include <cmath>
#define BRDFCL_PACK_FN static inline
#define BRDFCL_MAXF std::fmax
#define BRDFCL_COSF std::cos
#define BRDFCL_SINF std::sin
#endif

typedef struct brdfcl_material_params {
  float base_color[3], metallic, roughness;
  float sheen_color[3], sheen_roughness;     /* ratified KHR_materials_sheen */
  int draft;                                 /* 001's draft: sheen_color = colorFactor * intensityFactor */
  float clearcoat, clearcoat_roughness;
  float anisotropy_strength, anisotropy_rotation;
} brdfcl_material_params;

BRDFCL_PACK_FN float brdfcl_max3(const float* c) { return BRDFCL_MAXF(c[0], BRDFCL_MAXF(c[1], c[2])); }

BRDFCL_PACK_FN brdfcl_material brdfcl_pack_material(brdfcl_material_params m) {
  brdfcl_material p;
  const float alpha = m.roughness * m.roughness;
  const float s2 = m.anisotropy_strength * m.anisotropy_strength;
  for (int i = 0; i < 3; ++i) {
    p.base_color[i] = m.base_color[i];
    p.sheen_color[i] = m.sheen_color[i];
  }
  for (int i = 0; i < 6; ++i) p.reserved[i] = 0.0f;
  p.metallic = m.metallic;
  p.alpha = BRDFCL_MAXF(alpha, BRDFCL_MIN_ALPHA);
  p.alpha_t = BRDFCL_MAXF(alpha * (1.0f - s2) + s2, BRDFCL_MIN_ALPHA); /* 002: mix(alpha, 1, strength^2) */
  p.aniso_cos = BRDFCL_COSF(m.anisotropy_rotation);
  p.aniso_sin = BRDFCL_SINF(m.anisotropy_rotation);
  if (m.draft) {
    /* 001: sheen roughness is the material roughness; (1 - reflectance) weights the additive
       lobe, reflectance = max3(mix(0.04, baseColor, metallic)); no albedo scaling. */
    float f0[3];
    for (int i = 0; i < 3; ++i) f0[i] = 0.04f * (1.0f - m.metallic) + m.base_color[i] * m.metallic;
    p.sheen_max = 0.0f;
    p.sheen_alpha = BRDFCL_MAXF(alpha, BRDFCL_MIN_SHEEN_ALPHA);
    p.sheen_roughness = m.roughness;
    p.sheen_weight = 1.0f - brdfcl_max3(f0);
    p.flags = BRDFCL_MAT_DRAFT_SHEEN | (brdfcl_max3(m.sheen_color) > 0.0f ? BRDFCL_MAT_SHEEN : 0u);
  } else {
    p.sheen_max = brdfcl_max3(m.sheen_color);
    p.sheen_alpha = BRDFCL_MAXF(m.sheen_roughness * m.sheen_roughness, BRDFCL_MIN_SHEEN_ALPHA);
    p.sheen_roughness = m.sheen_roughness;
    p.sheen_weight = 1.0f;
    p.flags = p.sheen_max > 0.0f ? BRDFCL_MAT_SHEEN : 0u;
  }
  p.clearcoat = m.clearcoat;
  p.clearcoat_alpha = BRDFCL_MAXF(m.clearcoat_roughness * m.clearcoat_roughness, BRDFCL_MIN_ALPHA);
  return p;
}

#endif
