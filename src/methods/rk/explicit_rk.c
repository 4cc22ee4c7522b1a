/* Stepper for explicit Runge–Kutta tableaux: stage i evaluates f at y + h Σ_{j<i} a_ij k_j. */
#include <stdlib.h>

#include "methods/internal.h"

typedef struct {
  gm_tableau *tab;
  double *k;      /* n_stages × n stage derivatives */
  double *stage;  /* n: the stage value */
} explicit_rk_work;

static gm_status init(gm_integrator *it) {
  explicit_rk_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  gm_status st = gm_method_tableau(it->method, &w->tab);
  if (st != GM_OK) return st;
  w->k = calloc(it->method->n_stages * it->n, sizeof *w->k);
  w->stage = calloc(it->n, sizeof *w->stage);
  return (w->k && w->stage) ? GM_OK : GM_ENOMEM;
}

static void release(gm_integrator *it) {
  explicit_rk_work *w = it->work;
  if (w == NULL) return;
  gm_tableau_free(w->tab);
  free(w->k);
  free(w->stage);
  free(w);
  it->work = NULL;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  explicit_rk_work *w = it->work;
  const gm_tableau *m = w->tab;
  const size_t n = it->n, s = m->n_stages;
  for (size_t i = 0; i < s; ++i) {
    const double *arg = y;
    if (i > 0) {
      for (size_t r = 0; r < n; ++r) {
        double sum = 0.0;
        for (size_t j = 0; j < i; ++j) sum += m->a[i * s + j] * w->k[j * n + r];
        w->stage[r] = y[r] + h * sum;
      }
      arg = w->stage;
    }
    gm_status st = gm_eval_rhs(it, t + m->c[i] * h, arg, w->k + i * n);
    if (st != GM_OK) return st;
  }
  for (size_t r = 0; r < n; ++r) {
    double sum = 0.0;
    for (size_t j = 0; j < s; ++j) sum += m->b[j] * w->k[j * n + r];
    if (delta != NULL)
      delta[r] = h * sum;
    else
      y_new[r] = y[r] + h * sum;
  }
  return GM_OK;
}

const gm_stepper gm_explicit_rk_stepper = {init, step, release, NULL, NULL, NULL, 0};
