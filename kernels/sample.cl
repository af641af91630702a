/* Importance sampling of the layered material (brdfcl sample / pdf): one sampler per lobe
   (brdf/sampling.h) and their one-sample mixture, with lobe probabilities from each lobe's
   approximate directional albedo at V. Written once over lanes of BRDFCL_W rows (the host's lane
   width; ibl_exact.cl includes it at 1): every lobe's direction is drawn where any lane chose it
   and each lane keeps its own by select, so the CPU build runs as vector code. */
#include "brdf/sampling.h"
#include "brdf/material.h"
#include "common/rows.h"

/* A batch of one material (BRDFCL_ONE_MATERIAL, set by the host): every index is 0, so the
   material is read once for all lanes instead of gathered field by field. */
#ifndef BRDFCL_ONE_MATERIAL
#define BRDFCL_ONE_MATERIAL 0
#endif

/* The sheen sampler follows the spec's distribution for the batch's options: Ashikhmin's only
   where --sheen-distribution ashikhmin applies (profile spec, ratified lanes). */
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC && BRDFCL_SHEEN_DIST == BRDFCL_SHEEN_DIST_ASHIKHMIN
#define SAMPLE_ASHIKHMIN 1
#else
#define SAMPLE_ASHIKHMIN 0
#endif

/* --lobe specular or clearcoat alone under the spec's profile: the weight cancels the GGX D that
   f and the pdf share (sample_rows_group). */
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC && (BRDFCL_LOBE == BRDFCL_LOBE_SPECULAR || BRDFCL_LOBE == BRDFCL_LOBE_CLEARCOAT)
#define SAMPLE_GGX_CANCELLED 1
#else
#define SAMPLE_GGX_CANCELLED 0
#endif

/* Whether a group has lanes for a branch's work. A GGX lobe alone keeps nearly every lane, and any()
   of 16 lanes is some 40 extracts and tests on PoCL: there the work runs unconditionally (the
   lanes it does not keep are selected away). */
#define SAMPLE_ANY(x) (SAMPLE_GGX_CANCELLED || ANYW(x))

/* LOBE_UNIFORM: the uniform hemisphere, which takes the share of a sheen lobe that its own sampler
   serves poorly (docs/sampling.md). */
enum { LOBE_DIFFUSE, LOBE_SPECULAR, LOBE_SHEEN, LOBE_COAT, LOBE_UNIFORM, LOBE_COUNT };

BRDF_FN realw luminance3(realw r, realw g, realw b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

/* Karis 2014, "Physically Based Shading on Mobile" (EnvBRDFApprox): the directional albedo of
   a GGX lobe with Schlick's Fresnel, F0 A + B, fitted in perceptual roughness r and N.V; A in
   *a, B returned. */
BRDF_FN realw ggx_albedo_ab(realw r, realw nv, realw* a) {
  realw rx = 1.0f - r, ry = 0.0425f - 0.0275f * r, rz = 1.04f - 0.572f * r, rw = 0.022f * r - 0.04f;
  realw a004 = min(rx * rx, exp2(-9.28f * nv)) * rx + ry;
  *a = rz - 1.04f * a004;
  return rw + 1.04f * a004;
}

/* The lanes whose sheen follows Ashikhmin's distribution. */
BRDF_FN intw sheen_ashikhmin(const material_lanes m) {
#if SAMPLE_ASHIKHMIN
  return m.draft < 0.5f;
#else
  return (intw)(0);
#endif
}

/* The lobe --lobe names (sample.cl's index), for a batch that samples one lobe alone. */
#define LOBE_OF_OPTION                                                                                   \
  (BRDFCL_LOBE == BRDFCL_LOBE_DIFFUSE ? LOBE_DIFFUSE : BRDFCL_LOBE == BRDFCL_LOBE_SPECULAR ? LOBE_SPECULAR \
   : BRDFCL_LOBE == BRDFCL_LOBE_SHEEN ? LOBE_SHEEN : LOBE_COAT)

/* Lobe probabilities at V. Under --lobe one lobe takes all. Otherwise each lobe's directional
   albedo W_t is estimated under the layers above it: the coat's Fresnel times its GGX albedo;
   the sheen's colour times its E table; the specular's GGX albedo (Karis's fit) and the diffuse's
   0.96 base colour, both under what the coat and the sheen's albedo scaling leave. Each W_t is
   then split by K_t^4, K_t a lobe's breadth (docs/sampling.md): W_t K_t^4 goes to its own sampler
   and the rest to a hemisphere sampler that loses no directions: the cosine one for GGX, whose
   broad lobes it follows better than the VNDF (which ignores the masking of L), mostly the
   uniform one for the sheen, which peaks towards grazing L where the cosine density starves it.
   The cosine hemisphere keeps a floor of 0.01, so every direction where f > 0 stays reachable
   whatever the estimates. Lane-wise throughout: what is chosen per material is chosen by select. */
BRDF_FN void lobe_probabilities(const material_lanes m, realw NdotV, __global const float* albedo_e,
                                int albedo_size, realw p[LOBE_COUNT]) {
  for (int t = 0; t < LOBE_COUNT; ++t) p[t] = (realw)(0.0f);
  if (BRDFCL_LOBE != BRDFCL_LOBE_ALL) {
    p[LOBE_OF_OPTION] = (realw)(1.0f);
    return;
  }
  realw nv = clamp(NdotV, 1e-4f, 1.0f), fw = pow5w(1.0f - nv);
  realw coat_a, coat_b = ggx_albedo_ab(sqrt(m.clearcoat_alpha), nv, &coat_a);
  realw coatF = BRDFCL_HAS_CLEARCOAT ? m.clearcoat * (0.04f + 0.96f * fw) : (realw)(0.0f);
  realw sheen_lum = m.sheen_weight * luminance3(m.sheen_r, m.sheen_g, m.sheen_b);
  intw has_sheen = sheen_lum > 0.0f;
  if (!BRDFCL_HAS_SHEEN) has_sheen = (intw)(0);
  realw e_sheen = (realw)(0.0f);
  if (albedo_size > 2 && ANYW(has_sheen))
    e_sheen = select((realw)(0.0f),
                     E_SheenAlbedo(albedo_e, albedo_size, E_SheenAlbedoRow(albedo_size, sqrt(m.sheen_alpha)), nv),
                     has_sheen);
  /* E may exceed 1 / sheen_max (the fitted sheen visibility is not energy-conserving at grazing
     views and small roughness): what the sheen leaves below is then taken as nothing. */
  realw below = (1.0f - coatF) * max(1.0f - m.sheen_max * e_sheen, 0.0f);
  /* Anisotropic GGX as the isotropic lobe of the same alpha_t alpha_b. */
  realw spec_a, spec_b = ggx_albedo_ab(sqrt(sqrt(m.alpha_t * m.alpha)), nv, &spec_a);
  realw spec_f = (1.0f - m.metallic) * (0.04f * spec_a + spec_b) +
                 m.metallic * (luminance3(m.base_r, m.base_g, m.base_b) * spec_a + spec_b);
  realw W_diffuse = below * (1.0f - m.metallic) * 0.96f * luminance3(m.base_r, m.base_g, m.base_b);
  realw W_spec = below * spec_f;
  realw W_sheen = select((realw)(0.0f), (1.0f - coatF) * sheen_lum * e_sheen, has_sheen);
  realw W_coat = coatF * (coat_a + coat_b);
  /* Breadth: GGX's share of normals with tan^2(theta_h) < 1, 1 / (1 + alpha_t alpha_b); Charlie's
     with sin^2 < 1/2, 2^-(k + 1); Ashikhmin's, half its cosine part and t = cot^2 > 1 in its
     Gaussian. */
  realw K_spec = 1.0f / (1.0f + m.alpha_t * m.alpha);
  realw K_coat = 1.0f / (1.0f + m.clearcoat_alpha * m.clearcoat_alpha);
  realw K_sheen = exp2(-(0.5f / m.sheen_alpha + 1.0f));
#if SAMPLE_ASHIKHMIN
  realw m2 = m.sheen_alpha * m.sheen_alpha, pc = 1.0f / (1.0f + 4.0f * m2);
  K_sheen = select(K_sheen, 0.5f * pc + (1.0f - pc) * exp(-1.0f / m2), sheen_ashikhmin(m));
#endif
  /* A GGX lobe's own share: K^4 where it stands alone, falling to K^8 where a diffuse lobe, which
     the cosine hemisphere samples exactly, outweighs it. */
  K_spec *= K_spec, K_spec *= K_spec;
  K_coat *= K_coat, K_coat *= K_coat;
  K_spec = K_spec * K_spec + (K_spec - K_spec * K_spec) * W_spec / max(W_spec + W_diffuse, 1e-30f);
  K_coat = K_coat * K_coat + (K_coat - K_coat * K_coat) * W_coat / max(W_coat + W_diffuse, 1e-30f);
  K_sheen *= K_sheen, K_sheen *= K_sheen;
  /* The ratified sheen's albedo scaling takes from the base near grazing L what the sheen adds
     there, except at grazing views; the draft's sheen is added whole. */
  realw to_uniform = select(1.0f - nv, (realw)(1.0f), m.draft > 0.5f);
  realw w[LOBE_COUNT];
  w[LOBE_SPECULAR] = W_spec * K_spec;
  w[LOBE_SHEEN] = W_sheen * K_sheen;
  w[LOBE_COAT] = W_coat * K_coat;
  w[LOBE_UNIFORM] = W_sheen * (1.0f - K_sheen) * to_uniform;
  w[LOBE_DIFFUSE] = W_diffuse + W_spec * (1.0f - K_spec) + W_sheen * (1.0f - K_sheen) * (1.0f - to_uniform) +
                    W_coat * (1.0f - K_coat) + 0.01f;
  realw inv_total = 1.0f / (w[0] + w[1] + w[2] + w[3] + w[4]);
  for (int t = 0; t < LOBE_COUNT; ++t) p[t] = w[t] * inv_total;
}

/* Each lane's lobe for u3: the first lobe present whose interval of the running sum of p holds
   u3; where float rounding leaves u3 past the last lobe, the last lobe present. */
BRDF_FN intw lobe_choose(const realw p[LOBE_COUNT], realw u3) {
  intw t = (intw)(LOBE_COUNT - 1), found = (intw)(0);
  realw lo = (realw)(0.0f);
  for (int k = 0; k < LOBE_COUNT - 1; ++k) {
    intw hit = (u3 < lo + p[k]) & (p[k] > 0.0f);
    hit = hit & (found == 0);
    t = select(t, (intw)(k), hit);
    found |= hit;
    lo += p[k];
  }
  for (int k = LOBE_COUNT - 1; k > 0; --k) t = select(t, (intw)(k - 1), (t == k) & (p[k] <= 0.0f));
  return t;
}

/* V and L on the anisotropic lobe's axes T' = (cos r, sin r, 0), B' = (-sin r, cos r, 0), and back. */
BRDF_FN vec3w to_aniso(const material_lanes m, vec3w v) {
  vec3w o = {v.x * m.aniso_cos + v.y * m.aniso_sin, v.y * m.aniso_cos - v.x * m.aniso_sin, v.z};
  return o;
}
BRDF_FN vec3w from_aniso(const material_lanes m, vec3w v) {
  vec3w o = {v.x * m.aniso_cos - v.y * m.aniso_sin, v.x * m.aniso_sin + v.y * m.aniso_cos, v.z};
  return o;
}

BRDF_FN vec3w select3(vec3w a, vec3w b, intw c) {
  vec3w o = {select(a.x, b.x, c), select(a.y, b.y, c), select(a.z, b.z, c)};
  return o;
}

/* Lobe t's pdf of L (solid angle), L and V unit vectors in the shading frame. */
BRDF_FN realw lobe_pdf(int t, const material_lanes m, vec3w L, vec3w V) {
  if (t == LOBE_DIFFUSE) return PdfCosineHemisphere(L);
  if (t == LOBE_UNIFORM) return PdfUniformHemisphere(L);
  if (t == LOBE_SPECULAR) return PdfGGXVNDFBoundedReflect(to_aniso(m, L), to_aniso(m, V), m.alpha_t, m.alpha);
  if (t == LOBE_COAT) return PdfGGXVNDFBoundedReflect(L, V, m.clearcoat_alpha, m.clearcoat_alpha);
  realw hx = L.x + V.x, hy = L.y + V.y, hz = L.z + V.z;
  realw hxy2 = hx * hx + hy * hy, hn2 = hz * hz;
  realw D = D_Charlie(hxy2, hn2, m.sheen_alpha);
#if SAMPLE_ASHIKHMIN
  D = select(D, D_Ashikhmin(hxy2, hn2, m.sheen_alpha), sheen_ashikhmin(m));
#endif
  return PdfNormalReflect(D, L, V);
}

/* The mixture's pdf, sum over lobes of p_t pdf_t(L) (Veach 1997, section 9.2.4): the density the
   one-sample estimator divides by. A lobe no lane uses is skipped. */
BRDF_FN realw mixture_pdf(const realw p[LOBE_COUNT], const material_lanes m, vec3w L, vec3w V) {
  if (BRDFCL_LOBE != BRDFCL_LOBE_ALL) return lobe_pdf(LOBE_OF_OPTION, m, L, V);
  realw pdf = (realw)(0.0f);
  /* Unrolled by hand, each lobe's pdf with its index a constant: as a loop (which PoCL's LLVM
     keeps), lobe_pdf dispatched on t at run time, a fifth of --lobe all's time. */
#define MIXTURE_TERM(t)                                                                        \
  {                                                                                            \
    intw present = p[t] > 0.0f;                                                                \
    if (ANYW(present)) pdf += select((realw)(0.0f), p[t] * lobe_pdf(t, m, L, V), present);     \
  }
  MIXTURE_TERM(LOBE_DIFFUSE)
  MIXTURE_TERM(LOBE_SPECULAR)
  MIXTURE_TERM(LOBE_SHEEN)
  MIXTURE_TERM(LOBE_COAT)
  MIXTURE_TERM(LOBE_UNIFORM)
#undef MIXTURE_TERM
  return pdf;
}

/* A direction from each lane's lobe t with (u1, u2); L.z <= 0 (or no reflection) when it produced
   none. The samplers share one shape: a point (st cos phi, st sin phi, z), which is the direction
   itself for the two hemispheres, and for the GGX lobes and the sheen a microfacet normal (offset
   by Vh and scaled by the alphas for GGX) that reflects V in the lobe's frame (the specular's
   rotation; none for the others). Each lane selects its own lobe's parameters, so a group runs one
   azimuth, one normalization and one reflection whatever lobes its lanes chose; only each lobe's
   own inversion runs where a lane chose it. V is the unit view; Vk is V at any length (the
   caller's row before its normalization), from which the GGX cap is drawn, so that V's exact
   normalization (a square root and a division) runs beside the cap's chain rather than at its
   head. L is unit to a few ulp (H is normalized, V is unit). */
BRDF_FN vec3w lobe_sample_from(intw t, const material_lanes m, vec3w Vk, vec3w V, realw u1, realw u2) {
  const intw spec = t == LOBE_SPECULAR, ggx = spec | (t == LOBE_COAT), sheen = t == LOBE_SHEEN;
  const intw unif = t == LOBE_UNIFORM, hemi = (t == LOBE_DIFFUSE) | unif;
  const realw zero = (realw)(0.0f), one = (realw)(1.0f);
  realw rc = select(one, m.aniso_cos, spec), rs = select(zero, m.aniso_sin, spec);
  realw ax = select(one, select(m.clearcoat_alpha, m.alpha_t, spec), ggx);
  realw ay = select(one, select(m.clearcoat_alpha, m.alpha, spec), ggx);
  vec3w Va = {V.x * rc + V.y * rs, V.y * rc - V.x * rs, V.z};
  realw c, sn = sincos_2pi(select(u2, u1, ggx), &c);
  /* The hemispheres: Malley's (cosine) or uniform in z. */
  realw z = select(sqrt(max(1.0f - u1, zero)), u1, unif);
  realw st = select(sqrt(u1), sqrt(max(1.0f - u1 * u1, zero)), unif);
  vec3w Vh = {zero, zero, zero};
  if (ANYW(ggx)) {
    /* Eto & Tokuyoshi's bounded cap (SampleGGXVNDFBounded), every length of the point scaled by
       k's denominator dk > 0: the normal is normalized after, so k's division is never made. */
    vec3w Vka = {Vk.x * rc + Vk.y * rs, Vk.y * rc - Vk.x * rs, Vk.z};
    vec3w s = {ax * Vka.x, ay * Vka.y, Vka.z};
    vec3w h = vec3w_normalize_fast(s);
    realw dk, bn = BoundedVNDFKPartsOfUnnormalized(Vka, ax, ay, &dk) * h.z;
    realw zg = (1.0f - u2) * (dk + bn) - bn;
    z = select(z, zg, ggx);
    st = select(st, sqrt(max(dk * dk - zg * zg, zero)), ggx);
    vec3w dh = {dk * h.x, dk * h.y, dk * h.z};
    Vh = select3(Vh, dh, ggx);
  }
  if (ANYW(sheen)) {
    /* The sheen's normal at cos^2 c2, sin^2 s2 (SampleCharlieNormal, SampleAshikhminNormal). */
    realw e = 2.0f * m.sheen_alpha / (1.0f + 2.0f * m.sheen_alpha);
    realw lu = log(max(u1, (realw)(1.0e-38f)));
    realw c2 = clamp(-expm1(lu * e), zero, one), s2 = clamp(exp(lu * e), zero, one);
#if SAMPLE_ASHIKHMIN
    intw ash = sheen_ashikhmin(m);
    if (ANYW(ash & sheen)) {
      realw m2 = m.sheen_alpha * m.sheen_alpha, pc = 1.0f / (1.0f + 4.0f * m2);
      intw cosine = u1 < pc;
      realw v = select(clamp((u1 - pc) / (1.0f - pc), zero, one), u1 / pc, cosine);
      realw tt = -m2 * log1p(-min(v, (realw)(0.99999994f)));
      c2 = select(c2, max(select(tt / (1.0f + tt), 1.0f - v, cosine), zero), ash);
      s2 = select(s2, max(select(1.0f / (1.0f + tt), v, cosine), zero), ash);
    }
#endif
    z = select(z, sqrt(c2), sheen);
    st = select(st, sqrt(s2), sheen);
  }
  vec3w N = {st * c + Vh.x, st * sn + Vh.y, z + Vh.z};
  vec3w Ne = {ax * N.x, ay * N.y, max(N.z, zero)};
  vec3w H = vec3w_normalize_fast(Ne);
  realw k = 2.0f * dot3w(Va, H);
  vec3w R = {k * H.x - Va.x, k * H.y - Va.y, k * H.z - Va.z};
  vec3w L = {R.x * rc - R.y * rs, R.x * rs + R.y * rc, R.z};
  L = select3(L, N, hemi);
  vec3w none = {zero, zero, (realw)(-1.0f)};
  return select3(L, none, (t > LOBE_UNIFORM) | (sheen & (k <= 0.0f)));
}
BRDF_FN vec3w lobe_sample(intw t, const material_lanes m, vec3w V, realw u1, realw u2) {
  return lobe_sample_from(t, m, V, V, u1, u2);
}

/* Each lane's material: row k's index where there is an index array, else material 0. */
BRDF_FN material_lanes sample_material(__global const brdfcl_material* materials, __global const uint* index,
                                       uint n, const int partial) {
  if (BRDFCL_ONE_MATERIAL || !index) return material_splat(materials);
#if BRDFCL_W == 1
  return material_splat(materials + index[0]);
#else
  uintw k;
  if (partial) {
    uint tmp[BRDFCL_W];
    for (uint j = 0; j < BRDFCL_W; ++j) tmp[j] = j < n ? index[j] : 0u;
    k = VLOADW(0, tmp);
  } else {
    k = VLOADW(0, index);
  }
  return material_gather(materials, k);
#endif
}

/* BRDFCL_W rows of 7 floats (Lx Ly Lz pdf wr wg wb) from the 7 column vectors o0..o6, stored as 7
   whole vectors: element j = q W + p of output vector q is column j % 7 of lane j / 7, which a tree
   of constant shuffles picks (pairs of columns, then their halves), the inverse of rows.h's
   TABLE_COLUMN. A lane-by-lane store of 7 scalars would cost more than drawing the direction. */
#if BRDFCL_W > 1
#define OUT7_C(q, p) (((q) * BRDFCL_W + (p)) % 7)
#define OUT7_K(q, p) (((q) * BRDFCL_W + (p)) / 7)
#define OUT7_PAIR(q, pr, p) (OUT7_C(q, p) / 2 == (pr) ? (OUT7_C(q, p) % 2) * BRDFCL_W + OUT7_K(q, p) : -1)
#define OUT7_LOW(q, unused, p) (OUT7_C(q, p) < 2 ? (p) : OUT7_C(q, p) < 4 ? BRDFCL_W + (p) : -1)
#define OUT7_HIGH(q, unused, p) (OUT7_C(q, p) < 4 ? -1 : OUT7_C(q, p) < 6 ? (p) : BRDFCL_W + (p))
#define OUT7_HALF(q, unused, p) (OUT7_C(q, p) < 4 ? (p) : BRDFCL_W + (p))
#define OUT7_VECTOR(o, q)                                                                                    \
  __builtin_shufflevector(                                                                                   \
      __builtin_shufflevector(__builtin_shufflevector(o##0, o##1, ROWS_LANES(OUT7_PAIR, q, 0)),              \
                              __builtin_shufflevector(o##2, o##3, ROWS_LANES(OUT7_PAIR, q, 1)),              \
                              ROWS_LANES(OUT7_LOW, q, 0)),                                                   \
      __builtin_shufflevector(__builtin_shufflevector(o##4, o##5, ROWS_LANES(OUT7_PAIR, q, 2)),              \
                              __builtin_shufflevector(o##6, o##6, ROWS_LANES(OUT7_PAIR, q, 3)),              \
                              ROWS_LANES(OUT7_HIGH, q, 0)),                                                  \
      ROWS_LANES(OUT7_HALF, q, 0))
#define OUT7_STORE(o, p)                                                                                          \
  PLANE_STORE(OUT7_VECTOR(o, 0), 0, p), PLANE_STORE(OUT7_VECTOR(o, 1), 1, p), PLANE_STORE(OUT7_VECTOR(o, 2), 2, p), \
      PLANE_STORE(OUT7_VECTOR(o, 3), 3, p), PLANE_STORE(OUT7_VECTOR(o, 4), 4, p),                                 \
      PLANE_STORE(OUT7_VECTOR(o, 5), 5, p), PLANE_STORE(OUT7_VECTOR(o, 6), 6, p)
#endif

/* Rows of V (3 floats, unit vectors) and u (3 floats in [0, 1)): u3 picks the lobe, u1 and u2
   drive the lobe's sampler. Writes Lx Ly Lz pdf wr wg wb, w = f(L, V) cos(theta_L) / pdf, all 0
   where no direction above the horizon came out. The host has checked the rows and the indices.
   Every row's result depends on its own row alone, whichever lane it lands in. */
BRDF_FN void sample_rows_group(uint first, uint n, const int partial, __global const float* restrict V,
                               __global const uint* restrict index, __global const float* restrict u, uint count,
                               __global const brdfcl_material* restrict materials,
                               __global const float* restrict sheen_e, int sheen_e_size,
                               __global const float* restrict albedo_e, int albedo_size, __global float* restrict out) {
  V += 3 * (ulong)first;
  u += 3 * (ulong)first;
  out += 7 * (ulong)first;
  material_lanes m = sample_material(materials, index ? index + first : index, n, partial);
  vec3w v_row = partial ? rows_load_partial(V, n) : rows_load(V);
  vec3w v = vec3w_normalize(v_row);
  vec3w uu = partial ? rows_load_partial(u, n) : rows_load(u);
  realw p[LOBE_COUNT];
  lobe_probabilities(m, v.z, albedo_e, albedo_size, p);
  intw t = BRDFCL_LOBE == BRDFCL_LOBE_ALL ? lobe_choose(p, uu.z) : (intw)(LOBE_OF_OPTION);
  vec3w L = lobe_sample_from(t, m, v_row, v, uu.x, uu.y);
  intw above = (v.z > 0.0f) & (L.z > 0.0f);
  realw pdf = (realw)(0.0f);
#if SAMPLE_GGX_CANCELLED
  /* One GGX lobe alone: its D is in f and in the pdf, so w = (f / D) cos (D / pdf), D never formed,
     and the visibility's division and the pdf's ratio share one. */
  realw d_num = (realw)(0.0f), d_den = (realw)(1.0f);
  if (SAMPLE_ANY(above)) {
    realw lobe_pdf_of_l =
        BRDFCL_LOBE == BRDFCL_LOBE_SPECULAR
            ? PdfGGXVNDFBoundedReflectD(to_aniso(m, L), to_aniso(m, v), m.alpha_t, m.alpha, &d_num, &d_den)
            : PdfGGXVNDFBoundedReflectD(L, v, m.clearcoat_alpha, m.clearcoat_alpha, &d_num, &d_den);
    pdf = select((realw)(0.0f), lobe_pdf_of_l, above);
  }
#else
  if (ANYW(above)) pdf = select((realw)(0.0f), mixture_pdf(p, m, L, v), above);
#endif
  intw keep = (pdf > 0.0f) & isfinite(pdf);
  /* Seven named vectors, not an array: PoCL keeps a private array that its loops index in memory,
     a slot a work-item in the work-group's context (448 bytes of stack a work-item). */
  realw o0 = (realw)(0.0f), o1 = o0, o2 = o0, o3 = o0, o4 = o0, o5 = o0, o6 = o0;
  if (SAMPLE_ANY(keep)) {
#if SAMPLE_GGX_CANCELLED
    realw vis_half_rcp;
    rgbw f = brdf_lobe_over_dv(m, L, v, sheen_e, sheen_e_size, &vis_half_rcp);
    realw k = (L.z * d_num) / (d_den * vis_half_rcp);
#else
    rgbw f = brdf_material(m, L, v, sheen_e, sheen_e_size);
    realw k = L.z / pdf;
#endif
    o0 = keep_or_zero(L.x, keep), o1 = keep_or_zero(L.y, keep), o2 = keep_or_zero(L.z, keep);
    o3 = keep_or_zero(pdf, keep), o4 = keep_or_zero(f.r * k, keep), o5 = keep_or_zero(f.g * k, keep);
    o6 = keep_or_zero(f.b * k, keep);
  }
#if BRDFCL_W == 1
  out[0] = o0, out[1] = o1, out[2] = o2, out[3] = o3, out[4] = o4, out[5] = o5, out[6] = o6;
#else
  if (!partial) {
    OUT7_STORE(o, out);
  } else {
    float cols[7][BRDFCL_W];
    VSTOREW(o0, 0, cols[0]), VSTOREW(o1, 0, cols[1]), VSTOREW(o2, 0, cols[2]), VSTOREW(o3, 0, cols[3]);
    VSTOREW(o4, 0, cols[4]), VSTOREW(o5, 0, cols[5]), VSTOREW(o6, 0, cols[6]);
    for (uint j = 0; j < n; ++j)
      for (int c = 0; c < 7; ++c) out[7 * j + c] = cols[c][j];
  }
#endif
}

/* The mixture's pdf (as sample_rows draws) of rows of L (unit vectors, as sample_rows writes them)
   and V (normalized here as sample_rows does): 0 below the horizon. */
BRDF_FN void pdf_rows_group(uint first, uint n, const int partial, __global const float* restrict L,
                            __global const float* restrict V, __global const uint* restrict index, uint count,
                            __global const brdfcl_material* restrict materials,
                            __global const float* restrict albedo_e, int albedo_size, __global float* restrict out) {
  L += 3 * (ulong)first;
  V += 3 * (ulong)first;
  out += first;
  material_lanes m = sample_material(materials, index ? index + first : index, n, partial);
  vec3w l = partial ? rows_load_partial(L, n) : rows_load(L);
  vec3w v = vec3w_normalize(partial ? rows_load_partial(V, n) : rows_load(V));
  realw p[LOBE_COUNT];
  lobe_probabilities(m, v.z, albedo_e, albedo_size, p);
  intw above = (v.z > 0.0f) & (l.z > 0.0f);
  realw pdf = (realw)(0.0f);
  if (ANYW(above)) pdf = select((realw)(0.0f), mixture_pdf(p, m, l, v), above);
#if BRDFCL_W == 1
  out[0] = pdf;
#else
  if (!partial) {
    VSTOREW(pdf, 0, out);
  } else {
    float tmp[BRDFCL_W];
    VSTOREW(pdf, 0, tmp);
    for (uint j = 0; j < n; ++j) out[j] = tmp[j];
  }
#endif
}

/* Two entry points a kernel, as eval.cl's row kernels: `name` runs the whole groups of BRDFCL_W
   rows (a work-item each), `name_tail`, one work-item, the partial group at the end, if any. */
#define SAMPLE_ROW_KERNELS(name, PARAMS, ARGS)                                             \
  __kernel void name PARAMS {                                                             \
    uint first = get_global_id(0) * BRDFCL_W;                                             \
    if (first + BRDFCL_W <= count) name##_group(first, BRDFCL_W, 0, ARGS);                \
  }                                                                                       \
  __kernel void name##_tail PARAMS {                                                      \
    uint first = count / BRDFCL_W * BRDFCL_W;                                             \
    if (first < count) name##_group(first, count - first, 1, ARGS);                       \
  }

/* The entry points a program holds, as a mask (both without the define): 1 sample_rows, 2 pdf_rows,
   so that `sample` and `pdf` each load only their own (host/src/eval/sampling.cpp). */
#ifndef BRDFCL_SAMPLER_KERNELS
#define BRDFCL_SAMPLER_KERNELS 3
#endif
#if BRDFCL_SAMPLER_KERNELS & 1
#define SAMPLE_ROWS_ARGS V, index, u, count, materials, sheen_e, sheen_e_size, albedo_e, albedo_size, out
SAMPLE_ROW_KERNELS(sample_rows,
                   (__global const float* restrict V, __global const uint* restrict index,
                    __global const float* restrict u, uint count, __global const brdfcl_material* restrict materials,
                    __global const float* restrict sheen_e, int sheen_e_size, __global const float* restrict albedo_e,
                    int albedo_size, __global float* restrict out),
                   SAMPLE_ROWS_ARGS)
#endif
#if BRDFCL_SAMPLER_KERNELS & 2
#define PDF_ROWS_ARGS L, V, index, count, materials, albedo_e, albedo_size, out
SAMPLE_ROW_KERNELS(pdf_rows,
                   (__global const float* restrict L, __global const float* restrict V,
                    __global const uint* restrict index, uint count, __global const brdfcl_material* restrict materials,
                    __global const float* restrict albedo_e, int albedo_size, __global float* restrict out),
                   PDF_ROWS_ARGS)
#endif
