/* Stepper for implicit Runge–Kutta and partitioned Runge–Kutta methods.
 *
 * The unknowns are the stage increments Z_i = Y_i − y_n, solving
 *   Z_i = h Σ_j Ã_ij f(t + c_j h, y_n + Z_j),
 * where Ã_ij = a_ij on the q-components (or all components, for plain RK) and ā_ij on the
 * p-components of a partitioned method (f = (∇_p H, −∇_q H)). Solvers (gm_solver; the default
 * is chosen by the problem's kind: fixed-point on positions for q'' = f(q), fixed-point
 * otherwise; Newton only when asked for, as for stiff problems):
 *   - Newton with the exact Jacobian δ_ij I − h Ã_ij ∂f(y_n + Z_j);
 *   - simplified Newton: ∂f(y_n) once per step, one LU of I − h Ã⊗J per step
 *     (Hairer & Wanner, Solving ODEs II (1996), §IV.8);
 *   - fixed-point iteration Z ← h Ã F(y_n + Z) (GNI (2006), §VIII.6);
 *   - for q'' = f(q) (separable, quadratic T): fixed-point iteration on positions only.
 * Every solver starts from the previous step's collocation polynomial extrapolated to the new
 * stages (GNI §VIII.6.1) when the step size did not change, and iterates to round-off (the
 * iteration on positions extrapolates the forces instead and has its own stopping test, see
 * step_positions and positions_converged). The other fixed-point iterations stop when the error left, estimated from the contraction rate
 * θ = ‖ΔZ_k‖/‖ΔZ_{k−1}‖ as θ/(1 − θ)‖ΔZ_k‖ (Hairer & Wanner II, §IV.8, eq. (8.10)), is below
 * round-off, or when the increments stop decreasing near it (round-off reached, as GNI's
 * irk2 does); the q and p halves of a Hamiltonian state are measured each against its own size,
 * so small momenta (the solar system's are 1e-5 of its positions) converge too.
 * The update is y_{n+1} = y_n + Σ_j d_j Z_j with dᵀ = bᵀA⁻¹ when A is invertible (no extra
 * evaluation of f; Hairer & Wanner II, eq. (IV.8.2b)), else y_n + h Σ_j b_j f(Y_j). */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "methods/internal.h"

#define FIXED_POINT_MAX_ITERATIONS 200

typedef struct {
  gm_tableau *tab;
  const double *a_p;   /* the tableau for the p-components (tab->a for plain RK) */
  int partitioned;
  double *d;           /* s update weights bᵀA⁻¹, or NULL when A is singular */
  double *extrap;      /* s×s: Z⁰ = extrap · Z_prev (previous collocation polynomial) */
  double *a2, *ba;     /* A² (s×s) and bᵀA (s): the positions-only form */
  double *fextrap;     /* s×(s+1): forces at the new stages from the previous ones, or NULL */
  double a2_norm;      /* max_i Σ_k |(A²)_ik| */
  gm_newton *newton, *simplified; /* created when a Newton solver is chosen */
  double *z, *z_prev, *z_next;  /* s·n */
  double *f;           /* s·n values f(Y_j) */
  double *stage;       /* n */
  double *stage_change; /* s: positions-only iteration, each stage's move since its evaluation */
  double *stage_force;  /* s: positions-only iteration, max |K(g_k)| of each stage */
  double *base;         /* s·d: positions-only iteration, h c_i K(p) of the step */
  int kinetic_identity; /* K = ∇T is the identity: K(x) = x without a call */
  double *jac;         /* n×n, with the Newton solvers */
  /* simplified Newton through the eigenvalues of A (Gauss rows; stage_transform.c): */
  gm_stage_transform *tr;
  double complex *clu, *cw; /* n_pairs LU factors (n×n) of λ_k/h I − J; n_blocks·n rhs */
  double *rlu, *g;          /* n_real LU factors (n×n); s·n: G = −(hA)⁻¹R */
  double *z_start;          /* s·n: the starting values of the step, for a retry */
  int *cpiv, *rpiv;
  double lu_h;              /* h of the factors; 0: none */
  int jac_stale;            /* recompute J before the next step (slow convergence) */
  double h_prev;       /* step size of z_prev, 0 when there is none */
  /* the step being solved, seen by the Newton callbacks */
  gm_integrator *it;
  const double *y;
  double t, h;
  gm_status callback_status;
} implicit_rk_work;

static const double *coef_row(const implicit_rk_work *w, size_t component, size_t n) {
  return (w->partitioned && component >= n / 2) ? w->a_p : w->tab->a;
}

/* Lagrange basis on the nodes {0, c_1..c_s} at 1 + c_i, minus d_j: Z⁰_i = Σ_j G_ij Z_prev_j,
 * because y_{n+1} − y_n = Σ_j d_j Z_j and the basis sums to one. */
static gm_status extrapolation_matrix(implicit_rk_work *w, size_t s) {
  double nodes[65], values[65];
  if (s + 1 > 65) return GM_EINVAL;
  nodes[0] = 0.0;
  for (size_t j = 0; j < s; ++j) nodes[j + 1] = w->tab->c[j];
  for (size_t i = 0; i < s; ++i) {
    gm_status st = gm_lagrange_basis(s + 1, nodes, 1.0 + w->tab->c[i], values);
    if (st != GM_OK) return st;
    for (size_t j = 0; j < s; ++j) w->extrap[i * s + j] = values[j + 1] - w->d[j];
  }
  return GM_OK;
}

/* The forces along the previous step's collocation polynomial u, at its stages and at its end
 * (u(t_n + h) = q_{n+1}), as a polynomial of degree s in time, at the new stages: the Lagrange
 * basis on the nodes c_1 − 1, …, c_s − 1, 0 at c_i (the time unit is h, the new step starts at
 * 0). An s × (s + 1) matrix; NULL for a tableau with repeated nodes. */
static void force_extrapolation_matrix(implicit_rk_work *w, size_t s) {
  double nodes[65];
  for (size_t j = 0; j < s && j < 64; ++j) nodes[j] = w->tab->c[j] - 1.0;
  nodes[s < 64 ? s : 64] = 0.0;
  for (size_t i = 0; i < s; ++i)
    if (s + 1 > 65 ||
        gm_lagrange_basis(s + 1, nodes, w->tab->c[i], w->fextrap + i * (s + 1)) != GM_OK ||
        !isfinite(w->fextrap[i * (s + 1)])) {
      free(w->fextrap);
      w->fextrap = NULL;
      return;
    }
}

static gm_status set_solver(gm_integrator *it, gm_solver solver);

static gm_status init(gm_integrator *it) {
  implicit_rk_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  const gm_method *m = it->method;
  gm_status st = gm_method_tableau(m, &w->tab);
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "method '%s': no tableau", m->name);
  const size_t n = it->n, s = w->tab->n_stages;
  w->partitioned = m->family == GM_FAMILY_PARTITIONED_RK;
  w->a_p = w->partitioned ? w->tab->a_bar : w->tab->a;
  w->d = calloc(s, sizeof(double));
  w->extrap = calloc(s * s, sizeof(double));
  w->a2 = calloc(s * s, sizeof(double));
  w->ba = calloc(s, sizeof(double));
  w->fextrap = calloc(s * (s + 1), sizeof(double));
  w->z = calloc(s * n, sizeof(double));
  w->z_prev = calloc(s * n, sizeof(double));
  w->z_next = calloc(s * n, sizeof(double));
  w->f = calloc(s * n, sizeof(double));
  w->stage = calloc(n, sizeof(double));
  w->stage_change = calloc(s, sizeof(double));
  w->stage_force = calloc(s, sizeof(double));
  w->base = calloc(s * it->dim + 1, sizeof(double));
  w->kinetic_identity = it->problem->kind == GM_PROBLEM_SEPARABLE &&
                        gm_kinetic_is_identity(it->problem);
  double *at = calloc(s * s, sizeof(double));
  if (!w->d || !w->extrap || !w->a2 || !w->ba || !w->fextrap || !w->z || !w->z_prev || !w->z_next || !w->f ||
      !w->stage || !w->stage_change || !w->stage_force || !w->base || !at) {
    free(at);
    return GM_ENOMEM;
  }
  for (size_t i = 0; i < s; ++i) {
    w->d[i] = w->tab->b[i];
    for (size_t j = 0; j < s; ++j) {
      at[i * s + j] = w->tab->a[j * s + i];
      for (size_t k = 0; k < s; ++k) w->a2[i * s + j] += w->tab->a[i * s + k] * w->tab->a[k * s + j];
      w->ba[j] += w->tab->b[i] * w->tab->a[i * s + j];
    }
  }
  /* Aᵀ d = b; partitioned methods and singular A (Lobatto IIIA) update with f instead. */
  if (w->partitioned || gm_dense_solve(s, at, w->d) != GM_OK) {
    free(w->d);
    w->d = NULL;
  }
  free(at);
  force_extrapolation_matrix(w, s);
  for (size_t i = 0; i < s; ++i) {
    double row = 0.0;
    for (size_t k = 0; k < s; ++k) row += fabs(w->a2[i * s + k]);
    w->a2_norm = fmax(w->a2_norm, row);
  }
  if (w->d != NULL && (st = extrapolation_matrix(w, s)) != GM_OK) return st;
  return set_solver(it, GM_SOLVER_DEFAULT);
}

/* Simplified Newton through the eigenvalues of A: (s/2 complex + 1 real) n×n factors instead of
 * the (sn)² matrix. Only for Runge–Kutta rows with invertible A (Gauss); partitioned rows and
 * Lobatto IIIA keep the (sn)² system. */
static gm_status transformed_work(gm_integrator *it, implicit_rk_work *w) {
  const size_t n = it->n, s = w->tab->n_stages;
  if (w->tr != NULL) return GM_OK;
  gm_status st = gm_stage_transform_create(s, w->tab->a, &w->tr);
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "'%s': no eigen-decomposition of A",
                   it->method->name);
  const size_t np = w->tr->n_pairs, nr = w->tr->n_real;
  w->clu = calloc(np * n * n + 1, sizeof(double complex));
  w->cw = calloc(w->tr->n_blocks * n + 1, sizeof(double complex));
  w->rlu = calloc(nr * n * n + 1, sizeof(double));
  w->g = calloc(s * n, sizeof(double));
  w->z_start = calloc(s * n, sizeof(double));
  w->cpiv = calloc(np * n + 1, sizeof(int));
  w->rpiv = calloc(nr * n + 1, sizeof(int));
  if (!w->clu || !w->cw || !w->rlu || !w->g || !w->z_start || !w->cpiv || !w->rpiv)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM,
                   "out of memory for the Newton factors (%zu x %zu)", n, n);
  return GM_OK;
}

static int transformable(const gm_integrator *it, const implicit_rk_work *w) {
  return it->method->family == GM_FAMILY_IMPLICIT_RK && w->d != NULL;
}

/* The Newton solvers and their Jacobian work, only when one is chosen: full Newton and the
 * simplified Newton of partitioned rows solve the (sn)² system. */
static gm_status newton_work(gm_integrator *it, implicit_rk_work *w, gm_solver solver) {
  const size_t n = it->n, s = w->tab->n_stages;
  gm_status st = gm_jacobian_work(it);
  if (st != GM_OK) return st;
  if (w->jac == NULL && (w->jac = calloc(n * n, sizeof(double))) == NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory for a Jacobian");
  gm_newton_options opt = gm_newton_defaults();
  if (solver == GM_SOLVER_NEWTON)
    return w->newton != NULL ? GM_OK : gm_newton_create(s * n, &opt, &w->newton);
  if (transformable(it, w)) return transformed_work(it, w);
  if (w->simplified != NULL) return GM_OK;
  opt.simplified = 1;
  opt.max_iterations = 100; /* linear convergence, rate O(h‖J‖) */
  return gm_newton_create(s * n, &opt, &w->simplified);
}

/* q'' = f(q) (separable, T quadratic) with a Runge–Kutta method: positions only. */
static int positions_possible(const gm_integrator *it) {
  const gm_problem *pb = it->problem;
  return it->method->family == GM_FAMILY_IMPLICIT_RK && pb->kind == GM_PROBLEM_SEPARABLE &&
         pb->kinetic_is_quadratic;
}

static gm_status set_solver(gm_integrator *it, gm_solver solver) {
  implicit_rk_work *w = it->work;
  if (solver == GM_SOLVER_FIXED_POINT_POSITIONS && !positions_possible(it))
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "solver fixed-point-positions needs a Runge-Kutta method (got '%s') and a "
                   "separable problem with quadratic kinetic energy (kinetic_is_quadratic)",
                   it->method->name);
  /* The default, by measurement (docs/work-precision.md): positions where possible, else
   * fixed-point; both need no Jacobian. A problem that declares a fast potential W (a split
   * U + W, geomint/oscillatory.h) is stiff by that declaration: fixed-point iteration diverges
   * once h‖Ω‖ ≳ 2 (midpoint on toy-resonance, ω = 10, h = 0.2), so it gets simplified Newton. */
  if (solver == GM_SOLVER_DEFAULT)
    solver = it->problem->split != NULL      ? GM_SOLVER_SIMPLIFIED_NEWTON
             : positions_possible(it)        ? GM_SOLVER_FIXED_POINT_POSITIONS
                                             : GM_SOLVER_FIXED_POINT;
  if (solver == GM_SOLVER_NEWTON || solver == GM_SOLVER_SIMPLIFIED_NEWTON) {
    gm_status st = newton_work(it, w, solver);
    if (st != GM_OK) return st;
  }
  it->solver = solver;
  w->h_prev = 0.0; /* the stored stages have another shape */
  w->lu_h = 0.0;
  return GM_OK;
}

static void release(gm_integrator *it) {
  implicit_rk_work *w = it->work;
  if (w == NULL) return;
  gm_tableau_free(w->tab);
  gm_newton_free(w->newton);
  gm_newton_free(w->simplified);
  free(w->d);
  free(w->extrap);
  free(w->a2);
  free(w->ba);
  free(w->fextrap);
  free(w->z);
  free(w->z_prev);
  free(w->z_next);
  free(w->f);
  free(w->stage);
  free(w->stage_change);
  free(w->stage_force);
  free(w->base);
  free(w->jac);
  gm_stage_transform_free(w->tr);
  free(w->clu);
  free(w->cw);
  free(w->rlu);
  free(w->g);
  free(w->z_start);
  free(w->cpiv);
  free(w->rpiv);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  implicit_rk_work *w = it->work;
  if (w != NULL) {
    w->h_prev = 0.0;
    w->lu_h = 0.0;
  }
}

/* F_j = f(t + c_j h, y + Z_j) for every stage. */
static gm_status eval_stages(implicit_rk_work *w, const double *z) {
  gm_integrator *it = w->it;
  const size_t n = it->n, s = w->tab->n_stages;
  for (size_t j = 0; j < s; ++j) {
    for (size_t k = 0; k < n; ++k) w->stage[k] = w->y[k] + z[j * n + k];
    gm_status st = gm_eval_rhs(it, w->t + w->tab->c[j] * w->h, w->stage, w->f + j * n);
    if (st != GM_OK) return st;
  }
  return GM_OK;
}

/* out_i = h Σ_j Ã_ij F_j */
static void apply_tableau(const implicit_rk_work *w, double *out) {
  const size_t n = w->it->n, s = w->tab->n_stages;
  for (size_t i = 0; i < s; ++i)
    for (size_t k = 0; k < n; ++k) {
      const double *a = coef_row(w, k, n);
      double sum = 0.0;
      for (size_t j = 0; j < s; ++j) sum += a[i * s + j] * w->f[j * n + k];
      out[i * n + k] = w->h * sum;
    }
}

/* R = Z − h Ã F(y + Z) */
static int stage_residual(void *ctx, const double *z, double *r) {
  implicit_rk_work *w = ctx;
  const size_t sn = w->tab->n_stages * w->it->n;
  if ((w->callback_status = eval_stages(w, z)) != GM_OK) return 1;
  apply_tableau(w, r);
  for (size_t k = 0; k < sn; ++k) r[k] = z[k] - r[k];
  return 0;
}

/* Block (i, j): δ_ij I − h Ã_ij J_j, with J_j = ∂f(y + Z_j) (full) or ∂f(y) (simplified). */
static int fill_jacobian(implicit_rk_work *w, const double *z, double *jac, int at_stages) {
  gm_integrator *it = w->it;
  const size_t n = it->n, s = w->tab->n_stages, ns = n * s;
  for (size_t j = 0; j < s; ++j) {
    if (j == 0 || at_stages) {
      for (size_t k = 0; k < n; ++k) w->stage[k] = w->y[k] + (at_stages ? z[j * n + k] : 0.0);
      w->callback_status = gm_eval_rhs_jacobian(it, w->t + w->tab->c[j] * w->h, w->stage, w->jac);
      if (w->callback_status != GM_OK) return 1;
    }
    for (size_t i = 0; i < s; ++i)
      for (size_t r = 0; r < n; ++r) {
        double coef = -w->h * coef_row(w, r, n)[i * s + j];
        for (size_t c = 0; c < n; ++c)
          jac[(i * n + r) * ns + j * n + c] = coef * w->jac[r * n + c] + (i == j && r == c);
      }
  }
  return 0;
}

static int stage_jacobian(void *ctx, const double *z, double *jac) {
  return fill_jacobian(ctx, z, jac, 1);
}

static int stage_jacobian_at_y(void *ctx, const double *z, double *jac) {
  return fill_jacobian(ctx, z, jac, 0);
}

/* Has a linearly converging iteration converged? change[0]: the scaled max-norm of its latest
 * increment, change[1], change[2]: the two before (INFINITY when there are none), floor: the
 * round-off level of the state. The error left is about θ/(1 − θ)·change with the rate θ
 * (Hairer & Wanner II, §IV.8, eq. (8.10)), estimated as the larger of the last two ratios of
 * increments (one ratio can be small by accident where the q and p halves converge in turn).
 * Stop when that is below floor/64, or when the increments stop decreasing near the floor
 * (round-off reached). Why floor/64: the iteration error is smooth from step to step, so it
 * adds up linearly (a drift) where round-off adds up like a random walk; stopping at the floor
 * itself made Kepler's energy drift from 1.3e-11 to 1.3e-10 over 10⁶ steps of gauss-5
 * (tests/invariants/test_long_time.c). */
static int iteration_converged(const double change[3], double floor) {
  const double target = floor / 64.0;
  if (change[0] <= target) return 1;
  if (change[0] >= change[1]) return change[0] <= 1e3 * floor; /* round-off reached */
  if (!isfinite(change[2])) return 0; /* no rate yet */
  const double theta = fmax(change[0] / change[1], change[1] / change[2]);
  return theta < 0.5 && theta / (1.0 - theta) * change[0] <= target;
}

/* Shift the history of increments and record the latest. */
static void push_change(double change[3], double latest) {
  change[2] = change[1];
  change[1] = change[0];
  change[0] = latest;
}

#define ROUNDOFF_FLOOR (4.0 * 2.220446049250313e-16)

/* The iteration on positions updates with the forces of its last iteration, evaluated at the
 * previous iterate, whose error is about the latest change (not θ times it): what is left is
 * systematic (the starting error contracted a few times, smooth from step to step), so it adds
 * up over the run instead of averaging out like round-off. It stops when every stage's force
 * was evaluated within POSITIONS_STOP × the round-off floor of q of where its stage is now, or
 * when the change stops decreasing near the floor (round-off reached; GNI's irk2 stops on the
 * same two conditions, in its own norm). A stage whose force is within POSITIONS_SKIP × the
 * floor of its stage is not evaluated again (the first stages, Z_k ∝ c_k² h², settle early).
 * Both by measurement on the outer solar system, gauss-6 over 500 000 days, errors at h = 200 /
 * 250 / 312.5 against the reference of bench/implicit_force_count.c (the old solver, which
 * iterated to floor/64 and evaluated the forces again at the converged stages: 7.3e-13 /
 * 2.7e-13 / 3.2e-12, 38.0 evaluations a step at 312.5):
 *   stop 1,   no skipping: 8.3e-12 / 1.6e-12 / 3.7e-12, 28.7 a step
 *   stop 0.1, no skipping: 2.8e-13 / 3.1e-13 / 3.6e-12, 30.8
 *   stop 0.1, skip 0.1:    2.8e-12 / 1.1e-12 / 3.7e-12, 27.3
 *   stop 0.1, skip 0.03:   5.6e-13 / 3.9e-13 / 3.2e-12, 28.6  (these; with compensated summation
 *                          7.0e-13 / 1.6e-13 / 3.4e-12, the old solver's 3.4e-13 / 1.8e-13 /
 *                          3.4e-12: equal within round-off). */
#define POSITIONS_STOP 0.1
#define POSITIONS_SKIP 0.03

static int positions_converged(const double change[3], double floor) {
  if (change[0] <= POSITIONS_STOP * floor) return 1;
  return change[0] >= change[1] && change[0] <= 8.0 * floor;
}

/* The change from z to z_next in the scaled max-norm: a Hamiltonian state (q, p) by halves, a
 * change in p relative to the size of p (or of its stage increments, when p is 0), in q to q. */
static double stage_change(const implicit_rk_work *w) {
  const gm_integrator *it = w->it;
  const size_t n = it->n, s = w->tab->n_stages;
  const int halves = it->problem->kind == GM_PROBLEM_HAMILTONIAN ||
                     it->problem->kind == GM_PROBLEM_SEPARABLE;
  const size_t split = halves ? n / 2 : n;
  double change_a = 0.0, change_b = 0.0;
  double scale_a = gm_norm_inf(split, w->y), scale_b = gm_norm_inf(n - split, w->y + split);
  for (size_t i = 0; i < s; ++i) {
    const double *zn = w->z_next + i * n, *zo = w->z + i * n;
    for (size_t k = 0; k < split; ++k) {
      change_a = fmax(change_a, fabs(zn[k] - zo[k]));
      scale_a = fmax(scale_a, fabs(zn[k]));
    }
    for (size_t k = split; k < n; ++k) {
      change_b = fmax(change_b, fabs(zn[k] - zo[k]));
      scale_b = fmax(scale_b, fabs(zn[k]));
    }
  }
  if (!halves) scale_b = scale_a = fmax(scale_a, scale_b);
  return fmax(change_a / fmax(scale_a, 1e-300), change_b / fmax(scale_b, 1e-300));
}

/* Iterate Z ← h Ã F(y + Z) until the change is at the round-off of y. */
static gm_status solve_fixed_point(implicit_rk_work *w) {
  gm_integrator *it = w->it;
  const size_t sn = w->tab->n_stages * it->n;
  double history[3] = {INFINITY, INFINITY, INFINITY};
  for (size_t iter = 1; iter <= FIXED_POINT_MAX_ITERATIONS; ++iter) {
    gm_status st = eval_stages(w, w->z);
    if (st != GM_OK) return st;
    apply_tableau(w, w->z_next);
    const double change = stage_change(w);
    memcpy(w->z, w->z_next, sn * sizeof *w->z);
    it->stats.fixed_point_iterations++;
    if (!isfinite(change))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                     "fixed-point iteration diverged (a non-finite stage); for a stiff problem use "
                     "--solver simplified-newton");
    push_change(history, change);
    if (iteration_converged(history, ROUNDOFF_FLOOR)) return GM_OK;
  }
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                 "fixed-point iteration did not converge in %d iterations (relative change "
                 "%.2e); a stiff problem needs --solver simplified-newton",
                 FIXED_POINT_MAX_ITERATIONS, history[0]);
}

/* fmax(m, x) for m not NaN, without the library call (fmax is one when errno matters): x when
 * it is larger, else m, so a NaN x leaves m as fmax does. */
static inline double max_of(double m, double x) { return x > m ? x : m; }
/* The same, but a NaN x wins (as in gm_norm_inf, whose value this reproduces in parts). */
static inline double max_or_nan(double m, double x) { return x > m || isnan(x) ? x : m; }

#if defined(__GNUC__)
#define GM_ALWAYS_INLINE __attribute__((always_inline)) inline
#define GM_UNROLL _Pragma("GCC unroll 8")
#else
#define GM_ALWAYS_INLINE inline
#define GM_UNROLL
#endif

/* The stage update of the iteration on positions, z_i = base_i − h² Σ_k (A²)_ik K(g_k), summed
 * in the order k = 1..s; each stage's largest move from where its force was evaluated
 * (moved_i), the largest of those (*change) and of |z_i| (*scale). Inlined with s constant
 * (stage_update below), so that the sum over k unrolls with the row of A² in registers. */
static GM_ALWAYS_INLINE void stage_update_s(size_t s, size_t d, const double *a2,
                                            const double *kg, const double *base, double hh,
                                            const double *z_eval, double *z, double *moved,
                                            double *change, double *scale) {
  double c = *change, sc = *scale;
  for (size_t i = 0; i < s; ++i) {
    const double *ai = a2 + i * s;
    double m = 0.0;
    for (size_t r = 0; r < d; ++r) {
      double sum = 0.0;
      GM_UNROLL
      for (size_t k = 0; k < s; ++k) sum += ai[k] * kg[k * d + r];
      const double zi = base[i * d + r] - hh * sum;
      m = max_of(m, fabs(zi - z_eval[i * d + r]));
      sc = max_of(sc, fabs(zi));
      z[i * d + r] = zi;
    }
    moved[i] = m;
    c = max_of(c, m);
  }
  *change = c;
  *scale = sc;
}

static void stage_update(size_t s, size_t d, const double *a2, const double *kg,
                         const double *base, double hh, const double *z_eval, double *z,
                         double *moved, double *change, double *scale) {
  switch (s) {
#define STAGES(n) \
  case n: stage_update_s(n, d, a2, kg, base, hh, z_eval, z, moved, change, scale); return;
    STAGES(1) STAGES(2) STAGES(3) STAGES(4) STAGES(5) STAGES(6)
#undef STAGES
    default: stage_update_s(s, d, a2, kg, base, hh, z_eval, z, moved, change, scale);
  }
}

/* Forces at the new stages predicted from the previous step's (w->fextrap, s × (s + 1)):
 * out_i = e_is K(g(q_n)) + Σ_j e_ij kg_prev_j, in that order; inlined with s constant. */
static GM_ALWAYS_INLINE void force_predict_s(size_t s, size_t d, const double *e,
                                             const double *kg0, const double *kg_prev,
                                             double *out) {
  for (size_t i = 0; i < s; ++i) {
    const double *ei = e + i * (s + 1);
    for (size_t r = 0; r < d; ++r) {
      double f_i = kg0[r] * ei[s];
      GM_UNROLL
      for (size_t j = 0; j < s; ++j) f_i += ei[j] * kg_prev[j * d + r];
      out[i * d + r] = f_i;
    }
  }
}

static void force_predict(size_t s, size_t d, const double *e, const double *kg0,
                          const double *kg_prev, double *out) {
  switch (s) {
#define STAGES(n) \
  case n: force_predict_s(n, d, e, kg0, kg_prev, out); return;
    STAGES(1) STAGES(2) STAGES(3) STAGES(4) STAGES(5) STAGES(6)
#undef STAGES
    default: force_predict_s(s, d, e, kg0, kg_prev, out);
  }
}

/* K(x) into out, or x itself when K is the identity (then out is not written). */
static inline gm_status kinetic_map(implicit_rk_work *w, const double *x, double *out,
                                    const double **result) {
  if (w->kinetic_identity) {
    *result = x;
    return GM_OK;
  }
  *result = out;
  return gm_eval_kinetic_gradient(w->it, w->t, x, out);
}

/* q'' = f(q) with T(p) = ½pᵀM⁻¹p, K = ∇T linear: Q_i = q + h c_i K(p) − h² Σ_k (A²)_ik K(g_k),
 * g_k = ∇V(Q_k); then q_{n+1} = q + h K(p) − h² Σ_k (bᵀA)_k K(g_k), p_{n+1} = p − h Σ b_k g_k
 * (the Runge–Kutta–Nyström form of a Runge–Kutta method; Hairer, Nørsett & Wanner, Solving
 * ODEs I (1993), §II.14). The unknowns are the s·d stage positions only; z holds them.
 * Cost (issue 25; instructions per force evaluation, callgrind, bench/ode_eval_cost.c, Kepler,
 * gauss-6): the sums over stages unrolled with s constant, max without libm's fmax, the force
 * norm kept per stage instead of recomputed each iteration, h c_i K(p) once per step, and no
 * call for K when it is the identity; the same numbers in the same order as before. */
static gm_status step_positions(implicit_rk_work *w, int have_prev, double *y_new, double *delta) {
  gm_integrator *it = w->it;
  const size_t d = it->dim, s = w->tab->n_stages;
  const double *q = w->y, *p = w->y + d, h = w->h, hh = h * h;
  double *g = w->f, *kg = w->f + s * d; /* f has room for 2·s·d */
  const double *kp;
  gm_status st = kinetic_map(w, p, w->stage, &kp);
  if (st != GM_OK) return st;
  double *base = w->base;
  for (size_t i = 0; i < s; ++i) {
    const double hc = h * w->tab->c[i];
    for (size_t r = 0; r < d; ++r) base[i * d + r] = hc * kp[r];
  }
  /* Starting values Z_i = h c_i K(p) − h² Σ_k (A²)_ik K(g_k) from forces g_k predicted at the
   * new stages: the force at q_n (one evaluation) and, after a step of the same size, the
   * previous step's stage forces, all on the previous collocation polynomial u (u(t_n) = q_n),
   * extrapolated as a polynomial of degree s in time (w->fextrap); else the force at q_n alone.
   * Measured on the outer solar system (gauss-6, h = 312.5), the first change in units of the
   * round-off floor: 2e9–9e9 with the positions of u extrapolated (degree s, as the other
   * solvers start), 4e8–1.5e9 from the stage forces alone, 2e7–2e8 with the force at q_n too:
   * one iteration (s evaluations) fewer for the one evaluation (docs/work-precision.md). */
  double *g0 = g; /* free until the iteration starts */
  const double *kg0;
  if ((st = gm_eval_potential_gradient(it, w->t, q, g0)) != GM_OK) return st;
  if ((st = kinetic_map(w, g0, w->stage + d, &kg0)) != GM_OK) return st; /* stage is 2d */
  if (have_prev && w->fextrap != NULL)
    force_predict(s, d, w->fextrap, kg0, w->z_prev, kg);
  else
    for (size_t i = 0; i < s; ++i) memcpy(kg + i * d, kg0, d * sizeof *kg);
  /* The iteration, stage by stage: the force of stage k is evaluated again only while Z_k has
   * moved from where it was last evaluated (z_eval) by more than the stopping threshold, so
   * stages that converge early (Z_k ∝ c_k² h²: the first ones) stop costing evaluations. The
   * step has converged when every force is at its stage to within that threshold. */
  double *z_eval = w->z_next, *pos = w->z_next + s * d; /* z_next is s·2d */
  double *moved = w->stage_change; /* s: |Z_k − z_eval_k| */
  double *force_size = w->stage_force; /* s: max_r |K(g_k)_r|, set at each evaluation */
  {
    double unused_change = 0.0, unused_scale = 0.0;
    stage_update(s, d, w->a2, kg, base, hh, w->z, w->z, moved, &unused_change, &unused_scale);
  }
  for (size_t k = 0; k < s; ++k) moved[k] = INFINITY;
  const double size_q = gm_norm_inf(d, q), size_terms = h * gm_norm_inf(d, kp);
  double history[3] = {INFINITY, INFINITY, INFINITY}, threshold = 0.0;
  size_t iter = 0;
  for (;;) {
    for (size_t k = 0; k < s; ++k) {
      if (moved[k] <= threshold) continue;
      const double *zk = w->z + k * d;
      double *gk = g + k * d, *kgk = kg + k * d, *ek = z_eval + k * d;
      for (size_t r = 0; r < d; ++r) pos[r] = q[r] + zk[r];
      if ((st = gm_eval_potential_gradient(it, w->t, pos, gk)) != GM_OK) return st;
      if (w->kinetic_identity)
        for (size_t r = 0; r < d; ++r) kgk[r] = gk[r];
      else if ((st = gm_eval_kinetic_gradient(it, w->t, gk, kgk)) != GM_OK)
        return st;
      double size = 0.0;
      for (size_t r = 0; r < d; ++r) {
        ek[r] = zk[r];
        size = max_or_nan(size, fabs(kgk[r]));
      }
      force_size[k] = size;
    }
    if (++iter > FIXED_POINT_MAX_ITERATIONS)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                     "fixed-point iteration on positions did not converge in %d iterations; "
                     "for a stiff problem use --solver simplified-newton",
                     FIXED_POINT_MAX_ITERATIONS);
    it->stats.fixed_point_iterations++;
    /* The round-off floor: of q, of the stages (q may be 0), and of the terms that make a stage,
     * h c_i K(p) and h² (A² K(g))_i, which exceed both when h‖Ω‖ is large (the harmonic
     * oscillator at h = 12: the iteration stalls at 10 × the floor of q) */
    double force_norm = 0.0;
    for (size_t k = 0; k < s; ++k) force_norm = max_or_nan(force_norm, force_size[k]);
    double change = 0.0, scale = fmax(size_q, size_terms + hh * w->a2_norm * force_norm);
    stage_update(s, d, w->a2, kg, base, hh, z_eval, w->z, moved, &change, &scale);
    const double floor = ROUNDOFF_FLOOR * fmax(scale, 1e-300);
    threshold = POSITIONS_SKIP * floor;
    if (!isfinite(change))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                     "fixed-point iteration diverged (a non-finite stage); for a stiff problem use "
                     "--solver simplified-newton");
    push_change(history, change);
    if (positions_converged(history, floor)) break;
  }
  /* The update with the forces already evaluated, for q and p alike (no further evaluation;
   * GNI's irk2 does the same): each is within POSITIONS_STOP × the floor of its stage. */
  for (size_t r = 0; r < d; ++r) {
    double dq = 0.0, dp = 0.0;
    for (size_t k = 0; k < s; ++k) {
      dq += w->ba[k] * kg[k * d + r];
      dp += w->tab->b[k] * g[k * d + r];
    }
    double inc_q = h * kp[r] - hh * dq, inc_p = -h * dp;
    if (delta != NULL) {
      delta[r] = inc_q;
      delta[d + r] = inc_p;
    } else {
      y_new[r] = q[r] + inc_q;
      y_new[d + r] = p[r] + inc_p;
    }
  }
  memcpy(w->z_prev, kg, s * d * sizeof *kg); /* the stage forces, for the next start */
  return GM_OK;
}

/* J = ∂f(t, y_n) and the factors of λ_k/h I − J for every block. */
static gm_status factor_blocks(implicit_rk_work *w, int new_jacobian) {
  gm_integrator *it = w->it;
  const size_t n = it->n, nn = n * n;
  const gm_stage_transform *tr = w->tr;
  if (new_jacobian) {
    gm_status st = gm_eval_rhs_jacobian(it, w->t, w->y, w->jac);
    if (st != GM_OK) return st;
    w->jac_stale = 0;
  }
  size_t kc = 0, kr = 0;
  for (size_t b = 0; b < tr->n_blocks; ++b) {
    const double complex shift = tr->lambda[b] / w->h;
    gm_status st;
    if (cimag(tr->lambda[b]) != 0.0) {
      double complex *m = w->clu + kc * nn;
      for (size_t k = 0; k < nn; ++k) m[k] = -w->jac[k];
      for (size_t k = 0; k < n; ++k) m[k * n + k] += shift;
      st = gm_complex_lu_factor(n, m, w->cpiv + kc * n);
      ++kc;
    } else {
      double *m = w->rlu + kr * nn;
      for (size_t k = 0; k < nn; ++k) m[k] = -w->jac[k];
      for (size_t k = 0; k < n; ++k) m[k * n + k] += creal(shift);
      st = gm_lu_factor(n, m, w->rpiv + kr * n);
      ++kr;
    }
    if (st != GM_OK)
      return gm_fail(it->errmsg, sizeof it->errmsg, st,
                     "the Newton matrix lambda/h I - J is singular (h = %g)", w->h);
  }
  w->lu_h = w->h;
  return GM_OK;
}

/* One simplified Newton iteration through the eigenvalues of A: R = Z − hAF(y + Z),
 * G = −(hA)⁻¹R, (λ_b/h I − J) ΔW_b = (V⁻¹G)_b, ΔZ = Re VΔW. Returns the scaled change. */
static gm_status transformed_iteration(implicit_rk_work *w, double *change) {
  gm_integrator *it = w->it;
  const size_t n = it->n, s = w->tab->n_stages, nn = n * n;
  const gm_stage_transform *tr = w->tr;
  gm_status st = eval_stages(w, w->z);
  if (st != GM_OK) return st;
  apply_tableau(w, w->z_next);
  for (size_t k = 0; k < s * n; ++k) w->z_next[k] = w->z[k] - w->z_next[k]; /* R */
  for (size_t i = 0; i < s; ++i)
    for (size_t k = 0; k < n; ++k) {
      double sum = 0.0;
      for (size_t j = 0; j < s; ++j) sum += tr->ainv[i * s + j] * w->z_next[j * n + k];
      w->g[i * n + k] = -sum / w->h;
    }
  size_t kc = 0, kr = 0;
  for (size_t b = 0; b < tr->n_blocks; ++b) {
    double complex *x = w->cw + b * n;
    for (size_t k = 0; k < n; ++k) {
      double complex sum = 0.0;
      for (size_t j = 0; j < s; ++j) sum += tr->vinv[b * s + j] * w->g[j * n + k];
      x[k] = sum;
    }
    if (cimag(tr->lambda[b]) != 0.0) {
      gm_complex_lu_solve(n, w->clu + kc * nn, w->cpiv + kc * n, x);
      ++kc;
    } else {
      double *tmp = w->stage; /* free between evaluations */
      for (size_t k = 0; k < n; ++k) tmp[k] = creal(x[k]);
      if ((st = gm_lu_solve(n, w->rlu + kr * nn, w->rpiv + kr * n, tmp)) != GM_OK)
        return gm_fail(it->errmsg, sizeof it->errmsg, st, "Newton solve failed");
      for (size_t k = 0; k < n; ++k) x[k] = tmp[k];
      ++kr;
    }
  }
  /* ΔZ into z_next, then the scaled change as in the fixed-point iteration */
  for (size_t i = 0; i < s; ++i)
    for (size_t k = 0; k < n; ++k) {
      double complex sum = 0.0;
      for (size_t b = 0; b < tr->n_blocks; ++b) sum += tr->v[i * s + b] * w->cw[b * n + k];
      w->z_next[i * n + k] = w->z[i * n + k] + creal(sum);
    }
  *change = stage_change(w);
  memcpy(w->z, w->z_next, s * n * sizeof *w->z);
  it->stats.newton_iterations++;
  return isfinite(*change) ? GM_OK
                           : gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                                     "Newton iteration produced a non-finite stage");
}

#define TRANSFORMED_MAX_ITERATIONS 50

/* Simplified Newton with factors kept across steps while they serve (same h, and the last
 * solve contracted fast); on a failure with old factors, once more with a fresh J. */
static gm_status solve_transformed(implicit_rk_work *w) {
  gm_integrator *it = w->it;
  const size_t sn = w->tab->n_stages * it->n;
  memcpy(w->z_start, w->z, sn * sizeof *w->z); /* the starting values, for a retry */
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int fresh = attempt > 0 || w->jac_stale || w->lu_h == 0.0;
    if (fresh || w->lu_h != w->h) {
      gm_status st = factor_blocks(w, fresh);
      if (st != GM_OK) return st;
    }
    if (attempt > 0) memcpy(w->z, w->z_start, sn * sizeof *w->z);
    double history[3] = {INFINITY, INFINITY, INFINITY};
    gm_status st = GM_OK;
    for (size_t iter = 1; iter <= TRANSFORMED_MAX_ITERATIONS; ++iter) {
      double change = 0.0;
      if ((st = transformed_iteration(w, &change)) != GM_OK) break;
      push_change(history, change);
      if (iteration_converged(history, ROUNDOFF_FLOOR)) {
        /* keep J (and, for the same h, the factors) while the iteration contracts well: a
         * new J when the rate θ exceeded 0.1 (RADAU5 tests θ against 0.001 for stiff problems;
         * here a factorization costs more than a few extra iterations) */
        w->jac_stale = isfinite(history[1]) && history[0] > 0.1 * history[1];
        return GM_OK;
      }
      if (iter >= 3 && history[0] > 0.9 * history[1]) {
        st = GM_ENOCONV;
        break;
      }
    }
    if (st == GM_OK) st = GM_ENOCONV;
    if (st != GM_ENOCONV || fresh) {
      if (st == GM_ENOCONV)
        gm_fail(it->errmsg, sizeof it->errmsg, st,
                "simplified Newton did not converge (relative change %.2e)", history[0]);
      w->jac_stale = 1;
      return st;
    }
  }
  return GM_ENOCONV;
}

static gm_status solve(implicit_rk_work *w) {
  gm_integrator *it = w->it;
  if (it->solver == GM_SOLVER_SIMPLIFIED_NEWTON && w->tr != NULL) return solve_transformed(w);
  gm_newton *nw = NULL;
  gm_jacobian_fn jac = NULL;
  switch (it->solver) {
    case GM_SOLVER_FIXED_POINT:
      return solve_fixed_point(w);
    case GM_SOLVER_NEWTON:
      nw = w->newton;
      jac = stage_jacobian;
      break;
    default: /* simplified Newton (set_solver resolved the default) */
      nw = w->simplified;
      jac = stage_jacobian_at_y;
      break;
  }
  gm_status st = gm_newton_solve(nw, stage_residual, jac, w, w->z);
  it->stats.newton_iterations += gm_newton_iterations(nw);
  if (st == GM_ECALLBACK && w->callback_status != GM_OK) return w->callback_status;
  if (st != GM_OK) gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", gm_newton_errmsg(nw));
  return st;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  implicit_rk_work *w = it->work;
  const size_t n = it->n, s = w->tab->n_stages;
  const int positions = it->solver == GM_SOLVER_FIXED_POINT_POSITIONS;
  const size_t sn = s * (positions ? it->dim : n);
  w->it = it;
  w->y = y;
  w->t = t;
  w->h = h;
  w->callback_status = GM_OK;
  if (positions) {
    const int have_prev = w->h_prev == h;
    w->h_prev = 0.0;
    gm_status st = step_positions(w, have_prev, y_new, delta);
    if (st != GM_OK) return gm_stage_solve_failed(it, st, t, h);
    w->h_prev = h;
    return GM_OK;
  }
  /* starting values: the previous collocation polynomial, extrapolated */
  if (w->h_prev == h && w->d != NULL)
    gm_stage_extrapolate(s, sn / s, w->extrap, w->z_prev, w->z);
  else
    memset(w->z, 0, sn * sizeof *w->z);
  w->h_prev = 0.0;
  gm_status st = solve(w);
  if (st != GM_OK) return gm_stage_solve_failed(it, st, t, h);
  memcpy(w->z_prev, w->z, sn * sizeof *w->z);
  w->h_prev = h;
  if (w->d == NULL && (st = eval_stages(w, w->z)) != GM_OK) return st;
  for (size_t k = 0; k < n; ++k) {
    double sum = 0.0;
    if (w->d != NULL)
      for (size_t j = 0; j < s; ++j) sum += w->d[j] * w->z[j * n + k];
    else {
      for (size_t j = 0; j < s; ++j) sum += w->tab->b[j] * w->f[j * n + k];
      sum *= h;
    }
    if (delta != NULL)
      delta[k] = sum;
    else
      y_new[k] = y[k] + sum;
  }
  return GM_OK;
}

const gm_stepper gm_implicit_rk_stepper = {init, step, release, invalidate, NULL, set_solver, 0};

/* Checkpoints: the previous step's stage increments and step size, from which the next step
 * starts its iteration (collocation polynomial extrapolated); with simplified Newton through the
 * eigenvalues of A also the kept Jacobian, its step size and whether it is stale (the factors
 * are recomputed from them on load: the same J gives the same factors). */
static size_t newton_state_doubles(const gm_integrator *it, const implicit_rk_work *w) {
  return w->tr != NULL ? 2 + it->n * it->n : 0;
}
static size_t state_size(const gm_integrator *it) {
  const implicit_rk_work *w = it->work;
  return sizeof(double) * (1 + w->tab->n_stages * it->n + newton_state_doubles(it, w));
}
static void state_save(const gm_integrator *it, unsigned char *out) {
  const implicit_rk_work *w = it->work;
  const size_t nz = w->tab->n_stages * it->n;
  memcpy(out, &w->h_prev, sizeof(double));
  memcpy(out + sizeof(double), w->z_prev, sizeof(double) * nz);
  if (newton_state_doubles(it, w) > 0) {
    unsigned char *p = out + sizeof(double) * (1 + nz);
    const double head[2] = {w->lu_h, w->jac_stale ? 1.0 : 0.0};
    memcpy(p, head, sizeof head);
    memcpy(p + sizeof head, w->jac, sizeof(double) * it->n * it->n);
  }
}
static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  implicit_rk_work *w = it->work;
  const size_t nz = w->tab->n_stages * it->n;
  memcpy(&w->h_prev, in, sizeof(double));
  memcpy(w->z_prev, in + sizeof(double), sizeof(double) * nz);
  if (newton_state_doubles(it, w) > 0) {
    const unsigned char *p = in + sizeof(double) * (1 + nz);
    double head[2];
    memcpy(head, p, sizeof head);
    memcpy(w->jac, p + sizeof head, sizeof(double) * it->n * it->n);
    w->jac_stale = head[1] != 0.0;
    w->lu_h = 0.0;
    if (head[0] != 0.0) {
      w->it = it;
      w->h = head[0];
      return factor_blocks(w, 0);
    }
  }
  return GM_OK;
}
const gm_stepper_state gm_implicit_rk_stepper_state = {0, state_size, state_save, state_load};
