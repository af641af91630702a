/* The microfacet terms, one small function each (letter + model), over width-generic lanes.
   Angles come in as components of the UNNORMALIZED half vector h = L + V in the shading frame:
   sin^2 from the tangent components and cos^2 from the normal one keep N.H -> 1 exact in float. */
/* Sources, cited in kernels/ by title and section:
   glTF 2.0 Appendix B: https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html#appendix-b-brdf-implementation
   KHR_materials_sheen: https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_materials_sheen
   KHR_materials_anisotropy: https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_materials_anisotropy
   KHR_materials_clearcoat: https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_materials_clearcoat
   Narkowicz 2018, "Cloth Shading": https://knarkowicz.wordpress.com/2018/01/04/cloth-shading/ */
#ifndef BRDFCL_TERMS_H
#define BRDFCL_TERMS_H

#include "common/lanes.h"
#include "common/fastmath.h"

/* Burley 2012 anisotropic GGX; KHR_materials_anisotropy "Anisotropy". ht, hb, hn: h on T', B', N;
   h2 = |h|^2. With at == ab == alpha it is glTF Appendix B's isotropic D_GGX. */
BRDF_FN realw D_GGX_Anisotropic(realw ht, realw hb, realw hn, realw h2, realw at, realw ab) {
  realw t = ht / at, b = hb / ab;
  realw d = t * t + b * b + hn * hn;  /* = |h|^2 ((H.T/at)^2 + (H.B/ab)^2 + (H.N)^2) */
  return (h2 * h2) / (M_PI_F * at * ab * d * d);
}

/* The same D with 1/at and 1/ab given: where the alphas are the same for every lane (one material),
   the compiler hoists the two divisions out of the loop over samples, and they leave the chain of
   dependent operations that bounds a sample's latency. t, b round twice instead of once. */
BRDF_FN realw D_GGX_Anisotropic_rcp(realw ht, realw hb, realw hn, realw h2, realw at, realw ab, realw inv_at,
                                    realw inv_ab) {
  realw t = ht * inv_at, b = hb * inv_ab;
  realw d = t * t + b * b + hn * hn;
  return (h2 * h2) / (M_PI_F * at * ab * d * d);
}

/* Walter et al. 2007 GGX; glTF 2.0 Appendix B "Microfacet Surfaces". hxy2 = hx^2 + hy^2. */
BRDF_FN realw D_GGX(realw hxy2, realw hn2, realw alpha) {
  realw a2 = alpha * alpha;
  realw d = hxy2 + hn2 * a2;
  realw h2 = hxy2 + hn2;
  return a2 * h2 * h2 / (M_PI_F * d * d);
}

/* Heitz 2014 height-correlated Smith, anisotropic form; KHR_materials_anisotropy "Individual lights".
   V = 1 / (2 W): W (the _half_rcp form) alone serves a caller that folds the division into its own. */
BRDF_FN realw V_GGX_Anisotropic_half_rcp(realw NdotL, realw NdotV, realw TdotV, realw BdotV, realw TdotL,
                                         realw BdotL, realw at, realw ab) {
  realw tv = at * TdotV, bv = ab * BdotV, tl = at * TdotL, bl = ab * BdotL;
  realw GGXV = NdotL * sqrt(tv * tv + bv * bv + NdotV * NdotV);
  realw GGXL = NdotV * sqrt(tl * tl + bl * bl + NdotL * NdotL);
  return GGXV + GGXL;
}
BRDF_FN realw V_GGX_Anisotropic(realw NdotL, realw NdotV, realw TdotV, realw BdotV, realw TdotL,
                                realw BdotL, realw at, realw ab) {
  return 0.5f / V_GGX_Anisotropic_half_rcp(NdotL, NdotV, TdotV, BdotV, TdotL, BdotL, at, ab);
}

/* Heitz 2014 height-correlated Smith; glTF 2.0 Appendix B "Microfacet Surfaces". */
BRDF_FN realw V_SmithGGXCorrelated_half_rcp(realw NdotL, realw NdotV, realw alpha) {
  realw a2 = alpha * alpha;
  realw GGXV = NdotL * sqrt(NdotV * NdotV * (1.0f - a2) + a2);
  realw GGXL = NdotV * sqrt(NdotL * NdotL * (1.0f - a2) + a2);
  return GGXV + GGXL;
}
BRDF_FN realw V_SmithGGXCorrelated(realw NdotL, realw NdotV, realw alpha) {
  return 0.5f / V_SmithGGXCorrelated_half_rcp(NdotL, NdotV, alpha);
}

/* Schlick 1994; glTF 2.0 Appendix B. `w` = (1 - |V.H|)^5, computed once by the caller. */
BRDF_FN realw F_Schlick(realw f0, realw w) { return f0 + (1.0f - f0) * w; }

/* Conty & Kulla 2017 "Charlie" sheen; KHR_materials_sheen "Sheen distribution".
   (sin^2)^(1/(2 alpha)) = 2^(-log2(1 + cot^2) / (2 alpha)): no precision loss near N.H = 1 and
   exact at the large exponents of small alpha; log2 and exp2, so no scaling by ln 2 either way. */
BRDF_FN realw D_Charlie(realw hxy2, realw hn2, realw alpha) {
  realw inv_r = 1.0f / alpha;
  realw log2_sin2 = -brdf_log2_1p(hn2 / hxy2);
  return (2.0f + inv_r) * brdf_exp2_nonpositive((0.5f * inv_r) * log2_sin2) * (0.5f / M_PI_F);
}

/* Ashikhmin & Premoze 2007 velvet, inverted Gaussian; "Cloth Shading" AshikhminD, called with
   roughness = alpha (m2 = alpha^2). sin^2 below 1e-6 leaves exp(-cot^2/m2) = 0 exactly in float
   (cot^2/m2 >= 1e6), so the floor only avoids 0/0 at N.H = 1. */
BRDF_FN realw D_Ashikhmin(realw hxy2, realw hn2, realw alpha) {
  realw h2 = hxy2 + hn2;
  realw sin2 = max(hxy2 / h2, 1.0e-6f);
  realw cos2 = hn2 / h2;
  realw m2 = alpha * alpha;
  realw lobe = 4.0f * brdf_exp(-cos2 / (sin2 * m2)) / (sin2 * sin2);
  return (1.0f + lobe) / (M_PI_F * (1.0f + 4.0f * m2));
}

/* Conty & Kulla 2017 fit of the Charlie Lambda; KHR_materials_sheen "Sheen visibility", with its constants.
   The five coefficients depend on alpha only, so one set serves both directions. */
typedef struct { realw a, b, c, d, e, l_half; } charlie_fit;

BRDF_FN charlie_fit CharlieFit(realw alpha) {
  realw t = (1.0f - alpha) * (1.0f - alpha);
  charlie_fit f;
  f.a = mix((realw)(21.5473f), (realw)(25.3245f), t);
  f.b = mix((realw)(3.82987f), (realw)(3.32435f), t);
  f.c = mix((realw)(0.19823f), (realw)(0.16801f), t);
  f.d = mix((realw)(-1.97760f), (realw)(-1.27393f), t);
  f.e = mix((realw)(-4.32054f), (realw)(-4.85967f), t);
  /* l(0.5): 0.5^c = 2^-c exactly, one exp2 instead of a pow. */
  f.l_half = f.a / (1.0f + f.b * brdf_exp2(-f.c)) + 0.5f * f.d + f.e;
  return f;
}

/* l(x) = a / (1 + b x^c) + d x + e, with x^c = 2^(c log2 x) (x = 0 gives 0). */
BRDF_FN realw L_CharlieFit(charlie_fit f, realw x) {
  return f.a * brdf_rcp(1.0f + f.b * brdf_exp2_nonpositive(f.c * brdf_log2(x))) + f.d * x + f.e;
}

/* Lambda(cos) = exp(l(cos)) below 0.5, exp(2 l(0.5) - l(1 - cos)) above: l is evaluated once, at
   whichever argument the branch needs. */
BRDF_FN realw Lambda_Charlie(charlie_fit f, realw cos_theta) {
  intw low = cos_theta < 0.5f;
  realw l = L_CharlieFit(f, select(1.0f - cos_theta, cos_theta, low));
  return brdf_exp_bounded(select(2.0f * f.l_half - l, l, low));
}

/* Conty & Kulla 2017 height-correlated visibility with the fitted Lambda; KHR_materials_sheen "Sheen visibility". */
BRDF_FN realw V_Charlie(realw NdotL, realw NdotV, realw alpha) {
  charlie_fit f = CharlieFit(alpha);
  return brdf_rcp((1.0f + Lambda_Charlie(f, NdotV) + Lambda_Charlie(f, NdotL)) * (4.0f * NdotV * NdotL));
}

/* Neubelt & Pettineo 2013, after Ashikhmin & Premoze 2007; KHR_materials_sheen "Sheen visibility",
   "Cloth Shading" AshikhminV. */
BRDF_FN realw V_Ashikhmin(realw NdotL, realw NdotV) {
  return 1.0f / (4.0f * (NdotL + NdotV - NdotL * NdotV));
}

#endif
