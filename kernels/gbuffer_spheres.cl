/* Ray-casts the built-in "spheres" scene analytically into G-buffer planes (common/
   shading_layout.h order): nearest sphere hit per pixel, its normal, a tangent field along the
   sphere's parallels (T = Y x N, so anisotropy brushes around the vertical axis), and its glTF
   parameters. Pixels that miss every sphere get mask 0. */
#include "common/shading_layout.h"

/* One launch covers the band of rows [y0, y0 + band_h) of a width x height image; gb holds the
   band's planes (width * band_h floats each), so no buffer exceeds the device's largest allocation. */
__kernel void gbuffer_spheres(__global const brdfcl_sphere* restrict spheres, int sphere_count, int width,
                              int height, int y0, int band_h, brdfcl_camera cam, __global float* restrict gb) {
  int x = get_global_id(0), y = y0 + (int)get_global_id(1);
  if (x >= width || y >= height || y >= y0 + band_h) return;
  const int np = width * band_h, i = (y - y0) * width + x;
  for (int k = 0; k < GB_PLANES; ++k) gb[k * np + i] = 0.0f;
  float sx = (2.0f * ((float)x + 0.5f) / (float)width - 1.0f) * cam.tan_half_fov * cam.aspect;
  float sy = (1.0f - 2.0f * ((float)y + 0.5f) / (float)height) * cam.tan_half_fov;
  float3 o = (float3)(cam.position[0], cam.position[1], cam.position[2]);
  float3 d = normalize((float3)(cam.forward[0], cam.forward[1], cam.forward[2]) +
                       sx * (float3)(cam.right[0], cam.right[1], cam.right[2]) +
                       sy * (float3)(cam.up[0], cam.up[1], cam.up[2]));
  float best = INFINITY;
  int hit = -1;
  for (int k = 0; k < sphere_count; ++k) {
    float3 c = (float3)(spheres[k].center[0], spheres[k].center[1], spheres[k].center[2]);
    float3 oc = o - c;
    float b = dot(oc, d), cc = dot(oc, oc) - spheres[k].radius * spheres[k].radius;
    float disc = b * b - cc;
    if (disc < 0.0f) continue;
    float t = -b - sqrt(disc);
    if (t > 1e-4f && t < best) best = t, hit = k;
  }
  if (hit < 0) return;
  __global const brdfcl_sphere* s = spheres + hit;
  float3 p = o + best * d;
  float3 n = normalize(p - (float3)(s->center[0], s->center[1], s->center[2]));
  float3 t = cross((float3)(0.0f, 1.0f, 0.0f), n);
  t = dot(t, t) > 1e-8f ? normalize(t) : (float3)(1.0f, 0.0f, 0.0f);
  float v[GB_PLANES] = {0};
  v[GB_PX] = p.x; v[GB_PY] = p.y; v[GB_PZ] = p.z;
  v[GB_NX] = n.x; v[GB_NY] = n.y; v[GB_NZ] = n.z;
  v[GB_TX] = t.x; v[GB_TY] = t.y; v[GB_TZ] = t.z;
  v[GB_BASE_R] = s->base_color[0]; v[GB_BASE_G] = s->base_color[1]; v[GB_BASE_B] = s->base_color[2];
  v[GB_METALLIC] = s->metallic; v[GB_ROUGHNESS] = s->roughness; v[GB_MASK] = 1.0f;
  v[GB_SHEEN_R] = s->sheen_color[0]; v[GB_SHEEN_G] = s->sheen_color[1]; v[GB_SHEEN_B] = s->sheen_color[2];
  v[GB_SHEEN_ROUGHNESS] = s->sheen_roughness;
  v[GB_CLEARCOAT] = s->clearcoat; v[GB_CLEARCOAT_ROUGHNESS] = s->clearcoat_roughness;
  v[GB_CCN_X] = n.x; v[GB_CCN_Y] = n.y; v[GB_CCN_Z] = n.z;
  v[GB_ANISO_STRENGTH] = s->anisotropy_strength; v[GB_ANISO_ROTATION] = s->anisotropy_rotation;
  for (int k = 0; k < GB_PLANES; ++k) gb[k * np + i] = v[k];
}
