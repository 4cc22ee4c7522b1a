/* Galerkin Lie group variational integrators in the exponential chart (seed 001 §5.3) and, for
 * left-invariant Lagrangians, their reduced form, the discrete Euler–Poincaré equations
 * (§5.4). The stationarity conditions printed in the thesis are garbled (seeds/notes/001 §4);
 * the ones below are derived here and written out in docs/lie-groups.md.
 *
 * Curve on one step: R(τh) = R0 exp(ξ(τ)), ξ(τ) = Σ_{κ=0..s} ξ^κ l_κ(τ), degree s, control
 * times d_κ (Gauss–Lobatto, d_0 = 0, d_s = 1; any s + 1 distinct times span the same space),
 * ξ^0 = 0, ξ^s = log(R0ᵀR1). Body velocity Ω = dexp_{−ξ} ξ̇ (geomint/lie.h). With s Gauss
 * points (c_i, b_i) the action is
 *   S = h Σ_i b_i [½ Ω_i·JΩ_i + ½ m|ẋ_i|² − V(R0 exp ξ_i, x_i)],  ξ_i = ξ(c_i), ξ̇_i = ξ'(c_i)/h,
 * x(τ) likewise with x^0 = x0. L_d(R0, R1) is S made stationary in ξ^1..ξ^{s−1}. Then, with
 * M_i = JΩ_i and g_i the body gradient of V at R_i = R0 exp ξ_i,
 *   ∂S/∂ξ^ν = h Σ_i b_i [ (l'_ν(c_i)/h) dexp_{−ξ_i}ᵀ M_i
 *                         + l_ν(c_i) (D(ξ_i, ξ̇_i)ᵀ M_i − dexp_{−ξ_i}ᵀ g_i) ],
 * D(ξ, v) = ∂(dexp_{−ξ} v)/∂ξ the derivative of the body velocity in the base point of the chart
 * ("ddexp", below). The left-trivialized discrete Legendre transforms follow from
 * R0 → R0 exp(εη) (which moves ξ^s by −dexp_{ξ^s}⁻¹η and every R_i by exp(ε exp(−ξ̂_i)η)) and
 * R1 → R1 exp(εη) (which moves ξ^s by dexp_{−ξ^s}⁻¹η):
 *   Π0 = −D₁L_d = h Σ_i b_i exp(ξ̂_i) g_i + dexp_{ξ^s}⁻ᵀ ∂S/∂ξ^s,
 *   Π1 =  D₂L_d = dexp_{−ξ^s}⁻ᵀ ∂S/∂ξ^s,
 * and for x: p0 = −∂S/∂x^0, p1 = ∂S/∂x^s. A step solves ∂S/∂ξ^ν = 0, ∂S/∂x^ν = 0
 * (ν = 1..s−1) and the two momentum equations at the start for (ξ^1..ξ^s, x^1..x^s) by Newton's
 * method (difference Jacobian), then R1 = R0 exp(ξ^s). For s = 1 the curve is a one-parameter
 * subgroup and Π1 = exp(−ξ̂)Π0 for a free body.
 * Discrete Euler–Poincaré: for a free body S does not depend on R0, L_d(R0, R1) = l_d(f) with
 * f = R0ᵀR1, and the same conditions are the reduced equations μ_k ↦ f_k ↦ μ_{k+1} with
 * reconstruction R_{k+1} = R_k f_k; the dep-* rows solve them without ever evaluating R. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "methods/lie_group/lie_group.h"

/* c2'(θ)/θ and c3'(θ)/θ for c2 = (1 − cos θ)/θ², c3 = (θ − sin θ)/θ³:
 *   c2'/θ = Σ_{k≥1} (−1)^k 2k θ^{2k−2}/(2k+2)!,  c3'/θ = Σ_{k≥1} (−1)^k 2k θ^{2k−2}/(2k+3)!
 * (series below θ = 2, closed forms above). */
static double c2_prime_over_theta(double t) {
  double t2 = t * t;
  if (t >= 2.0) return (t * sin(t) - 2.0 * (1.0 - cos(t))) / (t2 * t2);
  double a = -1.0 / 24.0, sum = 2.0 * a; /* a_k = (−1)^k θ^{2k−2}/(2k+2)! */
  for (int k = 2; k < 40 && fabs(a) > 1e-19; ++k) {
    a *= -t2 / ((2.0 * k + 1.0) * (2.0 * k + 2.0));
    sum += 2.0 * k * a;
  }
  return sum;
}

static double c3_prime_over_theta(double t) {
  double t2 = t * t;
  if (t >= 2.0) return (3.0 * sin(t) - 2.0 * t - t * cos(t)) / (t2 * t2 * t);
  double a = -1.0 / 120.0, sum = 2.0 * a;
  for (int k = 2; k < 40 && fabs(a) > 1e-19; ++k) {
    a *= -t2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
    sum += 2.0 * k * a;
  }
  return sum;
}

/* D(ξ, v) = ∂/∂ξ [dexp_{−ξ} v], dexp_{−ξ} v = v − c2 ξ × v + c3 ξ × (ξ × v):
 * D = c2 v̂ + c3 ((ξ·v) I + ξ vᵀ − 2 v ξᵀ) − (c2'/θ)(ξ × v) ξᵀ + (c3'/θ)(ξ × (ξ × v)) ξᵀ */
static void ddexp(const double xi[3], const double v[3], double d[9]) {
  double t = gm_vec3_norm(xi), c2 = gm_so3_cosc(t), c3 = gm_so3_sinc3(t);
  double dc2 = c2_prime_over_theta(t), dc3 = c3_prime_over_theta(t);
  double xv[3], xxv[3], vh[9];
  gm_vec3_cross(xi, v, xv);
  gm_vec3_cross(xi, xv, xxv);
  gm_so3_hat(v, vh);
  double xdv = gm_vec3_dot(xi, v);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      d[3 * r + c] = c2 * vh[3 * r + c] +
                     c3 * ((r == c ? xdv : 0.0) + xi[r] * v[c] - 2.0 * v[r] * xi[c]) -
                     dc2 * xv[r] * xi[c] + dc3 * xxv[r] * xi[c];
}

#define GAL_MAX_S 4

typedef struct gm_lie_galerkin {
  size_t s, nt, n_unknowns;  /* degree, translational dimension, 3s(1 + nt/3) */
  int reduced;               /* dep-*: free body, V never evaluated */
  double c[GAL_MAX_S], b[GAL_MAX_S];               /* Gauss points on [0, 1] */
  double l[GAL_MAX_S][GAL_MAX_S + 1];              /* l_κ(c_i) */
  double dl[GAL_MAX_S][GAL_MAX_S + 1];             /* l'_κ(c_i) */
  double d[GAL_MAX_S + 1];                         /* control times */
  gm_newton *newton;                               /* simplified Newton */
  gm_newton *full;                                 /* full Newton, when simplified stalls */
  double *u;                                       /* unknowns: ξ^κ/h, then (x^κ − x0)/h */
  /* the current step */
  gm_integrator *it;
  const double *y0;
  double t, h;
  gm_status callback_status;
  double ds_last[3], dsx_last[3];                  /* ∂S/∂ξ^s, ∂S/∂x^s at the solution */
  int warm;                                        /* u holds the last step's solution */
  double h_warm;                                   /* ... for this step size */
} gm_lie_galerkin;

/* Residual of the step equations at the scaled unknowns u. */
static int residual(void *ctx, const double *u, double *res) {
  gm_lie_galerkin *g = ctx;
  gm_integrator *it = g->it;
  gm_lie_work *w = it->work;
  const size_t s = g->s, nt = g->nt, pi = w->pi;
  const double h = g->h, *y0 = g->y0;
  double ds[GAL_MAX_S + 1][3], dsx[GAL_MAX_S + 1][3], sum_rg[3] = {0, 0, 0};
  memset(ds, 0, sizeof ds);
  memset(dsx, 0, sizeof dsx);
  for (size_t i = 0; i < s; ++i) {
    double xi[3] = {0, 0, 0}, xid[3] = {0, 0, 0}, x[3] = {0, 0, 0}, xd[3] = {0, 0, 0};
    for (size_t k = 1; k <= s; ++k)
      for (int a = 0; a < 3; ++a) {
        xi[a] += g->l[i][k] * h * u[3 * (k - 1) + a];
        xid[a] += g->dl[i][k] * u[3 * (k - 1) + a]; /* (1/h) Σ l'_κ ξ^κ */
        if (nt) {
          x[a] += g->l[i][k] * h * u[3 * s + 3 * (k - 1) + a];
          xd[a] += g->dl[i][k] * u[3 * s + 3 * (k - 1) + a];
        }
      }
    if (nt)
      for (int a = 0; a < 3; ++a) x[a] += y0[9 + a]; /* Σ_κ l_κ = 1 */
    const double minus[3] = {-xi[0], -xi[1], -xi[2]};
    double dm[9], omega[3], m_i[3], dd[9], grad[3] = {0, 0, 0}, fx[3] = {0, 0, 0};
    gm_so3_dexp(minus, dm);
    gm_mat3_vec(dm, xid, omega);
    gm_mat3_vec(w->j, omega, m_i);
    ddexp(xi, xid, dd);
    if (!g->reduced) {
      double e[9], r[9];
      gm_so3_expm1(xi, e);
      gm_mat3_mul(y0, e, r);
      for (int k = 0; k < 9; ++k) r[k] += y0[k];
      gm_status st = gm_lie_gradient(it, g->t + g->c[i] * h, r, nt ? x : NULL, grad, fx);
      if (st != GM_OK) {
        g->callback_status = st;
        return 1;
      }
      double rg[3];
      gm_so3_exp(xi, e);
      gm_mat3_vec(e, grad, rg); /* exp(ξ̂_i) g_i */
      for (int a = 0; a < 3; ++a) sum_rg[a] += g->b[i] * rg[a];
    }
    double dm_m[3], dd_m[3], dm_g[3];
    gm_mat3_tvec(dm, m_i, dm_m);
    gm_mat3_tvec(dd, m_i, dd_m);
    gm_mat3_tvec(dm, grad, dm_g);
    for (size_t k = 0; k <= s; ++k)
      for (int a = 0; a < 3; ++a) {
        ds[k][a] += g->b[i] * (g->dl[i][k] * dm_m[a] + h * g->l[i][k] * (dd_m[a] - dm_g[a]));
        if (nt) dsx[k][a] += g->b[i] * (g->dl[i][k] * w->mass * xd[a] - h * g->l[i][k] * fx[a]);
      }
  }
  /* interior stationarity, then the momentum equations at the start */
  for (size_t k = 1; k < s; ++k)
    for (int a = 0; a < 3; ++a) {
      res[3 * (k - 1) + a] = ds[k][a];
      if (nt) res[3 * s + 3 * (k - 1) + a] = dsx[k][a];
    }
  const double *xis = u + 3 * (s - 1);
  const double xs[3] = {h * xis[0], h * xis[1], h * xis[2]};
  double di[9], p0[3];
  gm_so3_dexp_inv(xs, di);
  gm_mat3_tvec(di, ds[s], p0); /* dexp_{ξ^s}⁻ᵀ ∂S/∂ξ^s */
  for (int a = 0; a < 3; ++a) {
    res[3 * (s - 1) + a] = h * sum_rg[a] + p0[a] - y0[pi + a];
    if (nt) res[3 * s + 3 * (s - 1) + a] = y0[pi + 3 + a] + dsx[0][a];
  }
  memcpy(g->ds_last, ds[s], sizeof g->ds_last);
  memcpy(g->dsx_last, dsx[s], sizeof g->dsx_last);
  return 0;
}

gm_status gm_lie_galerkin_init(gm_integrator *it, int reduced) {
  gm_lie_work *w = it->work;
  const size_t s = it->method->n_stages;
  if (s < 1 || s > GAL_MAX_S)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL, "'%s': degree %zu not in 1..%d",
                   it->method->name, s, GAL_MAX_S);
  if (reduced && it->problem->rigid_potential_gradient != NULL)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_EINVAL,
                   "'%s' solves the reduced (Euler-Poincare) equations of a left-invariant "
                   "Lagrangian: it needs a free body (no potential)", it->method->name);
  gm_lie_galerkin *g = calloc(1, sizeof *g);
  if (g == NULL) return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
  w->galerkin = g;
  g->s = s;
  g->nt = w->nt;
  g->reduced = reduced;
  g->n_unknowns = 3 * s * (g->nt ? 2 : 1);
  double nodes[GAL_MAX_S + 1], weights[GAL_MAX_S + 1];
  gm_status st = gm_gauss_legendre(s, g->c, g->b);
  if (st == GM_OK) {
    gm_quadrature_map(s, 0.0, 1.0, g->c, g->b);
    if (s == 1) {
      g->d[0] = 0.0;
      g->d[1] = 1.0;
    } else if ((st = gm_gauss_lobatto(s + 1, nodes, weights)) == GM_OK) {
      gm_quadrature_map(s + 1, 0.0, 1.0, nodes, weights);
      memcpy(g->d, nodes, (s + 1) * sizeof *nodes);
      g->d[0] = 0.0;
      g->d[s] = 1.0;
    }
  }
  for (size_t i = 0; i < s && st == GM_OK; ++i) {
    st = gm_lagrange_basis(s + 1, g->d, g->c[i], g->l[i]);
    if (st == GM_OK) st = gm_lagrange_basis_derivative(s + 1, g->d, g->c[i], g->dl[i]);
  }
  if (st != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, st, "'%s': quadrature set-up failed",
                   it->method->name);
  /* simplified Newton: one difference Jacobian per step (3s or 6s residuals), then iterations
   * of one residual each (about 3 from the warm start), instead of a Jacobian per iteration */
  gm_newton_options opt = gm_newton_defaults();
  opt.max_iterations = 40;
  opt.simplified = 1;
  opt.increment_tol = 1e-15; /* near round-off: inexact solves would show as energy drift */
  g->u = calloc(g->n_unknowns, sizeof *g->u);
  if (g->u == NULL || gm_newton_create(g->n_unknowns, &opt, &g->newton) != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
  opt.simplified = 0;
  if (gm_newton_create(g->n_unknowns, &opt, &g->full) != GM_OK)
    return gm_fail(it->errmsg, sizeof it->errmsg, GM_ENOMEM, "out of memory");
  return GM_OK;
}

void gm_lie_galerkin_invalidate(gm_lie_work *w) {
  if (w->galerkin != NULL) w->galerkin->warm = 0;
}

void gm_lie_galerkin_release(gm_lie_work *w) {
  gm_lie_galerkin *g = w->galerkin;
  if (g == NULL) return;
  gm_newton_free(g->newton);
  gm_newton_free(g->full);
  free(g->u);
  free(g);
  w->galerkin = NULL;
}

/* Starting values: the free rotation with Ω0 and the free flight with p0/m. */
static void cold_start(gm_lie_galerkin *g, const gm_lie_work *w, const double *y) {
  const size_t s = g->s, nt = g->nt, pi = w->pi;
  double omega[3];
  gm_mat3_vec(w->jinv, y + pi, omega);
  for (size_t k = 1; k <= s; ++k)
    for (int a = 0; a < 3; ++a) {
      g->u[3 * (k - 1) + a] = g->d[k] * omega[a];
      if (nt) g->u[3 * s + 3 * (k - 1) + a] = g->d[k] * y[pi + 3 + a] / w->mass;
    }
}

static void count_solve(gm_integrator *it, const gm_newton *nw) {
  it->stats.newton_iterations += gm_newton_iterations(nw);
  it->stats.jacobian_evals += gm_newton_jacobian_evals(nw);
  it->stats.fd_jacobians += gm_newton_jacobian_evals(nw);
}

gm_status gm_lie_galerkin_step(gm_integrator *it, double t, double h, const double *y,
                               double *y_new, double e[9]) {
  gm_lie_work *w = it->work;
  gm_lie_galerkin *g = w->galerkin;
  const size_t s = g->s, nt = g->nt, pi = w->pi;
  g->it = it;
  g->y0 = y;
  g->t = t;
  g->h = h;
  g->callback_status = GM_OK;
  /* Start from the last step's solution (scaled by 1/h, it changes by O(h) from step to step),
   * or cold. Simplified Newton; if it stalls (large steps), full Newton from the cold start. */
  if (!(g->warm && g->h_warm == h)) cold_start(g, w, y);
  g->warm = 0;
  gm_newton *nw = g->newton;
  gm_status st = gm_newton_solve(nw, residual, NULL, g, g->u);
  if (st == GM_ENOCONV || st == GM_ESINGULAR) { /* simplified Newton stalled: full Newton */
    count_solve(it, nw);
    nw = g->full;
    cold_start(g, w, y);
    st = gm_newton_solve(nw, residual, NULL, g, g->u);
  }
  count_solve(it, nw);
  if (st == GM_ECALLBACK && g->callback_status != GM_OK) return g->callback_status;
  if (st != GM_OK) {
    gm_fail(it->errmsg, sizeof it->errmsg, st, "%s", gm_newton_errmsg(nw));
    return gm_stage_solve_failed(it, st, t, h);
  }
  if (residual(g, g->u, w->scratch) != 0) return g->callback_status; /* ∂S/∂ξ^s at the root */
  g->warm = 1;
  g->h_warm = h;
  const double *xis = g->u + 3 * (s - 1);
  const double xs[3] = {h * xis[0], h * xis[1], h * xis[2]};
  double di[9];
  gm_so3_expm1(xs, e);
  const double minus[3] = {-xs[0], -xs[1], -xs[2]};
  gm_so3_dexp_inv(minus, di);
  gm_mat3_tvec(di, g->ds_last, y_new + pi); /* Π1 = dexp_{−ξ^s}⁻ᵀ ∂S/∂ξ^s */
  if (nt)
    for (int a = 0; a < 3; ++a) {
      y_new[9 + a] = y[9 + a] + h * g->u[3 * s + 3 * (s - 1) + a];
      y_new[pi + 3 + a] = g->dsx_last[a];
    }
  return GM_OK;
}
