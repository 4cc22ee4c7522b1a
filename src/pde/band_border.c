/* Banded LU with partial pivoting of a matrix whose entries lie in the band kl below / ku above
 * the diagonal plus a dense border of the last nb columns: the shape of a periodic chain of
 * blocks in natural order, whose wrap-around block is the border. Row interchanges stay within
 * kl rows, so U keeps the band kl + ku and the border, and nothing else fills.
 *
 * Memory (issue 28): the factorization is made with one right-hand side, eliminated with it as
 * the rows arrive, so the multipliers of L are never kept. Rows live in a small ring window of
 * full LINPACK-width rows (layout as band.c) while they are eliminated; a finished pivot row
 * keeps only its U part, packed. The lower profile is block-aligned with block size bs: the
 * entries below the diagonal of column k lie in rows < bs⌊k/bs⌋ + kl + 1 (true for the block
 * chain, whose kl = 2·bs − 1, and for any band with bs = 1), so row k of U ends at column
 * bs⌊k/bs⌋ + kl + ku: kl + ku + 1 − (k mod bs) entries. Rows and columns outside that profile
 * hold structural zeros, so leaving them out changes no floating-point operation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pde/internal.h"

/* packed U: rows of one block have kl + ku + 1 − j entries, j = 0..bs−1 */
static size_t ulen(const gm_bband *b, size_t k) { return b->kl + b->ku + 1 - k % b->bs; }
static size_t uoff(const gm_bband *b, size_t k) {
  size_t j = k % b->bs, L = b->kl + b->ku + 1;
  return (k / b->bs) * b->ublock + j * L - j * (j - 1) / 2;
}

gm_status gm_bband_init(gm_bband *b, size_t n, size_t kl, size_t ku, size_t nb, size_t bs) {
  memset(b, 0, sizeof *b);
  if (nb > n || bs == 0 || bs > kl + ku + 1) return GM_EINVAL;
  b->n = n;
  b->kl = kl;
  b->ku = ku;
  b->nb = nb;
  b->bs = bs;
  b->w = 2 * kl + ku + 1;
  b->ublock = bs * (kl + ku + 1) - bs * (bs - 1) / 2;
  b->nwin = bs * ((kl + 1 + bs - 1) / bs + 1); /* column block c needs rows of c..c + ⌈(kl+1)/bs⌉ */
  size_t nbb = nb > 0 ? nb : 1;
  b->win = calloc(b->nwin * (b->w + nbb), sizeof *b->win);
  b->u = calloc((n + bs - 1) / bs * b->ublock, sizeof *b->u);
  b->border = calloc(n * nbb, sizeof *b->border);
  if (b->win == NULL || b->u == NULL || b->border == NULL) {
    gm_bband_release(b);
    return GM_ENOMEM;
  }
  return GM_OK;
}

void gm_bband_release(gm_bband *b) {
  free(b->win);
  free(b->u);
  free(b->border);
  b->win = b->u = b->border = NULL;
}

size_t gm_bband_bytes(const gm_bband *b) {
  size_t nbb = b->nb > 0 ? b->nb : 1;
  return (b->nwin * (b->w + nbb) + (b->n + b->bs - 1) / b->bs * b->ublock + b->n * nbb) *
         sizeof(double);
}

void gm_bband_reset(gm_bband *b) {
  size_t nbb = b->nb > 0 ? b->nb : 1;
  memset(b->win, 0, b->nwin * (b->w + nbb) * sizeof *b->win);
  b->k = 0;
}

/* entry (r, c) of a row in the window: the border for the last nb columns, else the band */
static double *ent(const gm_bband *b, size_t r, size_t c) {
  double *row = b->win + (r % b->nwin) * (b->w + (b->nb > 0 ? b->nb : 1));
  if (c >= b->n - b->nb) return &row[b->w + (c - (b->n - b->nb))];
  return &row[c + b->kl - r];
}

void gm_bband_add(gm_bband *b, size_t r, size_t c, double v) { *ent(b, r, c) += v; }

/* row k is final: keep its U part (band from the diagonal, and the border), free its slot */
static void retire(gm_bband *b, size_t k, size_t cband) {
  size_t c0 = b->n - b->nb;
  double *u = b->u + uoff(b, k);
  for (size_t c = k; c <= cband && c < c0; c++) u[c - k] = *ent(b, k, c);
  double *row = b->win + (k % b->nwin) * (b->w + (b->nb > 0 ? b->nb : 1));
  memcpy(b->border + k * b->nb, row + b->w, b->nb * sizeof *row);
  memset(row, 0, (b->w + (b->nb > 0 ? b->nb : 1)) * sizeof *row);
}

gm_status gm_bband_eliminate(gm_bband *b, size_t kend, double *rhs) {
  size_t n = b->n, c0 = n - b->nb; /* first border column */
  if (kend > n) kend = n;
  for (size_t k = b->k; k < kend; k++) {
    size_t top = k - k % b->bs; /* the profile: rows < top + kl + 1, U columns ≤ top + kl + ku */
    size_t rmax = top + b->kl < n - 1 ? top + b->kl : n - 1;
    size_t cband = top + b->kl + b->ku < c0 - 1 ? top + b->kl + b->ku : c0 - 1; /* last band col */
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
        t = *ent(b, k, c0 + c);
        *ent(b, k, c0 + c) = *ent(b, p, c0 + c);
        *ent(b, p, c0 + c) = t;
      }
      t = rhs[k];
      rhs[k] = rhs[p];
      rhs[p] = t;
    }
    double pivot = *ent(b, k, k);
    for (size_t r = k + 1; r <= rmax; r++) {
      double m = *ent(b, r, k) / pivot;
      rhs[r] -= m * rhs[k];
      if (m == 0.0) continue;
      if (k < c0)
        for (size_t c = k + 1; c <= cband && c < c0; c++) *ent(b, r, c) -= m * *ent(b, k, c);
      for (size_t c = bfirst; c < b->nb; c++) *ent(b, r, c0 + c) -= m * *ent(b, k, c0 + c);
    }
    retire(b, k, cband);
    b->k = k + 1;
  }
  return GM_OK;
}

void gm_bband_back(const gm_bband *b, double *x) {
  size_t n = b->n, c0 = n - b->nb;
  for (size_t k = n; k-- > 0;) {
    double s = x[k];
    const double *u = b->u + uoff(b, k), *br = b->border + k * b->nb;
    size_t len = ulen(b, k);
    if (k < c0)
      for (size_t c = k + 1; c < k + len && c < c0; c++) s -= u[c - k] * x[c];
    for (size_t c = k + 1 > c0 ? k + 1 - c0 : 0; c < b->nb; c++) s -= br[c] * x[c0 + c];
    x[k] = s / (k < c0 ? u[0] : br[k - c0]);
  }
}
