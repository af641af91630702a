/* The spec's lobes, one function each, built from terms.h: the diffuse and specular halves of
   glTF 2.0 Appendix B (specular in KHR_materials_anisotropy's forms), the sheen of
   KHR_materials_sheen and the clearcoat of KHR_materials_clearcoat. brdf/profiles/spec.h layers
   them. Included by brdf/material.h after material_lanes. */
#ifndef BRDFCL_LOBES_H
#define BRDFCL_LOBES_H

#include "common/lanes.h"
#include "brdf/terms.h"

/* Half-vector components with the degenerate L = -V case mapped to H = N. */
BRDF_FN vec3w half_vector(vec3w L, vec3w V) {
  vec3w h = {L.x + V.x, L.y + V.y, L.z + V.z};
  realw h2 = h.x * h.x + h.y * h.y + h.z * h.z;
  /* L = -V with both within ~1e-15 of the horizon: |L + V|^2 underflows and H is undefined.
     Taking H = N there keeps f finite (documented clamp; such pairs sit far outside the domain). */
  intw degenerate = h2 < 1.0e-30f;
  /* Nearly opposite L and V: the D terms square |h|^2 twice, which underflows to 0/0 (NaN f, e.g.
     at grazing L, V mirrored about N with N.L = N.V = 1e-12). Every consumer of h is homogeneous
     of degree 0 in it, so an exact power-of-two rescale (2^40) changes nothing else. */
  realw scale = select((realw)(1.0f), (realw)(1099511627776.0f), h2 < 1.0e-12f);
  h.x = select(h.x * scale, (realw)(0.0f), degenerate);
  h.y = select(h.y * scale, (realw)(0.0f), degenerate);
  h.z = select(h.z * scale, (realw)(1.0f), degenerate);
  return h;
}

/* What the lobes of one layer share: L, V in the shading frame (N = +Z), the clamped cosines,
   the unnormalized half vector h with |h_xy|^2, h_z^2, |h|^2, and w = (1 - V.H)^5. */
typedef struct {
  vec3w L, V, h;
  realw NdotL, NdotV, hxy2, hn2, h2, w;
} lobe_geometry;

BRDF_FN lobe_geometry lobe_geometry_of(vec3w L, vec3w V) {
  lobe_geometry g;
  g.L = L;
  g.V = V;
  g.NdotL = max(L.z, BRDFCL_MIN_COS);
  g.NdotV = max(V.z, BRDFCL_MIN_COS);
  vec3w h = half_vector(L, V);
  g.h = h;
  g.hxy2 = h.x * h.x + h.y * h.y;
  g.hn2 = h.z * h.z;
  g.h2 = g.hxy2 + g.hn2;
  realw inv_h = brdf_rsqrt(g.h2);
  /* 1 - V.H = |V - H|^2 / 2 for unit vectors: no cancellation as H -> V. At most 1 (V.H >= 0):
     the rounding of inv_h must not take it above, where 1 - F would turn negative. */
  realw dx = V.x - h.x * inv_h, dy = V.y - h.y * inv_h, dz = V.z - h.z * inv_h;
  g.w = pow5w(min(0.5f * (dx * dx + dy * dy + dz * dz), 1.0f));
  return g;
}

/* A lobe's value f = colour * weight (1/sr). The product is left to lobe_add so that adding a lobe
   to a layer is one multiply-add wherever the compiler contracts a * b + c. */
typedef struct {
  rgbw colour;
  realw weight;
} lobe_value;

BRDF_FN rgbw lobe_add(rgbw below, lobe_value l) {
  below.r += l.colour.r * l.weight;
  below.g += l.colour.g * l.weight;
  below.b += l.colour.b * l.weight;
  return below;
}

/* Appendix B's diffuse: the dielectric's Lambertian under its Fresnel, (1 - metallic)(1 - F) / pi. */
BRDF_FN lobe_value lobe_diffuse(const material_lanes m, lobe_geometry g) {
  realw F = F_Schlick(0.04f, g.w);
  realw dielectric_w = 1.0f - m.metallic;
  lobe_value out;
  out.colour.r = m.base_r;
  out.colour.g = m.base_g;
  out.colour.b = m.base_b;
  out.weight = dielectric_w * (1.0f - F) * M_1_PI_F;
  return out;
}

/* Appendix B's specular colour, the Fresnel of the dielectric and metal mixed by metallic. */
BRDF_FN rgbw lobe_specular_colour(const material_lanes m, lobe_geometry g) {
  realw F = F_Schlick(0.04f, g.w);
  realw ks = (1.0f - m.metallic) * F;
  rgbw colour;
  colour.r = ks + m.metallic * F_Schlick(m.base_r, g.w);
  colour.g = ks + m.metallic * F_Schlick(m.base_g, g.w);
  colour.b = ks + m.metallic * F_Schlick(m.base_b, g.w);
  return colour;
}

/* The specular's visibility term as 1 / (2 V), V in KHR_materials_anisotropy's form when the batch
   has anisotropy. */
BRDF_FN realw lobe_specular_vis_half_rcp(const material_lanes m, lobe_geometry g) {
  vec3w L = g.L, V = g.V;
#if BRDFCL_HAS_ANISOTROPY
  realw c = m.aniso_cos, s = m.aniso_sin;
  realw TdotV = V.x * c + V.y * s, BdotV = V.y * c - V.x * s;
  realw TdotL = L.x * c + L.y * s, BdotL = L.y * c - L.x * s;
  return V_GGX_Anisotropic_half_rcp(g.NdotL, g.NdotV, TdotV, BdotV, TdotL, BdotL, m.alpha_t, m.alpha);
#else
  return V_SmithGGXCorrelated_half_rcp(g.NdotL, g.NdotV, m.alpha);
#endif
}

/* Appendix B's specular, dielectric and metal mixed by metallic; D and V in KHR_materials_anisotropy's
   forms ("Anisotropy", "Individual lights") when the batch has anisotropy. */
BRDF_FN lobe_value lobe_specular(const material_lanes m, lobe_geometry g) {
  vec3w h = g.h;
#if BRDFCL_HAS_ANISOTROPY
  /* T' = (cos r, sin r, 0), B' = N x T' = (-sin r, cos r, 0). */
  realw c = m.aniso_cos, s = m.aniso_sin;
  realw ht = h.x * c + h.y * s, hb = h.y * c - h.x * s;
  realw D = D_GGX_Anisotropic_rcp(ht, hb, h.z, g.h2, m.alpha_t, m.alpha, 1.0f / m.alpha_t, 1.0f / m.alpha);
#else
  realw D = D_GGX(g.hxy2, g.hn2, m.alpha);
#endif
  lobe_value out;
  out.colour = lobe_specular_colour(m, g);
  out.weight = D * (0.5f / lobe_specular_vis_half_rcp(m, g));
  return out;
}

/* White sheen D * V for the batch's options (KHR_materials_sheen "Sheen distribution", "Sheen
   visibility"; Ashikhmin's as the cloth-shading article gives them). */
BRDF_FN realw sheen_dv(realw hxy2, realw hn2, realw NdotL, realw NdotV, realw alpha) {
  /* V before D: the Charlie V's chain (log2, exp2, reciprocal, exp, reciprocal) is the longer, and
     the compiler keeps about the source order, so D's work fills its waits. */
#if BRDFCL_SHEEN_VIS == BRDFCL_SHEEN_VIS_ASHIKHMIN
  realw V = V_Ashikhmin(NdotL, NdotV);
#else
  realw V = V_Charlie(NdotL, NdotV, alpha);
#endif
#if BRDFCL_SHEEN_DIST == BRDFCL_SHEEN_DIST_ASHIKHMIN
  realw D = D_Ashikhmin(hxy2, hn2, alpha);
#else
  realw D = D_Charlie(hxy2, hn2, alpha);
#endif
  return D * V;
}

/* The sheen: KHR_materials_sheen (ratified), or the experimental draft's Charlie D with
   Ashikhmin V on draft lanes, whatever the ratified options say. */
BRDF_FN lobe_value lobe_sheen(const material_lanes m, lobe_geometry g) {
  realw dv = sheen_dv(g.hxy2, g.hn2, g.NdotL, g.NdotV, m.sheen_alpha);
  const int draft_differs = BRDFCL_HAS_DRAFT &&
                            !(BRDFCL_SHEEN_DIST == BRDFCL_SHEEN_DIST_CHARLIE && BRDFCL_SHEEN_VIS == BRDFCL_SHEEN_VIS_ASHIKHMIN);
  if (draft_differs) {
    realw dv_draft = D_Charlie(g.hxy2, g.hn2, m.sheen_alpha) * V_Ashikhmin(g.NdotL, g.NdotV);
    dv = select(dv, dv_draft, m.draft > 0.5f);
  }
  lobe_value out;
  out.colour.r = m.sheen_r;
  out.colour.g = m.sheen_g;
  out.colour.b = m.sheen_b;
  /* sheen_weight is 1 but on draft lanes: a batch without them neither reads nor multiplies it. */
  out.weight = BRDFCL_HAS_DRAFT ? m.sheen_weight * dv : dv;
  return out;
}

/* The clearcoat's white value, coat * D * V with coat = clearcoat * Fc (KHR_materials_clearcoat
   "Layering"). Lc, Vc: L and V in the clearcoat normal's frame (Nc = +Z). */
BRDF_FN realw lobe_clearcoat(realw coat, realw clearcoat_alpha, vec3w Lc, vec3w Vc) {
  vec3w h = half_vector(Lc, Vc);
  realw NcL = max(Lc.z, BRDFCL_MIN_COS), NcV = max(Vc.z, BRDFCL_MIN_COS);
  realw cc = D_GGX(h.x * h.x + h.y * h.y, h.z * h.z, clearcoat_alpha) * V_SmithGGXCorrelated(NcL, NcV, clearcoat_alpha);
  return coat * cc;
}

/* The clearcoat's visibility as 1 / (2 V): what a sampler whose pdf holds the same D divides by
   (sample.cl). */
BRDF_FN realw lobe_clearcoat_vis_half_rcp(realw clearcoat_alpha, vec3w Lc, vec3w Vc) {
  realw NcL = max(Lc.z, BRDFCL_MIN_COS), NcV = max(Vc.z, BRDFCL_MIN_COS);
  return V_SmithGGXCorrelated_half_rcp(NcL, NcV, clearcoat_alpha);
}

#endif
