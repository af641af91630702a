/* Radiance arriving from a KHR_lights_punctual light: directional, point and spot, with the
   extension's inverse-square falloff, smooth range window and spot cone
   (https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_lights_punctual). */
#ifndef BRDFCL_LIGHT_PUNCTUAL_H
#define BRDFCL_LIGHT_PUNCTUAL_H

#include "common/shading_layout.h"

/* The light's radiance at P, and in *L the unit direction from P towards the light. */
static inline float3 punctual_radiance(__global const brdfcl_light* lt, float3 P, float3* L) {
  float3 radiance = (float3)(lt->color[0], lt->color[1], lt->color[2]);
  float3 dir = (float3)(lt->direction[0], lt->direction[1], lt->direction[2]);
  if ((int)lt->type == BRDFCL_LIGHT_DIRECTIONAL) {
    *L = -dir;
    return radiance;
  }
  float3 to = (float3)(lt->position[0], lt->position[1], lt->position[2]) - P;
  float d2 = max(dot(to, to), 1e-12f), d = sqrt(d2);
  *L = to / d;
  float window = 1.0f;
  if (lt->range > 0.0f) {
    float r = d / lt->range;
    window = clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
  }
  radiance *= window / d2;
  if ((int)lt->type == BRDFCL_LIGHT_SPOT) {
    float t = clamp(dot(dir, -*L) * lt->cone_scale + lt->cone_offset, 0.0f, 1.0f);
    radiance *= t * t;
  }
  return radiance;
}

#endif
