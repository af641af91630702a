/* --profile threejs: three.js's WebGPU (TSL) PhysicalLightingModel@011d3c8d, docs/profiles.md
   "threejs": spherical-Gaussian Fresnel, roughness floor 0.045, direct multiscatter from its DFG
   table, Neubelt sheen with its analytic albedo, F(V.H) inside the coat, sheen above the coat. */
#ifndef BRDFCL_PROFILE_THREEJS_H
#define BRDFCL_PROFILE_THREEJS_H

#include "brdf/profiles/engine_terms.h"

/* V.H as the engine takes it, dot(V, normalize(L + V)): below 0.5 the difference form
   1 - |V - H|^2/2 of engine_geometry keeps no digits (grazing mirrored pairs, V.H -> 0). */
BRDF_FN realw threejs_VdotH(engine_geometry g, vec3w V) {
  return g.VdotH < 0.5f ? max(V.x * g.hx + V.y * g.hy + V.z * g.hz, 0.0f) : g.VdotH;
}

/* 1 - Fs for Fs = 2^(-y), y = (5.55473 x + 6.98316) x: its series where Fs -> 1, so that
   1 - F = (1 - f0)(1 - Fs) keeps its digits as x -> 0. */
BRDF_FN realw threejs_OneMinusFs(realw x, realw fs) {
  realw t = (5.55473f * x + 6.98316f) * x * 0.693147181f;
  return t < 0.01f ? t * (1.0f - t * (0.5f - t * (1.0f / 6.0f))) : 1.0f - fs;
}

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
  realw vdh = threejs_VdotH(g, V);
  realw fs = Fs_SphericalGaussian(vdh);
  realw f0d = m.ior_f0;
  realw ms_k = 1.0f / Ess_ThreeJs(dfg, m.roughness, g.NdotV) - 1.0f;
  rgbw f0 = f0_metallic(m);
  rgbw specular = {F_SchlickSG(f0.r, 1.0f, fs) * S * (1.0f + f0.r * ms_k), F_SchlickSG(f0.g, 1.0f, fs) * S * (1.0f + f0.g * ms_k),
                   F_SchlickSG(f0.b, 1.0f, fs) * S * (1.0f + f0.b * ms_k)};
  realw kd = (1.0f - m.metallic) * (1.0f - f0d) * threejs_OneMinusFs(vdh, fs) * M_1_PI_F;
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
    realw nvc = Vc.z, fsc = Fs_SphericalGaussian(nvc);
    realw C = F_SchlickSG(0.04f, 1.0f, Fs_SphericalGaussian(threejs_VdotH(gc, Vc))) *
              D_GGX_HalfAngle(gc.sin2, gc.cos2, m.clearcoat_alpha) * 0.5f /
              max(Lambda_SmithSum(gc.NdotL, gc.NdotV, m.clearcoat_alpha), 1e-6f);
    /* 1 - cc F(N.V) = (1 - cc) + cc (1 - 0.04)(1 - Fs): no cancellation at grazing N.V. */
    realw k = (1.0f - m.clearcoat) + m.clearcoat * (1.0f - 0.04f) * threejs_OneMinusFs(nvc, fsc);
    scale_base(&diffuse, &specular, k);
    coat = m.clearcoat * C; /* TSL finish(): the sheen is added after this, unattenuated */
  }
#endif
  return select_lobe(diffuse, specular, sheen, coat);
}

#endif
