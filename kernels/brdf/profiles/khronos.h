/* --profile khronos: the glTF Sample Renderer's punctual BRDF (pbr.frag@9dfbb82b, brdf.glsl as in
   glTF-Sample-Viewer@d0b428c8), docs/profiles.md "khronos". No alpha floors (D is infinite where
   the engine's float D_GGX denominator is 0, NaN at alpha = 0, as there), F0 from the IOR for base
   and coat, sheen D on the engine's float 1 - N.H^2, sheen V clamped to 1, the sheen albedo from
   the renderer's lut_sheen_E.png. */
#ifndef BRDFCL_PROFILE_KHRONOS_H
#define BRDFCL_PROFILE_KHRONOS_H

#include "brdf/profiles/engine_terms.h"

BRDF_FN rgbw brdf_profile(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                          __global const float* tables, int e_size) {
  engine_geometry g = engine_geometry_of(L, V, 0.0f, 0.0f);
  realw S = D_GGX_EngineZero(g.sin2, g.cos2, g.hz, m.alpha) * 0.5f / Lambda_SmithSum(g.NdotL, g.NdotV, m.alpha);
#if BRDFCL_HAS_ANISOTROPY
  {
    /* BRDF_specularGGXAnisotropy, taken whenever the extension is present (MATERIAL_ANISOTROPY),
       strength 0 included: ab floored at 0.001 (packed), N.H clamped to [0.001, 1], V <= 1; D in
       the engine's grouping, finite at at = 0 (roughness 0). */
    realw D = D_BurleyW2(along_t(g.hx, g.hy, m.aniso_cos, m.aniso_sin), along_b(g.hx, g.hy, m.aniso_cos, m.aniso_sin),
                         clamp(g.hz, 0.001f, 1.0f), m.alpha_t, m.alpha);
    realw Va = 0.5f / Lambda_HeitzRotated(m, g, L, V);
    S = select(S, D * min(Va, 1.0f), m.aniso_ext > 0.0f);
  }
#endif
  realw Fd = F_Schlick90(m.ior_f0, 1.0f, g.s5);
  /* 1 - Fd = (1 - f0)(1 - S5) with 1 - S5 = V.H (1 + x + x^2 + x^3 + x^4), x = 1 - V.H, and V.H
     taken as the dot product: no cancellation at V.H << 1, where 1 - V.H rounds near 1. */
  realw vh = V.x * g.hx + V.y * g.hy + V.z * g.hz, x = 1.0f - g.VdotH;
  realw one_minus_s5 = vh * (1.0f + x * (1.0f + x * (1.0f + x * (1.0f + x))));
  realw kd = (1.0f - m.metallic) * ((1.0f - m.ior_f0) * one_minus_s5) * M_1_PI_F;
  /* The engine mixes the dielectric and metal products, mix(S Fd, S F_m, metallic): an infinite S
     gives NaN at any metallic (0 * inf), as there. */
  realw ks = (1.0f - m.metallic) * Fd * S;
  rgbw diffuse = {kd * m.base_r, kd * m.base_g, kd * m.base_b};
  rgbw specular = {ks + m.metallic * (F_Schlick90(m.base_r, 1.0f, g.s5) * S),
                   ks + m.metallic * (F_Schlick90(m.base_g, 1.0f, g.s5) * S),
                   ks + m.metallic * (F_Schlick90(m.base_b, 1.0f, g.s5) * S)};
  rgbw sheen = rgbw_splat(0.0f);
#if BRDFCL_HAS_SHEEN
  {
    sheen = sheen_coloured(m, D_CharlieOneMinusCos2(g.hz, m.sheen_alpha) * min(V_Charlie(g.NdotL, g.NdotV, m.sheen_alpha), 1.0f));
    /* albedoSheenScalingLUT: the renderer's own 8-bit table, after the E and DFG tables. */
    __global const float* lut = tables + e_size * e_size + 2 * BRDFCL_DFG_SIZE * BRDFCL_DFG_SIZE;
    realw sh = min(1.0f - m.sheen_max * E_SheenKhronos(lut, g.NdotV, m.sheen_roughness),
                   1.0f - m.sheen_max * E_SheenKhronos(lut, g.NdotL, m.sheen_roughness));
    scale_base(&diffuse, &specular, sh);
  }
#endif
  realw coat = 0.0f;
#if BRDFCL_HAS_CLEARCOAT
  {
    engine_geometry gc = engine_geometry_of(Lc, Vc, 0.0f, 0.0f);
    realw Fc = F_Schlick90(m.ior_f0, 1.0f, pow5w(1.0f - Vc.z));
    realw C = D_GGX_EngineZero(gc.sin2, gc.cos2, gc.hz, m.clearcoat_alpha) * 0.5f /
              Lambda_SmithSum(gc.NdotL, gc.NdotV, m.clearcoat_alpha);
    /* 1 - cc Fc = (1 - cc) + cc (1 - f0) N.V (1 + x + x^2 + x^3 + x^4), x = 1 - N.V: no
       cancellation at N.V << 1, where Fc rounds near 1. */
    realw xc = 1.0f - Vc.z;
    realw k = (1.0f - m.clearcoat) +
              m.clearcoat * (1.0f - m.ior_f0) * (Vc.z * (1.0f + xc * (1.0f + xc * (1.0f + xc * (1.0f + xc)))));
    scale_below(&diffuse, &specular, &sheen, k);
    /* Only materials with the extension evaluate the coat: at r_c = 0, C is 0/0 at N.H = 1. */
    coat = select((realw)(0.0f), m.clearcoat * Fc * C, m.clearcoat > 0.0f);
  }
#endif
  return select_lobe(diffuse, specular, sheen, coat);
}

#endif
