/* Inlinable exp2, log2, exp and log1p over width-generic lanes. PoCL's builtins are accurate but
   heavy (its log2 alone costs more than a whole Charlie lobe in LLVM's inline budget), and C++
   peers compiling these headers get the same code. Accuracy, measured against double over the
   ranges the BRDF uses (tests/unit/test_fastmath.cpp): <= 2 ulp for exp2 and log2 on normal
   inputs (log2 near 1: <= 2 ulp of 1, absolute), <= 4 ulp for log1p, and exp within 3 ulp plus
   the rounding of x log2(e), i.e. about |x| ulp. */
#ifndef BRDFCL_FASTMATH_H
#define BRDFCL_FASTMATH_H

#include "common/lanes.h"

/* 2^y: y = n + f with |f| <= 1/2, 2^f by its degree-7 Taylor series in f ln2 (truncation
   5e-9), 2^n by building the exponent bits. Below -126 the result flushes to 0, as the BRDF's
   factors underflow there anyway; above 127 it saturates at 2^127-ish (never reached). */
BRDF_FN realw brdf_exp2(realw y) {
  realw yc = clamp(y, -126.0f, 127.0f);
  realw n = floor(yc + 0.5f);
  realw t = (yc - n) * 0.69314718056f;
  realw p = 1.0f + t * (1.0f + t * (0.5f + t * (0.16666666667f + t * (0.041666666667f +
            t * (0.0083333333333f + t * (0.0013888888889f + t * 0.00019841269841f))))));
  realw scale = AS_REALW((CONVERT_INTW(n) + 127) << 23);
  return select(p * scale, (realw)(0.0f), y < -126.0f);
}

BRDF_FN realw brdf_exp(realw x) { return brdf_exp2(x * 1.44269504089f); }

/* log2 x for x > 0: x = 2^e m with m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(t), t = (m-1)/(m+1),
   |t| <= 0.1716, by its odd series to t^9 (truncation 7e-10). x below FLT_MIN (0 or subnormal)
   gives -inf, so that pow(0, c) = exp2(c log2 0) = 0. */
BRDF_FN realw brdf_log2(realw x) {
  intw bits = AS_INTW(x);
  realw e = CONVERT_REALW(((bits >> 23) & 0xff) - 127);
  realw m = AS_REALW((bits & 0x007fffff) | 0x3f800000);
  intw big = m > 1.41421356f;
  m = select(m, m * 0.5f, big);
  e = select(e, e + 1.0f, big);
  realw t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  realw ln_m = t * (2.0f + t2 * (0.66666666667f + t2 * (0.4f + t2 * (0.28571428571f + t2 * 0.22222222222f))));
  realw r = e + ln_m * 1.44269504089f;
  return select(r, (realw)(-INFINITY), x < 1.17549435e-38f);
}

/* log(1 + u) for u >= 0, exact for small u by the classic correction log(w) u / (w - 1) with
   w = 1 + u rounded (Goldberg 1991); +inf stays +inf. */
BRDF_FN realw brdf_log1p(realw u) {
  realw w = 1.0f + u;
  realw r = brdf_log2(w) * 0.69314718056f * (u / (w - 1.0f));
  r = select(r, u, w == 1.0f);
  return select(r, u, isinf(u));
}

#endif
