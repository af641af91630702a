/* --profile materialx: MaterialX gltf_pbr (1.39, nodedef 2.0.1, 4177b2cb), docs/profiles.md
   "materialx": layers by directional-albedo throughput, GGX energy compensation from the analytic
   albedo fit tinted by the average Fresnel, isotropic Smith on sqrt(alpha_t alpha_b), exact
   dielectric Fresnel on the coat, sheen D on the engine's float 1 - N.H^2. */
#ifndef BRDFCL_PROFILE_MATERIALX_H
#define BRDFCL_PROFILE_MATERIALX_H

#include "brdf/profiles/engine_terms.h"

/* mx_ggx_energy_compensation: 1 + Favg (1 - E) / E with E = A + B of the fit and Favg the
   cosine-weighted hemispherical average of a Schlick Fresnel, F0 + (F90 - F0) / 21 (mx_fresnel_average,
   MaterialX ce2398cde). */
BRDF_FN realw comp_MaterialX(realw F0, realw F90, realw E) {
  realw favg = F0 + (F90 - F0) * (1.0f / 21.0f);
  return 1.0f + favg * (1.0f - E) / E;
}

BRDF_FN rgbw brdf_profile(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                          __global const float* tables, int e_size) {
  engine_geometry g = engine_geometry_of(L, V, 1e-8f, 1e-8f); /* clamp(dot, M_FLOAT_EPS, 1) */
#if BRDFCL_HAS_ANISOTROPY
  realw D = D_BurleyRotated(m, g, g.hz);
  realw avg = sqrt(m.alpha_t * m.alpha);
#else
  realw D = D_GGX_HalfAngle(g.sin2, g.cos2, m.alpha);
  realw avg = m.alpha;
#endif
  realw DV = D * 0.5f / Lambda_SmithSum(g.NdotL, g.NdotV, avg);
  realw A, B;
  DFG_MaterialXFit(g.NdotV, avg, &A, &B);
  realw E = A + B;
  realw f0 = m.ior_f0;
  realw Fd = F_Schlick90(f0, 1.0f, g.s5);
  realw comp_d = comp_MaterialX(f0, 1.0f, E);
  realw spec_d = DV * Fd * comp_d;
  realw t_d = 1.0f - (f0 * A + B) * comp_d;
  realw Fr = F_Schlick90(m.base_r, 1.0f, g.s5), Fg = F_Schlick90(m.base_g, 1.0f, g.s5), Fb = F_Schlick90(m.base_b, 1.0f, g.s5);
  realw dw = 1.0f - m.metallic;
  rgbw specular = {dw * spec_d + m.metallic * DV * Fr * comp_MaterialX(m.base_r, 1.0f, E),
                   dw * spec_d + m.metallic * DV * Fg * comp_MaterialX(m.base_g, 1.0f, E),
                   dw * spec_d + m.metallic * DV * Fb * comp_MaterialX(m.base_b, 1.0f, E)};
  realw kd = dw * t_d * M_1_PI_F;
  rgbw diffuse = {kd * m.base_r, kd * m.base_g, kd * m.base_b};
  rgbw sheen = rgbw_splat(0.0f);
#if BRDFCL_HAS_SHEEN
  {
    /* mx_sheen_bsdf returns at once for a weight max3(c) below M_FLOAT_EPS: no response, throughput 1. */
    intw on = m.sheen_max >= 1e-8f;
    realw dv = D_CharlieOneMinusCos2(g.hz, max(m.sheen_alpha, 0.005f)) * V_Ashikhmin(g.NdotL, g.NdotV);
    sheen = sheen_coloured(m, select((realw)(0.0f), dv, on));
    realw t_s = select((realw)(1.0f), 1.0f - m.sheen_max * E_SheenMaterialX(g.NdotV, m.sheen_alpha), on);
    scale_base(&diffuse, &specular, t_s);
  }
#endif
  realw coat = 0.0f;
#if BRDFCL_HAS_CLEARCOAT
  {
    engine_geometry gc = engine_geometry_of(Lc, Vc, 1e-8f, 1e-8f);
    realw Ac, Bc;
    DFG_MaterialXFit(gc.NdotV, m.clearcoat_alpha, &Ac, &Bc);
    realw Fc = F_Dielectric(gc.VdotH, 1.5f);
    realw comp_c = comp_MaterialX(0.04f, 1.0f, Ac + Bc); /* F_diel(1, 1.5) = 0.04, F90 = 1 */
    /* mx_dielectric_bsdf likewise returns at once for a weight cc below M_FLOAT_EPS. */
    intw on = m.clearcoat >= 1e-8f;
    realw t_c = select((realw)(1.0f), 1.0f - m.clearcoat * (0.04f * Ac + Bc) * comp_c, on);
    scale_below(&diffuse, &specular, &sheen, t_c);
    coat = select((realw)(0.0f),
                  m.clearcoat * D_GGX_HalfAngle(gc.sin2, gc.cos2, m.clearcoat_alpha) * 0.5f /
                      Lambda_SmithSum(gc.NdotL, gc.NdotV, m.clearcoat_alpha) * Fc * comp_c,
                  on);
  }
#endif
  return select_lobe(diffuse, specular, sheen, coat);
}

#endif
