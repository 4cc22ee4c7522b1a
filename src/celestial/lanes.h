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

/* Passing 32-byte vectors without AVX has another ABI than with it; the helpers here are
 * static inline, so no such call crosses a compilation unit. */
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

typedef double vd __attribute__((vector_size(8 * VW)));
typedef long long vdi __attribute__((vector_size(8 * VW)));

static inline vd vd_splat(double x) {
  vd r;
  for (int j = 0; j < VW; ++j) r[j] = x;
  return r;
}

/* (q[3 k_0 + c], …, q[3 k_{VW−1} + c]) and (v[k_0], …) built in registers: an element-by-element
 * build goes through the stack, and the vector load that follows waits for the stores
 * (measured: a third of a drift's time). */
static inline vd vd_gather(const double *q, const size_t *k, int c) {
#if VW == 4
  return (vd){q[3 * k[0] + c], q[3 * k[1] + c], q[3 * k[2] + c], q[3 * k[3] + c]};
#else
  return (vd){q[3 * k[0] + c], q[3 * k[1] + c]};
#endif
}

static inline vd vd_pick(const double *v, const size_t *k) {
#if VW == 4
  return (vd){v[k[0]], v[k[1]], v[k[2]], v[k[3]]};
#else
  return (vd){v[k[0]], v[k[1]]};
#endif
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
#if VW == 4 && defined(__AVX__)
  return _mm256_movemask_pd((__m256d)mask);
#elif VW == 2 && defined(__SSE2__)
  return _mm_movemask_pd((__m128d)mask);
#else
  int bits = 0;
  for (int j = 0; j < VW; ++j) bits |= (int)(mask[j] & 1) << j;
  return bits;
#endif
}

/* finite: x − x is 0, not NaN */
static inline vdi vd_finite(vd a) { return a - a == 0.0; }

/* Four lanes whatever VW: kernels that sum across lanes (the kick's rows) use them in both
 * instantiations, so the order of their sums, and so their rounding, is the same on every CPU
 * (with VW = 2 the compiler runs each operation as two halves). */
typedef double v4 __attribute__((vector_size(32)));
typedef long long v4i __attribute__((vector_size(32)));

static inline v4 v4_sqrt(v4 a) {
#if defined(__AVX__)
  return (v4)_mm256_sqrt_pd((__m256d)a);
#elif defined(__SSE2__)
  const __m128d lo = _mm_sqrt_pd((__m128d){a[0], a[1]}), hi = _mm_sqrt_pd((__m128d){a[2], a[3]});
  return (v4){lo[0], lo[1], hi[0], hi[1]};
#else
  return (v4){sqrt(a[0]), sqrt(a[1]), sqrt(a[2]), sqrt(a[3])};
#endif
}

static inline v4 v4_load(const double *p) { return (v4){p[0], p[1], p[2], p[3]}; }
static inline v4 v4_splat(double x) { return (v4){x, x, x, x}; }

#endif
