/* Stepper of the mimetic time integrators (seed 003, Palha & Gerritsma, §5).
 *
 * One step is one time element [t_n, t_n + h], τ = 2(t − t_n)/h − 1. The unknowns are the
 * values y^1..y^p of the trajectory at the Gauss–Lobatto nodes ξ_1..ξ_p (y^0 = y_n is given and
 * y^p = y_{n+1}); the trajectory is y_h(τ) = Σ_k y^k l_k(τ). We solve for the increments
 * Z^k = y^k − y^0, which keep their digits when they are small. The equations are, for the p
 * Gauss nodes τ̃_j (dual grid) with weights w_j:
 *   MCI (eq. 5.10):  Σ_l (y^l − y^{l−1}) e_l(τ̃_j) = (h/2) f(y_h(τ̃_j)),
 *   MGI (eq. 5.15):  Σ_l (y^l − y^{l−1}) e_l(τ̃_j) = (h/2) (1/w_j) ∫_{−1}^{1} f(y_h(τ)) l̃_j(τ) dτ,
 * with e_l the edge basis of the primal grid (4.10), l̃_j the Lagrange polynomials of degree
 * p − 1 on the Gauss nodes, and the metric factor h/2 restored as in the notes (the printed
 * equations omit it). The Galerkin integral is computed by a Q-point Gauss rule (option
 * gm_integrator_set_quadrature). Both read, with K_jk = e_k(τ̃_j) − e_{k+1}(τ̃_j) (e_{p+1} = 0),
 * L_qk = l_k(x_q) at the evaluation points x_q and test weights G_jq (MCI: G = I at x = τ̃;
 * MGI: G_jq = W_q l̃_j(x_q) / w_j),
 *   R_j(Z) = Σ_k K_jk Z^k − (h/2) Σ_q G_jq f(t_n + (1 + x_q) h/2, y^0 + Σ_k L_qk Z^k) = 0.
 * Solvers ("Newton-Raphson", §5): full Newton (Jacobian blocks K_jk I − (h/2) Σ_q G_jq L_qk
 * ∂f(y_h(x_q))), simplified Newton (∂f(y_n) once per step: blocks K_jk I − (h/2) (GL)_jk ∂f),
 * or fixed-point iteration Z = (h/2) K⁻¹ G F. Starting values: the previous element's polynomial
 * extrapolated, when the step size did not change (as for Gauss methods, GNI §VIII.6.1). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/mimetic.h"
#include "methods/energy.h"

#define FIXED_POINT_MAX_ITERATIONS 200
#define ENERGY_INCREMENT_TOL 1e-18

typedef struct {
  size_t p;            /* degree: p unknown nodal values */
  int galerkin;
  size_t n_quad;       /* MGI: Gauss points of the Galerkin integral */
  size_t n_points;     /* evaluation points: p (MCI) or n_quad (MGI) */
  gm_time_element *el;
  double *k;           /* p×p */
  double *l;           /* n_points×p */
  double *g;           /* p×n_points (MGI only) */
  double *gl;          /* p×p: G L */
  double *kinv_g;      /* p×n_points: K⁻¹ G */
  double *x;           /* n_points reference nodes */
  double *extrap;      /* p×p: Z⁰ = extrap · Z_prev */
  gm_newton *newton, *simplified;
  double *z, *z_prev, *f, *stage, *jac, *jac_block;
  double h_prev;
  /* dense output: the last element */
  int has_dense;
  double t_dense, h_dense;
  double *y_dense, *z_dense;
  /* the step being solved, seen by the Newton callbacks */
  gm_integrator *it;
  const double *y;
  double t, h;
  gm_status callback_status;
} mimetic_work;

/* K_jk = e_k(τ̃_j) − e_{k+1}(τ̃_j) = l_k'(τ̃_j), j, k = 1..p (row-major p×p), by the edge-basis
 * identity d l_k = e_k − e_{k+1} (seed 003 eq. 4.15; tests/unit/test_mimetic.c checks it to
 * round-off). The nodal derivative is evaluated directly: the running sum of eq. (4.10) carries
 * rounding errors of ε Σ|l'| into K, the same every step, and MGI's energy error would then
 * drift (by about 3e-17 relative per step for p ≥ 3 on Kepler, measured). */
static gm_status edge_matrix(const gm_time_element *el, double *k) {
  const size_t p = el->degree;
  double dl[GM_MIMETIC_MAX_NODES];
  for (size_t j = 0; j < p; ++j) {
    gm_status st = gm_mimetic_nodal_basis_derivative(el->primal, el->gauss_nodes[j], dl);
    if (st != GM_OK) return st;
    for (size_t c = 0; c < p; ++c) k[j * p + c] = dl[c + 1];
  }
  return GM_OK;
}

/* L_qk = l_k(x_q), k = 1..p (l_0 multiplies Z^0 = 0). */
static gm_status nodal_matrix(const gm_time_element *el, size_t n_points, const double *x,
                              double *l) {
  const size_t p = el->degree;
  double v[GM_MIMETIC_MAX_NODES];
  for (size_t q = 0; q < n_points; ++q) {
    gm_status st = gm_mimetic_nodal_basis(el->primal, x[q], v);
    if (st != GM_OK) return st;
    for (size_t c = 0; c < p; ++c) l[q * p + c] = v[c + 1];
  }
  return GM_OK;
}

/* inv = K⁻¹ (p×p) */
static gm_status invert(size_t p, const double *k, double *inv) {
  double lu[GM_MIMETIC_MAX_NODES * GM_MIMETIC_MAX_NODES], col[GM_MIMETIC_MAX_NODES];
  int piv[GM_MIMETIC_MAX_NODES];
  memcpy(lu, k, p * p * sizeof *k);
  gm_status st = gm_lu_factor(p, lu, piv);
  if (st != GM_OK) return st;
  for (size_t c = 0; c < p; ++c) {
    for (size_t r = 0; r < p; ++r) col[r] = r == c;
    if ((st = gm_lu_solve(p, lu, piv, col)) != GM_OK) return st;
    for (size_t r = 0; r < p; ++r) inv[r * p + c] = col[r];
  }
  return GM_OK;
}

/* MCI as a Runge–Kutta method (seed 003 eqs. 5.16–5.32, in the increment form): the stage
 * values are Y_j = y_h(τ̃_j) = y_n + Σ_k L_jk Z^k and Z = (h/2) K⁻¹ F(Y), so
 * A = ½ L K⁻¹, bᵀ = ½ (K⁻¹)_{p,·} (Z^p = y_{n+1} − y_n), c_j = (1 + τ̃_j)/2. */
gm_status gm_mimetic_canonical_tableau(const gm_method *m, gm_tableau *t) {
  const size_t p = m->n_stages;
  gm_time_element *el = NULL;
  double k[GM_MIMETIC_MAX_NODES * GM_MIMETIC_MAX_NODES];
  double inv[GM_MIMETIC_MAX_NODES * GM_MIMETIC_MAX_NODES];
  double l[GM_MIMETIC_MAX_NODES * GM_MIMETIC_MAX_NODES];
  if (p > GM_MIMETIC_MAX_NODES - 2) return GM_EINVAL;
  gm_status st = gm_time_element_create(p, &el, NULL);
  if (st == GM_OK) st = edge_matrix(el, k);
  if (st == GM_OK) st = nodal_matrix(el, p, el->gauss_nodes, l);
  if (st == GM_OK) st = invert(p, k, inv);
  if (st == GM_OK)
    for (size_t i = 0; i < p; ++i) {
      t->c[i] = 0.5 * (1.0 + el->gauss_nodes[i]);
      t->b[i] = 0.5 * inv[(p - 1) * p + i];
      for (size_t j = 0; j < p; ++j) {
        double s = 0.0;
        for (size_t r = 0; r < p; ++r) s += l[i * p + r] * inv[r * p + j];
        t->a[i * p + j] = 0.5 * s;
      }
    }
  gm_time_element_free(el);
  return st;
}

static void free_points(mimetic_work *w) {
  free(w->l);
  free(w->g);
  free(w->gl);
  free(w->kinv_g);
  free(w->x);
  free(w->f);
  w->l = w->g = w->gl = w->kinv_g = w->x = w->f = NULL;
}

/* The evaluation points and the matrices that depend on them. */
static gm_status build_points(mimetic_work *w, size_t n) {
  const size_t p = w->p, np = w->galerkin ? w->n_quad : p;
  free_points(w);
  w->n_points = np;
  w->l = calloc(np * p, sizeof(double));
  w->g = calloc(p * np, sizeof(double));
  w->gl = calloc(p * p, sizeof(double));
  w->kinv_g = calloc(p * np, sizeof(double));
  w->x = calloc(np, sizeof(double));
  w->f = calloc(np * n, sizeof(double));
  double *wq = calloc(np, sizeof(double)), *kinv = calloc(p * p, sizeof(double));
  if (!w->l || !w->g || !w->gl || !w->kinv_g || !w->x || !w->f || !wq || !kinv) {
    free(wq);
    free(kinv);
    return GM_ENOMEM;
  }
  gm_status st = GM_OK;
  const gm_time_element *el = w->el;
  if (w->galerkin) {
    /* G_jq = W_q l̃_j(x_q) / w_j: the dual mass matrix N = diag(w) (eq. 5.39) */
    double lt[GM_MIMETIC_MAX_NODES];
    st = gm_gauss_legendre(np, w->x, wq);
    for (size_t q = 0; q < np && st == GM_OK; ++q) {
      st = gm_lagrange_basis(p, el->gauss_nodes, w->x[q], lt);
      for (size_t j = 0; j < p; ++j) w->g[j * np + q] = wq[q] * lt[j] / el->gauss_weights[j];
    }
  } else {
    memcpy(w->x, el->gauss_nodes, p * sizeof(double));
    for (size_t j = 0; j < p; ++j) w->g[j * np + j] = 1.0;
  }
  if (st == GM_OK) st = nodal_matrix(el, np, w->x, w->l);
  if (st == GM_OK) st = invert(p, w->k, kinv);
  if (st == GM_OK)
    for (size_t j = 0; j < p; ++j) {
      for (size_t c = 0; c < p; ++c) {
        double s = 0.0;
        for (size_t q = 0; q < np; ++q) s += w->g[j * np + q] * w->l[q * p + c];
        w->gl[j * p + c] = s;
      }
      for (size_t q = 0; q < np; ++q) {
        double s = 0.0;
        for (size_t r = 0; r < p; ++r) s += kinv[j * p + r] * w->g[r * np + q];
        w->kinv_g[j * np + q] = s;
      }
    }
  free(wq);
  free(kinv);
  return st;
}

/* Z⁰_k = y_prev(ξ_k + 2) − y_prev(1) = Σ_m l_m(ξ_k + 2) Z_prev^m − Z_prev^p (the nodal basis
 * sums to one and Z_prev^0 = 0). */
static gm_status build_extrapolation(mimetic_work *w) {
  const size_t p = w->p;
  const double *xi = gm_mimetic_grid_nodes(w->el->primal);
  double v[GM_MIMETIC_MAX_NODES];
  for (size_t r = 0; r < p; ++r) {
    gm_status st = gm_mimetic_nodal_basis(w->el->primal, xi[r + 1] + 2.0, v);
    if (st != GM_OK) return st;
    for (size_t c = 0; c < p; ++c) w->extrap[r * p + c] = v[c + 1] - (c + 1 == p ? 1.0 : 0.0);
  }
  return GM_OK;
}

static gm_status init(gm_integrator *it) {
  mimetic_work *w = calloc(1, sizeof *w);
  if (w == NULL) return GM_ENOMEM;
  it->work = w;
  const gm_method *m = it->method;
  const size_t n = it->n, p = m->n_stages;
  gm_error err;
  w->p = p;
  w->galerkin = gm_mimetic_is_galerkin(m);
  w->n_quad = 2 * p + 6;
  gm_status st = gm_jacobian_work(it); /* its Newton solvers evaluate Jacobians */
  if (st != GM_OK) return st;
  st = gm_time_element_create(p, &w->el, &err);
  if (st != GM_OK) return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s: %s", m->name, err.message);
  w->k = calloc(p * p, sizeof(double));
  w->extrap = calloc(p * p, sizeof(double));
  w->z = calloc(p * n, sizeof(double));
  w->z_prev = calloc(p * n, sizeof(double));
  w->stage = calloc(n, sizeof(double));
  w->jac = calloc(n * n, sizeof(double));
  w->y_dense = calloc(n, sizeof(double));
  w->z_dense = calloc(p * n, sizeof(double));
  if (!w->k || !w->extrap || !w->z || !w->z_prev || !w->stage || !w->jac || !w->y_dense ||
      !w->z_dense)
    return GM_ENOMEM;
  if ((st = edge_matrix(w->el, w->k)) != GM_OK || (st = build_points(w, n)) != GM_OK ||
      (st = build_extrapolation(w)) != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "%s: setting up the element failed",
                   m->name);
  gm_newton_options opt = gm_newton_defaults();
  /* MGI keeps H only as well as the equations are solved: ΔH = Σ_j (residual_j)ᵀ(∫∇H l̃_j), so
   * it iterates until the increments stop shrinking (round-off) rather than to 1e-14. */
  if (w->galerkin) opt.increment_tol = ENERGY_INCREMENT_TOL;
  if ((st = gm_newton_create(p * n, &opt, &w->newton)) != GM_OK) return st;
  opt.simplified = 1;
  opt.max_iterations = 100; /* linear convergence, rate O(h‖J‖) */
  return gm_newton_create(p * n, &opt, &w->simplified);
}

static void release(gm_integrator *it) {
  mimetic_work *w = it->work;
  if (w == NULL) return;
  free_points(w);
  gm_time_element_free(w->el);
  gm_newton_free(w->newton);
  gm_newton_free(w->simplified);
  free(w->k);
  free(w->extrap);
  free(w->z);
  free(w->z_prev);
  free(w->stage);
  free(w->jac);
  free(w->y_dense);
  free(w->z_dense);
  free(w);
  it->work = NULL;
}

static void invalidate(gm_integrator *it) {
  mimetic_work *w = it->work;
  if (w == NULL) return;
  w->h_prev = 0.0;
  w->has_dense = 0;
}

/* F_q = f(y_h(x_q)) at every evaluation point. */
static gm_status eval_points(mimetic_work *w, const double *z) {
  gm_integrator *it = w->it;
  const size_t n = it->n, p = w->p;
  for (size_t q = 0; q < w->n_points; ++q) {
    const double *lq = w->l + q * p;
    for (size_t r = 0; r < n; ++r) {
      double s = 0.0;
      for (size_t c = 0; c < p; ++c) s += lq[c] * z[c * n + r];
      w->stage[r] = w->y[r] + s;
    }
    gm_status st = gm_eval_rhs(it, w->t + 0.5 * (1.0 + w->x[q]) * w->h, w->stage, w->f + q * n);
    if (st != GM_OK) return st;
  }
  return GM_OK;
}

/* R_j = Σ_k K_jk Z^k − (h/2) Σ_q G_jq F_q */
static int residual(void *ctx, const double *z, double *r) {
  mimetic_work *w = ctx;
  const size_t n = w->it->n, p = w->p, np = w->n_points;
  const double half_h = 0.5 * w->h;
  if ((w->callback_status = eval_points(w, z)) != GM_OK) return 1;
  for (size_t j = 0; j < p; ++j)
    for (size_t i = 0; i < n; ++i) {
      double lhs = 0.0, rhs = 0.0;
      for (size_t c = 0; c < p; ++c) lhs += w->k[j * p + c] * z[c * n + i];
      if (w->galerkin)
        for (size_t q = 0; q < np; ++q) rhs += w->g[j * np + q] * w->f[q * n + i];
      else
        rhs = w->f[j * n + i];
      r[j * n + i] = lhs - half_h * rhs;
    }
  return 0;
}

/* Simplified: blocks K_jk I − (h/2)(GL)_jk ∂f(y_n). */
static int jacobian_at_y(void *ctx, const double *z, double *jac) {
  (void)z;
  mimetic_work *w = ctx;
  gm_integrator *it = w->it;
  const size_t n = it->n, p = w->p, pn = p * n;
  w->callback_status = gm_eval_rhs_jacobian(it, w->t, w->y, w->jac);
  if (w->callback_status != GM_OK) return 1;
  for (size_t j = 0; j < p; ++j)
    for (size_t c = 0; c < p; ++c) {
      const double kc = w->k[j * p + c], mc = -0.5 * w->h * w->gl[j * p + c];
      for (size_t r = 0; r < n; ++r)
        for (size_t s = 0; s < n; ++s)
          jac[(j * n + r) * pn + c * n + s] = mc * w->jac[r * n + s] + (r == s ? kc : 0.0);
    }
  return 0;
}

/* Full Newton: blocks K_jk I − (h/2) Σ_q G_jq L_qk ∂f(y_h(x_q)). */
static int jacobian_full(void *ctx, const double *z, double *jac) {
  mimetic_work *w = ctx;
  gm_integrator *it = w->it;
  const size_t n = it->n, p = w->p, pn = p * n, np = w->n_points;
  for (size_t j = 0; j < p; ++j)
    for (size_t c = 0; c < p; ++c)
      for (size_t r = 0; r < n; ++r)
        for (size_t s = 0; s < n; ++s)
          jac[(j * n + r) * pn + c * n + s] = r == s ? w->k[j * p + c] : 0.0;
  for (size_t q = 0; q < np; ++q) {
    const double *lq = w->l + q * p;
    for (size_t r = 0; r < n; ++r) {
      double s = 0.0;
      for (size_t c = 0; c < p; ++c) s += lq[c] * z[c * n + r];
      w->stage[r] = w->y[r] + s;
    }
    w->callback_status =
        gm_eval_rhs_jacobian(it, w->t + 0.5 * (1.0 + w->x[q]) * w->h, w->stage, w->jac);
    if (w->callback_status != GM_OK) return 1;
    for (size_t j = 0; j < p; ++j) {
      const double gjq = w->galerkin ? w->g[j * np + q] : (j == q ? 1.0 : 0.0);
      if (gjq == 0.0) continue;
      for (size_t c = 0; c < p; ++c) {
        const double coef = -0.5 * w->h * gjq * lq[c];
        for (size_t r = 0; r < n; ++r)
          for (size_t s = 0; s < n; ++s) jac[(j * n + r) * pn + c * n + s] += coef * w->jac[r * n + s];
      }
    }
  }
  return 0;
}

/* Z ← (h/2) K⁻¹ G F(y_h), until the change is below the round-off of y. */
static gm_status solve_fixed_point(mimetic_work *w) {
  gm_integrator *it = w->it;
  const size_t n = it->n, p = w->p, np = w->n_points;
  const double floor = 4.0 * 2.220446049250313e-16 * fmax(gm_norm_inf(n, w->y), 1e-300);
  double previous = INFINITY;
  for (size_t iter = 1; iter <= FIXED_POINT_MAX_ITERATIONS; ++iter) {
    gm_status st = eval_points(w, w->z);
    if (st != GM_OK) return st;
    double change = 0.0;
    for (size_t c = 0; c < p; ++c)
      for (size_t i = 0; i < n; ++i) {
        double s = 0.0;
        for (size_t q = 0; q < np; ++q) s += w->kinv_g[c * np + q] * w->f[q * n + i];
        s *= 0.5 * w->h;
        change = fmax(change, fabs(s - w->z[c * n + i]));
        w->z[c * n + i] = s;
      }
    it->stats.fixed_point_iterations++;
    if (!isfinite(change))
      return gm_fail(it->errmsg, sizeof it->errmsg, GM_EDOMAIN,
                     "fixed-point iteration produced a non-finite node value");
    if (change <= floor || (change >= previous && change <= 1e3 * floor)) return GM_OK;
    previous = change;
  }
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOCONV,
                 "fixed-point iteration did not converge in %d iterations (change %.2e)",
                 FIXED_POINT_MAX_ITERATIONS, previous);
}

static gm_status solve(mimetic_work *w) {
  gm_integrator *it = w->it;
  if (it->solver == GM_SOLVER_FIXED_POINT) return solve_fixed_point(w);
  const int full = it->solver == GM_SOLVER_NEWTON;
  gm_newton *nw = full ? w->newton : w->simplified;
  gm_status st = gm_newton_solve(nw, residual, full ? jacobian_full : jacobian_at_y, w, w->z);
  it->stats.newton_iterations += gm_newton_iterations(nw);
  if (st == GM_ECALLBACK && w->callback_status != GM_OK) return w->callback_status;
  if (st != GM_OK) gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", gm_newton_errmsg(nw));
  return st;
}

static gm_status step(gm_integrator *it, double t, double h, const double *y, double *y_new,
                      double *delta) {
  mimetic_work *w = it->work;
  const size_t n = it->n, p = w->p, pn = p * n;
  w->it = it;
  w->y = y;
  w->t = t;
  w->h = h;
  w->callback_status = GM_OK;
  if (w->h_prev == h)
    gm_stage_extrapolate(p, n, w->extrap, w->z_prev, w->z);
  else
    memset(w->z, 0, pn * sizeof *w->z);
  w->h_prev = 0.0;
  gm_status st = solve(w);
  if (st != GM_OK) return gm_stage_solve_failed(it, st, t, h);
  memcpy(w->z_prev, w->z, pn * sizeof *w->z);
  w->h_prev = h;
  memcpy(w->z_dense, w->z, pn * sizeof *w->z);
  memcpy(w->y_dense, y, n * sizeof *y);
  w->t_dense = t;
  w->h_dense = h;
  w->has_dense = 1;
  const double *zp = w->z + (p - 1) * n; /* y^p − y^0 */
  for (size_t i = 0; i < n; ++i) {
    if (delta != NULL)
      delta[i] = zp[i];
    else
      y_new[i] = y[i] + zp[i];
  }
  return GM_OK;
}

static gm_status set_solver(gm_integrator *it, gm_solver solver) {
  if (solver == GM_SOLVER_FIXED_POINT_POSITIONS)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "solver fixed-point-positions needs a Runge-Kutta method; '%s' solves for "
                   "its nodal values (use newton, simplified-newton or fixed-point)",
                   it->method->name);
  it->solver = solver;
  return GM_OK;
}

const gm_stepper gm_mimetic_stepper = {init, step, release, invalidate, NULL, set_solver, 0};

gm_status gm_mimetic_set_quadrature(gm_integrator *it, size_t n_points) {
  mimetic_work *w = it->work;
  if (!w->galerkin)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                   "'%s' evaluates f at the Gauss points: it has no Galerkin integral to set a "
                   "quadrature for", it->method->name);
  if (n_points > 256)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "at most 256 quadrature points, got %zu", n_points);
  w->n_quad = n_points == GM_QUADRATURE_DEFAULT ? 2 * w->p + 6 : n_points;
  gm_status st = build_points(w, it->n);
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "quadrature of %zu points: %s", w->n_quad,
                   gm_strerror(st));
  return GM_OK;
}

size_t gm_mimetic_quadrature(const gm_integrator *it) {
  const mimetic_work *w = it->work;
  return w->galerkin ? w->n_quad : 0;
}

gm_status gm_mimetic_dense_output(const gm_integrator *it, double t, double *y) {
  if (it == NULL || y == NULL) return GM_EINVAL;
  if (it->method->family != GM_FAMILY_MIMETIC) return GM_EUNSUPPORTED;
  const mimetic_work *w = it->work;
  if (!w->has_dense || !isfinite(t)) return GM_EINVAL;
  double v[GM_MIMETIC_MAX_NODES];
  const double tau = 2.0 * (t - w->t_dense) / w->h_dense - 1.0;
  gm_status st = gm_mimetic_nodal_basis(w->el->primal, tau, v);
  if (st != GM_OK) return st;
  const size_t n = it->n, p = w->p;
  for (size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (size_t c = 0; c < p; ++c) s += v[c + 1] * w->z_dense[c * n + i];
    y[i] = w->y_dense[i] + s;
  }
  return GM_OK;
}

gm_status gm_integrator_set_quadrature(gm_integrator *it, size_t n_points) {
  if (it == NULL) return GM_EINVAL;
  if (it->method->family == GM_FAMILY_MIMETIC) return gm_mimetic_set_quadrature(it, n_points);
  if (it->method->family == GM_FAMILY_DISCRETE_GRADIENT)
    return gm_discrete_gradient_set_quadrature(it, n_points);
  return gm_fail(it->errmsg, sizeof it->errmsg, GM_EUNSUPPORTED,
                 "'%s' has no quadrature setting (mimetic-galerkin-p and avf do)",
                 it->method->name);
}

size_t gm_integrator_quadrature(const gm_integrator *it) {
  if (it == NULL) return 0;
  if (it->method->family == GM_FAMILY_MIMETIC) return gm_mimetic_quadrature(it);
  if (it->method->family == GM_FAMILY_DISCRETE_GRADIENT)
    return gm_discrete_gradient_quadrature(it);
  return 0;
}

/* Checkpoints: the previous step's coefficients and size (starting values of the next step).
 * The dense output of the last step (gm_mimetic_dense_output) is not saved: after a restart it
 * is available again after the next step. */
static size_t state_size(const gm_integrator *it) {
  const mimetic_work *w = it->work;
  return sizeof(double) * (1 + w->p * it->n);
}
static void state_save(const gm_integrator *it, unsigned char *out) {
  const mimetic_work *w = it->work;
  memcpy(out, &w->h_prev, sizeof(double));
  memcpy(out + sizeof(double), w->z_prev, sizeof(double) * w->p * it->n);
}
static gm_status state_load(gm_integrator *it, const unsigned char *in) {
  mimetic_work *w = it->work;
  memcpy(&w->h_prev, in, sizeof(double));
  memcpy(w->z_prev, in + sizeof(double), sizeof(double) * w->p * it->n);
  w->has_dense = 0;
  return GM_OK;
}
const gm_stepper_state gm_mimetic_stepper_state = {0, state_size, state_save, state_load};
