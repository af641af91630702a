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
  engine_geometry g = engine_geometry_of(L, V, BRDFCL_MIN_COS, BRDFCL_MIN_COS);
#if BRDFCL_HAS_ANISOTROPY
  realw S = D_BurleyRotated(m, g, g.hz) * 0.5f / Lambda_HeitzRotated(m, g, L, V);
#else
  realw S = D_GGX_HalfAngle(g.sin2, g.cos2, m.alpha) * 0.5f / Lambda_SmithSum(g.NdotL, g.NdotV, m.alpha);
#endif
  rgbw f0 = f0_metallic(m);
  realw ec_k = 1.0f / Ess_ThreeJs(dfg, m.roughness, g.NdotV) - 1.0f;
  rgbw specular = {F_Schlick90(f0.r, 1.0f, g.s5) * S * (1.0f + f0.r * ec_k), F_Schlick90(f0.g, 1.0f, g.s5) * S * (1.0f + f0.g * ec_k),
                   F_Schlick90(f0.b, 1.0f, g.s5) * S * (1.0f + f0.b * ec_k)};
  /* (1 - N.H)^5 with 1 - N.H = sin^2 / (1 + N.H): exact near N.H = 1. */
  realw s5nh = pow5w(g.sin2 / (1.0f + g.hz));
  realw kd = (1.0f - m.metallic) * M_1_PI_F;
  rgbw diffuse = {kd * m.base_r * (1.0f - F_Schlick90(f0.r, 1.0f, s5nh)), kd * m.base_g * (1.0f - F_Schlick90(f0.g, 1.0f, s5nh)),
                  kd * m.base_b * (1.0f - F_Schlick90(f0.b, 1.0f, s5nh))};
  rgbw sheen = rgbw_splat(0.0f);
#if BRDFCL_HAS_SHEEN
  {
    sheen = sheen_coloured(m, D_Charlie(g.sin2, g.cos2, m.sheen_alpha) * V_Ashikhmin(g.NdotL, g.NdotV));
    realw sh = sheen_scaling_view(m, tables, e_size, g.NdotV);
    scale_base(&diffuse, &specular, sh);
  }
#endif
  realw coat = 0.0f;
#if BRDFCL_HAS_CLEARCOAT
  {
    engine_geometry gc = engine_geometry_of(Lc, Vc, BRDFCL_MIN_COS, BRDFCL_MIN_COS);
    realw Fc = m.clearcoat * F_Schlick90(0.04f, 1.0f, gc.s5);
    realw k = 1.0f - Fc;
    scale_below(&diffuse, &specular, &sheen, k);
    coat = Fc * D_GGX_HalfAngle(gc.sin2, gc.cos2, m.clearcoat_alpha) * V_Kelemen(gc.VdotH);
  }
#endif
  return select_lobe(diffuse, specular, sheen, coat);
}

#endif
