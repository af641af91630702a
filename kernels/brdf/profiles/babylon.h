/* --profile babylon: Babylon.js PBRMaterial with the defines its glTF loader leaves set
   (docs/profiles.md "babylon"): LEGACY_SPECULAR_ENERGY_CONSERVATION, BASE_DIFFUSE_MODEL EON at
   diffuse roughness 0, MS_BRDF_ENERGY_CONSERVATION on the specular and the coat, alpha + 0.0005
   on every lobe, Ashikhmin sheen with view-only scaling and its D on the engine's float
   1 - N.H^2, Kelemen coat with F on V.H. */
#ifndef BRDFCL_PROFILE_BABYLON_H
#define BRDFCL_PROFILE_BABYLON_H

#include "brdf/profiles/engine_terms.h"

/* helperFunctions.fx: saturateEps clamps N.L to [1e-7, 1]; absEps adds 1e-7 to |N.V|. */
#define BRDFCL_BABYLON_EPS 1.0e-7f

BRDF_FN engine_geometry babylon_geometry(vec3w L, vec3w V) {
  engine_geometry g = engine_geometry_of(L, V, BRDFCL_BABYLON_EPS, 0.0f);
  g.NdotV = V.z + BRDFCL_BABYLON_EPS;
  return g;
}

BRDF_FN rgbw brdf_profile(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                          __global const float* tables, int e_size) {
  /* Babylon's BRDF texture: after the E table and three.js's DFG table (material_layout.h). */
  __global const float* lut = tables + e_size * e_size + 2 * BRDFCL_DFG_SIZE * BRDFCL_DFG_SIZE;
  engine_geometry g = babylon_geometry(L, V);
#if BRDFCL_HAS_ANISOTROPY
  realw S = D_BurleyRotated(m, g, g.hz) * 0.5f / Lambda_HeitzRotated(m, g, L, V);
#else
  realw S = D_GGX_HalfAngle(g.sin2, g.cos2, m.alpha) * 0.5f / Lambda_SmithSum(g.NdotL, g.NdotV, m.alpha);
#endif
  rgbw f0 = f0_metallic(m);
  realw ec_k = 1.0f / BRDF_Babylon(lut, g.NdotV, m.roughness, 1) - 1.0f;
  rgbw specular = {F_Schlick90(f0.r, 1.0f, g.s5) * S * (1.0f + f0.r * ec_k), F_Schlick90(f0.g, 1.0f, g.s5) * S * (1.0f + f0.g * ec_k),
                   F_Schlick90(f0.b, 1.0f, g.s5) * S * (1.0f + f0.b * ec_k)};
  /* Legacy energy conservation: the albedo loses the dielectric F0 once, with no angle. */
  realw kd = (1.0f - m.ior_f0) * (1.0f - m.metallic) * M_1_PI_F;
  rgbw diffuse = {kd * m.base_r, kd * m.base_g, kd * m.base_b};
  rgbw sheen = rgbw_splat(0.0f);
#if BRDFCL_HAS_SHEEN
  {
    sheen = sheen_coloured(m, D_CharlieOneMinusCos2(g.hz, m.sheen_alpha) * V_Ashikhmin(g.NdotL, g.NdotV));
    /* SHEEN_ALBEDOSCALING: the texture's .b at (N.V, sheen roughness), view only. */
    realw sh = 1.0f - m.sheen_max * BRDF_Babylon(lut, g.NdotV, m.sheen_roughness, 2);
    scale_base(&diffuse, &specular, sh);
  }
#endif
  rgbw coat = rgbw_splat(0.0f);
#if BRDFCL_HAS_CLEARCOAT
  {
    engine_geometry gc = babylon_geometry(Lc, Vc);
    realw Fc = m.clearcoat * F_Schlick90(0.04f, 1.0f, gc.s5);
    realw k = 1.0f - Fc;
    scale_below(&diffuse, &specular, &sheen, k);
    realw c = Fc * D_GGX_HalfAngle(gc.sin2, gc.cos2, m.clearcoat_alpha) * V_Kelemen(gc.VdotH);
    /* The coat's multiscatter factor takes the base's F0 (pbrBlockClearcoat), so it is coloured. */
    realw cc_k = 1.0f / BRDF_Babylon(lut, gc.NdotV, m.clearcoat_roughness, 1) - 1.0f;
    coat.r = c * (1.0f + f0.r * cc_k);
    coat.g = c * (1.0f + f0.g * cc_k);
    coat.b = c * (1.0f + f0.b * cc_k);
  }
#endif
  /* pbrBlockFinalUnlitComponents: finalDiffuse = max(diffuseBase * surfaceAlbedo, 0), after the
     sheen scaling, which turns negative where max3(c) .b exceeds 1. */
  diffuse.r = max(diffuse.r, 0.0f);
  diffuse.g = max(diffuse.g, 0.0f);
  diffuse.b = max(diffuse.b, 0.0f);
#if BRDFCL_LOBE == BRDFCL_LOBE_CLEARCOAT
  return coat;
#elif BRDFCL_LOBE == BRDFCL_LOBE_DIFFUSE || BRDFCL_LOBE == BRDFCL_LOBE_SPECULAR || BRDFCL_LOBE == BRDFCL_LOBE_SHEEN
  return select_lobe(diffuse, specular, sheen, 0.0f);
#else
  return rgbw_add(select_lobe(diffuse, specular, sheen, 0.0f), coat);
#endif
}

#endif
