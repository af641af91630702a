/* Sampling of equirectangular environment levels (RGB planes) with bilinear filtering, wrapping
   in u and clamping in v, and linear blending between levels of a prefiltered chain. */
#ifndef BRDFCL_ENVIRONMENT_H
#define BRDFCL_ENVIRONMENT_H

#include "common/shading_layout.h"

typedef struct { float3 rgb; } env_sample;

static inline float2 env_uv(float3 d, float rotation) {
  float u = 0.5f + (atan2(d.x, -d.z) + rotation) * (0.5f * M_1_PI_F);
  float v = acos(clamp(d.y, -1.0f, 1.0f)) * M_1_PI_F;
  return (float2)(u - floor(u), v);
}

/* A level: width * height texels, 3 planes (r, g, b) of width * height floats from `base`. */
static inline float3 env_fetch(__global const float* base, int w, int h, int x, int y) {
  x = ((x % w) + w) % w;
  y = clamp(y, 0, h - 1);
  int i = y * w + x, n = w * h;
  return (float3)(base[i], base[n + i], base[2 * n + i]);
}

static inline float3 env_bilinear(__global const float* base, int w, int h, float2 uv) {
  float x = uv.x * (float)w - 0.5f, y = uv.y * (float)h - 0.5f;
  int x0 = (int)floor(x), y0 = (int)floor(y);
  float fx = x - (float)x0, fy = y - (float)y0;
  float3 a = mix(env_fetch(base, w, h, x0, y0), env_fetch(base, w, h, x0 + 1, y0), fx);
  float3 b = mix(env_fetch(base, w, h, x0, y0 + 1), env_fetch(base, w, h, x0 + 1, y0 + 1), fx);
  return mix(a, b, fy);
}

/* A chain of `levels` levels stored one after another: level 0 of max(w0, 8) x max(h0, 4), level
   k >= 1 of max(min(w0, cap_w) >> k, 8) x max(min(h0, cap_h) >> k, 4). The cap lets a prefiltered
   chain keep level 0 (the mirror) at the map's resolution while its blurred levels stay as small
   as their lobes allow; a plain mip chain passes cap = w0, h0. `lod` in [0, levels - 1] blends
   the two nearest levels. host/src/render/prefilter.cpp lays the chains out by the same rule. */
static inline int env_level_w(int w0, int cap_w, int k) { return k == 0 ? max(w0, 8) : max(min(w0, cap_w) >> k, 8); }
static inline int env_level_h(int h0, int cap_h, int k) { return k == 0 ? max(h0, 4) : max(min(h0, cap_h) >> k, 4); }

static inline float3 env_chain(__global const float* chain, int w0, int h0, int cap_w, int cap_h, int levels, float3 d,
                               float rotation, float lod) {
  float2 uv = env_uv(d, rotation);
  lod = clamp(lod, 0.0f, (float)(levels - 1));
  int k0 = min((int)lod, levels - 1), k1 = min(k0 + 1, levels - 1);
  __global const float* p = chain;
  for (int k = 0; k < k0; ++k) p += 3 * env_level_w(w0, cap_w, k) * env_level_h(h0, cap_h, k);
  float3 a = env_bilinear(p, env_level_w(w0, cap_w, k0), env_level_h(h0, cap_h, k0), uv);
  if (k1 == k0) return a;
  __global const float* q = p + 3 * env_level_w(w0, cap_w, k0) * env_level_h(h0, cap_h, k0);
  float3 b = env_bilinear(q, env_level_w(w0, cap_w, k1), env_level_h(h0, cap_h, k1), uv);
  return mix(a, b, lod - (float)k0);
}

#endif
