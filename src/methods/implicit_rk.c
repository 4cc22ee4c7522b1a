/* Stepper for implicit Runge–Kutta and partitioned Runge–Kutta methods.
 *
 * The unknowns are the stage increments Z_i = Y_i − y_n, solving
 *   Z_i = h Σ_j Ã_ij f(t + c_j h, y_n + Z_j),
 * where Ã_ij = a_ij on the q-components (or all components, for plain RK) and ā_ij on the
 * p-components of a partitioned method (f = (∇_p H, −∇_q H)). Solvers (gm_solver):
 *   - Newton with the exact Jacobian δ_ij I − h Ã_ij ∂f(y_n + Z_j);
 *   - simplified Newton: ∂f(y_n) once per step, one LU of I − h Ã⊗J per step
 *     (Hairer & Wanner, Solving ODEs II (1996), §IV.8);
 *   - fixed-point iteration Z ← h Ã F(y_n + Z) (GNI (2006), §VIII.6);
 *   - for q'' = f(q) (separable, quadratic T): fixed-point iteration on positions only.
 * Every solver starts from the previous step's collocation polynomial extrapolated to the new
 * stages (GNI §VIII.6.1) when the step size did not change, and iterates to round-off.
 * The update is y_{n+1} = y_n + Σ_j d_j Z_j with dᵀ = bᵀA⁻¹ when A is invertible (no extra
 * evaluation of f; Hairer & Wanner II, eq. (IV.8.2b)), else y_n + h Σ_j b_j f(Y_j). */
#include <math.h>
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
  gm_newton *newton, *simplified;
  double *z, *z_prev, *z_next;  /* s·n */
  double *f;           /* s·n values f(Y_j) */
  double *stage;       /* n */
  double *jac;         /* n×n */
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
  w->z = calloc(s * n, sizeof(double));
  w->z_prev = calloc(s * n, sizeof(double));
  w->z_next = calloc(s * n, sizeof(double));
  w->f = calloc(s * n, sizeof(double));
  w->stage = calloc(n, sizeof(double));
  w->jac = calloc(n * n, sizeof(double));
  double *at = calloc(s * s, sizeof(double));
  if (!w->d || !w->extrap || !w->a2 || !w->ba || !w->z || !w->z_prev || !w->z_next || !w->f ||
      !w->stage || !w->jac || !at) {
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
  if (w->d != NULL && (st = extrapolation_matrix(w, s)) != GM_OK) return st;
  gm_newton_options opt = gm_newton_defaults();
  if ((st = gm_newton_create(s * n, &opt, &w->newton)) != GM_OK) return st;
  opt.simplified = 1;
  opt.max_iterations = 100; /* linear convergence, rate O(h‖J‖) */
  return gm_newton_create(s * n, &opt, &w->simplified);
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
  free(w->z);
  free(w->z_prev);
  free(w->z_next);
  free(w->f);
  free(w->stage);
  free(w->jac);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  implicit_rk_work *w = it->work;
  if (w != NULL) w->h_prev = 0.0;
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

/* Iterate Z ← h Ã F(y + Z) until the change is below the round-off of y, or stops shrinking
 * there. */
static gm_status solve_fixed_point(implicit_rk_work *w) {
  gm_integrator *it = w->it;
  const size_t sn = w->tab->n_stages * it->n;
  const double floor = 4.0 * 2.220446049250313e-16 * fmax(gm_norm_inf(it->n, w->y), 1e-300);
  double previous = INFINITY;
  for (size_t iter = 1; iter <= FIXED_POINT_MAX_ITERATIONS; ++iter) {
    gm_status st = eval_stages(w, w->z);
    if (st != GM_OK) return st;
    apply_tableau(w, w->z_next);
    double change = 0.0;
    for (size_t k = 0; k < sn; ++k) change = fmax(change, fabs(w->z_next[k] - w->z[k]));
    memcpy(w->z, w->z_next, sn * sizeof *w->z);
    it->stats.fixed_point_iterations++;
    if (!isfinite(change))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                     "fixed-point iteration produced a non-finite stage");
    if (change <= floor || (change >= previous && change <= 1e3 * floor)) return GM_OK;
    previous = change;
  }
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                 "fixed-point iteration did not converge in %d iterations (change %.2e)",
                 FIXED_POINT_MAX_ITERATIONS, previous);
}

/* q'' = f(q) with T(p) = ½pᵀM⁻¹p, K = ∇T linear: Q_i = q + h c_i K(p) − h² Σ_k (A²)_ik K(g_k),
 * g_k = ∇V(Q_k); then q_{n+1} = q + h K(p) − h² Σ_k (bᵀA)_k K(g_k), p_{n+1} = p − h Σ b_k g_k
 * (the Runge–Kutta–Nyström form of a Runge–Kutta method; Hairer, Nørsett & Wanner, Solving
 * ODEs I (1993), §II.14). The unknowns are the s·d stage positions only; z holds them. */
static gm_status step_positions(implicit_rk_work *w, double *y_new, double *delta) {
  gm_integrator *it = w->it;
  const size_t d = it->dim, s = w->tab->n_stages;
  const double *q = w->y, *p = w->y + d, h = w->h;
  double *kp = w->stage, *g = w->f, *kg = w->f + s * d; /* f has room for 2·s·d */
  gm_status st = gm_eval_kinetic_gradient(it, w->t, p, kp);
  if (st != GM_OK) return st;
  const double floor = 4.0 * 2.220446049250313e-16 * fmax(gm_norm_inf(d, q), 1e-300);
  double previous = INFINITY;
  size_t iter = 0;
  for (;;) {
    for (size_t k = 0; k < s; ++k) {
      for (size_t r = 0; r < d; ++r) w->z_next[r] = q[r] + w->z[k * d + r];
      if ((st = gm_eval_potential_gradient(it, w->t, w->z_next, g + k * d)) != GM_OK) return st;
      if ((st = gm_eval_kinetic_gradient(it, w->t, g + k * d, kg + k * d)) != GM_OK) return st;
    }
    if (++iter > FIXED_POINT_MAX_ITERATIONS)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                     "fixed-point iteration on positions did not converge in %d iterations",
                     FIXED_POINT_MAX_ITERATIONS);
    it->stats.fixed_point_iterations++;
    double change = 0.0;
    for (size_t i = 0; i < s; ++i)
      for (size_t r = 0; r < d; ++r) {
        double sum = 0.0;
        for (size_t k = 0; k < s; ++k) sum += w->a2[i * s + k] * kg[k * d + r];
        double zi = h * w->tab->c[i] * kp[r] - h * h * sum;
        change = fmax(change, fabs(zi - w->z[i * d + r]));
        w->z[i * d + r] = zi;
      }
    if (!isfinite(change))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                     "fixed-point iteration produced a non-finite stage");
    if (change <= floor || (change >= previous && change <= 1e3 * floor)) break;
    previous = change;
  }
  /* forces at the converged positions */
  for (size_t k = 0; k < s; ++k) {
    for (size_t r = 0; r < d; ++r) w->z_next[r] = q[r] + w->z[k * d + r];
    if ((st = gm_eval_potential_gradient(it, w->t, w->z_next, g + k * d)) != GM_OK) return st;
    if ((st = gm_eval_kinetic_gradient(it, w->t, g + k * d, kg + k * d)) != GM_OK) return st;
  }
  for (size_t r = 0; r < d; ++r) {
    double dq = 0.0, dp = 0.0;
    for (size_t k = 0; k < s; ++k) {
      dq += w->ba[k] * kg[k * d + r];
      dp += w->tab->b[k] * g[k * d + r];
    }
    double inc_q = h * kp[r] - h * h * dq, inc_p = -h * dp;
    if (delta != NULL) {
      delta[r] = inc_q;
      delta[d + r] = inc_p;
    } else {
      y_new[r] = q[r] + inc_q;
      y_new[d + r] = p[r] + inc_p;
    }
  }
  return GM_OK;
}

static gm_status solve(implicit_rk_work *w) {
  gm_integrator *it = w->it;
  gm_newton *nw = NULL;
  gm_jacobian_fn jac = NULL;
  switch (it->solver) {
    case GM_SOLVER_FIXED_POINT:
      return solve_fixed_point(w);
    case GM_SOLVER_NEWTON:
      nw = w->newton;
      jac = stage_jacobian;
      break;
    default:
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
  /* starting values: the previous collocation polynomial, extrapolated */
  if (w->h_prev == h && w->d != NULL)
    gm_stage_extrapolate(s, sn / s, w->extrap, w->z_prev, w->z);
  else
    memset(w->z, 0, sn * sizeof *w->z);
  w->h_prev = 0.0;
  gm_status st = positions ? step_positions(w, y_new, delta) : solve(w);
  if (st != GM_OK) return gm_stage_solve_failed(it, st, t, h);
  memcpy(w->z_prev, w->z, sn * sizeof *w->z);
  w->h_prev = h;
  if (positions) return GM_OK;
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

static gm_status set_solver(gm_integrator *it, gm_solver solver) {
  if (solver == GM_SOLVER_FIXED_POINT_POSITIONS) {
    const gm_problem *pb = it->problem;
    if (it->method->family != GM_FAMILY_IMPLICIT_RK || pb->kind != GM_PROBLEM_SEPARABLE ||
        !pb->kinetic_is_quadratic)
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                     "solver fixed-point-positions needs a Runge-Kutta method (got '%s') and a "
                     "separable problem with quadratic kinetic energy (kinetic_is_quadratic)",
                     it->method->name);
  }
  it->solver = solver;
  invalidate(it); /* the stored stages have another shape */
  return GM_OK;
}

const gm_stepper gm_implicit_rk_stepper = {init, step, release, invalidate, NULL, set_solver};

/* Checkpoints: the previous step's stage increments and step size, from which the next step
 * starts its iteration (collocation polynomial extrapolated). */
static size_t state_size(const gm_integrator *it) {
  const implicit_rk_work *w = it->work;
  return sizeof(double) * (1 + w->tab->n_stages * it->n);
}
static void state_save(const gm_integrator *it, unsigned char *out) {
  const implicit_rk_work *w = it->work;
  memcpy(out, &w->h_prev, sizeof(double));
  memcpy(out + sizeof(double), w->z_prev, sizeof(double) * w->tab->n_stages * it->n);
}
static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  implicit_rk_work *w = it->work;
  memcpy(&w->h_prev, in, sizeof(double));
  memcpy(w->z_prev, in + sizeof(double), sizeof(double) * w->tab->n_stages * it->n);
  return GM_OK;
}
const gm_stepper_state gm_implicit_rk_stepper_state = {0, state_size, state_save, state_load};
