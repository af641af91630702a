/* --profile babylon: Babylon.js PBRMaterial as its glTF loader sets it up (pbrBRDFFunctions.fx@00e0487b
   and the pbrBlock*.fx files), docs/profiles.md "babylon": alpha + 0.0005 on every lobe, diffuse
   weighted by 1 - F(N.H), multiscatter energy conservation, Ashikhmin sheen with view-only
   scaling, Kelemen coat with F on V.H. */
#ifndef BRDFCL_PROFILE_BABYLON_H
#define BRDFCL_PROFILE_BABYLON_H

#include "brdf/profiles/engine_terms.h"

BRDF_FN rgbw brdf_profile(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                          __global const float* tables, int e_size) {
  __global const float* dfg = tables + e_size * e_size;
  engine_geometry g = engine_geometry_of(L, V);
#if BRDFCL_HAS_ANISOTROPY
  realw c = m.aniso_cos, s = m.aniso_sin;
  realw S = D_Burley(along_t(g.hx, g.hy, c, s), along_b(g.hx, g.hy, c, s), g.hz, m.alpha_t, m.alpha) * 0.5f /
            Lambda_HeitzSum(g.NdotL, g.NdotV, along_t(V.x, V.y, c, s), along_b(V.x, V.y, c, s),
                            along_t(L.x, L.y, c, s), along_b(L.x, L.y, c, s), m.alpha_t, m.alpha);
#else
  realw S = D_GGX_HalfAngle(g.sin2, g.cos2, m.alpha) * 0.5f / Lambda_SmithSum(g.NdotL, g.NdotV, m.alpha);
#endif
  realw f0r = mix(m.ior_f0, m.base_r, m.metallic), f0g = mix(m.ior_f0, m.base_g, m.metallic),
        f0b = mix(m.ior_f0, m.base_b, m.metallic);
  realw ec_k = 1.0f / Ess_ThreeJs(dfg, m.roughness, g.NdotV) - 1.0f;
  rgbw specular = {F_Schlick90(f0r, 1.0f, g.s5) * S * (1.0f + f0r * ec_k), F_Schlick90(f0g, 1.0f, g.s5) * S * (1.0f + f0g * ec_k),
                   F_Schlick90(f0b, 1.0f, g.s5) * S * (1.0f + f0b * ec_k)};
  /* (1 - N.H)^5 with 1 - N.H = sin^2 / (1 + N.H): exact near N.H = 1. */
  realw s5nh = pow5w(g.sin2 / (1.0f + g.hz));
  realw kd = (1.0f - m.metallic) * M_1_PI_F;
  rgbw diffuse = {kd * m.base_r * (1.0f - F_Schlick90(f0r, 1.0f, s5nh)), kd * m.base_g * (1.0f - F_Schlick90(f0g, 1.0f, s5nh)),
                  kd * m.base_b * (1.0f - F_Schlick90(f0b, 1.0f, s5nh))};
  rgbw sheen = rgbw_splat(0.0f);
#if BRDFCL_HAS_SHEEN
  {
    realw dv = D_Charlie(g.sin2, g.cos2, m.sheen_alpha) * V_Ashikhmin(g.NdotL, g.NdotV);
    sheen.r = m.sheen_r * dv;
    sheen.g = m.sheen_g * dv;
    sheen.b = m.sheen_b * dv;
    realw sh = 1.0f - m.sheen_max * E_SheenAlbedo(tables, e_size, E_SheenAlbedoRow(e_size, m.sheen_roughness), g.NdotV);
    diffuse = rgbw_scale(diffuse, sh);
    specular = rgbw_scale(specular, sh);
  }
#endif
  realw coat = 0.0f;
#if BRDFCL_HAS_CLEARCOAT
  {
    engine_geometry gc = engine_geometry_of(Lc, Vc);
    realw Fc = m.clearcoat * F_Schlick90(0.04f, 1.0f, gc.s5);
    realw k = 1.0f - Fc;
    diffuse = rgbw_scale(diffuse, k);
    specular = rgbw_scale(specular, k);
    sheen = rgbw_scale(sheen, k);
    coat = Fc * D_GGX_HalfAngle(gc.sin2, gc.cos2, m.clearcoat_alpha) * V_Kelemen(gc.VdotH);
  }
#endif
  return select_lobe(diffuse, specular, sheen, coat);
}

#endif
