/* --profile spec, the default: the specs' layered material composed from brdf/lobes.h. glTF 2.0
   Appendix B's base (specular per KHR_materials_anisotropy), KHR_materials_sheen over it with
   albedo scaling, KHR_materials_clearcoat on top. BRDFCL_LOBE keeps one lobe by value: a
   compile-time constant, so the lobes it drops fold away. */
#ifndef BRDFCL_PROFILE_SPEC_H
#define BRDFCL_PROFILE_SPEC_H

#include "brdf/lobes.h"
#include "brdf/sheen_albedo.h"

/* Conty & Kulla albedo scaling of the base under the sheen (KHR_materials_sheen "Albedo-scaling
   technique"): 1 - max(sheenColor) E(N.V), and under BRDFCL_SCALING_MIN the smaller of that and
   its N.L twin. Draft lanes have sheen_max 0. */
BRDF_FN realw sheen_base_scale(const material_lanes m, lobe_geometry g, __global const float* sheen_e, int sheen_e_size) {
#if BRDFCL_E_ROW
  /* Each material's row of E, blended once by the host (material.h, BRDFCL_E_ROW). */
  realw s_view = 1.0f - m.sheen_max * E_SheenAlbedoAlong(sheen_e, sheen_e_size, m.e_row, g.NdotV);
  if (BRDFCL_SCALING != BRDFCL_SCALING_MIN) return s_view;
  realw s_light = 1.0f - m.sheen_max * E_SheenAlbedoAlong(sheen_e, sheen_e_size, m.e_row, g.NdotL);
#else
  sheen_albedo_row row = E_SheenAlbedoRow(sheen_e_size, m.sheen_roughness);
  realw s_view = 1.0f - m.sheen_max * E_SheenAlbedo(sheen_e, sheen_e_size, row, g.NdotV);
  if (BRDFCL_SCALING != BRDFCL_SCALING_MIN) return s_view;
  realw s_light = 1.0f - m.sheen_max * E_SheenAlbedo(sheen_e, sheen_e_size, row, g.NdotL);
#endif
  return min(s_view, s_light);
}

/* Base and sheen layers (everything below the clearcoat), f in 1/sr without the cosine. L, V:
   unit vectors in the shading frame (N = +Z); not yet zeroed below the horizon. `sheen_e`: E
   table for the batch's sheen options (unused without scaling). */
BRDF_FN rgbw brdf_sheened(const material_lanes m, vec3w L, vec3w V, __global const float* sheen_e,
                          int sheen_e_size) {
  const int lobe = BRDFCL_LOBE;
  const int has_sheen = BRDFCL_HAS_SHEEN;
  lobe_geometry g = lobe_geometry_of(L, V);
  rgbw result = rgbw_splat(0.0f);
  if (lobe == BRDFCL_LOBE_ALL || lobe == BRDFCL_LOBE_DIFFUSE || lobe == BRDFCL_LOBE_SPECULAR) {
    rgbw base = rgbw_splat(0.0f);
    if (lobe != BRDFCL_LOBE_SPECULAR) base = lobe_add(base, lobe_diffuse(m, g));
    if (lobe != BRDFCL_LOBE_DIFFUSE) base = lobe_add(base, lobe_specular(m, g));
    if (has_sheen && BRDFCL_SCALING != BRDFCL_SCALING_NONE) base = rgbw_scale(base, sheen_base_scale(m, g, sheen_e, sheen_e_size));
    result = base;
  }
  /* The ratified sheen, or the experimental draft's additive (1 - reflectance) blend on draft lanes. */
  if (has_sheen && (lobe == BRDFCL_LOBE_ALL || lobe == BRDFCL_LOBE_SHEEN)) result = lobe_add(result, lobe_sheen(m, g));
  return result;
}

/* The clearcoat on top (KHR_materials_clearcoat "Layering"): what is below times 1 - coat, plus
   the coat's lobe, coat = clearcoat * Fresnel on Nc.V. Lc, Vc are L and V in the clearcoat
   normal's frame (Nc = +Z); in batch evaluation Nc = N. */
BRDF_FN rgbw layer_clearcoat(rgbw below, realw clearcoat, realw clearcoat_alpha, vec3w Lc, vec3w Vc) {
  const int lobe = BRDFCL_LOBE;
  if (!BRDFCL_HAS_CLEARCOAT) return below;
  realw Fc = F_Schlick(0.04f, pow5w(1.0f - Vc.z));
  realw coat = clearcoat * Fc;
  rgbw result;
  if (lobe == BRDFCL_LOBE_CLEARCOAT) {
    result = rgbw_splat(0.0f);
  } else {
    result = rgbw_scale(below, 1.0f - coat);
  }
  if (lobe == BRDFCL_LOBE_ALL || lobe == BRDFCL_LOBE_CLEARCOAT) {
    realw add = lobe_clearcoat(coat, clearcoat_alpha, Lc, Vc);
    result.r += add;
    result.g += add;
    result.b += add;
  }
  return result;
}

/* Under --lobe specular or --lobe clearcoat alone, f = c D / (2 W), D the lobe's GGX distribution
   and 1 / (2 W) its visibility: c is returned, W stored in *vis_half_rcp. A sampler whose pdf
   holds the same D forms the weight f cos / pdf with D cancelled (docs/sampling.md, "The weight of
   a GGX lobe alone"). Unit L and V above the horizon. */
#if BRDFCL_LOBE == BRDFCL_LOBE_SPECULAR || BRDFCL_LOBE == BRDFCL_LOBE_CLEARCOAT
BRDF_FN rgbw brdf_lobe_over_dv(const material_lanes m, vec3w L, vec3w V, __global const float* sheen_e,
                               int sheen_e_size, realw* vis_half_rcp) {
  realw coat = (realw)(0.0f);
  if (BRDFCL_HAS_CLEARCOAT) coat = m.clearcoat * F_Schlick(0.04f, pow5w(1.0f - V.z));
  if (BRDFCL_LOBE == BRDFCL_LOBE_CLEARCOAT) {
    *vis_half_rcp = lobe_clearcoat_vis_half_rcp(m.clearcoat_alpha, L, V);
    return rgbw_splat(coat);
  }
  lobe_geometry g = lobe_geometry_of(L, V);
  *vis_half_rcp = lobe_specular_vis_half_rcp(m, g);
  rgbw result = lobe_specular_colour(m, g);
  if (BRDFCL_HAS_SHEEN && BRDFCL_SCALING != BRDFCL_SCALING_NONE)
    result = rgbw_scale(result, sheen_base_scale(m, g, sheen_e, sheen_e_size));
  if (BRDFCL_HAS_CLEARCOAT) result = rgbw_scale(result, 1.0f - coat);
  return result;
}
#endif

/* Every layer, as the engine profiles' brdf_profile: f in 1/sr without the cosine. */
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC
BRDF_FN rgbw brdf_profile(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                          __global const float* sheen_e, int sheen_e_size) {
  return layer_clearcoat(brdf_sheened(m, L, V, sheen_e, sheen_e_size), m.clearcoat, m.clearcoat_alpha, Lc, Vc);
}
#endif

#endif
