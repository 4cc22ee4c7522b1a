/* Banded LU with partial pivoting (the dgbtrf/dgbtrs algorithm, written out) and the
 * interleaved ordering that turns a periodic ring of blocks into a band. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pde/internal.h"

gm_status gm_band_init(gm_band *b, size_t n, size_t kl, size_t ku) {
  b->n = n;
  b->kl = kl;
  b->ku = ku;
  b->w = 2 * kl + ku + 1;
  b->ab = calloc(n * b->w, sizeof *b->ab);
  b->piv = calloc(n, sizeof *b->piv);
  if (b->ab == NULL || b->piv == NULL) {
    gm_band_release(b);
    return GM_ENOMEM;
  }
  return GM_OK;
}

void gm_band_release(gm_band *b) {
  free(b->ab);
  free(b->piv);
  b->ab = NULL;
  b->piv = NULL;
}

void gm_band_zero(gm_band *b) { memset(b->ab, 0, b->n * b->w * sizeof *b->ab); }

static double *at(const gm_band *b, size_t r, size_t c) {
  return &b->ab[r * b->w + (c + b->kl - r)];
}

void gm_band_add(gm_band *b, size_t r, size_t c, double v) { *at(b, r, c) += v; }

gm_status gm_band_factor(gm_band *b) {
  size_t n = b->n;
  for (size_t k = 0; k < n; k++) {
    size_t rmax = k + b->kl < n - 1 ? k + b->kl : n - 1;
    size_t cmax = k + b->kl + b->ku < n - 1 ? k + b->kl + b->ku : n - 1;
    size_t p = k;
    double best = fabs(*at(b, k, k));
    for (size_t r = k + 1; r <= rmax; r++) {
      double a = fabs(*at(b, r, k));
      if (a > best) {
        best = a;
        p = r;
      }
    }
    if (!(best > 0.0)) return GM_ESINGULAR;
    b->piv[k] = (int)p;
    if (p != k)
      for (size_t c = k; c <= cmax; c++) {
        double t = *at(b, k, c);
        *at(b, k, c) = *at(b, p, c);
        *at(b, p, c) = t;
      }
    double pivot = *at(b, k, k);
    for (size_t r = k + 1; r <= rmax; r++) {
      double m = *at(b, r, k) / pivot;
      *at(b, r, k) = m;
      if (m == 0.0) continue;
      for (size_t c = k + 1; c <= cmax; c++) *at(b, r, c) -= m * *at(b, k, c);
    }
  }
  return GM_OK;
}

void gm_band_solve(const gm_band *b, double *x) {
  size_t n = b->n;
  for (size_t k = 0; k < n; k++) {
    size_t p = (size_t)b->piv[k];
    if (p != k) {
      double t = x[k];
      x[k] = x[p];
      x[p] = t;
    }
    size_t rmax = k + b->kl < n - 1 ? k + b->kl : n - 1;
    for (size_t r = k + 1; r <= rmax; r++) x[r] -= *at(b, r, k) * x[k];
  }
  for (size_t k = n; k-- > 0;) {
    size_t cmax = k + b->kl + b->ku < n - 1 ? k + b->kl + b->ku : n - 1;
    double s = x[k];
    for (size_t c = k + 1; c <= cmax; c++) s -= *at(b, k, c) * x[c];
    x[k] = s / *at(b, k, k);
  }
}

void gm_ring_positions(size_t n, size_t *pos) {
  for (size_t p = 0; p < n; p++) {
    size_t block = p % 2 == 0 ? p / 2 : n - 1 - (p - 1) / 2;
    pos[block] = p;
  }
}
