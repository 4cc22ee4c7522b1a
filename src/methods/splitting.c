/* Stepper for drift–kick splitting methods on separable H = T(p) + V(q).
 * Stage i: drift q += a_i h ∇T(p), then kick p -= b_i h ∇V(q); zero coefficients are skipped.
 * When the first operation is a kick (a_0 = 0) and the last one too (b_{s-1} ≠ 0), the last
 * force of a step is the first of the next one and is reused (first same as last). */
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

typedef struct {
  double *force;      /* ∇V at the last kick point */
  double *velocity;   /* ∇T at the last drift point */
  double *q_eval;     /* compensated mode: q + Δq */
  double *p_eval;     /* compensated mode: p + Δp */
  int fsal;           /* the method's coefficients allow reuse */
  int force_valid;    /* `force` holds ∇V at the current state's q */
} splitting_work;

static gm_status init(gm_integrator *it) {
  splitting_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  const size_t d = it->dim, s = it->method->n_stages;
  w->force = calloc(d, sizeof(double));
  w->velocity = calloc(d, sizeof(double));
  w->q_eval = calloc(d, sizeof(double));
  w->p_eval = calloc(d, sizeof(double));
  w->fsal = it->method->a[0] == 0.0 && it->method->b[s - 1] != 0.0;
  return (w->force && w->velocity && w->q_eval && w->p_eval) ? GM_OK : GM_ENOMEM;
}

static void release(gm_integrator *it) {
  splitting_work *w = it->work;
  if (w == NULL) return;
  free(w->force);
  free(w->velocity);
  free(w->q_eval);
  free(w->p_eval);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  splitting_work *w = it->work;
  if (w != NULL) w->force_valid = 0;
}

/* dst = src + c·v (dst may equal src). */
static void axpy_into(size_t d, double *dst, const double *src, double c, const double *v) {
  for (size_t i = 0; i < d; ++i) dst[i] = src[i] + c * v[i];
}

/* In place on a separate output buffer: each half of y_new is first written from y. */
static gm_status step_direct(gm_integrator *it, double t, double h, const double *y,
                             double *y_new) {
  splitting_work *w = it->work;
  const gm_method *m = it->method;
  const size_t d = it->dim, s = m->n_stages;
  const double *q = y, *p = y + d;
  double *q_new = y_new, *p_new = y_new + d;
  int reuse = w->fsal && w->force_valid;
  w->force_valid = 0;
  for (size_t i = 0; i < s; ++i) {
    if (m->a[i] != 0.0) {
      gm_status st = gm_eval_kinetic_gradient(it, t, p, w->velocity);
      if (st != GM_OK) return st;
      axpy_into(d, q_new, q, m->a[i] * h, w->velocity);
      q = q_new;
    }
    if (m->b[i] != 0.0) {
      if (!(i == 0 && reuse)) {
        gm_status st = gm_eval_potential_gradient(it, t, q, w->force);
        if (st != GM_OK) return st;
      }
      axpy_into(d, p_new, p, -m->b[i] * h, w->force);
      p = p_new;
    }
  }
  if (q != q_new) memcpy(q_new, q, d * sizeof *q);
  if (p != p_new) memcpy(p_new, p, d * sizeof *p);
  w->force_valid = w->fsal;
  return GM_OK;
}

/* Accumulate the increments Δq, Δp; forces are evaluated at q + Δq, p + Δp. */
static gm_status step_increment(gm_integrator *it, double t, double h, const double *y,
                                double *delta) {
  splitting_work *w = it->work;
  const gm_method *m = it->method;
  const size_t d = it->dim, s = m->n_stages;
  const double *q = y, *p = y + d;
  double *dq = delta, *dp = delta + d;
  memset(delta, 0, 2 * d * sizeof *delta);
  w->force_valid = 0;
  for (size_t i = 0; i < s; ++i) {
    if (m->a[i] != 0.0) {
      axpy_into(d, w->p_eval, p, 1.0, dp);
      gm_status st = gm_eval_kinetic_gradient(it, t, w->p_eval, w->velocity);
      if (st != GM_OK) return st;
      axpy_into(d, dq, dq, m->a[i] * h, w->velocity);
    }
    if (m->b[i] != 0.0) {
      axpy_into(d, w->q_eval, q, 1.0, dq);
      gm_status st = gm_eval_potential_gradient(it, t, w->q_eval, w->force);
      if (st != GM_OK) return st;
      axpy_into(d, dp, dp, -m->b[i] * h, w->force);
    }
  }
  return GM_OK;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  return delta != NULL ? step_increment(it, t, h, y, delta) : step_direct(it, t, h, y, y_new);
}

const gm_stepper gm_splitting_stepper = {init, step, release, invalidate};
