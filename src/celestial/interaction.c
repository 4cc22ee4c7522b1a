/* The Newtonian interaction evaluated by the splitting itself, for problems whose gm_celestial
 * says V is exactly point-mass gravity (gm_celestial.newtonian): the pair sums
 *   a_i = Σ_{j≠i} G m_j (q_j − q_i)/|q_j − q_i|³.
 * In three passes over a block of whole rows of pairs (i, j > i): the squared distances, their
 * 1/s^{3/2} several at a time in vector lanes (gm_inverse_cubes: a kick's cost is these square
 * roots and divisions, which queue on the one divider, and lanes divide it), then the sums,
 * row by row so that a_i accumulates in registers. Work memory is one block, whatever the
 * number of bodies. */
#include <string.h>

#include "celestial/internal.h"

#define BLOCK 64

/* Rows i0..i1−1, pairs (i, j) with j from max(i + 1, j_from) (j_from only for the first row,
 * which may continue a row split across blocks) to n − 1. */
static int block(size_t n, size_t i0, size_t i1, size_t j_from, const double *m, double G,
                 const double *q, double *a) {
  double s[BLOCK], w[BLOCK];
  size_t p = 0;
  for (size_t i = i0; i < i1; ++i) {
    const double *qi = q + 3 * i;
    for (size_t j = i == i0 && j_from > i + 1 ? j_from : i + 1; j < n && p < BLOCK; ++j, ++p) {
      const double *qj = q + 3 * j;
      const double dx = qj[0] - qi[0], dy = qj[1] - qi[1], dz = qj[2] - qi[2];
      s[p] = dx * dx + dy * dy + dz * dz;
      if (s[p] == 0.0) return 1;
    }
  }
  gm_inverse_cubes(p, s, w);
  p = 0;
  for (size_t i = i0; i < i1; ++i) {
    const double *qi = q + 3 * i;
    double ax = 0.0, ay = 0.0, az = 0.0;
    const double gmi = G * m[i];
    for (size_t j = i == i0 && j_from > i + 1 ? j_from : i + 1; j < n && p < BLOCK; ++j, ++p) {
      const double *qj = q + 3 * j;
      const double dx = qj[0] - qi[0], dy = qj[1] - qi[1], dz = qj[2] - qi[2];
      const double fi = G * m[j] * w[p], fj = gmi * w[p];
      ax += fi * dx;
      ay += fi * dy;
      az += fi * dz;
      double *aj = a + 3 * j;
      aj[0] -= fj * dx;
      aj[1] -= fj * dy;
      aj[2] -= fj * dz;
    }
    a[3 * i] += ax;
    a[3 * i + 1] += ay;
    a[3 * i + 2] += az;
  }
  return 0;
}

int gm_newtonian_accelerations(size_t n, size_t first, const double *m, double G,
                               const double *q, double *a) {
  memset(a + 3 * first, 0, 3 * (n - first) * sizeof *a);
  size_t i = first, j_from = 0;
  while (i + 1 < n) {
    /* as many whole rows as fit (row i has n − 1 − i pairs); a longer row goes in pieces */
    size_t i1 = i, pairs = 0, start = j_from > i + 1 ? j_from : i + 1;
    while (i1 + 1 < n && pairs + (n - (i1 == i ? start : i1 + 1)) <= BLOCK)
      pairs += n - (i1 == i ? start : i1 + 1), ++i1;
    if (i1 == i) { /* row i alone is longer than a block: its next BLOCK pairs */
      if (block(n, i, i + 1, start, m, G, q, a)) return 1;
      j_from = start + BLOCK;
      if (j_from >= n) ++i, j_from = 0;
      continue;
    }
    if (block(n, i, i1, start, m, G, q, a)) return 1;
    i = i1;
    j_from = 0;
  }
  return 0;
}
