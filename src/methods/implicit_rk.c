/* Stepper for implicit Runge–Kutta methods. The unknowns are the stage increments
 * Z_i = Y_i − y_n, solving Z_i = h Σ_j a_ij f(t + c_j h, y_n + Z_j) by Newton's method with
 * the exact Jacobian δ_ij I − h a_ij ∂f(y_n + Z_j). The update y_{n+1} = y_n + Σ_j d_j Z_j with
 * dᵀ = bᵀA⁻¹ needs no extra evaluation of f (Hairer & Wanner, Solving ODEs II (1996), §IV.8,
 * eq. (8.2b)). */
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

typedef struct {
  gm_newton *newton;
  double *z;          /* s·n stage increments, the Newton unknowns */
  double *z_prev;     /* last step's increments: the starting guess for an equal step */
  double *f;          /* s·n values f(Y_j) */
  double *stage;      /* n */
  double *jac;        /* n×n Jacobian of f at one stage */
  double *d;          /* s weights of the update, bᵀA⁻¹ */
  double h_prev;      /* step size of z_prev, 0 when there is none */
  /* the step being solved, seen by the Newton callbacks */
  gm_integrator *it;
  const double *y;
  double t, h;
  gm_status callback_status;
} implicit_rk_work;

static gm_status init(gm_integrator *it) {
  implicit_rk_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  const gm_method *m = it->method;
  const size_t n = it->n, s = m->n_stages;
  w->z = calloc(s * n, sizeof(double));
  w->z_prev = calloc(s * n, sizeof(double));
  w->f = calloc(s * n, sizeof(double));
  w->stage = calloc(n, sizeof(double));
  w->jac = calloc(n * n, sizeof(double));
  w->d = calloc(s, sizeof(double));
  double *at = calloc(s * s, sizeof(double));
  if (!w->z || !w->z_prev || !w->f || !w->stage || !w->jac || !w->d || !at) {
    free(at);
    return GM_ENOMEM;
  }
  /* Aᵀ d = b */
  for (size_t i = 0; i < s; ++i) {
    w->d[i] = m->b[i];
    for (size_t j = 0; j < s; ++j) at[i * s + j] = m->a[j * s + i];
  }
  gm_status st = gm_dense_solve(s, at, w->d);
  free(at);
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st,
                   "method '%s': its matrix A is singular, the update weights bᵀA⁻¹ do not exist",
                   m->name);
  return gm_newton_create(s * n, NULL, &w->newton);
}

static void release(gm_integrator *it) {
  implicit_rk_work *w = it->work;
  if (w == NULL) return;
  gm_newton_free(w->newton);
  free(w->z);
  free(w->z_prev);
  free(w->f);
  free(w->stage);
  free(w->jac);
  free(w->d);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  implicit_rk_work *w = it->work;
  if (w != NULL) w->h_prev = 0.0;
}

/* R_i = Z_i − h Σ_j a_ij f(t + c_j h, y + Z_j) */
static int stage_residual(void *ctx, const double *z, double *r) {
  implicit_rk_work *w = ctx;
  gm_integrator *it = w->it;
  const gm_method *m = it->method;
  const size_t n = it->n, s = m->n_stages;
  for (size_t j = 0; j < s; ++j) {
    for (size_t k = 0; k < n; ++k) w->stage[k] = w->y[k] + z[j * n + k];
    w->callback_status = gm_eval_rhs(it, w->t + m->c[j] * w->h, w->stage, w->f + j * n);
    if (w->callback_status != GM_OK) return 1;
  }
  for (size_t i = 0; i < s; ++i)
    for (size_t k = 0; k < n; ++k) {
      double sum = 0.0;
      for (size_t j = 0; j < s; ++j) sum += m->a[i * s + j] * w->f[j * n + k];
      r[i * n + k] = z[i * n + k] - w->h * sum;
    }
  return 0;
}

/* Block (i, j) of the Jacobian: δ_ij I − h a_ij ∂f(y + Z_j). */
static int stage_jacobian(void *ctx, const double *z, double *jac) {
  implicit_rk_work *w = ctx;
  gm_integrator *it = w->it;
  const gm_method *m = it->method;
  const size_t n = it->n, s = m->n_stages, ns = n * s;
  for (size_t j = 0; j < s; ++j) {
    for (size_t k = 0; k < n; ++k) w->stage[k] = w->y[k] + z[j * n + k];
    w->callback_status = gm_eval_rhs_jacobian(it, w->t + m->c[j] * w->h, w->stage, w->jac);
    if (w->callback_status != GM_OK) return 1;
    for (size_t i = 0; i < s; ++i) {
      double coef = -w->h * m->a[i * s + j];
      for (size_t r = 0; r < n; ++r)
        for (size_t c = 0; c < n; ++c)
          jac[(i * n + r) * ns + j * n + c] = coef * w->jac[r * n + c] + (i == j && r == c);
    }
  }
  return 0;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  implicit_rk_work *w = it->work;
  const gm_method *m = it->method;
  const size_t n = it->n, s = m->n_stages;
  w->it = it;
  w->y = y;
  w->t = t;
  w->h = h;
  w->callback_status = GM_OK;
  if (w->h_prev == h)
    memcpy(w->z, w->z_prev, s * n * sizeof *w->z);
  else
    memset(w->z, 0, s * n * sizeof *w->z);
  gm_status st = gm_newton_solve(w->newton, stage_residual, stage_jacobian, w, w->z);
  it->stats.newton_iterations += gm_newton_iterations(w->newton);
  if (st != GM_OK) {
    w->h_prev = 0.0;
    if (st == GM_ECALLBACK && w->callback_status != GM_OK) return w->callback_status;
    it->stats.newton_failures++;
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s: %s in the step from t = %.17g (h = %g)",
                   m->name, gm_newton_errmsg(w->newton), t, h);
  }
  memcpy(w->z_prev, w->z, s * n * sizeof *w->z);
  w->h_prev = h;
  for (size_t k = 0; k < n; ++k) {
    double sum = 0.0;
    for (size_t j = 0; j < s; ++j) sum += w->d[j] * w->z[j * n + k];
    if (delta != NULL)
      delta[k] = sum;
    else
      y_new[k] = y[k] + sum;
  }
  return GM_OK;
}

const gm_stepper gm_implicit_rk_stepper = {init, step, release, invalidate, NULL};
