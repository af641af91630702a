/* Batch BRDF evaluation. Directions arrive as SoA planes (Lx Ly Lz Vx Vy Vz) and results leave
   as planes (r g b), or both as the caller's interleaved (N, 3) rows (eval_rows, eval_grid_rows).
   Each work-item handles BRDFCL_W consecutive samples, so the host pads every plane to a multiple
   of BRDFCL_W; the row kernels instead treat the last, partial group of an array on its own. */
#include "brdf/material.h"
#include "common/rows.h"

#ifndef BRDFCL_ONE_MATERIAL
#define BRDFCL_ONE_MATERIAL 0
#endif

/* The entry points a program holds, as a mask of these bits (all without the define): the host
   builds one program a path with only the kernels that path launches, so a device loads and
   parses no more than it runs (host/src/eval/batch.hpp, Evaluator::Kernels). */
#define BRDFCL_KERNELS_SAMPLES 1
#define BRDFCL_KERNELS_ROWS 2
#define BRDFCL_KERNELS_GRID 4
#define BRDFCL_KERNELS_TABLE 8
#ifndef BRDFCL_KERNELS
#define BRDFCL_KERNELS 15
#endif

/* clang's non-temporal store on vector lanes (PoCL); other compilers store as usual. */
#if defined(__clang__) && BRDFCL_W > 1
#define STREAM_STORES 1
#else
#define STREAM_STORES 0
#endif

/* One material per sample, gathered by index (read once for all lanes in a program built for one
   material, BRDFCL_ONE_MATERIAL: a branch here instead costs the gathering kernel ~10 %). Every
   plane is its own buffer, so callers can hand over their arrays in place and a plane stays
   under the device's largest allocation. */
#if BRDFCL_KERNELS & BRDFCL_KERNELS_SAMPLES
__kernel void eval_samples(__global const float* restrict Lx, __global const float* restrict Ly,
                           __global const float* restrict Lz, __global const float* restrict Vx,
                           __global const float* restrict Vy, __global const float* restrict Vz,
                           __global const uint* restrict material_index,
                           __global const brdfcl_material* restrict materials,
                           __global const float* restrict sheen_e, int sheen_e_size,
                           __global float* restrict out_r, __global float* restrict out_g,
                           __global float* restrict out_b) {
  uint i = get_global_id(0);
  vec3w L = {PLANE_LOAD(i, Lx), PLANE_LOAD(i, Ly), PLANE_LOAD(i, Lz)};
  vec3w V = {PLANE_LOAD(i, Vx), PLANE_LOAD(i, Vy), PLANE_LOAD(i, Vz)};
#if BRDFCL_ONE_MATERIAL
  material_lanes m = material_splat(materials);
#else
  material_lanes m = material_gather(materials, INDEX_LOAD(i, material_index));
#endif
  rgbw f = brdf_material(m, L, V, sheen_e, sheen_e_size);
#if STREAM_STORES
  /* Results of a batch larger than the caches reach the host from memory anyway: non-temporal
     stores skip the read for ownership of each line (40 bytes a sample moved instead of 52).
     Smaller batches keep theirs in cache for the copy back. The stores need the alignment of a
     realw, which planes the host allocates have and a caller's arrays in place may not. */
  const ulong stream_bytes = 8ul << 20;
  if (get_global_size(0) * sizeof(realw) * 3 >= stream_bytes &&
      (((ulong)out_r | (ulong)out_g | (ulong)out_b) & (sizeof(realw) - 1)) == 0) {
    __builtin_nontemporal_store(f.r, (__global realw*)out_r + i);
    __builtin_nontemporal_store(f.g, (__global realw*)out_g + i);
    __builtin_nontemporal_store(f.b, (__global realw*)out_b + i);
    return;
  }
#endif
  PLANE_STORE(f.r, i, out_r);
  PLANE_STORE(f.g, i, out_g);
  PLANE_STORE(f.b, i, out_b);
}
#endif

/* Lowers *bad_row to the first row (`first` is lane 0's) whose lane is set in `bad`. */
BRDF_FN void report_bad_rows(intw bad, uint first, __global uint* bad_row) {
  if (!ANYW(bad)) return;
  int lanes[BRDFCL_W];
  VSTOREW(bad, 0, lanes);
  uint k = 0;
  while (k + 1 < BRDFCL_W && !lanes[k]) ++k;
  atomic_min(bad_row, first + k);
}

/* 0, 1, ..., BRDFCL_W - 1: each lane's row within its group. */
BRDF_FN intw lane_index(void) {
#if BRDFCL_W == 1
  return 0;
#else
  return (intw)(ROWS_LANES(ROWS_LANE_INDEX, 0, 0));
#endif
}

/* The lanes holding one of the first n rows of the group (the rest lie past the array's end). */
BRDF_FN intw lanes_before(uint n) { return lane_index() < (int)n; }

/* Each lane's material: index k where `inside`, else 0 (its f is discarded); one read for all
   lanes in a program built for one material. */
BRDF_FN material_lanes material_of_rows(__global const brdfcl_material* materials, intw k, intw inside) {
#if BRDFCL_ONE_MATERIAL
  return material_splat(materials);
#else
  return material_gather(materials, AS_UINTW(select((intw)(0), k, inside)));
#endif
}

/* Evaluates the group's lanes, reports its bad rows and writes the first n rows of f. */
BRDF_FN void finish_rows(material_lanes m, vec3w l, vec3w v, intw bad, uint first, uint n,
                         __global const float* sheen_e, int sheen_e_size, __global float* out,
                         __global uint* bad_row) {
  report_bad_rows(bad & lanes_before(n), first, bad_row);
  rgbw f = brdf_material(m, l, v, sheen_e, sheen_e_size);
  if (n == BRDFCL_W)
    rows_store(f, out);
  else
    rows_store_partial(f, out, n);
}
/* The material indices of the first n rows at p (the lanes past them read 0). */
#define INDICES_BODY(T)                                          \
  if (n == BRDFCL_W) return CONVERT_LONGW(VLOADW(0, p));         \
  T tmp[BRDFCL_W];                                               \
  for (uint j = 0; j < BRDFCL_W; ++j) tmp[j] = j < n ? p[j] : 0; \
  return CONVERT_LONGW(VLOADW(0, tmp));
BRDF_FN longw load_indices_long(__global const long* p, uint n) { INDICES_BODY(long) }
BRDF_FN longw load_indices_uint(__global const uint* p, uint n) { INDICES_BODY(uint) }

/* Every row kernel comes as two entry points over one body: `name` runs the whole groups of
   BRDFCL_W rows, one a work-item (global id 0), and `name_tail`, one work-item, the partial group
   at the end of the array, if any. Testing for the partial group inside one kernel cost the whole
   kernel ~13 % (register spills), so each entry point compiles one path: the body gets the
   group's first row, its n rows and `partial` as a constant. ARGS is a macro naming the
   parameters in order: OpenCL C 1.2 has no variadic macros, and NVIDIA's compiler rejects them. */
#define ROW_KERNELS(name, PARAMS, ARGS)                                                    \
  __kernel void name PARAMS {                                                             \
    uint first = get_global_id(0) * BRDFCL_W;                                             \
    if (first + BRDFCL_W <= count) name##_group(first, BRDFCL_W, 0, ARGS);                \
  }                                                                                       \
  __kernel void name##_tail PARAMS {                                                      \
    uint first = count / BRDFCL_W * BRDFCL_W;                                             \
    if (first < count) name##_group(first, count - first, 1, ARGS);                       \
  }

/* Rows where the caller holds them: L, V and f as (count, 3) float rows, each at its offset (in
   elements) from the start of its buffer, so that the host can hand over any array in place.
   With `normalize`, L and V are normalized here by the samples readers' arithmetic (rows.h);
   without, they must be unit vectors, and only NaN and infinities are caught. `index` holds a
   material index a row, int64 (index_longs) or uint32, or is null: material 0 everywhere. A row whose L or V is no direction, or whose index is not in
   [0, material_count), lowers *bad_row to its number, and its f is undefined. */
BRDF_FN void eval_rows_group(uint first, uint n, const int partial, __global const float* restrict L, uint L_at,
                             __global const float* restrict V, uint V_at, __global const uint* restrict index,
                             uint index_at, int index_longs, uint material_count, uint count, int normalize,
                             __global const brdfcl_material* restrict materials, __global const float* restrict sheen_e,
                             int sheen_e_size, __global float* restrict out, uint out_at,
                             __global uint* restrict bad_row) {
  L += L_at + 3 * (ulong)first;
  V += V_at + 3 * (ulong)first;
  out += out_at + 3 * (ulong)first;
  vec3w l = partial ? rows_load_partial(L, n) : rows_load(L);
  vec3w v = partial ? rows_load_partial(V, n) : rows_load(V);
  intw bad = normalize ? rows_normalize(&l) | rows_normalize(&v) : rows_not_finite(l) | rows_not_finite(v);
  material_lanes m;
  if (index) {
    /* Indices are checked as longs before narrowing, so -1 or 2^32 never alias a material. */
    longw k = index_longs ? load_indices_long((__global const long*)index + index_at + first, n)
                          : load_indices_uint(index + index_at + first, n);
    intw inside = CONVERT_INTW((k >= 0) & (k < (long)material_count));
    bad |= !inside;
    m = material_of_rows(materials, CONVERT_INTW(k), inside);
  } else {
    m = material_splat(materials);
  }
  finish_rows(m, l, v, bad, first, n, sheen_e, sheen_e_size, out, bad_row);
}
#define EVAL_ROWS_ARGS \
  L, L_at, V, V_at, index, index_at, index_longs, material_count, count, normalize, materials, sheen_e, sheen_e_size, \
      out, out_at, bad_row
#if BRDFCL_KERNELS & BRDFCL_KERNELS_ROWS
ROW_KERNELS(eval_rows,
            (__global const float* restrict L, uint L_at, __global const float* restrict V, uint V_at,
             __global const uint* restrict index, uint index_at, int index_longs, uint material_count, uint count,
             int normalize, __global const brdfcl_material* restrict materials, __global const float* restrict sheen_e,
             int sheen_e_size, __global float* restrict out, uint out_at, __global uint* restrict bad_row),
            EVAL_ROWS_ARGS)
#endif

/* Every material (global id 1, from `first_material`) x every
   row of L and V (global id 0), f written material-major: material k's row i at out row
   k * out_rows + i. Rows are checked (material 0's work-items report them) and normalized as in
   eval_rows. */
BRDF_FN void eval_grid_rows_group(uint first, uint n, const int partial, __global const float* restrict L,
                                  uint L_at, __global const float* restrict V, uint V_at, uint count, int normalize,
                                  __global const brdfcl_material* restrict materials, uint first_material,
                                  __global const float* restrict sheen_e, int sheen_e_size, __global float* restrict out,
                                  uint out_at, ulong out_rows, __global uint* restrict bad_row) {
  ulong material = get_global_id(1);
  L += L_at + 3 * (ulong)first;
  V += V_at + 3 * (ulong)first;
  out += out_at + 3 * (material * out_rows + first);
  vec3w l = partial ? rows_load_partial(L, n) : rows_load(L);
  vec3w v = partial ? rows_load_partial(V, n) : rows_load(V);
  intw bad = normalize ? rows_normalize(&l) | rows_normalize(&v) : rows_not_finite(l) | rows_not_finite(v);
  /* Material 0's work-items report the rows for all. */
  finish_rows(material_splat(materials + first_material + material), l, v, material == 0 ? bad : (intw)(0), first, n,
              sheen_e, sheen_e_size, out, bad_row);
}
#define EVAL_GRID_ROWS_ARGS \
  L, L_at, V, V_at, count, normalize, materials, first_material, sheen_e, sheen_e_size, out, out_at, out_rows, bad_row
#if BRDFCL_KERNELS & BRDFCL_KERNELS_GRID
ROW_KERNELS(eval_grid_rows,
            (__global const float* restrict L, uint L_at, __global const float* restrict V, uint V_at, uint count,
             int normalize, __global const brdfcl_material* restrict materials, uint first_material,
             __global const float* restrict sheen_e, int sheen_e_size, __global float* restrict out, uint out_at,
             ulong out_rows, __global uint* restrict bad_row),
            EVAL_GRID_ROWS_ARGS)
#endif

/* A samples file's rows as they lie in memory (a float32 C-order NPY of shape (count, 7)): the
   material index (a float that must hold an integer in [0, material_count)), then Lx Ly Lz Vx Vy
   Vz, read and checked as the samples readers read them, normalized as eval_rows does it; f is
   written as (count, 3) rows. */
BRDF_FN void eval_table_rows_group(uint first, uint n, const int partial, __global const float* restrict rows,
                                   uint rows_at, uint material_count, uint count,
                                   __global const brdfcl_material* restrict materials,
                                   __global const float* restrict sheen_e, int sheen_e_size,
                                   __global float* restrict out, uint out_at, __global uint* restrict bad_row) {
  __global const float* p = rows + rows_at + 7 * (ulong)first;
  out += out_at + 3 * (ulong)first;
  realw k;
  vec3w l, v;
  if (partial)
    table_load_partial(p, n, &k, &l, &v);
  else
    table_load(p, &k, &l, &v);
  intw bad = rows_normalize(&l) | rows_normalize(&v);
  /* The readers' test: an index is good when it is an integer in [0, min(material_count, 2^31)). */
  realw limit = (realw)((float)min(material_count, 0x80000000u));
  intw inside = (k >= 0.0f) & (k < limit) & (trunc(k) == k);
  bad |= !inside;
  finish_rows(material_of_rows(materials, CONVERT_INTW(k), inside), l, v, bad, first, n, sheen_e, sheen_e_size, out,
              bad_row);
}
#define EVAL_TABLE_ROWS_ARGS rows, rows_at, material_count, count, materials, sheen_e, sheen_e_size, out, out_at, bad_row
#if BRDFCL_KERNELS & BRDFCL_KERNELS_TABLE
ROW_KERNELS(eval_table_rows,
            (__global const float* restrict rows, uint rows_at, uint material_count, uint count,
             __global const brdfcl_material* restrict materials, __global const float* restrict sheen_e,
             int sheen_e_size, __global float* restrict out, uint out_at, __global uint* restrict bad_row),
            EVAL_TABLE_ROWS_ARGS)
#endif
