/* Banded LU with partial pivoting of a matrix whose entries lie in the band kl below / ku above
 * the diagonal plus a dense border of the last nb columns: the shape of a periodic chain of
 * blocks in natural order, whose wrap-around block is the border. Row interchanges stay within
 * kl rows, so L keeps kl sub-diagonals, U the band kl + ku and the border, and nothing else
 * fills: O(n·(2kl + ku + 1 + nb)) memory, against O(n·(6·block)) for the interleaved ring
 * ordering. LINPACK-style storage as band.c (the multipliers of column k stay where they were
 * made; the solve replays the interchanges in order). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pde/internal.h"

gm_status gm_bband_init(gm_bband *b, size_t n, size_t kl, size_t ku, size_t nb) {
  memset(b, 0, sizeof *b);
  if (nb > n) return GM_EINVAL;
  b->n = n;
  b->kl = kl;
  b->ku = ku;
  b->nb = nb;
  b->w = 2 * kl + ku + 1;
  b->ab = calloc(n * b->w, sizeof *b->ab);
  b->border = calloc(n * (nb > 0 ? nb : 1), sizeof *b->border);
  b->piv = calloc(n, sizeof *b->piv);
  if (b->ab == NULL || b->border == NULL || b->piv == NULL) {
    gm_bband_release(b);
    return GM_ENOMEM;
  }
  return GM_OK;
}

void gm_bband_release(gm_bband *b) {
  free(b->ab);
  free(b->border);
  free(b->piv);
  b->ab = b->border = NULL;
  b->piv = NULL;
}

void gm_bband_zero(gm_bband *b) {
  memset(b->ab, 0, b->n * b->w * sizeof *b->ab);
  memset(b->border, 0, b->n * b->nb * sizeof *b->border);
}

/* entry (r, c): the border for the last nb columns, else the band */
static double *ent(const gm_bband *b, size_t r, size_t c) {
  if (c >= b->n - b->nb) return &b->border[r * b->nb + (c - (b->n - b->nb))];
  return &b->ab[r * b->w + (c + b->kl - r)];
}

void gm_bband_add(gm_bband *b, size_t r, size_t c, double v) { *ent(b, r, c) += v; }

gm_status gm_bband_factor(gm_bband *b) {
  size_t n = b->n, c0 = n - b->nb; /* first border column */
  for (size_t k = 0; k < n; k++) {
    size_t rmax = k + b->kl < n - 1 ? k + b->kl : n - 1;
    size_t cband = k + b->kl + b->ku < c0 - 1 ? k + b->kl + b->ku : c0 - 1; /* last band col */
    size_t bfirst = k + 1 > c0 ? k + 1 - c0 : 0; /* border columns > k */
    size_t p = k;
    double best = fabs(*ent(b, k, k));
    for (size_t r = k + 1; r <= rmax; r++) {
      double a = fabs(*ent(b, r, k));
      if (a > best) {
        best = a;
        p = r;
      }
    }
    if (!(best > 0.0)) return GM_ESINGULAR;
    b->piv[k] = (int)p;
    if (p != k) {
      double t = *ent(b, k, k);
      *ent(b, k, k) = *ent(b, p, k);
      *ent(b, p, k) = t;
      if (k < c0)
        for (size_t c = k + 1; c <= cband && c < c0; c++) {
          t = *ent(b, k, c);
          *ent(b, k, c) = *ent(b, p, c);
          *ent(b, p, c) = t;
        }
      for (size_t c = bfirst; c < b->nb; c++) {
        t = b->border[k * b->nb + c];
        b->border[k * b->nb + c] = b->border[p * b->nb + c];
        b->border[p * b->nb + c] = t;
      }
    }
    double pivot = *ent(b, k, k);
    for (size_t r = k + 1; r <= rmax; r++) {
      double m = *ent(b, r, k) / pivot;
      *ent(b, r, k) = m;
      if (m == 0.0) continue;
      if (k < c0)
        for (size_t c = k + 1; c <= cband && c < c0; c++) *ent(b, r, c) -= m * *ent(b, k, c);
      for (size_t c = bfirst; c < b->nb; c++)
        b->border[r * b->nb + c] -= m * b->border[k * b->nb + c];
    }
  }
  return GM_OK;
}

void gm_bband_solve(const gm_bband *b, double *x) {
  size_t n = b->n, c0 = n - b->nb;
  for (size_t k = 0; k < n; k++) {
    size_t p = (size_t)b->piv[k];
    if (p != k) {
      double t = x[k];
      x[k] = x[p];
      x[p] = t;
    }
    size_t rmax = k + b->kl < n - 1 ? k + b->kl : n - 1;
    for (size_t r = k + 1; r <= rmax; r++) x[r] -= *ent(b, r, k) * x[k];
  }
  for (size_t k = n; k-- > 0;) {
    double s = x[k];
    size_t cband = k + b->kl + b->ku < c0 - 1 ? k + b->kl + b->ku : c0 - 1;
    if (k < c0)
      for (size_t c = k + 1; c <= cband && c < c0; c++) s -= *ent(b, k, c) * x[c];
    for (size_t c = k + 1 > c0 ? k + 1 - c0 : 0; c < b->nb; c++)
      s -= b->border[k * b->nb + c] * x[c0 + c];
    x[k] = s / *ent(b, k, k);
  }
}
