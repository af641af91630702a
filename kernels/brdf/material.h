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
/* The spec's albedo scaling reads each material's own row of E, blended once by the host for its
   sheen_roughness and placed after the table (brdfcl_material.sheen_e_row; Evaluator::prepare),
   instead of blending two rows of the table at every lookup. */
#ifndef BRDFCL_E_ROW
#define BRDFCL_E_ROW 0
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
#if BRDFCL_E_ROW
  intw e_row;      /* sheen_e_row */
#endif
} material_lanes;

#if BRDFCL_E_ROW
#define BRDFCL_SPLAT_E_ROW out.e_row = (intw)((int)m->sheen_e_row);
#else
#define BRDFCL_SPLAT_E_ROW
#endif

/* All lanes share one material (grid evaluation, shading): splat. OpenCL C 1.2 has no generic
   address space, hence a global and a private entry point over one body. */
#define BRDFCL_SPLAT_LANE(name, field) out.name = (realw)(m->field);
#define BRDFCL_SPLAT_BODY                                                    \
  material_lanes out;                                                        \
  BRDFCL_MATERIAL_LANES(BRDFCL_SPLAT_LANE)                                   \
  out.draft = (realw)((m->flags & BRDFCL_MAT_DRAFT_SHEEN) ? 1.0f : 0.0f);     \
  out.aniso_ext = (realw)((m->flags & BRDFCL_MAT_ANISOTROPY) ? 1.0f : 0.0f);  \
  BRDFCL_SPLAT_E_ROW                                                         \
  return out;
BRDF_FN material_lanes material_splat(__global const brdfcl_material* m) { BRDFCL_SPLAT_BODY }
#ifdef __OPENCL_VERSION__
BRDF_FN material_lanes material_splat_private(const brdfcl_material* m) { BRDFCL_SPLAT_BODY }
#endif

/* The lanes of the record's flags (BRDFCL_MAT_*) that the lobes read as factors. */
BRDF_FN void material_flag_lanes(material_lanes* out, intw flags) {
  out->draft = select((realw)(0.0f), (realw)(1.0f), (flags & (int)BRDFCL_MAT_DRAFT_SHEEN) != 0);
  out->aniso_ext = select((realw)(0.0f), (realw)(1.0f), (flags & (int)BRDFCL_MAT_ANISOTROPY) != 0);
}

/* Each lane has its own material index. Sixteen lanes under clang (PoCL) read each lane's record in
   32-byte pieces and transpose them into field lanes: a 16 x 8 block costs 16 loads and 32
   shuffles, where a gather costs 16 loads a field and its latency heads every chain. Other widths
   and compilers gather one field at a time, records being sizeof(brdfcl_material) / 4 floats apart.
   Either way only the data's path changes: every lane gets its record's bits.
   BRDFCL_MATERIAL_TRANSPOSE: which of the record's three 8-float pieces are transposed (bit p:
   floats [8p, 8p + 8)); the others are gathered. The base and sheen pieces are; the spec reads
   only two fields of the third (the coat), and two gathers cost less than its 16 loads and
   shuffles. 0 gathers every field, for comparison (docs/performance.md). */
#ifndef BRDFCL_MATERIAL_TRANSPOSE
#define BRDFCL_MATERIAL_TRANSPOSE 3
#endif
#ifndef BRDFCL_MATERIAL_VLOAD
#define BRDFCL_MATERIAL_VLOAD 0
#endif
#if BRDFCL_W == 1 && BRDFCL_MATERIAL_VLOAD
/* The record as six 16-byte loads instead of a load a field: on a GPU, a warp's loads of one field
   from 96-byte records touch a cache line a lane, once a field. A tuning define
   (BRDFCL_BUILD_OPTIONS=-DBRDFCL_MATERIAL_VLOAD=1, bench/gpu/variants.txt); records start at
   multiples of 96 bytes in a buffer, so every float4 is aligned. */
typedef union {
  brdfcl_material m;
  float4 words[6];
} brdfcl_material_words;
typedef char brdfcl_record_is_six_words[sizeof(brdfcl_material) == 6 * sizeof(float4) ? 1 : -1];
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  __global const float4* r = (__global const float4*)(materials + index);
  brdfcl_material_words w;
  for (int k = 0; k < 6; ++k) w.words[k] = r[k];
  return material_splat_private(&w.m);
}
#elif BRDFCL_W == 1
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  return material_splat(materials + index);
}
#elif BRDFCL_W == 16 && defined(__clang__) && BRDFCL_MATERIAL_TRANSPOSE
typedef float8 __attribute__((aligned(4))) material_piece;
typedef char brdfcl_record_is_three_pieces[sizeof(brdfcl_material) == 3 * sizeof(float8) ? 1 : -1];

/* Rows j and k (lanes j, k) of floats [at, at + 8) of their records, side by side. */
#define MATERIAL_PIECE(j) (*(__global const material_piece*)((__global const float*)(materials + index.s##j) + at))
#define MATERIAL_ROWS(j, k) __builtin_shufflevector(MATERIAL_PIECE(j), MATERIAL_PIECE(k), \
                                                    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15)
/* unpcklps / unpckhps, shufps 0x44 / 0xee and shuff32x4 on 16 floats, per 128-bit quarter. */
#define MATERIAL_UNPACKLO(x, y) __builtin_shufflevector(x, y, 0, 16, 1, 17, 4, 20, 5, 21, 8, 24, 9, 25, 12, 28, 13, 29)
#define MATERIAL_UNPACKHI(x, y) __builtin_shufflevector(x, y, 2, 18, 3, 19, 6, 22, 7, 23, 10, 26, 11, 27, 14, 30, 15, 31)
#define MATERIAL_MOVELH(x, y) __builtin_shufflevector(x, y, 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24, 25, 12, 13, 28, 29)
#define MATERIAL_MOVEHL(x, y) __builtin_shufflevector(x, y, 2, 3, 18, 19, 6, 7, 22, 23, 10, 11, 26, 27, 14, 15, 30, 31)
#define MATERIAL_EVEN_QUARTERS(x, y) \
  __builtin_shufflevector(x, y, 0, 1, 2, 3, 8, 9, 10, 11, 16, 17, 18, 19, 24, 25, 26, 27)
#define MATERIAL_ODD_QUARTERS(x, y) \
  __builtin_shufflevector(x, y, 4, 5, 6, 7, 12, 13, 14, 15, 20, 21, 22, 23, 28, 29, 30, 31)

/* Floats [at, at + 8) of each lane's record as 8 field lanes. The rows are paired (0, 4), (1, 5),
   (2, 6), (3, 7), (8, 12), ... so that after two in-quarter steps, which leave field e of rows
   4q..4q+3 in one quarter, the last step picks whole quarters in lane order. */
BRDF_FN void material_piece_lanes(__global const brdfcl_material* materials, uint16 index, int at, float16 f[8]) {
  float16 a0 = MATERIAL_ROWS(0, 4), a1 = MATERIAL_ROWS(1, 5), a2 = MATERIAL_ROWS(2, 6), a3 = MATERIAL_ROWS(3, 7);
  float16 a4 = MATERIAL_ROWS(8, c), a5 = MATERIAL_ROWS(9, d), a6 = MATERIAL_ROWS(a, e), a7 = MATERIAL_ROWS(b, f);
  float16 t0 = MATERIAL_UNPACKLO(a0, a1), t1 = MATERIAL_UNPACKHI(a0, a1);
  float16 t2 = MATERIAL_UNPACKLO(a2, a3), t3 = MATERIAL_UNPACKHI(a2, a3);
  float16 t4 = MATERIAL_UNPACKLO(a4, a5), t5 = MATERIAL_UNPACKHI(a4, a5);
  float16 t6 = MATERIAL_UNPACKLO(a6, a7), t7 = MATERIAL_UNPACKHI(a6, a7);
  float16 s0 = MATERIAL_MOVELH(t0, t2), s1 = MATERIAL_MOVEHL(t0, t2);
  float16 s2 = MATERIAL_MOVELH(t1, t3), s3 = MATERIAL_MOVEHL(t1, t3);
  float16 s4 = MATERIAL_MOVELH(t4, t6), s5 = MATERIAL_MOVEHL(t4, t6);
  float16 s6 = MATERIAL_MOVELH(t5, t7), s7 = MATERIAL_MOVEHL(t5, t7);
  f[0] = MATERIAL_EVEN_QUARTERS(s0, s4);
  f[1] = MATERIAL_EVEN_QUARTERS(s1, s5);
  f[2] = MATERIAL_EVEN_QUARTERS(s2, s6);
  f[3] = MATERIAL_EVEN_QUARTERS(s3, s7);
  f[4] = MATERIAL_ODD_QUARTERS(s0, s4);
  f[5] = MATERIAL_ODD_QUARTERS(s1, s5);
  f[6] = MATERIAL_ODD_QUARTERS(s2, s6);
  f[7] = MATERIAL_ODD_QUARTERS(s3, s7);
}

/* A piece no lane of the batch's lobes reads is dead code, loads included. */
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  float16 field[3 * 8];
#if (BRDFCL_MATERIAL_TRANSPOSE & 7) != 7
  intw at = AS_INTW(index) * (int)(sizeof(brdfcl_material) / 4);
#endif
#define MATERIAL_GATHER_FIELD(k) field[k] = GATHERW((__global const float*)materials + (k), at);
#define MATERIAL_GATHER_PIECE(p)                                                                  \
  MATERIAL_GATHER_FIELD(8 * (p)) MATERIAL_GATHER_FIELD(8 * (p) + 1) MATERIAL_GATHER_FIELD(8 * (p) + 2) \
  MATERIAL_GATHER_FIELD(8 * (p) + 3) MATERIAL_GATHER_FIELD(8 * (p) + 4) MATERIAL_GATHER_FIELD(8 * (p) + 5) \
  MATERIAL_GATHER_FIELD(8 * (p) + 6) MATERIAL_GATHER_FIELD(8 * (p) + 7)
#if BRDFCL_MATERIAL_TRANSPOSE & 1
  material_piece_lanes(materials, index, 0, field);
#else
  MATERIAL_GATHER_PIECE(0)
#endif
#if BRDFCL_MATERIAL_TRANSPOSE & 2
  material_piece_lanes(materials, index, 8, field + 8);
#else
  MATERIAL_GATHER_PIECE(1)
#endif
#if BRDFCL_MATERIAL_TRANSPOSE & 4
  material_piece_lanes(materials, index, 16, field + 16);
#else
  MATERIAL_GATHER_PIECE(2)
#endif
  material_lanes out;
#define BRDFCL_PIECE_LANE(name, field_) out.name = field[__builtin_offsetof(brdfcl_material, field_) / sizeof(float)];
  BRDFCL_MATERIAL_LANES(BRDFCL_PIECE_LANE)
  intw flags = as_int16(field[__builtin_offsetof(brdfcl_material, flags) / sizeof(float)]);
  material_flag_lanes(&out, flags);
#if BRDFCL_E_ROW
  out.e_row = as_int16(field[__builtin_offsetof(brdfcl_material, sheen_e_row) / sizeof(float)]);
#endif
  return out;
}
#else
BRDF_FN material_lanes material_gather(__global const brdfcl_material* materials, uintw index) {
  intw at = AS_INTW(index) * (int)(sizeof(brdfcl_material) / 4);
  material_lanes out;
#define BRDFCL_GATHER_LANE(name, field) out.name = GATHERW((__global const float*)&materials->field, at);
  BRDFCL_MATERIAL_LANES(BRDFCL_GATHER_LANE)
  intw flags = AS_INTW(GATHERW((__global const float*)&materials->flags, at));
  material_flag_lanes(&out, flags);
#if BRDFCL_E_ROW
  out.e_row = AS_INTW(GATHERW((__global const float*)&materials->sheen_e_row, at));
#endif
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
