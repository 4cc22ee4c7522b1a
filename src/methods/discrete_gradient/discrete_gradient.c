/* Stepper of the discrete gradient methods (rows in discrete_gradient_table.c):
 *   Δ = h S(y + Δ/2) ∇̄H(y, y + Δ),  y_{n+1} = y_n + Δ.
 * H(y + Δ) − H(y) = ∇̄Hᵀ Δ = h ∇̄Hᵀ S ∇̄H = 0 holds for the computed ∇̄H as soon as the equation
 * holds, so the solve goes to round-off. Solvers: simplified Newton with the matrix
 * I − (h/2) ∂f(y_n), f = S∇H (default; exact Jacobian of the midpoint rule, a close one here);
 * Newton with a finite-difference Jacobian of the residual; fixed-point iteration.
 * The discrete gradients (McLachlan, Quispel & Robidoux 1999):
 *   - average vector field: ∫_0^1 ∇H(y + sΔ) ds by a Q-point Gauss rule (exact for H
 *     polynomial of degree ≤ 2Q; default Q = 6);
 *   - Gonzalez (1996): ∇H(ȳ) + [H(y + Δ) − H(y) − ∇H(ȳ)·Δ] Δ/|Δ|², ȳ = y + Δ/2;
 *   - Itoh & Abe (1988): (H(z_i) − H(z_{i−1}))/Δ_i with z_i = y + Σ_{k≤i} Δ_k e_k. The
 *     difference quotient loses digits (ε|H|/|Δ_i|) when Δ_i is small; there (|Δ_i| below
 *     10⁻³ |Δ|_∞ or 10⁻⁴ (1 + |y_i|)) the same quantity, ∫_0^1 ∂_i H(z_{i−1} + sΔ_i e_i) ds, is
 *     computed by a 4-point Gauss rule, exact to round-off on so short a segment. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/mimetic.h"
#include "methods/energy.h"

#define FIXED_POINT_MAX_ITERATIONS 200
#define AVF_DEFAULT_POINTS 8
#define SEGMENT_POINTS 4
#define MAX_POINTS 256
#define IA_FRACTION 1e-3 /* quotients for |Δ_i| ≥ 1e-3 |Δ|∞ and ≥ 1e-4 (1 + |y_i|) */
#define IA_ABSOLUTE 1e-4

typedef struct {
  gm_discrete_gradient_kind kind;
  size_t n_quad;
  double s[MAX_POINTS], ws[MAX_POINTS];          /* Gauss rule on [0, 1] (AVF) */
  double seg_s[SEGMENT_POINTS], seg_w[SEGMENT_POINTS];
  int constant_s;
  double *structure, *gbar, *grad, *point, *point2, *delta, *delta_prev, *next, *jac;
  double h_prev, h0;                             /* h0 = H(y_n) */
  gm_newton *newton, *simplified;
  gm_integrator *it;
  const double *y;
  double t, h;
  gm_status callback_status;
} dg_work;

static gm_status set_rule(dg_work *w, size_t n_points) {
  gm_status st = gm_gauss_legendre(n_points, w->s, w->ws);
  if (st != GM_OK) return st;
  gm_quadrature_map(n_points, 0.0, 1.0, w->s, w->ws);
  w->n_quad = n_points;
  return GM_OK;
}

static gm_status init(gm_integrator *it) {
  dg_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  const size_t n = it->n;
  w->kind = gm_discrete_gradient_kind_of(it->method);
  w->constant_s = gm_poisson_structure_is_constant(it->problem);
  w->structure = calloc(n * n, sizeof(double));
  w->jac = calloc(n * n, sizeof(double));
  w->gbar = calloc(n, sizeof(double));
  w->grad = calloc(n, sizeof(double));
  w->point = calloc(n, sizeof(double));
  w->point2 = calloc(n, sizeof(double));
  w->delta = calloc(n, sizeof(double));
  w->delta_prev = calloc(n, sizeof(double));
  w->next = calloc(n, sizeof(double));
  if (!w->structure || !w->jac || !w->gbar || !w->grad || !w->point || !w->point2 ||
      !w->delta || !w->delta_prev || !w->next)
    return GM_ENOMEM;
  gm_status st = gm_jacobian_work(it); /* its Newton solver evaluates Jacobians */
  if (st == GM_OK) st = set_rule(w, AVF_DEFAULT_POINTS);
  if (st == GM_OK) st = gm_gauss_legendre(SEGMENT_POINTS, w->seg_s, w->seg_w);
  if (st != GM_OK) return st;
  gm_quadrature_map(SEGMENT_POINTS, 0.0, 1.0, w->seg_s, w->seg_w);
  if (w->constant_s && (st = gm_eval_poisson_structure(it, 0.0, NULL, w->structure)) != GM_OK)
    return st;
  gm_newton_options opt = gm_newton_defaults();
  /* H(y_{n+1}) − H(y_n) = ∇̄Hᵀ r for a residual r of the equation: iterate to increments of
   * 2ε rather than 1e-14. Not less: the difference quotients of Itoh–Abe and Gonzalez carry
   * rounding noise of that size, and the iteration would wander in it. */
  opt.increment_tol = 4.5e-16;
  if ((st = gm_newton_create(n, &opt, &w->newton)) != GM_OK) return st;
  opt.simplified = 1;
  opt.max_iterations = 100;
  return gm_newton_create(n, &opt, &w->simplified);
}

static void release(gm_integrator *it) {
  dg_work *w = it->work;
  if (w == NULL) return;
  gm_newton_free(w->newton);
  gm_newton_free(w->simplified);
  free(w->structure);
  free(w->jac);
  free(w->gbar);
  free(w->grad);
  free(w->point);
  free(w->point2);
  free(w->delta);
  free(w->delta_prev);
  free(w->next);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  dg_work *w = it->work;
  if (w != NULL) w->h_prev = 0.0;
}

/* ∫_0^1 ∇H(y + sΔ) ds */
static gm_status average_vector_field(dg_work *w, const double *d) {
  gm_integrator *it = w->it;
  const size_t n = it->n;
  memset(w->gbar, 0, n * sizeof *w->gbar);
  for (size_t q = 0; q < w->n_quad; ++q) {
    for (size_t i = 0; i < n; ++i) w->point[i] = w->y[i] + w->s[q] * d[i];
    gm_status st = gm_eval_poisson_gradient(it, w->t, w->point, w->grad);
    if (st != GM_OK) return st;
    for (size_t i = 0; i < n; ++i) w->gbar[i] += w->ws[q] * w->grad[i];
  }
  return GM_OK;
}

static gm_status gonzalez(dg_work *w, const double *d) {
  gm_integrator *it = w->it;
  const size_t n = it->n;
  for (size_t i = 0; i < n; ++i) w->point[i] = w->y[i] + 0.5 * d[i];
  gm_status st = gm_eval_poisson_gradient(it, w->t, w->point, w->gbar);
  if (st != GM_OK) return st;
  double dd = 0.0, gd = 0.0, h1;
  for (size_t i = 0; i < n; ++i) {
    dd += d[i] * d[i];
    gd += w->gbar[i] * d[i];
    w->point[i] = w->y[i] + d[i];
  }
  if (dd == 0.0) return GM_OK;
  if ((st = gm_eval_poisson_energy(it, w->t, w->point, &h1)) != GM_OK) return st;
  const double factor = (h1 - w->h0 - gd) / dd;
  for (size_t i = 0; i < n; ++i) w->gbar[i] += factor * d[i];
  return GM_OK;
}

static gm_status itoh_abe(dg_work *w, const double *d) {
  gm_integrator *it = w->it;
  const size_t n = it->n;
  const double big = IA_FRACTION * gm_norm_inf(n, d);
  double e_prev = w->h0, e;
  memcpy(w->point, w->y, n * sizeof *w->point); /* z_{i−1} */
  for (size_t i = 0; i < n; ++i) {
    gm_status st;
    if (fabs(d[i]) >= fmax(big, IA_ABSOLUTE * (1.0 + fabs(w->y[i])))) {
      w->point[i] = w->y[i] + d[i];
      if ((st = gm_eval_poisson_energy(it, w->t, w->point, &e)) != GM_OK) return st;
      w->gbar[i] = (e - e_prev) / d[i];
    } else {
      double sum = 0.0;
      memcpy(w->point2, w->point, n * sizeof *w->point);
      for (size_t q = 0; q < SEGMENT_POINTS; ++q) {
        w->point2[i] = w->y[i] + w->seg_s[q] * d[i];
        if ((st = gm_eval_poisson_gradient(it, w->t, w->point2, w->grad)) != GM_OK) return st;
        sum += w->seg_w[q] * w->grad[i];
      }
      w->gbar[i] = sum;
      w->point[i] = w->y[i] + d[i];
      if ((st = gm_eval_poisson_energy(it, w->t, w->point, &e)) != GM_OK) return st;
    }
    e_prev = e;
  }
  return GM_OK;
}

/* out = h S(y + Δ/2) ∇̄H(y, y + Δ) */
static gm_status increment(dg_work *w, const double *d, double *out) {
  gm_integrator *it = w->it;
  const size_t n = it->n;
  gm_status st;
  switch (w->kind) {
    case GM_DG_AVERAGE_VECTOR_FIELD:
      st = average_vector_field(w, d);
      break;
    case GM_DG_GONZALEZ:
      st = gonzalez(w, d);
      break;
    default:
      st = itoh_abe(w, d);
      break;
  }
  if (st != GM_OK) return st;
  if (!w->constant_s) {
    for (size_t i = 0; i < n; ++i) w->point[i] = w->y[i] + 0.5 * d[i];
    if ((st = gm_eval_poisson_structure(it, w->t + 0.5 * w->h, w->point, w->structure)) != GM_OK)
      return st;
  }
  for (size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (size_t j = 0; j < n; ++j) s += w->structure[i * n + j] * w->gbar[j];
    out[i] = w->h * s;
  }
  return GM_OK;
}

static int residual(void *ctx, const double *d, double *r) {
  dg_work *w = ctx;
  if ((w->callback_status = increment(w, d, r)) != GM_OK) return 1;
  for (size_t i = 0; i < w->it->n; ++i) r[i] = d[i] - r[i];
  return 0;
}

/* I − (h/2) ∂f(y_n) */
static int jacobian_at_y(void *ctx, const double *d, double *jac) {
  (void)d;
  dg_work *w = ctx;
  const size_t n = w->it->n;
  w->callback_status = gm_eval_rhs_jacobian(w->it, w->t, w->y, w->jac);
  if (w->callback_status != GM_OK) return 1;
  for (size_t i = 0; i < n * n; ++i) jac[i] = -0.5 * w->h * w->jac[i];
  for (size_t i = 0; i < n; ++i) jac[i * n + i] += 1.0;
  return 0;
}

static gm_status solve_fixed_point(dg_work *w) {
  gm_integrator *it = w->it;
  const size_t n = it->n;
  const double floor = 4.0 * 2.220446049250313e-16 * fmax(gm_norm_inf(n, w->y), 1e-300);
  double previous = INFINITY;
  for (size_t iter = 1; iter <= FIXED_POINT_MAX_ITERATIONS; ++iter) {
    gm_status st = increment(w, w->delta, w->next);
    if (st != GM_OK) return st;
    double change = 0.0;
    for (size_t i = 0; i < n; ++i) {
      change = fmax(change, fabs(w->next[i] - w->delta[i]));
      w->delta[i] = w->next[i];
    }
    it->stats.fixed_point_iterations++;
    if (!isfinite(change))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                     "fixed-point iteration produced a non-finite increment");
    if (change <= floor || (change >= previous && change <= 1e3 * floor)) return GM_OK;
    previous = change;
  }
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                 "fixed-point iteration did not converge in %d iterations (change %.2e)",
                 FIXED_POINT_MAX_ITERATIONS, previous);
}

static gm_status solve(dg_work *w) {
  gm_integrator *it = w->it;
  if (it->solver == GM_SOLVER_FIXED_POINT) return solve_fixed_point(w);
  const int full = it->solver == GM_SOLVER_NEWTON;
  gm_newton *nw = full ? w->newton : w->simplified;
  gm_status st = gm_newton_solve(nw, residual, full ? NULL : jacobian_at_y, w, w->delta);
  it->stats.newton_iterations += gm_newton_iterations(nw);
  /* The difference quotients are noisy at the level of ε|H|/|Δ_i|: an iteration that wanders
   * there without meeting the increment test has converged all the same. */
  if (st == GM_ENOCONV &&
      gm_newton_residual_norm(nw) <= 64.0 * 2.220446049250313e-16 * (1.0 + gm_norm_inf(it->n, w->y)))
    st = GM_OK;
  if (st == GM_ECALLBACK && w->callback_status != GM_OK) return w->callback_status;
  if (st != GM_OK) gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", gm_newton_errmsg(nw));
  return st;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  dg_work *w = it->work;
  const size_t n = it->n;
  w->it = it;
  w->y = y;
  w->t = t;
  w->h = h;
  w->callback_status = GM_OK;
  gm_status st = gm_eval_poisson_energy(it, t, y, &w->h0);
  if (st != GM_OK) return st;
  /* starting value: the previous increment (O(h²) off), else the explicit Euler increment */
  if (w->h_prev == h) {
    memcpy(w->delta, w->delta_prev, n * sizeof *w->delta);
  } else {
    if ((st = gm_eval_rhs(it, t, y, w->delta)) != GM_OK) return st;
    for (size_t i = 0; i < n; ++i) w->delta[i] *= h;
  }
  w->h_prev = 0.0;
  if ((st = solve(w)) != GM_OK) return gm_stage_solve_failed(it, st, t, h);
  memcpy(w->delta_prev, w->delta, n * sizeof *w->delta);
  w->h_prev = h;
  for (size_t i = 0; i < n; ++i) {
    if (delta != NULL)
      delta[i] = w->delta[i];
    else
      y_new[i] = y[i] + w->delta[i];
  }
  return GM_OK;
}

static gm_status set_solver(gm_integrator *it, gm_solver solver) {
  if (solver == GM_SOLVER_FIXED_POINT_POSITIONS)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "solver fixed-point-positions needs a Runge-Kutta method; '%s' is a "
                   "discrete gradient method (use newton, simplified-newton or fixed-point)",
                   it->method->name);
  it->solver = solver;
  return GM_OK;
}

const gm_stepper gm_discrete_gradient_stepper = {init,    step, release, invalidate,
                                                 NULL,    set_solver, 0};

gm_status gm_discrete_gradient_set_quadrature(gm_integrator *it, size_t n_points) {
  dg_work *w = it->work;
  if (w->kind != GM_DG_AVERAGE_VECTOR_FIELD)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "'%s' has no quadrature setting (avf has)", it->method->name);
  if (n_points > MAX_POINTS)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "at most %d quadrature points, got %zu", MAX_POINTS, n_points);
  gm_status st = set_rule(w, n_points == GM_QUADRATURE_DEFAULT ? AVF_DEFAULT_POINTS : n_points);
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "quadrature of %zu points: %s", n_points,
                   gm_strerror(st));
  return GM_OK;
}

size_t gm_discrete_gradient_quadrature(const gm_integrator *it) {
  const dg_work *w = it->work;
  return w->kind == GM_DG_AVERAGE_VECTOR_FIELD ? w->n_quad : 0;
}

/* Checkpoints: the previous step's increment and size (the next step's starting value). */
static size_t state_size(const gm_integrator *it) { return sizeof(double) * (1 + it->n); }
static void state_save(const gm_integrator *it, unsigned char *out) {
  const dg_work *w = it->work;
  memcpy(out, &w->h_prev, sizeof(double));
  memcpy(out + sizeof(double), w->delta_prev, sizeof(double) * it->n);
}
static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  dg_work *w = it->work;
  memcpy(&w->h_prev, in, sizeof(double));
  memcpy(w->delta_prev, in + sizeof(double), sizeof(double) * it->n);
  return GM_OK;
}
const gm_stepper_state gm_discrete_gradient_stepper_state = {0, state_size, state_save,
                                                             state_load};
