/* One covered G-buffer pixel decoded for shading: its frames (N with T, the clearcoat normal with
   a frame built from it), its view direction and its packed material. Shared by kernels/shade.cl
   and kernels/ibl_exact.cl, so both integrators light exactly the same surface. */
#ifndef BRDFCL_GBUFFER_PIXEL_H
#define BRDFCL_GBUFFER_PIXEL_H

#include "common/shading_layout.h"
#include "common/material_pack.h"

static inline float3 frame_local(float3 d, float3 t, float3 b, float3 n) { return (float3)(dot(d, t), dot(d, b), dot(d, n)); }

/* KHR_materials_clearcoat's layering needs a frame only for its normal: any tangent will do. */
static inline void frame_from_normal(float3 n, float3* t, float3* b) {
  float3 up = fabs(n.y) < 0.999f ? (float3)(0.0f, 1.0f, 0.0f) : (float3)(1.0f, 0.0f, 0.0f);
  *t = normalize(cross(up, n));
  *b = cross(n, *t);
}

typedef struct {
  float3 P, N, T, B, Nc, Tc, Bc, V;
  brdfcl_material_params q;
} gbuffer_pixel;

/* Pixel i of np; Vg is the G-buffer's own V (zero length when absent). */
static inline gbuffer_pixel gbuffer_pixel_decode(__global const float* gb, int np, int i, float3 Vg, float3 eye,
                                                 float3 forward, bool ortho) {
#define GBP(k) gb[(k) * np + i]
  gbuffer_pixel p;
  /* Frame: N; T made orthogonal to N, or built from N when absent (docs/gbuffer.md). */
  p.P = (float3)(GBP(GB_PX), GBP(GB_PY), GBP(GB_PZ));
  p.N = normalize((float3)(GBP(GB_NX), GBP(GB_NY), GBP(GB_NZ)));
  float3 T = (float3)(GBP(GB_TX), GBP(GB_TY), GBP(GB_TZ));
  T = T - dot(T, p.N) * p.N;
  if (dot(T, T) > 1e-12f) {
    p.T = normalize(T);
    p.B = cross(p.N, p.T);
  } else {
    frame_from_normal(p.N, &p.T, &p.B);
  }
  float3 Nc = (float3)(GBP(GB_CCN_X), GBP(GB_CCN_Y), GBP(GB_CCN_Z));
  p.Nc = dot(Nc, Nc) > 1e-12f ? normalize(Nc) : p.N;
  frame_from_normal(p.Nc, &p.Tc, &p.Bc);
  p.V = dot(Vg, Vg) > 0.0f ? normalize(Vg) : ortho ? -forward : normalize(eye - p.P);

  p.q.base_color[0] = GBP(GB_BASE_R); p.q.base_color[1] = GBP(GB_BASE_G); p.q.base_color[2] = GBP(GB_BASE_B);
  p.q.metallic = GBP(GB_METALLIC); p.q.roughness = GBP(GB_ROUGHNESS);
  p.q.sheen_color[0] = GBP(GB_SHEEN_R); p.q.sheen_color[1] = GBP(GB_SHEEN_G); p.q.sheen_color[2] = GBP(GB_SHEEN_B);
  p.q.sheen_roughness = GBP(GB_SHEEN_ROUGHNESS);
  p.q.draft = 0;
  p.q.ior = 1.5f; /* the G-buffer has no IOR channel: docs/profiles.md */
  p.q.clearcoat = GBP(GB_CLEARCOAT); p.q.clearcoat_roughness = GBP(GB_CLEARCOAT_ROUGHNESS);
  p.q.anisotropy_strength = GBP(GB_ANISO_STRENGTH); p.q.anisotropy_rotation = GBP(GB_ANISO_ROTATION);
  p.q.anisotropy = p.q.anisotropy_strength > 0.0f; /* no presence channel: docs/profiles.md "khronos" */
#undef GBP
  return p;
}

#endif
