/* Importance sampling of the layered material (brdfcl sample / pdf): one sampler per lobe
   (brdf/sampling.h) and their one-sample mixture, with lobe probabilities from each lobe's
   approximate directional albedo at V. Rows in, rows out, one work-item a row. */
#define BRDFCL_W 1
#include "brdf/material.h"
#include "brdf/sampling.h"

/* The sheen sampler follows the spec's distribution for the batch's options: Ashikhmin's only
   where --sheen-distribution ashikhmin applies (profile spec, ratified lanes). */
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC && BRDFCL_SHEEN_DIST == BRDFCL_SHEEN_DIST_ASHIKHMIN
#define SAMPLE_ASHIKHMIN 1
#else
#define SAMPLE_ASHIKHMIN 0
#endif

/* LOBE_UNIFORM: the uniform hemisphere, which takes the share of a sheen lobe that its own sampler
   serves poorly (docs/sampling.md). */
enum { LOBE_DIFFUSE, LOBE_SPECULAR, LOBE_SHEEN, LOBE_COAT, LOBE_UNIFORM, LOBE_COUNT };

static inline float luminance3(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

/* Karis 2014, "Physically Based Shading on Mobile" (EnvBRDFApprox): the directional albedo of
   a GGX lobe with Schlick's Fresnel, F0 A + B, fitted in perceptual roughness r and N.V. */
static inline float2 ggx_albedo_ab(float r, float nv) {
  float rx = 1.0f - r, ry = 0.0425f - 0.0275f * r, rz = 1.04f - 0.572f * r, rw = 0.022f * r - 0.04f;
  float a004 = min(rx * rx, exp2(-9.28f * nv)) * rx + ry;
  return (float2)(rz - 1.04f * a004, rw + 1.04f * a004);
}

/* Lobe probabilities at V. Under --lobe one lobe takes all. Otherwise each lobe's directional
   albedo W_t is estimated under the layers above it: the coat's Fresnel times its GGX albedo;
   the sheen's colour times its E table; the specular's GGX albedo (Karis's fit) and the diffuse's
   0.96 base colour, both under what the coat and the sheen's albedo scaling leave. Each W_t is
   then split by K_t^4, K_t a lobe's breadth (docs/sampling.md): W_t K_t^4 goes to its own sampler
   and the rest to a hemisphere sampler that loses no directions: the cosine one for GGX, whose
   broad lobes it follows better than the VNDF (which ignores the masking of L), mostly the
   uniform one for the sheen, which peaks towards grazing L where the cosine density starves it.
   The cosine hemisphere keeps a floor of 0.01, so every direction where f > 0 stays reachable
   whatever the estimates. */
static inline int sheen_ashikhmin(const material_lanes m) { return SAMPLE_ASHIKHMIN && m.draft < 0.5f; }

static inline void lobe_probabilities(const material_lanes m, float NdotV, __global const float* albedo_e,
                                      int albedo_size, float p[LOBE_COUNT]) {
  for (int t = 0; t < LOBE_COUNT; ++t) p[t] = 0.0f;
  const int lobe = BRDFCL_LOBE;
  if (lobe != BRDFCL_LOBE_ALL) {
    p[lobe == BRDFCL_LOBE_DIFFUSE ? LOBE_DIFFUSE : lobe == BRDFCL_LOBE_SPECULAR ? LOBE_SPECULAR
      : lobe == BRDFCL_LOBE_SHEEN ? LOBE_SHEEN : LOBE_COAT] = 1.0f;
    return;
  }
  float nv = clamp(NdotV, 1e-4f, 1.0f), fw = pow5w(1.0f - nv);
  float2 coat_ab = ggx_albedo_ab(sqrt(m.clearcoat_alpha), nv);
  float coatF = BRDFCL_HAS_CLEARCOAT ? m.clearcoat * (0.04f + 0.96f * fw) : 0.0f;
  float sheen_lum = m.sheen_weight * luminance3(m.sheen_r, m.sheen_g, m.sheen_b);
  int has_sheen = BRDFCL_HAS_SHEEN && sheen_lum > 0.0f;
  float e_sheen = 0.0f;
  if (has_sheen && albedo_size > 2)
    e_sheen = E_SheenAlbedo(albedo_e, albedo_size, E_SheenAlbedoRow(albedo_size, sqrt(m.sheen_alpha)), nv);
  /* E may exceed 1 / sheen_max (the fitted sheen visibility is not energy-conserving at grazing
     views and small roughness): what the sheen leaves below is then taken as nothing. */
  float below = (1.0f - coatF) * max(1.0f - m.sheen_max * e_sheen, 0.0f);
  /* Anisotropic GGX as the isotropic lobe of the same alpha_t alpha_b. */
  float2 spec_ab = ggx_albedo_ab(sqrt(sqrt(m.alpha_t * m.alpha)), nv);
  float spec_f = (1.0f - m.metallic) * (0.04f * spec_ab.x + spec_ab.y) +
                 m.metallic * (luminance3(m.base_r, m.base_g, m.base_b) * spec_ab.x + spec_ab.y);
  float W_diffuse = below * (1.0f - m.metallic) * 0.96f * luminance3(m.base_r, m.base_g, m.base_b);
  float W_spec = below * spec_f;
  float W_sheen = has_sheen ? (1.0f - coatF) * sheen_lum * e_sheen : 0.0f;
  float W_coat = coatF * (coat_ab.x + coat_ab.y);
  /* Breadth: GGX's share of normals with tan^2(theta_h) < 1, 1 / (1 + alpha_t alpha_b); Charlie's
     with sin^2 < 1/2, 2^-(k + 1); Ashikhmin's, half its cosine part and t = cot^2 > 1 in its
     Gaussian. */
  float K_spec = 1.0f / (1.0f + m.alpha_t * m.alpha);
  float K_coat = 1.0f / (1.0f + m.clearcoat_alpha * m.clearcoat_alpha);
  float m2 = m.sheen_alpha * m.sheen_alpha, pc = 1.0f / (1.0f + 4.0f * m2);
  float K_sheen = sheen_ashikhmin(m) ? 0.5f * pc + (1.0f - pc) * exp(-1.0f / m2)
                                     : exp2(-(0.5f / m.sheen_alpha + 1.0f));
  /* A GGX lobe's own share: K^4 where it stands alone, falling to K^8 where a diffuse lobe, which
     the cosine hemisphere samples exactly, outweighs it. */
  K_spec *= K_spec, K_spec *= K_spec;
  K_coat *= K_coat, K_coat *= K_coat;
  K_spec = K_spec * K_spec + (K_spec - K_spec * K_spec) * W_spec / max(W_spec + W_diffuse, 1e-30f);
  K_coat = K_coat * K_coat + (K_coat - K_coat * K_coat) * W_coat / max(W_coat + W_diffuse, 1e-30f);
  K_sheen *= K_sheen, K_sheen *= K_sheen;
  /* The ratified sheen's albedo scaling takes from the base near grazing L what the sheen adds
     there, except at grazing views; the draft's sheen is added whole. */
  float to_uniform = m.draft > 0.5f ? 1.0f : 1.0f - nv;
  float w[LOBE_COUNT];
  w[LOBE_SPECULAR] = W_spec * K_spec;
  w[LOBE_SHEEN] = W_sheen * K_sheen;
  w[LOBE_COAT] = W_coat * K_coat;
  w[LOBE_UNIFORM] = W_sheen * (1.0f - K_sheen) * to_uniform;
  w[LOBE_DIFFUSE] = W_diffuse + W_spec * (1.0f - K_spec) + W_sheen * (1.0f - K_sheen) * (1.0f - to_uniform) +
                    W_coat * (1.0f - K_coat) + 0.01f;
  float total = w[0] + w[1] + w[2] + w[3] + w[4];
  for (int t = 0; t < LOBE_COUNT; ++t) p[t] = w[t] / total;
}

/* V and L on the anisotropic lobe's axes T' = (cos r, sin r, 0), B' = (-sin r, cos r, 0), and back. */
static inline vec3w to_aniso(const material_lanes m, vec3w v) {
  vec3w o = {v.x * m.aniso_cos + v.y * m.aniso_sin, v.y * m.aniso_cos - v.x * m.aniso_sin, v.z};
  return o;
}
static inline vec3w from_aniso(const material_lanes m, vec3w v) {
  vec3w o = {v.x * m.aniso_cos - v.y * m.aniso_sin, v.x * m.aniso_sin + v.y * m.aniso_cos, v.z};
  return o;
}

/* Each lobe's pdf of L (solid angle), L and V unit vectors in the shading frame. */
static inline float lobe_pdf(int t, const material_lanes m, vec3w L, vec3w V) {
  if (t == LOBE_DIFFUSE) return PdfCosineHemisphere(L);
  if (t == LOBE_UNIFORM) return PdfUniformHemisphere(L);
  if (t == LOBE_SPECULAR) return PdfGGXVNDFBoundedReflect(to_aniso(m, L), to_aniso(m, V), m.alpha_t, m.alpha);
  if (t == LOBE_COAT) return PdfGGXVNDFBoundedReflect(L, V, m.clearcoat_alpha, m.clearcoat_alpha);
  float hx = L.x + V.x, hy = L.y + V.y, hz = L.z + V.z;
  float hxy2 = hx * hx + hy * hy, hn2 = hz * hz;
  float D = sheen_ashikhmin(m) ? D_Ashikhmin(hxy2, hn2, m.sheen_alpha) : D_Charlie(hxy2, hn2, m.sheen_alpha);
  return PdfNormalReflect(D, L, V);
}

/* The mixture's pdf, sum over lobes of p_t pdf_t(L) (Veach 1997, section 9.2.4): the density the
   one-sample estimator divides by. */
static inline float mixture_pdf(const float p[LOBE_COUNT], const material_lanes m, vec3w L, vec3w V) {
  float pdf = 0.0f;
  for (int t = 0; t < LOBE_COUNT; ++t)
    if (p[t] > 0.0f) pdf += p[t] * lobe_pdf(t, m, L, V);
  return pdf;
}

/* A direction from lobe t with (u1, u2); L.z <= 0 (or no reflection) when it produced none. */
static inline vec3w lobe_sample(int t, const material_lanes m, vec3w V, float u1, float u2) {
  if (t == LOBE_DIFFUSE) return SampleCosineHemisphere(u1, u2);
  if (t == LOBE_UNIFORM) return SampleUniformHemisphere(u1, u2);
  if (t == LOBE_SPECULAR) {
    vec3w Va = to_aniso(m, V);
    return from_aniso(m, reflect_about(Va, SampleGGXVNDFBounded(Va, m.alpha_t, m.alpha, u1, u2)));
  }
  if (t == LOBE_COAT) return reflect_about(V, SampleGGXVNDFBounded(V, m.clearcoat_alpha, m.clearcoat_alpha, u1, u2));
  vec3w H = sheen_ashikhmin(m) ? SampleAshikhminNormal(m.sheen_alpha, u1, u2) : SampleCharlieNormal(m.sheen_alpha, u1, u2);
  if (dot3w(V, H) <= 0.0f) {
    vec3w none = {0.0f, 0.0f, -1.0f};
    return none;
  }
  return reflect_about(V, H);
}

static inline vec3w load3(__global const float* p, size_t i) {
  vec3w v = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
  return v;
}

static inline material_lanes material_of(__global const brdfcl_material* materials, __global const uint* index,
                                         size_t i) {
  return material_splat(materials + (index ? index[i] : 0u));
}

/* Rows of V (3 floats, unit vectors) and u (3 floats in [0, 1)): u3 picks the lobe, u1 and u2 drive the lobe's sampler. Writes Lx Ly Lz pdf wr wg wb,
   w = f(L, V) cos(theta_L) / pdf, all 0 where no direction above the horizon came out. The host
   has checked the rows and the indices. */
__kernel void sample_rows(__global const float* restrict V, __global const uint* restrict index,
                          __global const float* restrict u, uint count,
                          __global const brdfcl_material* restrict materials, __global const float* restrict sheen_e,
                          int sheen_e_size, __global const float* restrict albedo_e, int albedo_size,
                          __global float* restrict out) {
  size_t i = get_global_id(0);
  if (i >= count) return;
  material_lanes m = material_of(materials, index, i);
  vec3w v = vec3w_normalize(load3(V, i));
  float u1 = u[3 * i], u2 = u[3 * i + 1], u3 = u[3 * i + 2];
  float p[LOBE_COUNT];
  lobe_probabilities(m, v.z, albedo_e, albedo_size, p);
  int t = 0;
  float lo = 0.0f;
  while (t < LOBE_COUNT - 1 && !(u3 < lo + p[t] && p[t] > 0.0f)) lo += p[t++];
  while (p[t] <= 0.0f) --t; /* float rounding left u3 past the last lobe present */
  float out7[7] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  if (v.z > 0.0f) {
    vec3w L = vec3w_normalize(lobe_sample(t, m, v, u1, u2));
    float pdf = L.z > 0.0f ? mixture_pdf(p, m, L, v) : 0.0f;
    if (pdf > 0.0f && isfinite(pdf)) {
      rgbw f = brdf_material(m, L, v, sheen_e, sheen_e_size);
      float k = L.z / pdf;
      out7[0] = L.x; out7[1] = L.y; out7[2] = L.z; out7[3] = pdf;
      out7[4] = f.r * k; out7[5] = f.g * k; out7[6] = f.b * k;
    }
  }
  for (int c = 0; c < 7; ++c) out[7 * i + c] = out7[c];
}

/* The mixture's pdf (as sample_rows draws) of rows of L (unit vectors, as sample_rows writes them)
   and V (normalized here as sample_rows does): 0 below the horizon. */
__kernel void pdf_rows(__global const float* restrict L, __global const float* restrict V,
                       __global const uint* restrict index, uint count,
                       __global const brdfcl_material* restrict materials, __global const float* restrict albedo_e,
                       int albedo_size, __global float* restrict out) {
  size_t i = get_global_id(0);
  if (i >= count) return;
  material_lanes m = material_of(materials, index, i);
  vec3w l = load3(L, i), v = vec3w_normalize(load3(V, i));
  float p[LOBE_COUNT];
  lobe_probabilities(m, v.z, albedo_e, albedo_size, p);
  out[i] = v.z > 0.0f && l.z > 0.0f ? mixture_pdf(p, m, l, v) : 0.0f;
}
