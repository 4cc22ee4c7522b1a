/* Stepper for compositions Φ_{γ_s h} ∘ … ∘ Φ_{γ_1 h} of a symmetric basic method Φ that is not
 * a splitting method (those are merged into one operation list by the splitting stepper):
 * e.g. the sixth-order composition of the implicit midpoint rule for a non-separable H.
 * The basic method runs in an inner integrator of its own; its statistics are added to ours.
 * Composition theory: Hairer, Lubich & Wanner, GNI (2006), §II.4 and §V.3. */
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

typedef struct {
  gm_tableau *tab;     /* γ */
  gm_integrator *inner;
  double *buf[2];      /* intermediate states */
  double *accum;       /* compensated mode: Σ δ_i */
} composition_work;

static gm_status init(gm_integrator *it) {
  composition_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  gm_status st = gm_method_tableau(it->method, &w->tab);
  if (st != GM_OK) return st;
  gm_error err = {{0}};
  st = gm_integrator_create(it->basic, it->problem, &w->inner, &err);
  if (st != GM_OK) return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", err.message);
  w->buf[0] = calloc(it->n, sizeof(double));
  w->buf[1] = calloc(it->n, sizeof(double));
  w->accum = calloc(it->n, sizeof(double));
  return (w->buf[0] && w->buf[1] && w->accum) ? GM_OK : GM_ENOMEM;
}

static void release(gm_integrator *it) {
  composition_work *w = it->work;
  if (w == NULL) return;
  gm_tableau_free(w->tab);
  gm_integrator_free(w->inner);
  free(w->buf[0]);
  free(w->buf[1]);
  free(w->accum);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  composition_work *w = it->work;
  if (w != NULL && w->inner->stepper->invalidate != NULL) w->inner->stepper->invalidate(w->inner);
}

static void add_stats(gm_stats *to, gm_stats *from) {
  to->force_evals += from->force_evals;
  to->jacobian_evals += from->jacobian_evals;
  to->fd_jacobians += from->fd_jacobians;
  to->newton_iterations += from->newton_iterations;
  to->fixed_point_iterations += from->fixed_point_iterations;
  to->newton_failures += from->newton_failures;
  memset(from, 0, sizeof *from);
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  composition_work *w = it->work;
  gm_integrator *in = w->inner;
  const size_t n = it->n, s = w->tab->n_stages;
  const double *cur = y;
  double t_i = t;
  gm_status st = GM_OK;
  if (delta != NULL) memset(w->accum, 0, n * sizeof *w->accum);
  for (size_t i = 0; i < s && st == GM_OK; ++i) {
    const double h_i = w->tab->gamma[i] * h;
    if (delta == NULL) {
      double *out = i + 1 == s ? y_new : w->buf[i % 2];
      st = in->stepper->step(in, t_i, h_i, cur, out, NULL);
      cur = out;
    } else {
      /* evaluate at y + Σδ, accumulate the small increments separately */
      double *at = w->buf[i % 2];
      for (size_t k = 0; k < n; ++k) at[k] = y[k] + w->accum[k];
      st = in->stepper->step(in, t_i, h_i, i == 0 ? y : at, NULL, delta);
      for (size_t k = 0; st == GM_OK && k < n; ++k) w->accum[k] += delta[k];
    }
    t_i += h_i;
  }
  add_stats(&it->stats, &in->stats);
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s of %s: %s", it->method->name,
                   it->basic->name, in->errmsg);
  if (delta != NULL) memcpy(delta, w->accum, n * sizeof *delta);
  return GM_OK;
}

static gm_status set_solver(gm_integrator *it, gm_solver solver) {
  composition_work *w = it->work;
  gm_status st = gm_integrator_set_solver(w->inner, solver);
  if (st != GM_OK) gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", w->inner->errmsg);
  else it->solver = w->inner->solver; /* the one the basic method chose */
  return st;
}

const gm_stepper gm_composition_stepper = {init, step, release, invalidate, NULL, set_solver, 0};

/* Checkpoints: the state of the basic method's integrator (its starting values). */
static const gm_stepper_state *inner_state(const gm_integrator *it) {
  const composition_work *w = it->work;
  return gm_stepper_state_of(w->inner->stepper);
}
static size_t state_size(const gm_integrator *it) {
  const gm_stepper_state *s = inner_state(it);
  const composition_work *w = it->work;
  return s != NULL && s->size != NULL ? s->size(w->inner) : 0;
}
static void state_save(const gm_integrator *it, unsigned char *out) {
  const gm_stepper_state *s = inner_state(it);
  const composition_work *w = it->work;
  if (s != NULL && s->save != NULL) s->save(w->inner, out);
}
static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  const gm_stepper_state *s = inner_state(it);
  composition_work *w = it->work;
  return s != NULL && s->load != NULL ? s->load(w->inner, in) : GM_OK;
}
const gm_stepper_state gm_composition_stepper_state = {0, state_size, state_save, state_load};
