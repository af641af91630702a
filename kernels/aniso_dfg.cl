/* The split-sum DFG terms of the anisotropic GGX lobe (KHR_materials_anisotropy), per texel of a
   4-D grid: x = N.V, y = perceptual roughness r (alpha_b = r^2, alpha_t = mix(alpha_b, 1, s^2)),
   z = anisotropy strength s, w = the view's azimuth from the anisotropy direction in [0, pi/2].
   The isotropic table cannot stand in for it: the albedo depends on both alphas and the azimuth. */
#include "common/material_layout.h"

/* Height-correlated Smith Lambda of the anisotropic GGX (Heitz 2014, "Understanding the
   Masking-Shadowing Function", eq. 86): the spec's V_GGX_anisotropic is G2 / (4 N.L N.V) with it. */
static inline float lambda_ggx(float3 w, float at, float ab) {
  float a2 = (at * at * w.x * w.x + ab * ab * w.y * w.y) / max(w.z * w.z, 1e-12f);
  return 0.5f * (-1.0f + sqrt(1.0f + a2));
}

/* A = integral (1 - Fc) D G2 / (4 N.V) dw_L, B = integral Fc D G2 / (4 N.V) dw_L, Fc = (1 - V.H)^5.
   Over the half vector in slope space scaled by the alphas: D(h) (N.H) dw_h is the standard
   density 1 / (pi (1 + rho^2)^2) of (u, v) = (slope_x / alpha_t, slope_y / alpha_b), and with
   t = rho^2 / (1 + rho^2) it is uniform in (t, phi): every alpha gets nodes where its lobe is. The
   integrand is then G2 (V.H) / ((N.V)(N.H)) times the Fresnel weight, zero where V.H <= 0 or
   N.L <= 0. t nodes: the host's graded Gauss-Legendre rule; phi: midpoint rule (periodic). */
__kernel void bake_aniso_dfg(int nv_n, int r_n, int s_n, int psi_n, __global const float* restrict t_nodes,
                             __global const float* restrict t_weights, int t_count, int phi_count,
                             __global float* restrict out) {
  const int i = get_global_id(0), j = get_global_id(1), kl = get_global_id(2);
  if (i >= nv_n || j >= r_n || kl >= s_n * psi_n) return;
  const int k = kl % s_n, l = kl / s_n;
  const float nv = max((float)i / (float)(nv_n - 1), 1e-4f);
  const float r = (float)j / (float)(r_n - 1), s = (float)k / (float)(s_n - 1);
  const float psi = 1.5707963267948966f * (float)l / (float)(psi_n - 1);
  const float ab = max(r * r, BRDFCL_MIN_ALPHA);
  const float at = max(r * r * (1.0f - s * s) + s * s, BRDFCL_MIN_ALPHA);
  const float sv = sqrt(max(1.0f - nv * nv, 0.0f));
  const float3 V = (float3)(sv * cos(psi), sv * sin(psi), nv);
  const float lambda_v = lambda_ggx(V, at, ab);
  float A = 0.0f, B = 0.0f;
  for (int a = 0; a < t_count; ++a) {
    const float t = t_nodes[a], rho = sqrt(t / (1.0f - t));
    float rowA = 0.0f, rowB = 0.0f;
    for (int b = 0; b < phi_count; ++b) {
      const float phi = 6.283185307179586f * ((float)b + 0.5f) / (float)phi_count;
      const float3 H = normalize((float3)(at * rho * cos(phi), ab * rho * sin(phi), 1.0f));
      const float VdotH = dot(V, H);
      if (VdotH <= 0.0f) continue;
      const float3 L = 2.0f * VdotH * H - V;
      if (L.z <= 0.0f) continue;
      const float G2 = 1.0f / (1.0f + lambda_v + lambda_ggx(L, at, ab));
      const float w = G2 * VdotH / (nv * H.z);
      const float c = 1.0f - VdotH, c2 = c * c, Fc = c2 * c2 * c;
      rowA += w * (1.0f - Fc);
      rowB += w * Fc;
    }
    A += t_weights[a] * rowA;
    B += t_weights[a] * rowB;
  }
  const int o = ((l * s_n + k) * r_n + j) * nv_n + i;
  out[2 * o] = A / (float)phi_count;
  out[2 * o + 1] = B / (float)phi_count;
}
