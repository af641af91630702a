/* Image-based light preparation on the device: the box-filtered mip chain of the environment,
   and its prefiltered versions for the split-sum shader: GGX radiance per roughness level, Charlie
   radiance per sheen roughness level, and cosine-weighted irradiance. Importance sampling reads
   the mip chain at the level whose texel matches the sample's solid angle (filtered importance
   sampling, Krivanek & Colbert 2008), so few samples give smooth results. */
#define BRDFCL_W 1
#include "common/material_layout.h"
#include "brdf/terms.h"
#include "common/environment.h"

/* Level k+1 of the source chain from level k: 2x2 box. */
__kernel void env_downsample(__global const float* restrict src, int sw, int sh, __global float* restrict dst,
                             int dw, int dh) {
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= dw || y >= dh) return;
  int sn = sw * sh, dn = dw * dh;
  for (int c = 0; c < 3; ++c) {
    float acc = 0.0f;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) acc += src[c * sn + min(2 * y + j, sh - 1) * sw + min(2 * x + i, sw - 1)];
    dst[c * dn + y * dw + x] = 0.25f * acc;
  }
}

static inline float3 texel_direction(int x, int y, int w, int h) {
  float u = ((float)x + 0.5f) / (float)w, v = ((float)y + 0.5f) / (float)h;
  float phi = (u - 0.5f) * 2.0f * M_PI_F, theta = v * M_PI_F;
  /* inverse of env_uv without rotation: u = 1/2 + atan2(d.x, -d.z) / 2pi */
  return (float3)(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

static inline float2 hammersley(uint i, uint n) {
  uint b = i;
  b = (b << 16u) | (b >> 16u);
  b = ((b & 0x55555555u) << 1u) | ((b & 0xAAAAAAAAu) >> 1u);
  b = ((b & 0x33333333u) << 2u) | ((b & 0xCCCCCCCCu) >> 2u);
  b = ((b & 0x0F0F0F0Fu) << 4u) | ((b & 0xF0F0F0F0u) >> 4u);
  b = ((b & 0x00FF00FFu) << 8u) | ((b & 0xFF00FF00u) >> 8u);
  return (float2)(((float)i + 0.5f) / (float)n, (float)b * 2.3283064365386963e-10f);
}

static inline void basis(float3 n, float3* t, float3* b) {
  float3 up = fabs(n.y) < 0.999f ? (float3)(0.0f, 1.0f, 0.0f) : (float3)(1.0f, 0.0f, 0.0f);
  *t = normalize(cross(up, n));
  *b = cross(n, *t);
}

/* Source chain level for a sample of density pdf among `count`: texel solid angle at level 0 is
   4 pi / (w0 h0) (equal-area average). */
static inline float sample_lod(float pdf, uint count, int w0, int h0) {
  float omega_s = 1.0f / ((float)count * max(pdf, 1e-8f));
  float omega_p = 4.0f * M_PI_F / (float)(w0 * h0);
  return max(0.5f * log2(omega_s / omega_p) + 1.0f, 0.0f);
}

/* kind 0: GGX with alpha = roughness^2 (N = V = R); 1: Charlie with alpha = roughness^2 over the
   hemisphere (uniform directions weighted by D N.L); 2: cosine-weighted irradiance. Output: one
   level of width w, height h, normalized so a uniform environment of radiance 1 gives 1. */
__kernel void env_prefilter(__global const float* restrict chain, int w0, int h0, int levels, int kind,
                            float roughness, uint count, __global float* restrict dst, int w, int h) {
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= w || y >= h) return;
  float3 n = texel_direction(x, y, w, h), t, b;
  basis(n, &t, &b);
  float alpha = max(roughness * roughness, BRDFCL_MIN_ALPHA);
  float sa = max(roughness * roughness, BRDFCL_MIN_SHEEN_ALPHA);
  /* Charlie's weights relative to the largest among the samples: D's factor and its peak cancel in
     the normalization, and at small alpha D itself (sin^(1/alpha), sin <= 1/sqrt(2) above the
     horizon) underflows to 0 for every sample, which would leave the level black. */
  float max_log_sin2 = -INFINITY;
  if (kind == 1)
    for (uint i = 0; i < count; ++i) {
      float2 xi = hammersley(i, count);
      float r = sqrt(xi.x), ph = 2.0f * M_PI_F * xi.y, z = sqrt(max(0.0f, 1.0f - xi.x));
      float3 hv = normalize(r * cos(ph) * t + r * sin(ph) * b + z * n + n);
      float hn = dot(hv, n), hxy2 = max(1.0f - hn * hn, 0.0f);
      max_log_sin2 = max(max_log_sin2, -log1p(hn * hn / hxy2));
    }
  float3 acc = (float3)(0.0f);
  float weight = 0.0f;
  for (uint i = 0; i < count; ++i) {
    float2 xi = hammersley(i, count);
    float3 l;
    float pdf, wgt;
    if (kind == 0) {
      /* GGX: cos^2 theta_h = (1 - xi) / (1 + (alpha^2 - 1) xi); L = reflect(-N, H). */
      float a2 = alpha * alpha;
      float c2 = (1.0f - xi.x) / (1.0f + (a2 - 1.0f) * xi.x), ch = sqrt(c2), sh = sqrt(max(0.0f, 1.0f - c2));
      float ph = 2.0f * M_PI_F * xi.y;
      float3 hv = sh * cos(ph) * t + sh * sin(ph) * b + ch * n;
      l = 2.0f * dot(n, hv) * hv - n;
      float nl = dot(n, l);
      if (nl <= 0.0f) continue;
      float d = a2 / (M_PI_F * pow(c2 * (a2 - 1.0f) + 1.0f, 2.0f));
      pdf = d * 0.25f; /* D cos_h / (4 V.H) with N = V */
      wgt = nl;
    } else {
      /* cosine-weighted directions: irradiance is their plain average; Charlie weights by D. */
      float r = sqrt(xi.x), ph = 2.0f * M_PI_F * xi.y;
      float z = sqrt(max(0.0f, 1.0f - xi.x));
      l = r * cos(ph) * t + r * sin(ph) * b + z * n;
      pdf = z * M_1_PI_F;
      if (kind == 1) {
        float3 hv = normalize(l + n);
        float hn = dot(hv, n), hxy2 = max(1.0f - hn * hn, 0.0f);
        /* N.L / pdf = pi for every sample: D alone weighs, here D / D(largest sample) */
        wgt = exp(0.5f / sa * (-log1p(hn * hn / hxy2) - max_log_sin2));
      } else {
        wgt = 1.0f;
      }
    }
    float lod = sample_lod(pdf, count, w0, h0);
    acc += wgt * env_chain(chain, w0, h0, w0, h0, levels, l, 0.0f, lod);
    weight += wgt;
  }
  float3 out = weight > 0.0f ? acc / weight : (float3)(0.0f);
  int np = w * h;
  dst[y * w + x] = out.x;
  dst[np + y * w + x] = out.y;
  dst[2 * np + y * w + x] = out.z;
}
