/* Stepper for drift–kick splitting methods on separable H = T(p) + V(q), and for compositions
 * of them (yoshida-6 of verlet...). Stage i: drift q += a_i h ∇T(p), then kick p -= b_i h ∇V(q);
 * zero coefficients are skipped. The table is compiled at create time into a flat list of
 * operations, adjacent kicks (drifts) merged, so a step is one loop over them. When the first
 * operation is a kick and so is the last, the last force of a step is the first of the next and
 * is reused (first same as last). */
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

typedef struct {
  double coef;   /* a_i (drift) or −b_i (kick) */
  int kick;      /* 0: drift q, 1: kick p */
  int first;     /* first update of its half in a step: read from the old state */
  int eval_old;  /* the other half, where the gradient is evaluated, is still the old one */
} split_op;

typedef struct {
  split_op *ops;
  size_t n_ops;
  double *force;      /* ∇V at the last kick point */
  double *velocity;   /* ∇T at the last drift point */
  double *q_eval;     /* compensated mode: q + Δq */
  double *p_eval;     /* compensated mode: p + Δp */
  int fsal;           /* first and last operations are kicks */
  int kinetic_identity; /* ∇T(p) = p: drifts read p itself (no call, no copy) */
  int force_valid;    /* `force` holds ∇V at the current state's q */
} splitting_work;

/* Append the drift–kick pairs (a_i, b_i), scaled by `scale`, merging an operation into the
 * previous one of the same kind: two kicks (or drifts) in a row commute exactly. */
static void append_ops(splitting_work *w, const double *a, const double *b, size_t s,
                       double scale) {
  for (size_t i = 0; i < s; ++i) {
    const double coef[2] = {scale * a[i], -scale * b[i]};
    for (int kick = 0; kick < 2; ++kick) {
      if (coef[kick] == 0.0) continue;
      if (w->n_ops > 0 && w->ops[w->n_ops - 1].kick == kick)
        w->ops[w->n_ops - 1].coef += coef[kick];
      else
        w->ops[w->n_ops++] = (split_op){coef[kick], kick, 0, 0};
    }
  }
}

/* The operation list of a splitting method, or of a composition of a splitting method
 * (Φ_{γ_s h} ∘ … ∘ Φ_{γ_1 h}: the basic method's operations scaled by each γ_i). */
static gm_status build_ops(gm_integrator *it, splitting_work *w) {
  const gm_method *m = it->method;
  const gm_method *split = m->family == GM_FAMILY_COMPOSITION ? it->basic : m;
  gm_tableau *outer = NULL, *tab = NULL;
  gm_status st = gm_method_tableau(split, &tab);
  if (st == GM_OK && m->family == GM_FAMILY_COMPOSITION) st = gm_method_tableau(m, &outer);
  if (st != GM_OK) {
    gm_tableau_free(tab);
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "method '%s': no coefficients", m->name);
  }
  size_t copies = outer != NULL ? outer->n_stages : 1;
  w->ops = calloc(2 * tab->n_stages * copies, sizeof *w->ops);
  if (w->ops == NULL) st = GM_ENOMEM;
  for (size_t k = 0; k < copies && st == GM_OK; ++k)
    append_ops(w, tab->a, tab->b, tab->n_stages, outer != NULL ? outer->gamma[k] : 1.0);
  gm_tableau_free(tab);
  gm_tableau_free(outer);
  return st;
}

static gm_status init(gm_integrator *it) {
  splitting_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  const size_t d = it->dim;
  gm_status st = build_ops(it, w);
  if (st != GM_OK) return st;
  w->force = calloc(d, sizeof(double));
  w->velocity = calloc(d, sizeof(double));
  w->q_eval = calloc(d, sizeof(double));
  w->p_eval = calloc(d, sizeof(double));
  if (!w->force || !w->velocity || !w->q_eval || !w->p_eval) return GM_ENOMEM;
  int q_touched = 0, p_touched = 0;
  for (size_t k = 0; k < w->n_ops; ++k) {
    split_op *op = &w->ops[k];
    op->first = op->kick ? !p_touched : !q_touched;
    op->eval_old = op->kick ? !q_touched : !p_touched;
    if (op->kick)
      p_touched = 1;
    else
      q_touched = 1;
  }
  if (!q_touched || !p_touched)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "method '%s' never updates %s",
                   it->method->name, q_touched ? "p" : "q");
  w->fsal = w->ops[0].kick && w->ops[w->n_ops - 1].kick;
  w->kinetic_identity = gm_kinetic_is_identity(it->problem);
  return GM_OK;
}

static void release(gm_integrator *it) {
  splitting_work *w = it->work;
  if (w == NULL) return;
  free(w->ops);
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

#if defined(__GNUC__)
#define GM_SPLIT_INLINE __attribute__((always_inline)) inline
#else
#define GM_SPLIT_INLINE inline
#endif

/* dst = src + c·v (dst may equal src). */
static inline void axpy_into(size_t d, double *dst, const double *src, double c, const double *v) {
  for (size_t i = 0; i < d; ++i) dst[i] = src[i] + c * v[i];
}

/* Writes y_new; each half is first written from y, then updated in place. Inlined for d = 2
 * and 3 (one body in the plane or in space; issue 25: Kepler's step is mostly this loop's
 * overhead), where the axpy loops unroll. */
static GM_SPLIT_INLINE gm_status step_direct_d(gm_integrator *it, double t, double h,
                                               const double *y, double *y_new, size_t d) {
  splitting_work *w = it->work;
  const double *q_old = y, *p_old = y + d;
  double *q = y_new, *p = y_new + d;
  const split_op *op = w->ops, *end = w->ops + w->n_ops;
  if (w->fsal && w->force_valid) { /* the first kick reuses the last force */
    axpy_into(d, p, p_old, op->coef * h, w->force);
    ++op;
  }
  w->force_valid = 0;
  for (; op < end; ++op) {
    gm_status st;
    if (op->kick) {
      st = gm_eval_potential_gradient(it, t, op->eval_old ? q_old : q, w->force);
      if (st != GM_OK) return st;
      axpy_into(d, p, op->first ? p_old : p, op->coef * h, w->force);
    } else {
      const double *at = op->eval_old ? p_old : p, *v = at;
      if (!w->kinetic_identity) {
        if ((st = gm_eval_kinetic_gradient(it, t, at, w->velocity)) != GM_OK) return st;
        v = w->velocity;
      }
      axpy_into(d, q, op->first ? q_old : q, op->coef * h, v);
    }
  }
  w->force_valid = w->fsal;
  return GM_OK;
}

static gm_status step_direct(gm_integrator *it, double t, double h, const double *y,
                             double *y_new) {
  switch (it->dim) {
    case 2: return step_direct_d(it, t, h, y, y_new, 2);
    case 3: return step_direct_d(it, t, h, y, y_new, 3);
    default: return step_direct_d(it, t, h, y, y_new, it->dim);
  }
}

/* Accumulate the increments Δq, Δp; forces are evaluated at q + Δq, p + Δp. */
static gm_status step_increment(gm_integrator *it, double t, double h, const double *y,
                                double *delta) {
  splitting_work *w = it->work;
  const size_t d = it->dim;
  const double *q = y, *p = y + d;
  double *dq = delta, *dp = delta + d;
  memset(delta, 0, 2 * d * sizeof *delta);
  w->force_valid = 0;
  for (size_t k = 0; k < w->n_ops; ++k) {
    const split_op op = w->ops[k];
    gm_status st;
    if (op.kick) {
      axpy_into(d, w->q_eval, q, 1.0, dq);
      if ((st = gm_eval_potential_gradient(it, t, w->q_eval, w->force)) != GM_OK) return st;
      axpy_into(d, dp, dp, op.coef * h, w->force);
    } else {
      axpy_into(d, w->p_eval, p, 1.0, dp);
      const double *v = w->p_eval;
      if (!w->kinetic_identity) {
        if ((st = gm_eval_kinetic_gradient(it, t, w->p_eval, w->velocity)) != GM_OK) return st;
        v = w->velocity;
      }
      axpy_into(d, dq, dq, op.coef * h, v);
    }
  }
  return GM_OK;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  return delta != NULL ? step_increment(it, t, h, y, delta) : step_direct(it, t, h, y, y_new);
}

/* The loop of a run inside the stepper: a Verlet step on a small problem costs about as much
 * as the dispatch around it. The two state buffers live in registers during the loop (their
 * swap through memory would sit on the step's critical path) and are written back after it. */
static gm_status run(gm_integrator *it, const gm_run *r, size_t k_from, size_t k_to) {
  double *y = it->y, *y_next = it->y_next, t = it->t;
  gm_status st = GM_OK;
  size_t k = k_from + 1;
  for (; k <= k_to; ++k) {
    st = step_direct(it, t, r->h, y, y_next);
    if (st != GM_OK) break;
    if (gm_first_nonfinite(it->n, y_next) < it->n) break;
    double *tmp = y;
    y = y_next;
    y_next = tmp;
    t = gm_run_time(r, k);
  }
  const size_t done = k - (k_from + 1);
  it->y = y;
  it->y_next = y_next;
  it->t = t;
  it->step_index += done;
  it->stats.steps += done;
  if (st == GM_OK && k <= k_to) st = gm_commit_step(it, gm_run_time(r, k)); /* reports it */
  return st;
}

const gm_stepper gm_splitting_stepper = {init, step, release, invalidate, run, NULL, 0};

/* Checkpoints: the force kept for the first kick of the next step (FSAL), so that a restarted
 * run evaluates (and counts) exactly the forces an uninterrupted one does. */
static size_t state_size(const gm_integrator *it) { return sizeof(double) * (1 + it->dim); }
static void state_save(const gm_integrator *it, unsigned char *out) {
  const splitting_work *w = it->work;
  const double valid = w->force_valid ? 1.0 : 0.0;
  memcpy(out, &valid, sizeof valid);
  memcpy(out + sizeof valid, w->force, sizeof(double) * it->dim);
}
static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  splitting_work *w = it->work;
  double valid;
  memcpy(&valid, in, sizeof valid);
  w->force_valid = valid != 0.0;
  memcpy(w->force, in + sizeof valid, sizeof(double) * it->dim);
  return GM_OK;
}
const gm_stepper_state gm_splitting_stepper_state = {0, state_size, state_save, state_load};
