/* The layered glTF material as a batch sees it: its lanes, the options and feature set (compile-time
   defines, so unused layers cost nothing), and brdf_layers, the batch's profile: the specs'
   (brdf/profiles/spec.h, layering brdf/lobes.h) or an engine's (brdf/profiles/, docs/profiles.md). */
#ifndef BRDFCL_MATERIAL_H
#define BRDFCL_MATERIAL_H

#include "common/material_layout.h"
#include "common/lanes.h"
#include "brdf/terms.h"
#include "brdf/sheen_albedo.h"

#ifndef BRDFCL_SHEEN_VIS
#define BRDFCL_SHEEN_VIS BRDFCL_SHEEN_VIS_CHARLIE
#endif
#ifndef BRDFCL_SHEEN_DIST
#define BRDFCL_SHEEN_DIST BRDFCL_SHEEN_DIST_CHARLIE
#endif
#ifndef BRDFCL_SCALING
#define BRDFCL_SCALING BRDFCL_SCALING_MIN
#endif
#ifndef BRDFCL_LOBE
#define BRDFCL_LOBE BRDFCL_LOBE_ALL
#endif
/* Whose BRDF: the specs (below) or an engine's (brdf/profiles/, docs/profiles.md). */
#ifndef BRDFCL_PROFILE
#define BRDFCL_PROFILE BRDFCL_PROFILE_SPEC
#endif
/* Feature set of the batch: a layer no material uses is compiled out. */
#ifndef BRDFCL_HAS_SHEEN
#define BRDFCL_HAS_SHEEN 1
#endif
#ifndef BRDFCL_HAS_DRAFT
#define BRDFCL_HAS_DRAFT 1
#endif
#ifndef BRDFCL_HAS_CLEARCOAT
#define BRDFCL_HAS_CLEARCOAT 1
#endif
#ifndef BRDFCL_HAS_ANISOTROPY
#define BRDFCL_HAS_ANISOTROPY 1
#endif

/* Below this cosine, denominators of V terms are evaluated at this cosine: keeps f finite at
   N.L or N.V -> 0+ (documented clamp; f = 0 at N.L <= 0 or N.V <= 0 anyway). */
#define BRDFCL_MIN_COS 1.0e-4f

/* The float fields a lane reads, as (lane name, field of brdfcl_material). */
#define BRDFCL_MATERIAL_LANES(X)                                                      \
  X(base_r, base_color[0]) X(base_g, base_color[1]) X(base_b, base_color[2])          \
  X(metallic, metallic) X(alpha, alpha) X(alpha_t, alpha_t)                           \
  X(aniso_cos, aniso_cos) X(aniso_sin, aniso_sin)                                     \
  X(sheen_r, sheen_color[0]) X(sheen_g, sheen_color[1]) X(sheen_b, sheen_color[2])    \
  X(sheen_max, sheen_max) X(sheen_alpha, sheen_alpha)                                 \
  X(sheen_roughness, sheen_roughness) X(sheen_weight, sheen_weight)                   \
  X(clearcoat, clearcoat) X(clearcoat_alpha, clearcoat_alpha)                       \
  BRDFCL_PROFILE_LANES(X)

/* The fields only engine profiles read: spec's gathers stay as they were. */
#if BRDFCL_PROFILE == BRDFCL_PROFILE_SPEC
#define BRDFCL_PROFILE_LANES(X)
#else
#define BRDFCL_PROFILE_LANES(X) \
  X(roughness, roughness) X(ior_f0, ior_f0) X(aniso_strength, aniso_strength) X(clearcoat_roughness, clearcoat_roughness)
#endif

#define BRDFCL_DECLARE_LANE(name, field) realw name;
typedef struct {
  BRDFCL_MATERIAL_LANES(BRDFCL_DECLARE_LANE)
  realw draft;     /* 1 for the experimental draft's sheen, else 0 */
  realw aniso_ext; /* 1 where BRDFCL_MAT_ANISOTROPY is set (khronos, filament), else 0 */
} material_lanes;

/* All lanes share one material (grid evaluation, shading): splat. OpenCL C 1.2 has no generic
   address space, hence a global and a private entry point over one body. */
#define BRDFCL_SPLAT_LANE(name, field) out.name = (realw)(m->field);
#define BRDFCL_SPLAT_BODY                                                    \
  material_lanes out;                                                        \
  BRDFCL_MATERIAL_LANES(BRDFCL_SPLAT_LANE)                                   \
  out.draft = (realw)((m->flags & BRDFCL_MAT_DRAFT_SHEEN) ? 1.0f : 0.0f);     \
  out.aniso_ext = (realw)((m->flags & BRDFCL_MAT_ANISOTROPY) ? 1.0f : 0.0f);  \
  return out;
BRDF_FN material_lanes material_splat(__global const brdfcl_material* m) { BRDFCL_SPLAT_BODY }
#ifdef __OPENCL_VERSION__
BRDF_FN material_lanes material_splat_private(const brdfcl_material* m) { BRDFCL_SPLAT_BODY }
#endif

/* Each lane has its own material index: one vector gather per field, records being
   sizeof(brdfcl_material) / 4 floats apart. */
#if BRDFCL_W == 1
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  return material_splat(materials + index);
}
#else
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  intw at = AS_INTW(index) * (int)(sizeof(brdfcl_material) / 4);
  material_lanes out;
#define BRDFCL_GATHER_LANE(name, field) out.name = GATHERW((__global const float*)&materials->field, at);
  BRDFCL_MATERIAL_LANES(BRDFCL_GATHER_LANE)
  intw flags = AS_INTW(GATHERW((__global const float*)&materials->flags, at));
  out.draft = select((realw)(0.0f), (realw)(1.0f), (flags & (int)BRDFCL_MAT_DRAFT_SHEEN) != 0);
  out.aniso_ext = select((realw)(0.0f), (realw)(1.0f), (flags & (int)BRDFCL_MAT_ANISOTROPY) != 0);
  return out;
}
#endif

#include "brdf/lobes.h"

/* Included here, outside the per-engine branches: the kernel loader inlines each header once, at
   its first #include, so that first one must not sit in a branch another profile skips. The
   spec's layers are in every build: ibl_exact.cl layers them itself. */
#include "brdf/profiles/spec.h"
#if BRDFCL_PROFILE != BRDFCL_PROFILE_SPEC
#include "brdf/profiles/engine_terms.h"
#endif
#if BRDFCL_PROFILE == BRDFCL_PROFILE_KHRONOS
#include "brdf/profiles/khronos.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_THREEJS
#include "brdf/profiles/threejs.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_FILAMENT
#include "brdf/profiles/filament.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_BABYLON
#include "brdf/profiles/babylon.h"
#elif BRDFCL_PROFILE == BRDFCL_PROFILE_MATERIALX
#include "brdf/profiles/materialx.h"
#endif

/* Every layer, f in 1/sr without the cosine; not yet zeroed below the horizon. L, V in the
   shading frame, Lc, Vc in the clearcoat normal's (the same in batch evaluation). `sheen_e`: the
   sheen E table; engine profiles find their DFG table right after it. */
BRDF_FN rgbw brdf_layers(const material_lanes m, vec3w L, vec3w V, vec3w Lc, vec3w Vc,
                         __global const float* sheen_e, int sheen_e_size) {
  return brdf_profile(m, L, V, Lc, Vc, sheen_e, sheen_e_size);
}

/* The layered material, f(L, V) in 1/sr without the cosine, 0 when N.L <= 0 or N.V <= 0. */
BRDF_FN rgbw brdf_material(const material_lanes m, vec3w L, vec3w V, __global const float* sheen_e,
                           int sheen_e_size) {
  intw valid = (L.z > 0.0f) & (V.z > 0.0f);
  rgbw result = brdf_layers(m, L, V, L, V, sheen_e, sheen_e_size);
  result.r = keep_or_zero(result.r, valid);
  result.g = keep_or_zero(result.g, valid);
  result.b = keep_or_zero(result.b, valid);
  return result;
}

#endif
