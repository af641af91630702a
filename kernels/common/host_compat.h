/* The few OpenCL C builtins and qualifiers the kernel headers use, as C++ inlines, so that host
   C++ compiles the very same source: the material packing (common/material_pack.h, in
   host/src/model/pack.cpp) and the benchmarks' peers (kernels/brdf/material.h). OpenCL never
   includes it. */
#ifndef BRDFCL_HOST_COMPAT_H
#define BRDFCL_HOST_COMPAT_H
#ifdef __OPENCL_VERSION__
#error "common/host_compat.h is for host C++ only"
#endif
#include <cmath>
#include <cstdint>
#include <cstring>

#define __global
#define __kernel
#define restrict __restrict__
typedef std::uint32_t uint;

#define M_PI_F 3.14159274101257324219f
#define M_1_PI_F 0.31830987334251403809f

static inline float select(float a, float b, int c) { return c ? b : a; }
static inline float mix(float a, float b, float t) { return a + (b - a) * t; }
static inline float max(float a, float b) { return a > b ? a : b; }
static inline float min(float a, float b) { return a < b ? a : b; }
static inline int min(int a, int b) { return a < b ? a : b; }
static inline float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
static inline float rsqrt(float x) { return 1.0f / std::sqrt(x); }
static inline int as_int(float x) { int i; std::memcpy(&i, &x, 4); return i; }
static inline float as_float(int i) { float x; std::memcpy(&x, &i, 4); return x; }
static inline int convert_int(float x) { return int(x); }
static inline int isinf(float x) { return std::isinf(x); }
using std::cos;
using std::floor;
using std::fmax;
using std::sin;
using std::exp;
using std::exp2;
using std::log1p;
using std::log2;
using std::sqrt;

#endif
