/* Width-generic lane types: every BRDF function is written once over `realw`, which is float
   (BRDFCL_W = 1) or floatN (BRDFCL_W = 2..16). PoCL's work-group vectorizer does not vectorize
   across work-items through library calls (pow, exp), so wide kernels vectorize by hand instead. */
#ifndef BRDFCL_LANES_H
#define BRDFCL_LANES_H

#ifndef BRDFCL_W
#define BRDFCL_W 16
#endif

#define BRDF_FN static inline __attribute__((always_inline))

#if BRDFCL_W == 1
typedef float realw;
typedef int intw;
typedef uint uintw;
typedef long longw;
#define VLOADW(i, p) ((p)[(i)])
#define VSTOREW(v, i, p) ((p)[(i)] = (v))
#define CONVERT_REALW(x) ((float)(x))
#define CONVERT_INTW(x) convert_int(x)
#define CONVERT_LONGW(x) convert_long(x)
#define AS_INTW(x) as_int(x)
#define AS_UINTW(x) as_uint(x)
#define AS_REALW(x) as_float(x)
#elif BRDFCL_W == 4
typedef float4 realw;
typedef int4 intw;
typedef uint4 uintw;
typedef long4 longw;
#define VLOADW vload4
#define VSTOREW vstore4
#define CONVERT_REALW convert_float4
#define CONVERT_INTW convert_int4
#define CONVERT_LONGW convert_long4
#define AS_INTW as_int4
#define AS_UINTW as_uint4
#define AS_REALW as_float4
#elif BRDFCL_W == 8
typedef float8 realw;
typedef int8 intw;
typedef uint8 uintw;
typedef long8 longw;
#define VLOADW vload8
#define VSTOREW vstore8
#define CONVERT_REALW convert_float8
#define CONVERT_INTW convert_int8
#define CONVERT_LONGW convert_long8
#define AS_INTW as_int8
#define AS_UINTW as_uint8
#define AS_REALW as_float8
#elif BRDFCL_W == 16
typedef float16 realw;
typedef int16 intw;
typedef uint16 uintw;
typedef long16 longw;
#define VLOADW vload16
#define VSTOREW vstore16
#define CONVERT_REALW convert_float16
#define CONVERT_INTW convert_int16
#define CONVERT_LONGW convert_long16
#define AS_INTW as_int16
#define AS_UINTW as_uint16
#define AS_REALW as_float16
#else
#error "BRDFCL_W must be 1, 4, 8 or 16"
#endif

/* Lanes p[W i .. W i + W) as one vector load or store (a plane's lanes, a group's output rows):
   PoCL's vload16 and vstore16 know only the float's alignment and assemble the vector from 8-byte
   pieces (8 loads and 7 shuffles a plane); a vector type aligned like a float lets the compiler
   issue one unaligned vector access. */
#if defined(__OPENCL_VERSION__) && defined(__clang__) && BRDFCL_W > 1
typedef realw __attribute__((aligned(4))) realw_plane;
typedef uintw __attribute__((aligned(4))) uintw_plane;
#define PLANE_LOAD(i, p) (((__global const realw_plane*)(p))[i])
#define INDEX_LOAD(i, p) (((__global const uintw_plane*)(p))[i])
#define PLANE_STORE(v, i, p) (((__global realw_plane*)(p))[i] = (v))
#else
#define PLANE_LOAD VLOADW
#define INDEX_LOAD VLOADW
#define PLANE_STORE VSTOREW
#endif

/* p[i] for each lane's index, written as one vector expression so the compiler can emit a
   hardware gather instead of a loop through private memory. */
#if BRDFCL_W == 1
#define GATHERW(p, i) ((p)[(i)])
#elif BRDFCL_W == 4
#define GATHERW(p, i) ((float4)((p)[(i).s0], (p)[(i).s1], (p)[(i).s2], (p)[(i).s3]))
#elif BRDFCL_W == 8
#define GATHERW(p, i) ((float8)((p)[(i).s0], (p)[(i).s1], (p)[(i).s2], (p)[(i).s3], \
                                (p)[(i).s4], (p)[(i).s5], (p)[(i).s6], (p)[(i).s7]))
#else
#define GATHERW(p, i) ((float16)((p)[(i).s0], (p)[(i).s1], (p)[(i).s2], (p)[(i).s3], \
                                 (p)[(i).s4], (p)[(i).s5], (p)[(i).s6], (p)[(i).s7], \
                                 (p)[(i).s8], (p)[(i).s9], (p)[(i).sa], (p)[(i).sb], \
                                 (p)[(i).sc], (p)[(i).sd], (p)[(i).se], (p)[(i).sf]))
#endif

typedef struct { realw x, y, z; } vec3w;
typedef struct { realw r, g, b; } rgbw;

BRDF_FN realw dot3w(vec3w a, vec3w b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
BRDF_FN rgbw rgbw_scale(rgbw c, realw s) { rgbw o = {c.r * s, c.g * s, c.b * s}; return o; }
BRDF_FN rgbw rgbw_add(rgbw a, rgbw b) { rgbw o = {a.r + b.r, a.g + b.g, a.b + b.b}; return o; }
BRDF_FN rgbw rgbw_splat(realw s) { rgbw o = {s, s, s}; return o; }
BRDF_FN realw pow5w(realw x) { realw x2 = x * x; return x2 * x2 * x; }

/* Lanes where `keep` is false become 0; masked lanes may hold NaN from invalid geometry. */
BRDF_FN realw keep_or_zero(realw v, intw keep) { return select((realw)(0.0f), v, keep); }

#endif
