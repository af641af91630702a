/* LUT bakes for engines, on the grid they sample: x = N.V = i/(size-1) (floored at BRDFCL_MIN_COS),
   y = perceptual roughness j/(size-1). The sheen tables (sheen-e, charlie-dfg) are sheen_albedo.cl's
   bake on that uniform grid; bake_ggx_dfg integrates the split-sum GGX terms over the half vector. */
#define BRDFCL_SHEEN_ALBEDO_UNIFORM 1
#include "sheen_albedo.cl"

#define LUT_MAX_BREAKS 24

/* Panel breaks in theta_h for one texel, ascending from 0 to the last theta_h at which any
   azimuth still has N.L >= 0. Graded by atan(alpha * c_k) because the GGX lobe's width in
   tan(theta_h) is alpha; theta_full (below it every azimuth has N.L >= 0) is a break because the
   azimuthal range, and so the theta_h integrand, has a kink there. At most 1 + grade_count + 1 + 4 + 1. */
static int theta_h_breaks(float alpha, float theta_full, float theta_end, __global const float* grade, int grade_count,
                          float* b) {
  int n = 0;
  b[n++] = 0.0f;
  int full_done = theta_full <= 0.0f || theta_full >= theta_end;
  for (int k = 0; k < grade_count && n < LUT_MAX_BREAKS - 7; ++k) {
    float t = atan(alpha * grade[k]);
    if (!full_done && theta_full <= t) {
      if (theta_full > b[n - 1]) b[n++] = theta_full;
      full_done = 1;
    }
    if (t >= theta_end) break;
    if (t > b[n - 1]) b[n++] = t;
  }
  if (!full_done && theta_full > b[n - 1]) b[n++] = theta_full;
  /* phi_max ~ sqrt(theta_end - theta_h): a square-root endpoint, tamed by geometrically
     shrinking last panels. */
  float span = theta_end - max(theta_full, 0.0f);
  for (float s = 0.1f; s > 5e-5f; s *= 0.1f)
    if (theta_end - s * span > b[n - 1]) b[n++] = theta_end - s * span;
  if (theta_end > b[n - 1]) b[n++] = theta_end;
  return n;
}

/* Split-sum GGX: A = integral (1 - w) D V (N.L) dw_L, B = integral w D V (N.L) dw_L, w = (1 - V.H)^5,
   over the half vector: dw_L = 4 (V.H) dw_H, dw_H = sin(theta_h) dtheta_h dphi_h. For each theta_h
   the azimuths with N.L = 2 (V.H)(N.H) - N.V >= 0 form [-phi_max, phi_max] (phi = 0 towards V), so
   the rule covers exactly the visible part and the integrand has no kink inside it. theta_h panels
   map the host's unit Gauss-Legendre rule; phi nodes are the host's rule on t in [0, 1] (phi =
   phi_max t), graded towards t = 1 where N.L -> 0 sharpens V at grazing N.V. Output: A, B interleaved. */
__kernel void bake_ggx_dfg(int size, __global const float* restrict grade, int grade_count,
                           __global const float* restrict theta_nodes, __global const float* restrict theta_weights,
                           int theta_count, __global const float* restrict phi_t, __global const float* restrict phi_w,
                           int phi_count, __global float* restrict out) {
  int ix = get_global_id(0), iy = get_global_id(1);
  float nv = max((float)ix / (float)(size - 1), BRDFCL_MIN_COS);
  float r = (float)iy / (float)(size - 1);
  float alpha = max(r * r, BRDFCL_MIN_ALPHA);
  float sv = sqrt(max(1.0f - nv * nv, 0.0f));
  float theta_v = acos(nv);
  /* phi = pi (H tilted away from V) is the last azimuth to keep N.L >= 0: cos(theta_v + 2 theta_h) >= 0;
     phi = 0 the first: cos(theta_v - 2 theta_h) >= 0. */
  float theta_full = 0.5f * (M_PI_2_F - theta_v), theta_end = 0.5f * (M_PI_2_F + theta_v);

  float b[LUT_MAX_BREAKS];
  int nb = theta_h_breaks(alpha, theta_full, theta_end, grade, grade_count, b);

  float sum_a = 0.0f, sum_b = 0.0f;
  for (int p = 0; p + 1 < nb; ++p) {
    float lo = b[p], width = b[p + 1] - b[p];
    for (int it = 0; it < theta_count; ++it) {
      float th = lo + width * theta_nodes[it];
      float st = sin(th), ct = cos(th);
      float phi_max = M_PI_F;
      if (th > theta_full && sv > 0.0f) {
        float c = (nv / (2.0f * ct) - nv * ct) / (sv * st);
        phi_max = acos(clamp(c, -1.0f, 1.0f));
      }
      /* D is the same on every lane; a splat keeps D_GGX written once over realw. */
      realw d = D_GGX((realw)(st * st), (realw)(ct * ct), (realw)(alpha));
      realw acc_a = (realw)(0.0f), acc_b = (realw)(0.0f);
      for (int ip = 0; ip < phi_count; ip += BRDFCL_W) {
        realw t = VLOADW(0, phi_t + ip), pw = VLOADW(0, phi_w + ip);
        realw vh = sv * st * cos(phi_max * t) + nv * ct;
        realw nl = max(2.0f * vh * ct - nv, 0.0f);
        realw f = pw * d * V_SmithGGXCorrelated(nl, (realw)(nv), (realw)(alpha)) * nl * vh;
        realw w = pow5w(1.0f - vh);
        acc_a += (1.0f - w) * f;
        acc_b += w * f;
      }
#if BRDFCL_W == 1
      float ra = acc_a, rb = acc_b;
#else
      float la[BRDFCL_W], lb[BRDFCL_W];
      VSTOREW(acc_a, 0, la);
      VSTOREW(acc_b, 0, lb);
      float ra = 0.0f, rb = 0.0f;
      for (int k = 0; k < BRDFCL_W; ++k) {
        ra += la[k];
        rb += lb[k];
      }
#endif
      /* 2 phi_max: the rule covers [0, phi_max], the lobe is symmetric in phi; 4 (V.H) sin: Jacobian. */
      float scale = width * theta_weights[it] * 2.0f * phi_max * 4.0f * st;
      sum_a += scale * ra;
      sum_b += scale * rb;
    }
  }
  out[2 * (iy * size + ix)] = sum_a;
  out[2 * (iy * size + ix) + 1] = sum_b;
}
