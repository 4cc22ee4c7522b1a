/* Coefficients of collocation methods, computed when an integrator is created:
 *   a_ij = ∫_0^{c_i} l_j(τ) dτ,  b_j = ∫_0^1 l_j(τ) dτ,
 * l_j the Lagrange polynomials on the nodes c (Hairer, Nørsett & Wanner, Solving ODEs I (1993),
 * Thm II.7.7). Gauss–Legendre nodes give the Gauss methods (order 2s); Gauss–Lobatto nodes give
 * Lobatto IIIA, and its symplectic conjugate ā_ij = b_j (1 − a_ji / b_i) is Lobatto IIIB
 * (GNI (2006), §II.2 and Thm VI.4.6; Sun Geng 1993). The integrals are exact: an s-point
 * Gauss rule on [0, c_i] integrates the degree s−1 polynomials l_j. */
#include "methods/internal.h"

#define MAX_STAGES 64

static gm_status collocation(size_t s, const double *c, double *a, double *b) {
  double x[MAX_STAGES], w[MAX_STAGES], l[MAX_STAGES];
  if (s == 0 || s > MAX_STAGES) return GM_EINVAL;
  for (size_t i = 0; i <= s; ++i) {
    double upper = i < s ? c[i] : 1.0;  /* row i of A, then b */
    gm_status st = gm_gauss_legendre(s, x, w);
    if (st != GM_OK) return st;
    gm_quadrature_map(s, 0.0, upper, x, w);
    double *row = i < s ? a + i * s : b;
    for (size_t j = 0; j < s; ++j) row[j] = 0.0;
    for (size_t k = 0; k < s; ++k) {
      if ((st = gm_lagrange_basis(s, c, x[k], l)) != GM_OK) return st;
      for (size_t j = 0; j < s; ++j) row[j] += w[k] * l[j];
    }
  }
  return GM_OK;
}

gm_status gm_gauss_tableau(const gm_method *m, gm_tableau *t) {
  const size_t s = m->n_stages;
  double w[MAX_STAGES];
  if (s > MAX_STAGES) return GM_EINVAL;
  gm_status st = gm_gauss_legendre(s, t->c, w);
  if (st != GM_OK) return st;
  gm_quadrature_map(s, 0.0, 1.0, t->c, w);
  return collocation(s, t->c, t->a, t->b);
}

gm_status gm_lobatto_iiia_iiib_tableau(const gm_method *m, gm_tableau *t) {
  const size_t s = m->n_stages;
  double w[MAX_STAGES];
  if (s < 2 || s > MAX_STAGES) return GM_EINVAL;
  gm_status st = gm_gauss_lobatto(s, t->c, w);
  if (st != GM_OK) return st;
  gm_quadrature_map(s, 0.0, 1.0, t->c, w);
  if ((st = collocation(s, t->c, t->a, t->b)) != GM_OK) return st;
  for (size_t i = 0; i < s; ++i) {
    t->b_bar[i] = t->b[i];
    for (size_t j = 0; j < s; ++j) t->a_bar[i * s + j] = t->b[j] * (1.0 - t->a[j * s + i] / t->b[i]);
  }
  return GM_OK;
}
