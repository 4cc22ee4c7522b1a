/* Vectors of VW doubles for the celestial kernels (GCC/Clang vector extensions), VW = 2 or 4,
 * defined by the file that includes this (lanes2.c, lanes4.c). Each lane computes exactly what
 * it would alone: no operation mixes lanes, the project compiles without FMA contraction, and
 * square roots and divisions are correctly rounded, so a kernel gives bitwise the same result
 * for a value whatever its lane, its partners or the width. Private to src/celestial. */
#ifndef GM_CELESTIAL_LANES_H
#define GM_CELESTIAL_LANES_H

#include <math.h>
#include <stdint.h>
#if defined(__SSE2__) || defined(__AVX__)
#include <immintrin.h>
#endif

#include "celestial/internal.h"

typedef double vd __attribute__((vector_size(8 * VW)));
typedef long long vdi __attribute__((vector_size(8 * VW)));

static inline vd vd_splat(double x) {
  vd r;
  for (int j = 0; j < VW; ++j) r[j] = x;
  return r;
}

static inline vd vd_sqrt(vd a) {
#if VW == 4 && defined(__AVX__)
  return (vd)_mm256_sqrt_pd((__m256d)a);
#elif VW == 2 && defined(__SSE2__)
  return (vd)_mm_sqrt_pd((__m128d)a);
#else
  vd r;
  for (int j = 0; j < VW; ++j) r[j] = sqrt(a[j]);
  return r;
#endif
}

static inline vd vd_abs(vd a) {
  vdi m;
  for (int j = 0; j < VW; ++j) m[j] = INT64_MAX;
  return (vd)((vdi)a & m);
}

/* lanes (bit j) where every component of the mask is true */
static inline int lanes(vdi mask) {
  int bits = 0;
  for (int j = 0; j < VW; ++j) bits |= (int)(mask[j] & 1) << j;
  return bits;
}

/* finite: x − x is 0, not NaN */
static inline vdi vd_finite(vd a) { return a - a == 0.0; }

#endif
