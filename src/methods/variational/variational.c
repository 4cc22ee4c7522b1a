/* Stepper of the variational integrators with a fixed step: the position–momentum form of the
 * discrete Euler–Lagrange equations of a Galerkin discrete Lagrangian (variational_engine.c).
 * Solvers of the step equations (gm_solver):
 *   - Newton's method with the exact Jacobian (second derivatives of L analytic, else central
 *     differences, counted in fd_jacobians); simplified Newton freezes it for the step;
 *   - for L = ½vᵀMv − V(q) without constraints: the kinetic-block iteration
 *     Δz = h (G⁻¹ ⊗ M⁻¹) R, whose matrix is the O(1/h) leading part (1/h) G ⊗ M of the Jacobian,
 *     so it contracts like a fixed-point iteration, at rate O(h²‖∇²V‖/M), with no factorization
 *     ("fixed-point"; the default, which falls back to Newton when it does not contract).
 * The Gauss rows on a separable problem (L = ½vᵀMv − V(q), no constraints, no forces) take the
 * fast path of Gauss collocation instead: their step is that method's (seed 001 Thm 2.12: the
 * Galerkin discrete Lagrangian with Gauss quadrature is the partitioned Runge–Kutta method with
 * ā = a, i.e. Gauss collocation; tests/invariants/test_variational.c checks the trajectories
 * against an independent implementation), so with the default or a fixed-point solver the step
 * runs gauss-s's fixed-point iteration on positions (implicit_rk.c). Newton stays the
 * variational engine's. Measured (bench/variational_cost.c): 1.5–1.7 × gauss-s before, the
 * same cost after.
 * Every solve starts from the previous step's polynomial extrapolated to the new control times
 * (as GNI (2006) §VIII.6.1 does for collocation), and iterates to round-off. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/variational.h"
#include "methods/variational/variational_internal.h"

/* ---- the equivalent partitioned Runge–Kutta tableaus (seed 001 Thm 2.12) ---------------- */

gm_status gm_vi_gauss_tableau(const gm_method *m, gm_tableau *t) {
  gm_status st = gm_gauss_tableau(m, t);
  if (st != GM_OK) return st;
  const size_t s = t->n_stages; /* Gauss: ā_ij = b_j(1 − a_ji/b_i) = a_ij, symplectic */
  for (size_t i = 0; i < s; ++i) {
    t->b_bar[i] = t->b[i];
    for (size_t j = 0; j < s; ++j) t->a_bar[i * s + j] = t->b[j] * (1.0 - t->a[j * s + i] / t->b[i]);
  }
  return GM_OK;
}

gm_status gm_vi_lobatto_tableau(const gm_method *m, gm_tableau *t) {
  return gm_lobatto_iiia_iiib_tableau(m, t);
}

/* α-rule L_d = h L((1−α)q0 + αq1, (q1 − q0)/h): one stage Q = q0 + hα Q', q1 = q0 + hQ', so
 * a = α, b = 1 and ā = b(1 − a/b) = 1 − α. α comes from the row's literal c. */
gm_status gm_vi_alpha_tableau(const gm_method *m, gm_tableau *t) {
  (void)m;
  const double alpha = t->c[0];
  t->a[0] = alpha;
  t->b[0] = 1.0;
  t->a_bar[0] = 1.0 - alpha;
  t->b_bar[0] = 1.0;
  return GM_OK;
}

gm_status gm_vi_rule_of(const gm_method *m, vi_rule *rule, size_t *degree) {
  if (m == NULL || m->family != GM_FAMILY_VARIATIONAL) return GM_EINVAL;
  if (m->compute == gm_vi_gauss_tableau) {
    *rule = VI_RULE_GAUSS;
    *degree = m->n_stages;
  } else if (m->compute == gm_vi_lobatto_tableau && m->n_stages >= 2) {
    *rule = VI_RULE_LOBATTO;
    *degree = m->n_stages - 1;
  } else if (m->compute == gm_vi_alpha_tableau) {
    *rule = VI_RULE_ALPHA;
    *degree = 1;
  } else {
    return GM_EINVAL;
  }
  return GM_OK;
}

/* ---- the stepper -------------------------------------------------------------------------- */

typedef struct {
  vi_engine e;
  vi_rule rule;
  size_t degree;
  double alpha;
  int have_prev;
  double h_prev;
  double *z_prev, *lam_prev, *dp;
  gm_integrator *gauss; /* owned: the Gauss collocation fast path, or NULL */
} vi_work;

static gm_status init_engine(gm_integrator *it, vi_work *w) {
  return gm_vi_engine_init(&w->e, it->problem, w->rule, w->degree, w->alpha, 0, &it->stats,
                           it->errmsg);
}

static gm_status init(gm_integrator *it) {
  vi_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  if (gm_vi_rule_of(it->method, &w->rule, &w->degree) != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "'%s' is no variational row",
                   it->method->name);
  w->alpha = (w->rule == VI_RULE_ALPHA && it->method->c != NULL) ? it->method->c[0] : 0.5;
  gm_status st = init_engine(it, w);
  if (st != GM_OK) return st;
  const size_t d = it->dim, s = w->degree, m = w->e.m;
  w->z_prev = calloc(s * d + 1, sizeof(double));
  w->lam_prev = calloc(s * m + 1, sizeof(double));
  w->dp = calloc(d, sizeof(double));
  if (!w->z_prev || !w->lam_prev || !w->dp) return GM_ENOMEM;
  if (w->rule == VI_RULE_GAUSS && it->problem->kind == GM_PROBLEM_SEPARABLE) {
    char name[32];
    snprintf(name, sizeof name, "gauss-%zu", w->degree);
    const gm_method *gauss = gm_method_find(name);
    gm_error err = {{0}};
    if (gauss != NULL && (st = gm_integrator_create(gauss, it->problem, &w->gauss, &err)) != GM_OK)
      return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", err.message);
  }
  return GM_OK;
}

static void release(gm_integrator *it) {
  vi_work *w = it->work;
  if (w == NULL) return;
  gm_vi_engine_release(&w->e);
  gm_integrator_free(w->gauss);
  free(w->z_prev);
  free(w->lam_prev);
  free(w->dp);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  vi_work *w = it->work;
  if (w == NULL) return;
  w->have_prev = 0;
  if (w->gauss != NULL) w->gauss->stepper->invalidate(w->gauss);
}

/* The step of Gauss collocation, with its statistics added to ours. */
static gm_status gauss_step(gm_integrator *it, vi_work *w, double t, double h, const double *y,
                            double *y_new, double *delta) {
  gm_integrator *in = w->gauss;
  gm_status st = in->stepper->step(in, t, h, y, y_new, delta);
  gm_stats *from = &in->stats, *to = &it->stats;
  to->force_evals += from->force_evals;
  to->fixed_point_iterations += from->fixed_point_iterations;
  to->newton_failures += from->newton_failures;
  memset(from, 0, sizeof *from);
  if (st != GM_OK) return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", in->errmsg);
  return GM_OK;
}

static int kinetic_block_possible(const vi_engine *e) { return e->quadratic && e->m == 0; }

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  vi_work *w = it->work;
  if (w->gauss != NULL && it->solver != GM_SOLVER_NEWTON &&
      it->solver != GM_SOLVER_SIMPLIFIED_NEWTON)
    return gauss_step(it, w, t, h, y, y_new, delta);
  vi_engine *e = &w->e;
  const size_t d = e->d, s = e->s, m = e->m, sd = s * d;
  e->t = t;
  e->h = h;
  e->q = y;
  e->p = y + d;
  gm_status st = GM_OK;
  if (e->quadratic && (st = gm_vi_prepare_mass(e, y)) != GM_OK) return st;
  /* starting values */
  if (w->have_prev && w->h_prev == h) {
    for (size_t nu = 0; nu < s; ++nu)
      for (size_t k = 0; k < d; ++k) {
        double sum = 0.0;
        for (size_t mu = 0; mu < s; ++mu) sum += e->extrap[nu * s + mu] * w->z_prev[mu * d + k];
        e->x[nu * d + k] = sum;
      }
    memcpy(e->x + sd, w->lam_prev, s * m * sizeof(double));
  } else {
    memset(e->x, 0, e->n_x * sizeof *e->x);
    if (e->quadratic) { /* straight line with the velocity M⁻¹p */
      double *v = w->dp;
      for (size_t k = 0; k < d; ++k) {
        double sum = 0.0;
        if (e->diagonal)
          sum = e->mass_inv[k * d + k] * e->p[k];
        else
          for (size_t j = 0; j < d; ++j) sum += e->mass_inv[k * d + j] * e->p[j];
        v[k] = sum;
      }
      for (size_t nu = 1; nu <= s; ++nu)
        for (size_t k = 0; k < d; ++k) e->x[(nu - 1) * d + k] = e->ctimes[nu] * h * v[k];
    }
  }
  const gm_solver solver = it->solver;
  const int kinetic = kinetic_block_possible(e) &&
                      (solver == GM_SOLVER_DEFAULT || solver == GM_SOLVER_FIXED_POINT ||
                       solver == GM_SOLVER_FIXED_POINT_POSITIONS);
  if (kinetic) {
    if (solver == GM_SOLVER_DEFAULT) memcpy(e->x_start, e->x, e->n_x * sizeof *e->x);
    st = gm_vi_solve(e, 0, 0);
    if (st != GM_OK && st != GM_ECALLBACK && solver == GM_SOLVER_DEFAULT) {
      memcpy(e->x, e->x_start, e->n_x * sizeof *e->x); /* fall back to Newton */
      st = gm_vi_solve(e, 1, 0);
    }
  } else {
    st = gm_vi_solve(e, 1, solver == GM_SOLVER_SIMPLIFIED_NEWTON);
  }
  if (st == GM_OK) st = gm_vi_momentum_increment(e, w->dp);
  if (st != GM_OK) {
    w->have_prev = 0;
    return gm_stage_solve_failed(it, st, t, h);
  }
  const double *dq = e->x + (s - 1) * d;
  for (size_t k = 0; k < d; ++k) {
    if (delta != NULL) {
      delta[k] = dq[k];
      delta[d + k] = w->dp[k];
    } else {
      y_new[k] = y[k] + dq[k];
      y_new[d + k] = y[d + k] + w->dp[k];
    }
  }
  memcpy(w->z_prev, e->x, sd * sizeof(double));
  memcpy(w->lam_prev, e->x + sd, s * m * sizeof(double));
  w->h_prev = h;
  w->have_prev = 1;
  return GM_OK;
}

static gm_status set_solver(gm_integrator *it, gm_solver solver) {
  vi_work *w = it->work;
  if ((solver == GM_SOLVER_FIXED_POINT || solver == GM_SOLVER_FIXED_POINT_POSITIONS) &&
      !kinetic_block_possible(&w->e))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "solver %s of '%s' needs L = v'Mv/2 - V(q) with constant M and no "
                   "constraints; use newton", gm_solver_name(solver), it->method->name);
  it->solver = solver;
  invalidate(it);
  return GM_OK;
}

const gm_stepper gm_variational_stepper = {init, step, release, invalidate, NULL, set_solver, 0};

gm_status gm_variational_set_alpha(gm_integrator *it, double alpha) {
  if (it == NULL) return GM_EINVAL;
  vi_work *w = it->work;
  if (it->stepper != &gm_variational_stepper || w == NULL || w->rule != VI_RULE_ALPHA)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "'%s' is not an alpha-rule variational integrator (vi-alpha)",
                   it->method->name);
  if (!(alpha >= 0.0 && alpha <= 1.0))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "alpha must be in [0, 1], got %g",
                   alpha);
  gm_vi_engine_release(&w->e);
  w->alpha = alpha;
  w->have_prev = 0;
  return init_engine(it, w);
}

/* Checkpoints: the previous step's control points and multipliers and its size, the starting
 * values of the next step. */
/* The fast path's Gauss integrator keeps its own starting values: saved after ours. */
static size_t inner_size(const vi_work *w) {
  if (w->gauss == NULL) return 0;
  const gm_stepper_state *inner = gm_stepper_state_of(w->gauss->stepper);
  return inner != NULL && inner->size != NULL ? inner->size(w->gauss) : 0;
}
static size_t state_size(const gm_integrator *it) {
  const vi_work *w = it->work;
  return sizeof(double) * (2 + (w->degree * it->dim + 1) + (w->degree * w->e.m + 1)) +
         inner_size(w);
}
static void state_save(const gm_integrator *it, unsigned char *out) {
  const vi_work *w = it->work;
  const double head[2] = {w->have_prev ? 1.0 : 0.0, w->h_prev};
  const size_t nz = w->degree * it->dim + 1, nl = w->degree * w->e.m + 1;
  memcpy(out, head, sizeof head);
  memcpy(out + sizeof head, w->z_prev, nz * sizeof(double));
  memcpy(out + sizeof head + nz * sizeof(double), w->lam_prev, nl * sizeof(double));
  if (inner_size(w) > 0)
    gm_stepper_state_of(w->gauss->stepper)
        ->save(w->gauss, out + sizeof head + (nz + nl) * sizeof(double));
}
static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  vi_work *w = it->work;
  double head[2];
  const size_t nz = w->degree * it->dim + 1, nl = w->degree * w->e.m + 1;
  memcpy(head, in, sizeof head);
  w->have_prev = head[0] != 0.0;
  w->h_prev = head[1];
  memcpy(w->z_prev, in + sizeof head, nz * sizeof(double));
  memcpy(w->lam_prev, in + sizeof head + nz * sizeof(double), nl * sizeof(double));
  if (inner_size(w) > 0)
    return gm_stepper_state_of(w->gauss->stepper)
        ->load(w->gauss, in + sizeof head + (nz + nl) * sizeof(double));
  return GM_OK;
}
const gm_stepper_state gm_variational_stepper_state = {0, state_size, state_save, state_load};
