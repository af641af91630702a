/* Interleaved (N, 3) rows (numpy's layout: x y z x y z ...) to and from lanes, and the samples
   readers' direction normalization done on the device, so that the batch kernels can read the
   caller's arrays and write its result array where they lie. */
#ifndef BRDFCL_ROWS_H
#define BRDFCL_ROWS_H

#include "common/lanes.h"

#if BRDFCL_W == 1
#define ANYW(x) (x)
#define ROWS_LOAD_BODY                      \
  vec3w v = {p[0], p[1], p[2]};             \
  return v;
#define ROWS_STORE_BODY p[0] = v.r, p[1] = v.g, p[2] = v.b;
#else
#define ANYW(x) any(x)
/* ROWS_LANES(F, a, b) lists F(a, b, k) for every lane k. OpenCL C 1.2 has no variadic macros
   (NVIDIA's compiler rejects them), so every list function takes two arguments before the lane. */
#define ROWS_LANES4(F, a, b) F(a, b, 0), F(a, b, 1), F(a, b, 2), F(a, b, 3)
#define ROWS_LANES8(F, a, b) ROWS_LANES4(F, a, b), F(a, b, 4), F(a, b, 5), F(a, b, 6), F(a, b, 7)
#define ROWS_LANES16(F, a, b)                                                                            \
  ROWS_LANES8(F, a, b), F(a, b, 8), F(a, b, 9), F(a, b, 10), F(a, b, 11), F(a, b, 12), F(a, b, 13), F(a, b, 14), \
      F(a, b, 15)
#if BRDFCL_W == 4
#define ROWS_LANES ROWS_LANES4
#elif BRDFCL_W == 8
#define ROWS_LANES ROWS_LANES8
#else
#define ROWS_LANES ROWS_LANES16
#endif
#define ROWS_LANE_INDEX(unused_a, unused_b, k) (k)
/* W rows are 3 consecutive vectors a b c; lane k of component comp is element 3k + comp of
   them. Two constant shuffles pick it: the lanes lying in a and b first, then those in c. */
#define ROWS_IN_AB(comp, unused, k) (3 * (k) + (comp) < 2 * BRDFCL_W ? 3 * (k) + (comp) : -1)
#define ROWS_FROM_C(comp, unused, k) (3 * (k) + (comp) < 2 * BRDFCL_W ? (k) : 3 * (k) + (comp) - BRDFCL_W)
#define ROWS_COMPONENT(a, b, c, comp) \
  __builtin_shufflevector(__builtin_shufflevector(a, b, ROWS_LANES(ROWS_IN_AB, comp, 0)), c, ROWS_LANES(ROWS_FROM_C, comp, 0))
/* Storing is the inverse: element j = qW + p of output vector q is channel j % 3 of lane j / 3;
   r and g are merged first, then b. */
#define ROWS_J(q, p) ((q) * BRDFCL_W + (p))
#define ROWS_RG(q, unused, p) (ROWS_J(q, p) % 3 == 0 ? ROWS_J(q, p) / 3 : ROWS_J(q, p) % 3 == 1 ? BRDFCL_W + ROWS_J(q, p) / 3 : -1)
#define ROWS_B(q, unused, p) (ROWS_J(q, p) % 3 == 2 ? BRDFCL_W + ROWS_J(q, p) / 3 : (p))
#define ROWS_INTERLEAVE(v, q) \
  __builtin_shufflevector(__builtin_shufflevector(v.r, v.g, ROWS_LANES(ROWS_RG, q, 0)), v.b, ROWS_LANES(ROWS_B, q, 0))
#define ROWS_LOAD_BODY                                                             \
  realw a = VLOADW(0, p), b = VLOADW(1, p), c = VLOADW(2, p);                      \
  vec3w v = {ROWS_COMPONENT(a, b, c, 0), ROWS_COMPONENT(a, b, c, 1), ROWS_COMPONENT(a, b, c, 2)}; \
  return v;
#define ROWS_STORE_BODY                 \
  VSTOREW(ROWS_INTERLEAVE(v, 0), 0, p); \
  VSTOREW(ROWS_INTERLEAVE(v, 1), 1, p); \
  VSTOREW(ROWS_INTERLEAVE(v, 2), 2, p);
#endif

/* BRDFCL_W rows from p (3 * BRDFCL_W floats). OpenCL C 1.2 has no generic address space: the
   private entry points serve the one partial group at the end of an array. */
BRDF_FN vec3w rows_load(__global const float* p) { ROWS_LOAD_BODY }
BRDF_FN vec3w rows_load_private(const float* p) { ROWS_LOAD_BODY }
BRDF_FN void rows_store(rgbw v, __global float* p) { ROWS_STORE_BODY }
BRDF_FN void rows_store_private(rgbw v, float* p) { ROWS_STORE_BODY }

/* The first n < BRDFCL_W rows from p; the lanes past them read 0. */
BRDF_FN vec3w rows_load_partial(__global const float* p, uint n) {
  float tmp[3 * BRDFCL_W];
  for (uint j = 0; j < 3 * BRDFCL_W; ++j) tmp[j] = j < 3 * n ? p[j] : 0.0f;
  return rows_load_private(tmp);
}

BRDF_FN void rows_store_partial(rgbw v, __global float* p, uint n) {
  float tmp[3 * BRDFCL_W];
  rows_store_private(v, tmp);
  for (uint j = 0; j < 3 * n; ++j) p[j] = tmp[j];
}

/* The same for rows of 7 floats, a samples file's (material, Lx Ly Lz Vx Vy Vz): lane k of column c
   is element 7k + c of 7 consecutive vectors v[0..6], which a tree of constant shuffles gathers
   (the pairs of vectors it lies in, then the halves). */
#if BRDFCL_W > 1
#define TABLE_STRIDE 7
#define TABLE_E(c, k) (TABLE_STRIDE * (k) + (c))
#define TABLE_SRC(c, k) (TABLE_E(c, k) / BRDFCL_W)
#define TABLE_PAIR(c, p, k) (TABLE_SRC(c, k) / 2 == (p) ? TABLE_E(c, k) - 2 * (p) * BRDFCL_W : -1)
#define TABLE_LOW(c, unused, k) (TABLE_SRC(c, k) < 2 ? (k) : TABLE_SRC(c, k) < 4 ? BRDFCL_W + (k) : -1)
#define TABLE_HIGH(c, unused, k) (TABLE_SRC(c, k) < 4 ? -1 : TABLE_SRC(c, k) < 6 ? (k) : BRDFCL_W + (k))
#define TABLE_HALF(c, unused, k) (TABLE_SRC(c, k) < 4 ? (k) : BRDFCL_W + (k))
#define TABLE_COLUMN(v, c)                                                                                   \
  __builtin_shufflevector(                                                                                   \
      __builtin_shufflevector(__builtin_shufflevector(v[0], v[1], ROWS_LANES(TABLE_PAIR, c, 0)),             \
                              __builtin_shufflevector(v[2], v[3], ROWS_LANES(TABLE_PAIR, c, 1)),             \
                              ROWS_LANES(TABLE_LOW, c, 0)),                                                  \
      __builtin_shufflevector(__builtin_shufflevector(v[4], v[5], ROWS_LANES(TABLE_PAIR, c, 2)),             \
                              __builtin_shufflevector(v[6], v[6], ROWS_LANES(TABLE_PAIR, c, 3)),             \
                              ROWS_LANES(TABLE_HIGH, c, 0)),                                                 \
      ROWS_LANES(TABLE_HALF, c, 0))
#define TABLE_LOAD_BODY                                                              \
  realw v[7];                                                                        \
  for (int q = 0; q < 7; ++q) v[q] = VLOADW(q, p);                                   \
  *material = TABLE_COLUMN(v, 0);                                                    \
  L->x = TABLE_COLUMN(v, 1), L->y = TABLE_COLUMN(v, 2), L->z = TABLE_COLUMN(v, 3);   \
  V->x = TABLE_COLUMN(v, 4), V->y = TABLE_COLUMN(v, 5), V->z = TABLE_COLUMN(v, 6);
#else
#define TABLE_LOAD_BODY                                                                                      \
  *material = p[0];                                                \
  L->x = p[1], L->y = p[2], L->z = p[3];                           \
  V->x = p[4], V->y = p[5], V->z = p[6];
#endif

/* BRDFCL_W rows of 7 floats from p: the material column, L and V. */
BRDF_FN void table_load(__global const float* p, realw* material, vec3w* L, vec3w* V) { TABLE_LOAD_BODY }
BRDF_FN void table_load_private(const float* p, realw* material, vec3w* L, vec3w* V) { TABLE_LOAD_BODY }

/* The first n < BRDFCL_W rows of 7 floats from p; the lanes past them read 0. */
BRDF_FN void table_load_partial(__global const float* p, uint n, realw* material, vec3w* L, vec3w* V) {
  float tmp[7 * BRDFCL_W];
  for (uint j = 0; j < 7 * BRDFCL_W; ++j) tmp[j] = j < 7 * n ? p[j] : 0.0f;
  table_load_private(tmp, material, L, V);
}

/* The normalization's root and quotients, correctly rounded as the host's are. Built without
   -cl-fp32-correctly-rounded-divide-sqrt (BRDFCL_ROWS_FP64, a GPU with doubles), they are taken
   in double and rounded once to float: for sqrt and division that is the correctly rounded float
   result, since 53 >= 2 * 24 + 2 bits (Figueroa, "When is double rounding innocuous?", 1995).
   For that very reason a compiler may turn (float)((double)a / (double)b) back into a float
   division, which without the flag is approximate (NVIDIA's did): both operands are doubled
   first, exactly, so that neither is a widened float any more. */
#if BRDFCL_ROWS_FP64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#if BRDFCL_W == 1
#define ROWS_DOUBLE(x) ((double)(x))
#elif BRDFCL_W == 4
#define ROWS_DOUBLE convert_double4
#elif BRDFCL_W == 8
#define ROWS_DOUBLE convert_double8
#else
#define ROWS_DOUBLE convert_double16
#endif
#define ROWS_SQRT(s) CONVERT_REALW(sqrt(ROWS_DOUBLE(s)))
#define ROWS_DIV(a, b) CONVERT_REALW((ROWS_DOUBLE(a) * 2.0) / (ROWS_DOUBLE(b) * 2.0))
#else
#define ROWS_SQRT(s) sqrt(s)
#define ROWS_DIV(a, b) ((a) / (b))
#endif

/* Normalizes d in place exactly as the samples readers do (host/src/io/directions.cpp,
   normalizeDirection): x / sqrt((x*x + y*y) + z*z), every operation rounded to float (no
   contraction), and a vector whose squared length leaves [2^-96, 2^96] first scaled by 2^-e,
   e = ilogb of its largest component (exact: ldexp rounds once, as the host's double scalbn and
   its conversion to float do). Returns the lanes that hold no direction (a component NaN or
   infinite, or all zero); their d is undefined. */
BRDF_FN intw rows_normalize(vec3w* d) {
#pragma OPENCL FP_CONTRACT OFF
  realw x = d->x, y = d->y, z = d->z;
  realw s = (x * x + y * y) + z * z;
  intw rescale = !((s >= 0x1p-96f) & (s <= 0x1p96f));
  intw bad = rescale & 0;
  if (ANYW(rescale)) {
    realw m = fmax(fabs(x), fmax(fabs(y), fabs(z)));
    bad = !(isfinite(x) & isfinite(y) & isfinite(z)) | (m == 0.0f);
    intw e = select(ilogb(m), (intw)(0), bad);
    intw scaled = rescale & !bad;
    x = select(x, ldexp(x, -e), scaled);
    y = select(y, ldexp(y, -e), scaled);
    z = select(z, ldexp(z, -e), scaled);
    s = (x * x + y * y) + z * z;
  }
  realw len = ROWS_SQRT(s);
  d->x = ROWS_DIV(x, len);
  d->y = ROWS_DIV(y, len);
  d->z = ROWS_DIV(z, len);
  return bad;
}

/* The lanes of d that hold a NaN or an infinity (directions given as unit vectors). */
BRDF_FN intw rows_not_finite(vec3w d) { return !(isfinite(d.x) & isfinite(d.y) & isfinite(d.z)); }

#endif
