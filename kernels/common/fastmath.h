/* Inlinable exp2, log2, exp, log1p, log2(1 + u), rsqrt and 1/x over width-generic lanes. PoCL's builtins are accurate but
   heavy (its log2 alone costs more than a whole Charlie lobe in LLVM's inline budget), and C++
   peers compiling these headers get the same code. Accuracy, measured against double over the
   ranges the BRDF uses (tests/unit/test_fastmath.cpp): <= 2 ulp for exp2 and log2 on normal
   inputs (log2 near 1: <= 2 ulp of 1, absolute), <= 4 ulp for log1p and log2(1 + u), <= 1 ulp
   for 1/x and <= 2.5 for 1/sqrt(x), and exp within 3 ulp plus the rounding of x log2(e), i.e.
   about |x| ulp; each at one lane and at sixteen. */
#ifndef BRDFCL_FASTMATH_H
#define BRDFCL_FASTMATH_H

#include "common/lanes.h"

#if BRDFCL_NATIVE_MATH
/* GPUs (Runtime's Arithmetic::Batch): the special-function unit's exp2, log2 and rsqrt, one
   instruction each (NVIDIA: ex2.approx, lg2.approx, rsqrt.approx, within 2 ulp, log2 within
   2^-22 absolute) where the polynomials below take twenty. log1p keeps its polynomial: a hardware
   log of 1 + u would lose u's low bits, which the Charlie lobe needs near N.H = 1. */
BRDF_FN realw brdf_exp2(realw y) { return native_exp2(y); }
BRDF_FN realw brdf_log2(realw x) { return native_log2(x); }
BRDF_FN realw brdf_rsqrt(realw x) { return native_rsqrt(x); }
BRDF_FN realw brdf_exp2_core(realw y) { return native_exp2(y); }
BRDF_FN realw brdf_rcp(realw x) { return 1.0f / x; }
#else
/* 2^y: y = n + f with n the nearest integer and |f| <= 1/2, 2^f = e^(f ln2) by its degree-7
   Taylor series in f (truncation 5e-9), 2^n by building the exponent bits. Below -126 the result flushes to 0, as the BRDF's
   factors underflow there anyway; above 127 it saturates at 2^127-ish (never reached). The series
   is 1 + f q(f) with q evaluated in Estrin's order (pairs of terms, then powers f^2 and f^4): four
   dependent multiply-adds instead of seven, so the chains of exp and log in the sheen lobes overlap
   more; q's rounding reaches the result scaled by |f| <= 1/2. brdf_exp2_core takes y already
   within [-127, 127]. */
BRDF_FN realw brdf_exp2_core(realw yc) {
  /* n, the nearest integer (ties to even), from the low bits of yc + 1.5 2^23 (exact for |yc| < 2^22):
     three operations where floor() is eleven in PoCL's library, and through the bits, so that no
     -ffast-math (the OpenMP peer) or -cl-fast-relaxed-math can fold the sum away. */
  intw ni = AS_INTW(yc + 12582912.0f) - 0x4b400000;
  /* The series in f = y - n with the powers of ln 2 in its coefficients (ln2^k / k!): no scaling by
     ln 2 in the chain. (n comes through the conversion of ni: (y + 1.5 2^23) - 1.5 2^23 in float
     would be one step shorter, but -ffast-math folds it to y.) */
  realw f = yc - CONVERT_REALW(ni);
  realw f2 = f * f;
  realw q01 = 6.93147180560e-01f + f * 2.40226506959e-01f, q23 = 5.55041086648e-02f + f * 9.61812910763e-03f;
  realw q45 = 1.33335581464e-03f + f * 1.54035303934e-04f;
  realw q = q01 + f2 * q23 + (f2 * f2) * (q45 + f2 * 1.52527338041e-05f);
  realw p = 1.0f + f * q;
  /* n = -127 gives the exponent bits 0: the result is exactly 0. */
  realw scale = AS_REALW((ni + 127) << 23);
  return p * scale;
}
BRDF_FN realw brdf_exp2(realw y) {
  return select(brdf_exp2_core(clamp(y, -126.0f, 127.0f)), (realw)(0.0f), y < -126.0f);
}

#endif

BRDF_FN realw brdf_exp(realw x) { return brdf_exp2(x * 1.44269504089f); }

/* The same without the clamp where the caller's range makes it idle: it and the flush are two or three
   operations at the head and the tail of a chain of dependent ones. brdf_exp2_nonpositive: y <= 0
   or -inf (a power of a number in [0, 1]), flushed to 0 below -127 by the exponent bits alone.
   brdf_exp_bounded: |x| log2(e) <= 126, unchecked. */
BRDF_FN realw brdf_exp2_nonpositive(realw y) { return brdf_exp2_core(max(y, -127.0f)); }
BRDF_FN realw brdf_exp_bounded(realw x) { return brdf_exp2_core(x * 1.44269504089f); }

/* ln(1 + f) / f on the reduced range f in [sqrt(1/2) - 1, sqrt(2) - 1]: a degree-9 polynomial,
   minimax in relative error (4.1e-9) fitted for these float coefficients, evaluated in Estrin's
   order (pairs of terms, then f^2, f^4, f^8: five dependent steps instead of ten). A polynomial in
   f = m - 1 needs no division (an atanh series in (m - 1)/(m + 1) would need one a call). */
BRDF_FN realw brdf_ln1p_reduced(realw f) {
  realw f2 = f * f, f4 = f2 * f2;
  realw a0 = 1.0f + f * -4.999998808e-01f, a1 = 3.333332539e-01f + f * -2.500158548e-01f;
  realw a2 = 2.000196874e-01f + f * -1.660900861e-01f, a3 = 1.418182403e-01f + f * -1.324348301e-01f;
  realw a4 = 1.290474683e-01f + f * -7.621168345e-02f;
  return f * (a0 + f2 * a1 + f4 * (a2 + f2 * a3) + (f4 * f4) * a4);
}

#if !BRDFCL_NATIVE_MATH
/* log2(1 + f) on the same range: the same fit for log2 (the coefficients above times log2 e,
   refitted), so that log2 near 1 keeps its relative accuracy without a rounded scaling. */
BRDF_FN realw brdf_log2_1p_reduced(realw f) {
  realw f2 = f * f, f4 = f2 * f2;
  realw a0 = 1.442695022e+00f + f * -7.213473320e-01f, a1 = 4.808982313e-01f + f * -3.606966436e-01f;
  realw a2 = 2.885674238e-01f + f * -2.396173477e-01f, a3 = 2.046004683e-01f + f * -1.910630763e-01f;
  realw a4 = 1.861761361e-01f + f * -1.099502221e-01f;
  return f * (a0 + f2 * a1 + f4 * (a2 + f2 * a3) + (f4 * f4) * a4);
}

/* log2 x for x > 0: x = 2^e m with m in [sqrt(1/2), sqrt(2)), log2 x = e + log2(1 + (m - 1)),
   m - 1 exact. x below FLT_MIN (0 or subnormal) gives -inf, so that pow(0, c) = exp2(c log2 0) = 0. */
BRDF_FN realw brdf_log2(realw x) {
  /* e and m in integer operations, one cycle each: k = floor(log2(x / sqrt(1/2))) from the bits of x
     less those of sqrt(1/2) (0x3f3504f3), and m = x 2^-k from the bits less k in the exponent field.
     Four short steps reach m - 1, where a compare and a masked halving of m in [1, 2) took three
     longer ones. */
  intw bits = AS_INTW(x);
  intw k = (bits - 0x3f3504f3) >> 23;
  realw m = AS_REALW(bits - k * 0x00800000); /* k 2^23: no shift of a negative number */
  realw r = CONVERT_REALW(k) + brdf_log2_1p_reduced(m - 1.0f);
  return select(r, (realw)(-INFINITY), x < 1.17549435e-38f);
}

#endif

#if !BRDFCL_NATIVE_MATH
/* log2(1 + u) for u >= 0 (+inf stays +inf) in the same way as brdf_log1p below, with brdf_log2's
   integer reduction (k from the bits of w = 1 + u less those of sqrt(1/2), 2^-k from k) and the
   log2 polynomial: no conversion or compare before the polynomial, and no scaling by ln 2 after
   it for a caller that wants a power of 2. */
BRDF_FN realw brdf_log2_1p(realw u) {
  intw bits = AS_INTW(1.0f + u);
  intw k = (bits - 0x3f3504f3) >> 23;
  realw s = AS_REALW((127 - min(k, 25)) * 0x00800000); /* 2^-k */
  realw m = AS_REALW(bits - k * 0x00800000);
  realw f = select(u * s + (s - 1.0f), m - 1.0f, k > 24);
  realw r = CONVERT_REALW(k) + brdf_log2_1p_reduced(f);
  return select(r, u, isinf(u));
}
#endif

/* log(1 + u) for u >= 0 without a division: w = 1 + u rounded gives the exponent e (with
   m in [sqrt(1/2), sqrt(2))), and f = (1 + u) 2^-e - 1 is formed from u itself, u 2^-e + (2^-e - 1):
   the scaling is exact and the sum rounds once, so the rounding of w is not inherited (exact for
   small u; f = u when e = 0). Above 2^24 that rounding is below float's resolution of the result
   and f = m - 1. +inf stays +inf. */
BRDF_FN realw brdf_log1p(realw u) {
  realw w = 1.0f + u;
  intw bits = AS_INTW(w);
  realw e = CONVERT_REALW(((bits >> 23) & 0xff) - 127);
  realw m = AS_REALW((bits & 0x007fffff) | 0x3f800000);
  intw big = m > 1.41421356f;
  m = select(m, m * 0.5f, big);
  e = select(e, e + 1.0f, big);
  realw s = AS_REALW((127 - CONVERT_INTW(min(e, 25.0f))) << 23); /* 2^-e */
  realw f = select(u * s + (s - 1.0f), m - 1.0f, e > 24.0f);
  realw r = e * 0.69314718056f + brdf_ln1p_reduced(f);
  return select(r, u, isinf(u));
}

#if BRDFCL_NATIVE_MATH
BRDF_FN realw brdf_log2_1p(realw u) { return brdf_log1p(u) * 1.44269504089f; }
#endif

#if !BRDFCL_NATIVE_MATH
#if BRDFCL_W == 16 && defined(__clang__) && defined(__AVX512F__)
/* 1/sqrt(x) for normal x > 0 on AVX-512 (PoCL's 16 lanes): the hardware's 14-bit estimate
   (vrsqrt14ps, relative error below 2^-14) and one Newton step, about float's rounding, where the
   bit-pattern estimate below needs three steps: two dependent steps fewer at the head of every
   chain through a half vector or a normalization. The step is y + y e with e = 1/2 - x y^2 / 2
   small, so its rounding stays near half an ulp, where y (3/2 - x y^2 / 2) rounds at full size. */
typedef float brdf_v16sf __attribute__((__vector_size__(64)));
typedef union {
  realw w;
  brdf_v16sf v;
} brdf_v16;
BRDF_FN realw brdf_rsqrt(realw x) {
  brdf_v16 in, est;
  in.w = x;
  est.v = __builtin_ia32_rsqrt14ps512_mask(in.v, in.v, (ushort)0xffff);
  realw y = est.w, e = fma(-0.5f * x, y * y, (realw)(0.5f));
  return fma(y, e, y);
}
/* 1/x for finite x > 0 on AVX-512: the 14-bit estimate (vrcp14ps) and one Newton step,
   y + y (1 - x y), about float's rounding (the step's error is below 2^-28). Where a division sits
   in a chain that ends in the result, this is two dependent multiply-adds after a short estimate
   instead of a vdivps, whose latency on 16 lanes is about that of a whole exp2, and it leaves the
   divider free for the divisions that stay. */
BRDF_FN realw brdf_rcp(realw x) {
  brdf_v16 in, est;
  in.w = x;
  est.v = __builtin_ia32_rcp14ps512_mask(in.v, in.v, (ushort)0xffff);
  realw y = est.w, e = fma(-x, y, (realw)(1.0f));
  return fma(y, e, y);
}
#else
/* 1/x: a division, correctly rounded, where no estimate instruction is at hand. */
BRDF_FN realw brdf_rcp(realw x) { return 1.0f / x; }
/* 1/sqrt(x) for normal x > 0 without a square root or a division: the classic bit-pattern
   estimate (Lomont 2003's constant, relative error <= 1.8e-3) and three Newton steps, which leave
   float's rounding (2.2 ulp at most without fma). rsqrt() itself is a sqrt and a correctly rounded division where the
   program is built with -cl-fp32-correctly-rounded-divide-sqrt. */
BRDF_FN realw brdf_rsqrt(realw x) {
  realw y = AS_REALW(0x5f375a86 - (AS_INTW(x) >> 1));
  realw hx = 0.5f * x;
  y = y * (1.5f - hx * y * y);
  y = y * (1.5f - hx * y * y);
  return y * (1.5f - hx * y * y);
}
#endif
#endif

#endif
