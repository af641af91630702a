/* --profile filament: Filament's standard model, desktop quality (surface_brdf.fs@04d50d42,
   surface_shading_model_standard.fs@1b47d187), docs/profiles.md "filament": base roughness raised
   by the coat, f90 from f0, Lambert without Fresnel, energy compensation, view-only sheen scaling,
   Kelemen coat with F on L.H, Kulla anisotropy wherever the extension is present. The isotropic D
   caps k at 453.5 (so D at 453.5^2/pi); V, Kelemen and the anisotropic D have no cap on desktop
   (PREVENT_DIV0 is n / d). */
#ifndef BRDFCL_PROFILE_FILAMENT_H
#define BRDFCL_PROFILE_FILAMENT_H

#include "brdf/profiles/engine_terms.h"

/* D_GGX: k = min(alpha / (1 - N.H^2 + (N.H alpha)^2), 453.5), D = k^2 / pi. */
BRDF_FN realw D_GGX_Filament(realw sin2, realw cos2, realw alpha) {
  realw k = min(alpha / (sin2 + cos2 * alpha * alpha), 453.5f);
  return k * k * M_1_PI_F;
}

BRDF_FN rgbw brdf_profile(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                          __global const float* tables, int e_size) {
  __global const float* dfg = tables + e_size * e_size;
  engine_geometry g = engine_geometry_of(L, V, 0.0f, 1e-4f); /* saturate(N.L), clampNoV */
  realw S = D_GGX_Filament(g.sin2, g.cos2, m.alpha) * 0.5f / Lambda_SmithSum(g.NdotL, g.NdotV, m.alpha);
#if BRDFCL_HAS_ANISOTROPY
  /* MATERIAL_HAS_ANISOTROPY, which gltfio defines when the extension is present (strength 0
     included): alpha_t = alpha (1 + A), alpha = alpha (1 - A), Burley's D without the cap. A
     material without the extension keeps the capped isotropic D in any batch. */
  S = select(S, D_BurleyRotated(m, g, g.hz) * 0.5f / Lambda_HeitzRotated(m, g, L, V), m.aniso_ext > 0.0f);
#endif
  rgbw f0 = f0_metallic(m);
  realw f90 = clamp(16.5f * (f0.r + f0.g + f0.b), 0.0f, 1.0f);
  realw ec_k = 1.0f / Ess_ThreeJs(dfg, m.roughness, g.NdotV) - 1.0f;
  rgbw specular = {F_Schlick90(f0.r, f90, g.s5) * S * (1.0f + f0.r * ec_k), F_Schlick90(f0.g, f90, g.s5) * S * (1.0f + f0.g * ec_k),
                   F_Schlick90(f0.b, f90, g.s5) * S * (1.0f + f0.b * ec_k)};
  realw kd = (1.0f - m.metallic) * M_1_PI_F;
  rgbw diffuse = {kd * m.base_r, kd * m.base_g, kd * m.base_b};
  rgbw sheen = rgbw_splat(0.0f);
#if BRDFCL_HAS_SHEEN
  {
    sheen = sheen_coloured(m, D_CharlieFloored(g.sin2, g.cos2, m.sheen_alpha) * V_Ashikhmin(g.NdotL, g.NdotV));
    realw sh = sheen_scaling_view(m, tables, e_size, g.NdotV);
    scale_base(&diffuse, &specular, sh);
  }
#endif
  realw coat = 0.0f;
#if BRDFCL_HAS_CLEARCOAT
  {
    engine_geometry gc = engine_geometry_of(Lc, Vc, 0.0f, 1e-4f);
    realw Fcc = m.clearcoat * F_Schlick90(0.04f, 1.0f, gc.s5);
    realw k = 1.0f - Fcc;
    scale_below(&diffuse, &specular, &sheen, k);
    coat = Fcc * D_GGX_Filament(gc.sin2, gc.cos2, m.clearcoat_alpha) * V_Kelemen(gc.VdotH);
  }
#endif
  return select_lobe(diffuse, specular, sheen, coat);
}

#endif
