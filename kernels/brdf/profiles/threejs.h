/* --profile threejs: three.js's WebGPU (TSL) PhysicalLightingModel@011d3c8d, docs/profiles.md
   "threejs": spherical-Gaussian Fresnel, roughness floor 0.045, direct multiscatter from its DFG
   table, Neubelt sheen with its analytic albedo, F(V.H) inside the coat, sheen above the coat. */
#ifndef BRDFCL_PROFILE_THREEJS_H
#define BRDFCL_PROFILE_THREEJS_H

#include "brdf/profiles/engine_terms.h"

BRDF_FN rgbw brdf_profile(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                          __global const float* tables, int e_size) {
  __global const float* dfg = tables + e_size * e_size;
  engine_geometry g = engine_geometry_of(L, V, 0.0f, 0.0f);
#if BRDFCL_HAS_ANISOTROPY
  /* With strength 0 (alpha_t = alpha) this is the isotropic lobe. */
  realw S = D_BurleyRotated(m, g, g.hz) * 0.5f / max(Lambda_HeitzRotated(m, g, L, V), 1e-6f);
#else
  realw S = D_GGX_HalfAngle(g.sin2, g.cos2, m.alpha) * 0.5f / max(Lambda_SmithSum(g.NdotL, g.NdotV, m.alpha), 1e-6f);
#endif
  realw fs = Fs_SphericalGaussian(g.VdotH);
  realw f0d = m.ior_f0;
  realw ms_k = 1.0f / Ess_ThreeJs(dfg, m.roughness, g.NdotV) - 1.0f;
  rgbw f0 = f0_metallic(m);
  rgbw specular = {F_SchlickSG(f0.r, 1.0f, fs) * S * (1.0f + f0.r * ms_k), F_SchlickSG(f0.g, 1.0f, fs) * S * (1.0f + f0.g * ms_k),
                   F_SchlickSG(f0.b, 1.0f, fs) * S * (1.0f + f0.b * ms_k)};
  realw kd = (1.0f - m.metallic) * (1.0f - F_SchlickSG(f0d, 1.0f, fs)) * M_1_PI_F;
  rgbw diffuse = {kd * m.base_r, kd * m.base_g, kd * m.base_b};
  rgbw sheen = rgbw_splat(0.0f);
#if BRDFCL_HAS_SHEEN
  {
    sheen = sheen_coloured(m, D_CharlieFloored(g.sin2, g.cos2, m.sheen_alpha) * min(V_Ashikhmin(g.NdotL, g.NdotV), 1.0f));
    realw sh = 1.0f - m.sheen_max * max(E_SheenThreeJs(g.NdotV, m.sheen_roughness), E_SheenThreeJs(g.NdotL, m.sheen_roughness));
    scale_base(&diffuse, &specular, sh);
  }
#endif
  realw coat = 0.0f;
#if BRDFCL_HAS_CLEARCOAT
  {
    engine_geometry gc = engine_geometry_of(Lc, Vc, 0.0f, 0.0f);
    realw Fcc = F_SchlickSG(0.04f, 1.0f, Fs_SphericalGaussian(Vc.z));
    realw C = F_SchlickSG(0.04f, 1.0f, Fs_SphericalGaussian(gc.VdotH)) *
              D_GGX_HalfAngle(gc.sin2, gc.cos2, m.clearcoat_alpha) * 0.5f /
              max(Lambda_SmithSum(gc.NdotL, gc.NdotV, m.clearcoat_alpha), 1e-6f);
    realw k = 1.0f - m.clearcoat * Fcc;
    scale_base(&diffuse, &specular, k);
    coat = m.clearcoat * C; /* TSL finish(): the sheen is added after this, unattenuated */
  }
#endif
  return select_lobe(diffuse, specular, sheen, coat);
}

#endif
