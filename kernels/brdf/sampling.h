/* Importance sampling of the layered BRDF's lobes, over width-generic lanes: GGX visible normals
   (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4); Dupuy & Benyoub 2023,
   "Sampling Visible GGX Normals with Spherical Caps"; Eto & Tokuyoshi 2023, "Bounded VNDF Sampling
   for Smith-GGX Reflections"), anisotropic or not, the sheen distributions
   (Charlie, Ashikhmin) exactly, and the cosine and uniform hemispheres. Each sampler has its pdf in
   solid angle of L beside it; docs/sampling.md derives them. */
#ifndef BRDFCL_SAMPLING_H
#define BRDFCL_SAMPLING_H

#include "common/lanes.h"
#include "brdf/terms.h"

BRDF_FN vec3w vec3w_normalize(vec3w v) {
  realw inv = rsqrt(max(dot3w(v, v), (realw)(1.0e-30f)));
  vec3w o = {v.x * inv, v.y * inv, v.z * inv};
  return o;
}

/* The samplers' own normalizations (the stretched view, the microfacet normal) without a division:
   rsqrt is a square root and a correctly rounded division on CPUs
   (-cl-fp32-correctly-rounded-divide-sqrt), and L = 2 (V.H) H - V is as good as H is. The caller's
   V keeps vec3w_normalize: the pdf of a sharp lobe at a grazing view is ill-conditioned in V (h = L +
   V cancels), and `brdfcl pdf` must normalize V as `brdfcl sample` did. */
BRDF_FN vec3w vec3w_normalize_fast(vec3w v) {
  realw inv = brdf_rsqrt(max(dot3w(v, v), (realw)(1.0e-30f)));
  vec3w o = {v.x * inv, v.y * inv, v.z * inv};
  return o;
}

/* sin and cos of 2 pi u for u in [0, 1), every sampler's azimuth, without the library's range
   reduction (a call per lobe and group on PoCL, 16 lanes each): u is folded exactly (Sterbenz) to
   y in [-1/4, 1/4] with 2 pi u = pi - 2 pi y or 2 pi y modulo 2 pi, and the Taylor polynomials of
   degrees 11 and 12 in a = 2 pi y, |a| <= pi / 2, are within 6e-8 of sin and cos there, about
   float's own rounding. The sine is returned, the cosine stored in *c. */
BRDF_FN realw sincos_2pi(realw u, realw* c) {
  realw x = u - select((realw)(0.0f), (realw)(1.0f), u >= 0.5f);
  intw fold = fabs(x) > 0.25f;
  realw y = select(x, copysign((realw)(0.5f), x) - x, fold);
  realw a = 6.28318530717958648f * y, a2 = a * a;
  realw sn = fma(a2, fma(a2, fma(a2, fma(a2, fma(a2, -2.5052108385441718775e-8f, 2.7557319223985890653e-6f),
                                                  -1.9841269841269841270e-4f), 8.3333333333333333333e-3f),
                         -1.6666666666666666667e-1f), 1.0f) * a;
  realw cs = fma(a2, fma(a2, fma(a2, fma(a2, fma(a2, fma(a2, 2.0876756987868098979e-9f, -2.7557319223985890653e-7f),
                                                          2.4801587301587301587e-5f), -1.3888888888888888889e-3f),
                                         4.1666666666666666667e-2f), -0.5f), 1.0f);
  *c = select(cs, -cs, fold);
  return sn;
}

/* Heitz 2018, section 4 and its sampling routine: a visible normal of the GGX lobe (alphas ax along +X, ay along +Y) seen
   from Ve (Ve.z > 0), from (u1, u2) in [0, 1)^2. The view is stretched to the hemisphere
   configuration, a point is drawn on the projected disk (half of it warped by the visible
   hemisphere's foreshortening), lifted, and the normal unstretched. */
BRDF_FN vec3w SampleGGXVNDF(vec3w Ve, realw ax, realw ay, realw u1, realw u2) {
  vec3w s = {ax * Ve.x, ay * Ve.y, Ve.z};
  vec3w Vh = vec3w_normalize(s);
  realw lensq = Vh.x * Vh.x + Vh.y * Vh.y;
  realw inv_len = rsqrt(max(lensq, (realw)(1.0e-30f)));
  intw tilted = lensq > 0.0f;
  vec3w T1 = {select((realw)(1.0f), -Vh.y * inv_len, tilted), select((realw)(0.0f), Vh.x * inv_len, tilted), (realw)(0.0f)};
  vec3w T2 = {Vh.y * T1.z - Vh.z * T1.y, Vh.z * T1.x - Vh.x * T1.z, Vh.x * T1.y - Vh.y * T1.x};
  realw r = sqrt(u1), cphi, sphi = sincos_2pi(u2, &cphi);
  realw t1 = r * cphi, t2 = r * sphi;
  realw sh = 0.5f * (1.0f + Vh.z);
  t2 = (1.0f - sh) * sqrt(max(1.0f - t1 * t1, (realw)(0.0f))) + sh * t2;
  realw tz = sqrt(max(1.0f - t1 * t1 - t2 * t2, (realw)(0.0f)));
  vec3w Nh = {t1 * T1.x + t2 * T2.x + tz * Vh.x, t1 * T1.y + t2 * T2.y + tz * Vh.y, t1 * T1.z + t2 * T2.z + tz * Vh.z};
  vec3w Ne = {ax * Nh.x, ay * Nh.y, max(Nh.z, (realw)(0.0f))};
  return vec3w_normalize(Ne);
}

/* Smith masking G1 = 1 / (1 + Lambda(W)) of the (anisotropic) GGX lobe, with Lambda in closed
   form: 2 W.z / (W.z + |(ax Wx, ay Wy, Wz)|) (Heitz 2018, section 2). */
BRDF_FN realw G1_GGX(vec3w W, realw ax, realw ay) {
  realw s = sqrt(ax * ax * W.x * W.x + ay * ay * W.y * W.y + W.z * W.z);
  return 2.0f * W.z / (W.z + s);
}

/* pdf of L = reflect(V, H) with H from SampleGGXVNDF: the visible-normal density
   D_V(H) = G1(V) max(0, V.H) D(H) / V.z (Heitz 2018) times the reflection Jacobian 1 / (4 V.H),
   = G1(V) D(H) / (4 V.z). L, V in the lobe's frame. */
BRDF_FN realw PdfGGXVNDFReflect(vec3w L, vec3w V, realw ax, realw ay) {
  vec3w h = {L.x + V.x, L.y + V.y, L.z + V.z};
  realw h2 = max(dot3w(h, h), (realw)(1.0e-30f));
  realw D = D_GGX_Anisotropic(h.x, h.y, h.z, h2, ax, ay);
  realw Vz = max(V.z, (realw)(1.0e-4f));
  realw pdf = G1_GGX(V, ax, ay) * D / (4.0f * Vz);
  return keep_or_zero(pdf, (L.z > 0.0f) & (h.z > 0.0f));
}

/* L = 2 (V.H) H - V. */
BRDF_FN vec3w reflect_about(vec3w V, vec3w H) {
  realw k = 2.0f * dot3w(V, H);
  vec3w L = {k * H.x - V.x, k * H.y - V.y, k * H.z - V.z};
  return L;
}

/* Malley's method: a uniform point on the disk lifted to the hemisphere; pdf N.L / pi. */
BRDF_FN vec3w SampleCosineHemisphere(realw u1, realw u2) {
  realw r = sqrt(u1), c, sn = sincos_2pi(u2, &c);
  vec3w L = {r * c, r * sn, sqrt(max(1.0f - u1, (realw)(0.0f)))};
  return L;
}
BRDF_FN realw PdfCosineHemisphere(vec3w L) { return max(L.z, (realw)(0.0f)) * M_1_PI_F; }

/* Uniform over the upper hemisphere; pdf 1 / (2 pi). The sheen lobe peaks towards grazing
   angles, where a cosine density would starve it. */
BRDF_FN vec3w SampleUniformHemisphere(realw u1, realw u2) {
  realw z = u1, r = sqrt(max(1.0f - z * z, (realw)(0.0f))), c, sn = sincos_2pi(u2, &c);
  vec3w L = {r * c, r * sn, z};
  return L;
}
BRDF_FN realw PdfUniformHemisphere(vec3w L) { return select((realw)(0.0f), (realw)(0.5f * M_1_PI_F), L.z > 0.0f); }

/* Dupuy & Benyoub 2023, listing 3: the same visible-normal distribution as SampleGGXVNDF, drawn as
   a point on the spherical cap of the unit sphere cut by the plane z = -Vh.z (uniform in z and
   phi), offset by Vh. No orthonormal basis, so fewer operations and no pole to special-case. */
BRDF_FN vec3w SampleGGXVNDFCaps(vec3w Ve, realw ax, realw ay, realw u1, realw u2) {
  vec3w s = {ax * Ve.x, ay * Ve.y, Ve.z};
  vec3w Vh = vec3w_normalize(s);
  realw c, sn = sincos_2pi(u1, &c);
  realw z = (1.0f - u2) * (1.0f + Vh.z) - Vh.z;
  realw st = sqrt(clamp(1.0f - z * z, (realw)(0.0f), (realw)(1.0f)));
  vec3w Nh = {st * c + Vh.x, st * sn + Vh.y, z + Vh.z};
  vec3w Ne = {ax * Nh.x, ay * Nh.y, max(Nh.z, (realw)(0.0f))};
  return vec3w_normalize(Ne);
}

/* Eto & Tokuyoshi 2023, "Bounded VNDF Sampling for Smith-GGX Reflections", listing 1: the
   spherical cap of SampleGGXVNDFCaps cut lower, at z = -k Vh.z with
   k = (1 - a^2) s^2 / (s^2 + a^2 Ve.z^2), a = min(ax, ay), s = 1 + |Ve.xy|; BoundedVNDFKParts gives
   the numerator and (in *den) the denominator, for a caller that folds the division into its own. The part cut away
   holds only normals whose reflection of Ve lies below the horizon, so the sampler keeps the same
   density shape above it and loses fewer directions: none at normal incidence (isotropic).
   Ve.z > 0. */
BRDF_FN realw BoundedVNDFKParts(vec3w Ve, realw ax, realw ay, realw* den) {
  realw a = clamp(min(ax, ay), (realw)(0.0f), (realw)(1.0f));
  realw s = 1.0f + sqrt(Ve.x * Ve.x + Ve.y * Ve.y);
  realw a2 = a * a, s2 = s * s;
  *den = s2 + a2 * Ve.z * Ve.z;
  return (1.0f - a2) * s2;
}
BRDF_FN realw BoundedVNDFK(vec3w Ve, realw ax, realw ay) {
  realw den, num = BoundedVNDFKParts(Ve, ax, ay, &den);
  return num / den;
}
/* The same k of Ve / |Ve| for any Ve with Ve.z > 0, as a numerator and (in *den) a denominator: with
   r = |Ve| and q = |Ve.xy|, s = (r + q) / r and k = (1 - a^2) (r + q)^2 / ((r + q)^2 + a^2 Ve.z^2),
   so a sampler can start from the caller's view before (and beside) its normalization. */
BRDF_FN realw BoundedVNDFKPartsOfUnnormalized(vec3w Ve, realw ax, realw ay, realw* den) {
  realw a = clamp(min(ax, ay), (realw)(0.0f), (realw)(1.0f)), a2 = a * a;
  /* |Ve| and |Ve.xy| as x / sqrt(x), off the divider that V's exact normalization holds. */
  realw q2 = Ve.x * Ve.x + Ve.y * Ve.y, r2 = q2 + Ve.z * Ve.z;
  realw rq = r2 * brdf_rsqrt(r2) + q2 * brdf_rsqrt(max(q2, (realw)(1.0e-30f))), rq2 = rq * rq;
  *den = rq2 + a2 * (Ve.z * Ve.z);
  return (1.0f - a2) * rq2;
}
BRDF_FN vec3w SampleGGXVNDFBounded(vec3w Ve, realw ax, realw ay, realw u1, realw u2) {
  vec3w s = {ax * Ve.x, ay * Ve.y, Ve.z};
  vec3w Vh = vec3w_normalize(s);
  realw b = BoundedVNDFK(Ve, ax, ay) * Vh.z;
  realw c, sn = sincos_2pi(u1, &c);
  realw z = (1.0f - u2) * (1.0f + b) - b;
  realw st = sqrt(clamp(1.0f - z * z, (realw)(0.0f), (realw)(1.0f)));
  vec3w Nh = {st * c + Vh.x, st * sn + Vh.y, z + Vh.z};
  vec3w Ne = {ax * Nh.x, ay * Nh.y, max(Nh.z, (realw)(0.0f))};
  return vec3w_normalize(Ne);
}

/* pdf of L = reflect(V, H), H from SampleGGXVNDFBounded: the VNDF's G1(V) D(H) / (4 V.z) times
   the ratio of the two caps' areas, (1 + Vh.z) / (1 + b), which simplifies to
   D(H) / (2 (t + k V.z)) with t = |(ax Vx, ay Vy, Vz)| (Eto & Tokuyoshi 2023, eq. 8). 0 unless
   L.z > 0. L, V in the lobe's frame, V.z > 0. D(H) / pdf = 2 (t + k V.z) =
   2 *d_num / *d_den, for a weight whose f holds the same D. */
BRDF_FN realw PdfGGXVNDFBoundedReflectD(vec3w L, vec3w V, realw ax, realw ay, realw* d_num, realw* d_den) {
  vec3w h = {L.x + V.x, L.y + V.y, L.z + V.z};
  realw h2 = max(dot3w(h, h), (realw)(1.0e-30f));
  /* One division where D_GGX_Anisotropic and k take four: with A = ax ay and
     d' = A^2 ((hx / ax)^2 + (hy / ay)^2 + hz^2), D = h2^2 A^3 / (pi d'^2); k = nk / dk. A >= 1e-6
     (BRDFCL_MIN_ALPHA), so A^3 and d'^2 stay normal floats. */
  realw A = ax * ay, ax2 = ax * ax, ay2 = ay * ay;
  realw d = h.x * h.x * ay2 + h.y * h.y * ax2 + h.z * h.z * (A * A);
  realw t = sqrt(ax2 * V.x * V.x + ay2 * V.y * V.y + V.z * V.z);
  realw dk, nk = BoundedVNDFKParts(V, ax, ay, &dk);
  *d_num = t * dk + nk * V.z;
  realw pdf = (h2 * h2 * (A * A * A) * dk) / ((2.0f * M_PI_F) * (d * d) * *d_num);
  *d_den = dk;
  return keep_or_zero(pdf, (L.z > 0.0f) & (h.z > 0.0f));
}
BRDF_FN realw PdfGGXVNDFBoundedReflect(vec3w L, vec3w V, realw ax, realw ay) {
  realw d_num, d_den;
  return PdfGGXVNDFBoundedReflectD(L, V, ax, ay, &d_num, &d_den);
}

/* A microfacet normal at polar cosine ct (sine st) and azimuth 2 pi u. */
BRDF_FN vec3w normal_at(realw ct, realw st, realw u) {
  realw c, sn = sincos_2pi(u, &c);
  vec3w H = {st * c, st * sn, ct};
  return H;
}

/* The Charlie sheen: H with density D(H) cos(theta_h) over the hemisphere, exactly. With
   s = sin^2(theta_h) and k = 1 / (2 alpha), D cos dw_h = (1 + k) s^k ds dphi / (2 pi), whose CDF in s
   is s^(k + 1): s = u1^(1 / (k + 1)). cos^2 = 1 - s is formed as -expm1(log(u1) / (k + 1)),
   which keeps its digits when s is within an ulp of 1 (small alpha). */
BRDF_FN vec3w SampleCharlieNormal(realw alpha, realw u1, realw u2) {
  realw e = 2.0f * alpha / (1.0f + 2.0f * alpha);
  realw lu = log(max(u1, (realw)(1.0e-38f)));
  realw c2 = clamp(-expm1(lu * e), (realw)(0.0f), (realw)(1.0f));
  realw s2 = clamp(exp(lu * e), (realw)(0.0f), (realw)(1.0f));
  return normal_at(sqrt(c2), sqrt(s2), u2);
}

/* The Ashikhmin velvet D cos(theta_h) = [cos + 4 exp(-cot^2 / m2) cos / sin^4] / (pi (1 + 4 m2)) is a
   mixture: its constant part is the cosine density with weight 1 / (1 + 4 m2), and its inverted
   Gaussian has t = cot^2(theta_h) exponentially distributed with mean m2, weight 4 m2 / (1 + 4 m2).
   u1 picks the part and is rescaled within it. */
BRDF_FN vec3w SampleAshikhminNormal(realw alpha, realw u1, realw u2) {
  realw m2 = alpha * alpha;
  realw pc = 1.0f / (1.0f + 4.0f * m2);
  intw cosine = u1 < pc;
  realw v = select(clamp((u1 - pc) / (1.0f - pc), (realw)(0.0f), (realw)(1.0f)), u1 / pc, cosine);
  /* Cosine part: cos^2 = 1 - v (Malley). Gaussian part: t = -m2 log(1 - v), cos^2 = t / (1 + t). */
  realw t = -m2 * log1p(-min(v, (realw)(0.99999994f)));
  realw c2 = select(t / (1.0f + t), 1.0f - v, cosine);
  realw s2 = select(1.0f / (1.0f + t), v, cosine);
  return normal_at(sqrt(max(c2, (realw)(0.0f))), sqrt(max(s2, (realw)(0.0f))), u2);
}

/* pdf of L = reflect(V, H) for H drawn with density D(H) cos(theta_h): D cos(theta_h) / (4 V.H),
   the reflection's Jacobian 1 / (4 V.H) (Walter et al. 2007, eq. 14). D is homogeneous of degree 0
   in h = L + V, so the unnormalized h serves: cos = h.z / |h|, V.H = V.h / |h|. 0 unless L.z > 0. */
BRDF_FN realw PdfNormalReflect(realw D, vec3w L, vec3w V) {
  vec3w h = {L.x + V.x, L.y + V.y, L.z + V.z};
  realw vh = dot3w(V, h);
  realw pdf = D * h.z / (4.0f * max(vh, (realw)(1.0e-30f)));
  return keep_or_zero(pdf, (L.z > 0.0f) & (h.z > 0.0f) & (vh > 0.0f));
}

#endif
