/* Terms the engines use where the specs use another, and the per-direction geometry every
   profile shares. One function per term, named after its model; docs/profiles.md cites each.
   Only compiled into programs built with -DBRDFCL_PROFILE != BRDFCL_PROFILE_SPEC. */
#ifndef BRDFCL_ENGINE_TERMS_H
#define BRDFCL_ENGINE_TERMS_H

#include "common/lanes.h"
#include "common/fastmath.h"
#include "brdf/terms.h"

/* The angles a profile needs, from unit L and V in one frame (N = +Z). sin2/cos2 of the half
   angle come from the unnormalized h, so 1 - N.H^2 is exact near N.H = 1. */
typedef struct {
  realw NdotL, NdotV;     /* floored where the engine floors them (min_nl, min_nv), not at spec's 1e-4 */
  realw hx, hy, hz;       /* unit H */
  realw sin2, cos2;       /* of the half angle */
  realw VdotH, s5;        /* s5 = (1 - V.H)^5 */
} engine_geometry;

/* Each engine clamps its cosines its own way (docs/profiles.md "Conventions"): min_nl and min_nv
   are its floors, 0 for an engine that only saturates. f = 0 at L.z <= 0 or V.z <= 0 is applied
   by the caller; the floor matters for the clearcoat frame and for cosines in (0, 1e-4). */
BRDF_FN engine_geometry engine_geometry_of(vec3w L, vec3w V, float min_nl, float min_nv) {
  engine_geometry g;
  g.NdotL = max(L.z, min_nl);
  g.NdotV = max(V.z, min_nv);
  vec3w h = half_vector(L, V);
  realw hxy2 = h.x * h.x + h.y * h.y, hn2 = h.z * h.z, h2 = hxy2 + hn2;
  realw inv_h = rsqrt(h2);
  g.hx = h.x * inv_h;
  g.hy = h.y * inv_h;
  g.hz = h.z * inv_h;
  g.sin2 = hxy2 / h2;
  g.cos2 = hn2 / h2;
  /* 1 - V.H = |V - H|^2 / 2 for unit vectors: no cancellation as H -> V. */
  realw dx = V.x - g.hx, dy = V.y - g.hy, dz = V.z - g.hz;
  realw one_minus = 0.5f * (dx * dx + dy * dy + dz * dz);
  g.VdotH = 1.0f - one_minus;
  g.s5 = pow5w(one_minus);
  return g;
}

/* Schlick 1994 with a free f90, s5 = (1 - cos)^5 given. */
BRDF_FN realw F_Schlick90(realw f0, realw f90, realw s5) { return f0 + (f90 - f0) * s5; }

/* Karis 2013 (Epic) spherical-Gaussian Schlick, three.js's F_Schlick: (1-x)^5 ~ 2^((-5.55473x - 6.98316)x). */
BRDF_FN realw Fs_SphericalGaussian(realw x) { return brdf_exp2((-5.55473f * x - 6.98316f) * x); }
BRDF_FN realw F_SchlickSG(realw f0, realw f90, realw fs) { return f0 * (1.0f - fs) + f90 * fs; }

/* Exact unpolarized dielectric Fresnel (Walter et al. 2007 eq. 22), MaterialX's mx_fresnel_dielectric. */
BRDF_FN realw F_Dielectric(realw c, realw eta) {
  realw g = sqrt(max(eta * eta + c * c - 1.0f, 0.0f));
  realw a = (g - c) / (g + c);
  realw b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
  return 0.5f * a * a * (1.0f + b * b);
}

/* Trowbridge-Reitz GGX from the half angle's sin^2/cos^2: alpha^2 / (pi (cos^2 (alpha^2-1) + 1)^2)
   written as alpha^2 / (pi (sin^2 + cos^2 alpha^2)^2). alpha = 0 at N.H = 1 gives 0/0 = NaN, as
   the engines that do not floor alpha give it. */
BRDF_FN realw D_GGX_HalfAngle(realw sin2, realw cos2, realw alpha) {
  realw a2 = alpha * alpha;
  realw d = sin2 + cos2 * a2;
  return a2 / (M_PI_F * d * d);
}

/* D_GGX_HalfAngle where the engine's own float form f = N.H^2 (alpha^2 - 1) + 1 is exactly 0
   (N.H = 1 with alpha^2 - 1 rounding to -1, i.e. alpha^2 <= 2^-25): D = alpha^2 / 0, infinite
   (NaN at alpha = 0), as the engine gets it; elsewhere the accurate half-angle form. */
BRDF_FN realw D_GGX_EngineZero(realw sin2, realw cos2, realw hz, realw alpha) {
  realw a2 = alpha * alpha;
  realw f = hz * hz * (a2 - 1.0f) + 1.0f;
  realw d = select(sin2 + cos2 * a2, (realw)(0.0f), f == 0.0f);
  return a2 / (M_PI_F * d * d);
}

/* Charlie sheen written as the Sample Renderer writes it, sin^2 = 1 - N.H^2 in float: below
   N.H ~ 1.7e-4 that rounds to 1, so at sheen roughness 0 (alpha 1e-12) D is (2 + 1/alpha)/2pi
   there, as the engine has it, not the exact (sin^2)^(1/(2 alpha)) = 0. */
BRDF_FN realw D_CharlieOneMinusCos2(realw hz, realw alpha) {
  realw inv_a = 1.0f / alpha;
  realw sin2 = 1.0f - hz * hz;
  return (2.0f + inv_a) * brdf_exp2(0.5f * inv_a * brdf_log2(sin2)) * (0.5f / M_PI_F);
}

/* Burley 2012 anisotropic GGX over unit-H components (T, B, N). */
BRDF_FN realw D_Burley(realw ht, realw hb, realw hn, realw at, realw ab) {
  realw t = ht / at, b = hb / ab;
  realw d = t * t + b * b + hn * hn;
  return 1.0f / (M_PI_F * at * ab * d * d);
}

/* The same D in the grouping the Sample Renderer and Babylon write: a = at ab,
   w2 = a / |(ab H.T, at H.B, a H.N)|^2, D = a w2^2 / pi. At at = 0 it is 0 off N.H = 1 (where
   the division by at above is 0 * inf = NaN) and NaN at N.H = 1. */
BRDF_FN realw D_BurleyW2(realw ht, realw hb, realw hn, realw at, realw ab) {
  realw a = at * ab;
  realw fx = ab * ht, fy = at * hb, fz = a * hn;
  realw w2 = a / (fx * fx + fy * fy + fz * fz);
  return a * w2 * w2 / M_PI_F;
}

/* Heitz 2014 anisotropic height-correlated Smith: the two terms of its denominator, summed. */
BRDF_FN realw Lambda_HeitzSum(realw NdotL, realw NdotV, realw TdotV, realw BdotV, realw TdotL, realw BdotL,
                              realw at, realw ab) {
  realw tv = at * TdotV, bv = ab * BdotV, tl = at * TdotL, bl = ab * BdotL;
  return NdotL * sqrt(tv * tv + bv * bv + NdotV * NdotV) + NdotV * sqrt(tl * tl + bl * bl + NdotL * NdotL);
}

/* Isotropic height-correlated Smith denominator (glTF Appendix B's V_GGX = 0.5 / this). */
BRDF_FN realw Lambda_SmithSum(realw NdotL, realw NdotV, realw alpha) {
  realw a2 = alpha * alpha;
  return NdotL * sqrt(NdotV * NdotV * (1.0f - a2) + a2) + NdotV * sqrt(NdotL * NdotL * (1.0f - a2) + a2);
}

/* Kelemen & Szirmay-Kalos 2001 visibility, Filament's and Babylon's clearcoat V. */
BRDF_FN realw V_Kelemen(realw LdotH) { return 0.25f / (LdotH * LdotH); }

/* Charlie sheen (Estevez & Kulla 2017) with sin^2 floored, as three.js and Filament write it:
   (2 + 1/alpha) max(sin^2, floor)^(1/(2 alpha)) / 2pi. Unfloored, log sin^2 = -log1p(cos^2/sin^2)
   keeps its precision near N.H = 0, where small alphas raise it to large powers. */
BRDF_FN realw D_CharlieFloored(realw sin2, realw cos2, realw alpha) {
  realw inv_a = 1.0f / alpha;
  /* floor 0.0078125 = 2^-7, ln of it = -7 ln 2 */
  realw log_sin2 = select(-brdf_log1p(cos2 / sin2), (realw)(-4.8520302639f), sin2 < 0.0078125f);
  return (2.0f + inv_a) * brdf_exp(0.5f * inv_a * log_sin2) * (0.5f / M_PI_F);
}

/* three.js's DFG table (docs/profiles.md "Tables"), sampled as a GPU samples a 16x16 texture with
   linear filtering and clamp-to-edge at u = roughness, v = N.V. Returns (A, B) through pointers. */
BRDF_FN void DFG_ThreeJs(__global const float* dfg, realw roughness, realw mu, realw* A, realw* B) {
  realw x = clamp(roughness * (float)BRDFCL_DFG_SIZE - 0.5f, 0.0f, (float)(BRDFCL_DFG_SIZE - 1));
  realw y = clamp(mu * (float)BRDFCL_DFG_SIZE - 0.5f, 0.0f, (float)(BRDFCL_DFG_SIZE - 1));
  intw x0 = min(CONVERT_INTW(x), BRDFCL_DFG_SIZE - 2), y0 = min(CONVERT_INTW(y), BRDFCL_DFG_SIZE - 2);
  realw fx = x - CONVERT_REALW(x0), fy = y - CONVERT_REALW(y0);
  intw i = (y0 * BRDFCL_DFG_SIZE + x0) * 2;
  const int row = 2 * BRDFCL_DFG_SIZE;
  realw a00 = GATHERW(dfg, i), a01 = GATHERW(dfg + 2, i), a10 = GATHERW(dfg + row, i), a11 = GATHERW(dfg + row + 2, i);
  realw b00 = GATHERW(dfg + 1, i), b01 = GATHERW(dfg + 3, i), b10 = GATHERW(dfg + row + 1, i), b11 = GATHERW(dfg + row + 3, i);
  *A = mix(mix(a00, a01, fx), mix(a10, a11, fx), fy);
  *B = mix(mix(b00, b01, fx), mix(b10, b11, fx), fy);
}

/* The Sample Renderer's lut_sheen_E.png (docs/profiles.md "Tables"), sampled as its LUTSampler
   (LINEAR, CLAMP_TO_EDGE) samples texture(u_SheenELUT, vec2(N.V, sheen roughness)).r: texel (i, j)
   centred at ((i + 0.5)/n, (j + 0.5)/n). The weights are float: a GPU's fixed-point rounding of
   them (8 fraction bits on most hardware) is not reproduced. */
BRDF_FN realw E_SheenKhronos(__global const float* lut, realw mu, realw r) {
  const int n = BRDFCL_KHRONOS_SHEEN_E_SIZE;
  realw x = clamp(mu * (float)n - 0.5f, 0.0f, (float)(n - 1));
  realw y = clamp(r * (float)n - 0.5f, 0.0f, (float)(n - 1));
  intw x0 = min(CONVERT_INTW(x), n - 2), y0 = min(CONVERT_INTW(y), n - 2);
  realw fx = x - CONVERT_REALW(x0), fy = y - CONVERT_REALW(y0);
  intw i = y0 * n + x0;
  realw t00 = GATHERW(lut, i), t01 = GATHERW(lut + 1, i), t10 = GATHERW(lut + n, i), t11 = GATHERW(lut + n + 1, i);
  return mix(mix(t00, t01, fx), mix(t10, t11, fx), fy);
}

/* Babylon's environment BRDF texture (docs/profiles.md "Tables"), channel ch of
   texture(environmentBrdfSampler, vec2(N.V, r)) with BILINEAR and CLAMP: 3 floats per texel, texel
   (i, j) centred at ((i + 0.5)/n, (j + 0.5)/n), row j = perceptual roughness. */
BRDF_FN realw BRDF_Babylon(__global const float* lut, realw mu, realw r, int ch) {
  const int n = BRDFCL_BABYLON_BRDF_SIZE;
  realw x = clamp(mu * (float)n - 0.5f, 0.0f, (float)(n - 1));
  realw y = clamp(r * (float)n - 0.5f, 0.0f, (float)(n - 1));
  intw x0 = min(CONVERT_INTW(x), n - 2), y0 = min(CONVERT_INTW(y), n - 2);
  realw fx = x - CONVERT_REALW(x0), fy = y - CONVERT_REALW(y0);
  intw i = (y0 * n + x0) * 3 + ch;
  realw t00 = GATHERW(lut, i), t01 = GATHERW(lut + 3, i), t10 = GATHERW(lut + 3 * n, i), t11 = GATHERW(lut + 3 * n + 3, i);
  return mix(mix(t00, t01, fx), mix(t10, t11, fx), fy);
}

/* Single-scattering GGX albedo with F = 1: A + B of the table. */
BRDF_FN realw Ess_ThreeJs(__global const float* dfg, realw roughness, realw mu) {
  realw A, B;
  DFG_ThreeJs(dfg, roughness, mu, &A, &B);
  return A + B;
}

/* MaterialX mx_ggx_dir_albedo_analytic: a rational fit of (A, B) over x = N.V, y = alpha. */
BRDF_FN void DFG_MaterialXFit(realw x, realw y, realw* A, realw* B) {
  realw xy = x * y, x2 = x * x, y2 = y * y, x2y = x2 * y, xy2 = x * y2, x2y2 = x2 * y2;
  realw r0 = 0.1003f - 0.6303f * x + 9.748f * y - 2.038f * xy + 29.34f * x2 - 8.245f * y2 - 26.44f * x2y + 19.99f * xy2 - 5.448f * x2y2;
  realw r1 = 0.9345f - 2.323f * x + 2.229f * y - 3.748f * xy + 1.424f * x2 - 0.7684f * y2 + 1.436f * x2y + 0.2913f * xy2 + 0.6286f * x2y2;
  realw r2 = 1.0f - 1.765f * x + 8.263f * y + 11.53f * xy + 28.96f * x2 - 7.507f * y2 - 36.11f * x2y + 15.86f * xy2 + 33.37f * x2y2;
  realw r3 = 1.0f + 0.2281f * x + 15.94f * y - 55.83f * xy + 13.08f * x2 + 41.26f * y2 + 54.9f * x2y + 300.2f * xy2 - 285.1f * x2y2;
  *A = clamp(r0 / r2, 0.0f, 1.0f);
  *B = clamp(r1 / r3, 0.0f, 1.0f);
}

/* MaterialX mx_imageworks_sheen_dir_albedo_analytic, clamped to [0, 1]; x = N.V, y = alpha. */
BRDF_FN realw E_SheenMaterialX(realw x, realw y) {
  realw num = 13.673f - 68.78018f * x + 799.08825f * y - 905.00061f * x * y + 60.28956f * x * x + 1086.96473f * y * y;
  realw den = 1.0f + 61.57746f * x + 442.78211f * y + 2597.49308f * x * y + 121.81241f * x * x + 3045.55075f * y * y;
  return clamp(num / den, 0.0f, 1.0f);
}

/* three.js IBLSheenBRDF (PR #32356): sat(exp(a mu + b)) over perceptual sheen roughness r. */
BRDF_FN realw E_SheenThreeJs(realw mu, realw r) {
  realw inv = 1.0f / (r + 0.1f);
  realw a = -1.9362f + 1.0678f * r + 0.4573f * r * r - 0.8469f * inv;
  realw b = -0.6014f + 0.5538f * r - 0.4670f * r * r - 0.1255f * inv;
  return clamp(brdf_exp(a * mu + b), 0.0f, 1.0f);
}

/* Where an engine's lobes land for the batch's --lobe: each profile computes its four lobes and
   this keeps the requested one (the others are dead code the compiler drops). */
BRDF_FN rgbw select_lobe(rgbw diffuse, rgbw specular, rgbw sheen, realw clearcoat) {
#if BRDFCL_LOBE == BRDFCL_LOBE_DIFFUSE
  return diffuse;
#elif BRDFCL_LOBE == BRDFCL_LOBE_SPECULAR
  return specular;
#elif BRDFCL_LOBE == BRDFCL_LOBE_SHEEN
  return sheen;
#elif BRDFCL_LOBE == BRDFCL_LOBE_CLEARCOAT
  return rgbw_splat(clearcoat);
#else
  rgbw all = rgbw_add(rgbw_add(diffuse, specular), sheen);
  all.r += clearcoat;
  all.g += clearcoat;
  all.b += clearcoat;
  return all;
#endif
}

/* T' and B' components of a vector, T' = (cos r, sin r, 0), B' = (-sin r, cos r, 0). */
BRDF_FN realw along_t(realw x, realw y, realw c, realw s) { return x * c + y * s; }
BRDF_FN realw along_b(realw x, realw y, realw c, realw s) { return y * c - x * s; }

/* The anisotropic lobe in the material's rotated frame, at (alpha_t, alpha) as the profile
   packed them: Burley's D (N.H given, for engines that clamp it) and Heitz's V denominator. */
BRDF_FN realw D_BurleyRotated(const material_lanes m, engine_geometry g, realw NdotH) {
  return D_Burley(along_t(g.hx, g.hy, m.aniso_cos, m.aniso_sin), along_b(g.hx, g.hy, m.aniso_cos, m.aniso_sin), NdotH,
                  m.alpha_t, m.alpha);
}

BRDF_FN realw Lambda_HeitzRotated(const material_lanes m, engine_geometry g, vec3w L, vec3w V) {
  realw c = m.aniso_cos, s = m.aniso_sin;
  return Lambda_HeitzSum(g.NdotL, g.NdotV, along_t(V.x, V.y, c, s), along_b(V.x, V.y, c, s), along_t(L.x, L.y, c, s),
                         along_b(L.x, L.y, c, s), m.alpha_t, m.alpha);
}

/* A sheen lobe: the sheen colour times the white lobe D V. */
BRDF_FN rgbw sheen_coloured(const material_lanes m, realw dv) {
  rgbw out = {m.sheen_r * dv, m.sheen_g * dv, m.sheen_b * dv};
  return out;
}

/* View-only albedo scaling, 1 - max3(c) E(N.V), from the E table (Filament, Babylon). */
BRDF_FN realw sheen_scaling_view(const material_lanes m, __global const float* table, int size, realw NdotV) {
  return 1.0f - m.sheen_max * E_SheenAlbedo(table, size, E_SheenAlbedoRow(size, m.sheen_roughness), NdotV);
}

/* A layer above scales what lies below it: the base (diffuse and specular) and, where the engine
   puts it below, the sheen. */
BRDF_FN void scale_base(rgbw* diffuse, rgbw* specular, realw k) {
  *diffuse = rgbw_scale(*diffuse, k);
  *specular = rgbw_scale(*specular, k);
}

BRDF_FN void scale_below(rgbw* diffuse, rgbw* specular, rgbw* sheen, realw k) {
  scale_base(diffuse, specular, k);
  *sheen = rgbw_scale(*sheen, k);
}

/* F0 per channel: mix(f0_dielectric, baseColor, metallic). */
BRDF_FN rgbw f0_metallic(const material_lanes m) {
  rgbw f0 = {mix(m.ior_f0, m.base_r, m.metallic), mix(m.ior_f0, m.base_g, m.metallic), mix(m.ior_f0, m.base_b, m.metallic)};
  return f0;
}

#endif
