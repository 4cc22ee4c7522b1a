/* gm_method_tableau: a method's coefficients in arrays sized for its family, copied from the
 * literal table or computed from closed forms. */
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

void gm_tableau_free(gm_tableau *t) {
  if (t == NULL) return;
  free(t->a);
  free(t->b);
  free(t->c);
  free(t->a_bar);
  free(t->b_bar);
  free(t->gamma);
  free(t);
}

static double *copy_or_zero(const double *src, size_t n) {
  double *dst = calloc(n ? n : 1, sizeof *dst);
  if (dst != NULL && src != NULL) memcpy(dst, src, n * sizeof *dst);
  return dst;
}

gm_status gm_method_tableau(const gm_method *m, gm_tableau **out) {
  if (m == NULL || out == NULL) return GM_EINVAL;
  *out = NULL;
  const size_t s = m->n_stages;
  if (s == 0) return GM_EINVAL;
  gm_tableau *t = calloc(1, sizeof *t);
  if (t == NULL) return GM_ENOMEM;
  t->n_stages = s;
  int ok = 1;
  switch (m->family) {
    case GM_FAMILY_EXPLICIT_RK:
    case GM_FAMILY_IMPLICIT_RK:
    case GM_FAMILY_MIMETIC: /* mimetic-canonical-p is a Runge–Kutta method (seed 003 §5.3) */
      ok = (t->a = copy_or_zero(m->a, s * s)) && (t->b = copy_or_zero(m->b, s)) &&
           (t->c = copy_or_zero(m->c, s));
      break;
    case GM_FAMILY_SPLITTING:
    case GM_FAMILY_NEAR_INTEGRABLE: /* drift (Kepler) a_i, kick (interaction) b_i */
      ok = (t->a = copy_or_zero(m->a, s)) && (t->b = copy_or_zero(m->b, s));
      break;
    case GM_FAMILY_COMPOSITION:
      ok = (t->gamma = copy_or_zero(m->gamma, s)) != NULL;
      break;
    case GM_FAMILY_PARTITIONED_RK:
    case GM_FAMILY_VARIATIONAL: /* the equivalent partitioned RK (seed 001 Thm 2.12) */
      ok = (t->a = copy_or_zero(m->a, s * s)) && (t->b = copy_or_zero(m->b, s)) &&
           (t->c = copy_or_zero(m->c, s)) && (t->a_bar = copy_or_zero(NULL, s * s)) &&
           (t->b_bar = copy_or_zero(NULL, s));
      break;
    case GM_FAMILY_DISCRETE_GRADIENT: /* no coefficients */
    case GM_FAMILY_OSCILLATORY:       /* filter functions, not coefficients */
      break;
    case GM_FAMILY_LIE_GROUP: /* RKMK, Crouch–Grossman: a Butcher tableau; others: none */
      if (m->a != NULL || m->compute != NULL)
        ok = (t->a = copy_or_zero(m->a, s * s)) && (t->b = copy_or_zero(m->b, s)) &&
             (t->c = copy_or_zero(m->c, s));
      break;
  }
  if (!ok) {
    gm_tableau_free(t);
    return GM_ENOMEM;
  }
  if (m->compute != NULL) {
    gm_status st = m->compute(m, t);
    if (st != GM_OK) {
      gm_tableau_free(t);
      return st;
    }
  }
  *out = t;
  return GM_OK;
}
