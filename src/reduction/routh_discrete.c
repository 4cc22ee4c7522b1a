/* Discrete Routh reduction for an abelian symmetry (seed 001 §2.3.2–2.3.5, eq. 2.3.29, Thm 2.17;
 * notes §1C). In the trivialisation q = (θ, x) with G acting by θ ↦ θ + φ, a θ-invariant L_d
 * has J_d(q0, q1) = D₂L_d(q0, q1)_θ = −D₁L_d(q0, q1)_θ. ψ_μ(x0, x1) solves J_d(0, x0, ψ, x1) = μ,
 * L̂_d(x0, x1) = L_d(0, x0, ψ_μ, x1), and the dropped connection terms are
 *   Â₁ = μ(D₁ψ_μ − A(x0)),  Â₂ = μ(D₂ψ_μ + A(x1))
 * (from 𝒜(δq0, δq1) = 𝔄_μ(q1)δq1 − 𝔄_μ(q0)δq0 at θ0 = 0, θ1 = ψ_μ; derived in
 * docs/reduction.md). With D₁L̂_d = D₁L_d|_x + μD₁ψ_μ and D₂L̂_d = D₂L_d|_x + μD₂ψ_μ the discrete
 * Routh equations are the x-rows of the DEL on J_d = μ (the θ-rows hold by J_d = μ). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "reduction/internal.h"

#define MAXN (GM_ROUTH_MAX_GROUP + GM_ROUTH_MAX_SHAPE)

/* ---- the midpoint discrete Lagrangian of a mechanical system ------------------------------- */

static int midpoint_parts(const gm_routh_system *sys, double h, const double *q0, const double *q1,
                          double *mw, double *half, double *value) {
  const size_t k = sys->k, n = sys->n, N = k + n;
  double xb[GM_ROUTH_MAX_SHAPE], w[MAXN], m[MAXN * MAXN];
  for (size_t i = 0; i < n; ++i) xb[i] = 0.5 * (q0[k + i] + q1[k + i]);
  for (size_t i = 0; i < N; ++i) w[i] = (q1[i] - q0[i]) / h;
  if (sys->metric(sys->ctx, xb, m)) return 1;
  double t = 0.0;
  for (size_t i = 0; i < N; ++i) {
    double v = 0.0;
    for (size_t j = 0; j < N; ++j) v += m[i * N + j] * w[j];
    if (mw) mw[i] = v;
    t += 0.5 * w[i] * v;
  }
  if (value) *value = h * (t - sys->potential(sys->ctx, xb));
  if (half) {
    /* (h/2)(½ wᵀ∂_lM w − ∂_lV) at the midpoint, the x-rows both slots share */
    double dm[GM_ROUTH_MAX_SHAPE * MAXN * MAXN], g[GM_ROUTH_MAX_SHAPE];
    if (gm_routh_metric_dx(sys, xb, dm) || sys->potential_dx(sys->ctx, xb, g)) return 1;
    for (size_t l = 0; l < n; ++l) {
      double u = 0.0;
      for (size_t i = 0; i < N; ++i)
        for (size_t j = 0; j < N; ++j) u += w[i] * dm[(l * N + i) * N + j] * w[j];
      half[l] = 0.5 * h * (0.5 * u - g[l]);
    }
  }
  return 0;
}

static double mid_value(void *ctx, double h, const double *q0, const double *q1) {
  double v;
  return midpoint_parts(ctx, h, q0, q1, NULL, NULL, &v) ? NAN : v;
}

static int mid_slot(void *ctx, double h, const double *q0, const double *q1, double *out,
                    double sign) {
  const gm_routh_system *sys = ctx;
  double mw[MAXN], half[GM_ROUTH_MAX_SHAPE];
  if (midpoint_parts(sys, h, q0, q1, mw, half, NULL)) return 1;
  for (size_t i = 0; i < sys->k + sys->n; ++i) out[i] = sign * mw[i];
  for (size_t l = 0; l < sys->n; ++l) out[sys->k + l] += half[l];
  return 0;
}
static int mid_d1(void *ctx, double h, const double *q0, const double *q1, double *out) {
  return mid_slot(ctx, h, q0, q1, out, -1.0);
}
static int mid_d2(void *ctx, double h, const double *q0, const double *q1, double *out) {
  return mid_slot(ctx, h, q0, q1, out, 1.0);
}

void gm_routh_midpoint_lagrangian(const gm_routh_system *sys, gm_discrete_lagrangian *ld) {
  *ld = (gm_discrete_lagrangian){.dim = sys->k + sys->n, .ctx = (void *)sys, .value = mid_value,
                                 .d1 = mid_d1, .d2 = mid_d2, .d1_jacobian = NULL};
}

/* ---- discrete Routh ----------------------------------------------------------------------- */

struct gm_routh_discrete {
  gm_discrete_lagrangian ld;
  gm_routh_system sys;
  gm_routh_discrete_options opts;
  double mu[GM_ROUTH_MAX_GROUP];
  char errmsg[GM_ERRMSG_SIZE];
};

gm_status gm_routh_discrete_create(const gm_discrete_lagrangian *ld, const gm_routh_system *sys,
                                   const double *mu, const gm_routh_discrete_options *opts,
                                   gm_routh_discrete **out, gm_error *err) {
  if (out) *out = NULL;
  gm_status st = gm_routh_check(sys, err);
  if (st != GM_OK) return st;
  if (out == NULL || ld == NULL || mu == NULL || ld->d1 == NULL || ld->d2 == NULL)
    return gm_error_set(err, GM_EINVAL, "discrete routh: need ld with d1, d2, and mu");
  if (ld->dim != sys->k + sys->n)
    return gm_error_set(err, GM_EINVAL, "discrete routh: ld->dim = %zu, expected k + n = %zu",
                        ld->dim, sys->k + sys->n);
  if (opts && opts->n_constraints > 0 &&
      (opts->n_constraints > sys->n || !opts->constraint || !opts->constraint_jacobian))
    return gm_error_set(err, GM_EINVAL,
                        "discrete routh: constraints need 1..n values, constraint and jacobian");
  gm_routh_discrete *d = calloc(1, sizeof *d);
  if (d == NULL) return gm_error_set(err, GM_ENOMEM, "discrete routh: out of memory");
  d->ld = *ld;
  d->sys = *sys;
  if (opts) d->opts = *opts;
  memcpy(d->mu, mu, sys->k * sizeof(double));
  *out = d;
  return GM_OK;
}

void gm_routh_discrete_free(gm_routh_discrete *d) { free(d); }
const char *gm_routh_discrete_errmsg(const gm_routh_discrete *d) { return d ? d->errmsg : ""; }

static void pack(size_t k, size_t n, const double *th, const double *x, double *q) {
  for (size_t p = 0; p < k; ++p) q[p] = th ? th[p] : 0.0;
  memcpy(q + k, x, n * sizeof(double));
}

/* J_d(0, x0, ψ, x1) − μ */
static int jd_minus_mu(gm_routh_discrete *d, double h, const double *x0, const double *psi,
                       const double *x1, double *out) {
  const size_t k = d->sys.k, n = d->sys.n;
  double q0[MAXN], q1[MAXN], g[MAXN];
  pack(k, n, NULL, x0, q0);
  pack(k, n, psi, x1, q1);
  if (d->ld.d2(d->ld.ctx, h, q0, q1, g)) return 1;
  for (size_t p = 0; p < k; ++p) out[p] = g[p] - d->mu[p];
  return 0;
}

gm_status gm_routh_psi(gm_routh_discrete *d, double h, const double *x0, const double *x1,
                       int warm, double *psi) {
  if (d == NULL || x0 == NULL || x1 == NULL || psi == NULL || !(h > 0.0)) return GM_EINVAL;
  const size_t k = d->sys.k, n = d->sys.n;
  if (!warm) {
    /* ψ ≈ h𝕀⁻¹μ − A(x̄)(x1 − x0), the continuous θ̇ = 𝕀⁻¹μ − Aẋ over one step */
    double xb[GM_ROUTH_MAX_SHAPE];
    gm_routh_shape o;
    for (size_t i = 0; i < n; ++i) xb[i] = 0.5 * (x0[i] + x1[i]);
    if (gm_routh_shape_eval(&d->sys, d->mu, xb, &o, NULL) != GM_OK)
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "psi: shape evaluation failed");
    for (size_t p = 0; p < k; ++p) {
      psi[p] = h * o.inertia_inv_mu[p];
      for (size_t i = 0; i < n; ++i) psi[p] -= o.conn[p * n + i] * (x1[i] - x0[i]);
    }
  }
  double last = INFINITY;
  for (int it = 0; it < 50; ++it) {
    double f[GM_ROUTH_MAX_GROUP], f2[GM_ROUTH_MAX_GROUP], jac[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_GROUP];
    if (jd_minus_mu(d, h, x0, psi, x1, f)) break;
    for (size_t c = 0; c < k; ++c) {
      const double pc = psi[c], e = 1e-7 * (1.0 + fabs(pc));
      psi[c] = pc + e;
      int bad = jd_minus_mu(d, h, x0, psi, x1, f2);
      psi[c] = pc;
      if (bad) break;
      for (size_t i = 0; i < k; ++i) jac[i * k + c] = (f2[i] - f[i]) / e;
    }
    if (gm_routh_small_solve(k, jac, f, 1)) break;
    double nd = 0.0, np = 0.0;
    for (size_t p = 0; p < k; ++p) {
      psi[p] -= f[p];
      nd = fmax(nd, fabs(f[p]));
      np = fmax(np, fabs(psi[p]));
    }
    if (!isfinite(nd)) break;
    if (nd <= 1e-15 * (1.0 + np) || (nd >= last && nd <= 1e-12 * (1.0 + np))) return GM_OK;
    last = nd;
  }
  return gm_fail(d->errmsg, sizeof d->errmsg, GM_ENOCONV,
                 "psi_mu: Newton for J_d = mu did not converge (group-regularity fails?) at "
                 "x0 = (%g, ...), x1 = (%g, ...), h = %g",
                 x0[0], x1[0], h);
}

gm_status gm_routh_reduced_lagrangian(gm_routh_discrete *d, double h, const double *x0,
                                      const double *x1, double *value, double *d1, double *d2,
                                      double *a1, double *a2, double *psi_out) {
  const size_t k = d->sys.k, n = d->sys.n;
  double psi[GM_ROUTH_MAX_GROUP];
  gm_status st = gm_routh_psi(d, h, x0, x1, 0, psi);
  if (st != GM_OK) return st;
  if (psi_out) memcpy(psi_out, psi, k * sizeof(double));
  double q0[MAXN], q1[MAXN];
  pack(k, n, NULL, x0, q0);
  pack(k, n, psi, x1, q1);
  if (value) {
    if (d->ld.value == NULL)
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_EINVAL, "reduced L_d: ld has no value");
    *value = d->ld.value(d->ld.ctx, h, q0, q1);
  }
  if (!d1 && !d2 && !a1 && !a2) return GM_OK;
  /* Dψ = −(∂J/∂ψ)⁻¹ [∂J/∂x0 | ∂J/∂x1] by central differences of J_d */
  double jp[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_GROUP], rhs[GM_ROUTH_MAX_GROUP * 2 * GM_ROUTH_MAX_SHAPE];
  double fp[GM_ROUTH_MAX_GROUP], fm[GM_ROUTH_MAX_GROUP], xs[GM_ROUTH_MAX_SHAPE], ps[GM_ROUTH_MAX_GROUP];
  memcpy(ps, psi, k * sizeof(double));
  for (size_t c = 0; c < k; ++c) {
    const double e = 1e-6 * (1.0 + fabs(psi[c]));
    ps[c] = psi[c] + e;
    int bad = jd_minus_mu(d, h, x0, ps, x1, fp);
    ps[c] = psi[c] - e;
    bad |= jd_minus_mu(d, h, x0, ps, x1, fm);
    ps[c] = psi[c];
    if (bad) return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "reduced L_d: callback");
    for (size_t i = 0; i < k; ++i) jp[i * k + c] = (fp[i] - fm[i]) / (2.0 * e);
  }
  for (int slot = 0; slot < 2; ++slot) {
    const double *xv = slot ? x1 : x0;
    memcpy(xs, xv, n * sizeof(double));
    for (size_t c = 0; c < n; ++c) {
      const double e = 1e-6 * (1.0 + fabs(xv[c]));
      int bad;
      xs[c] = xv[c] + e;
      bad = slot ? jd_minus_mu(d, h, x0, psi, xs, fp) : jd_minus_mu(d, h, xs, psi, x1, fp);
      xs[c] = xv[c] - e;
      bad |= slot ? jd_minus_mu(d, h, x0, psi, xs, fm) : jd_minus_mu(d, h, xs, psi, x1, fm);
      xs[c] = xv[c];
      if (bad) return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "reduced L_d: callback");
      for (size_t i = 0; i < k; ++i) rhs[i * 2 * n + slot * n + c] = -(fp[i] - fm[i]) / (2.0 * e);
    }
  }
  if (gm_routh_small_solve(k, jp, rhs, 2 * n))
    return gm_fail(d->errmsg, sizeof d->errmsg, GM_ESINGULAR,
                   "reduced L_d: dJ_d/dpsi is singular (group-regularity fails)");
  /* μ·Dψ in each slot */
  double mdpsi[2][GM_ROUTH_MAX_SHAPE];
  for (int slot = 0; slot < 2; ++slot)
    for (size_t i = 0; i < n; ++i) {
      double t = 0.0;
      for (size_t p = 0; p < k; ++p) t += d->mu[p] * rhs[p * 2 * n + slot * n + i];
      mdpsi[slot][i] = t;
    }
  double g[MAXN];
  if (d1) {
    if (d->ld.d1(d->ld.ctx, h, q0, q1, g))
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "reduced L_d: d1 failed");
    for (size_t i = 0; i < n; ++i) d1[i] = g[k + i] + mdpsi[0][i];
  }
  if (d2) {
    if (d->ld.d2(d->ld.ctx, h, q0, q1, g))
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "reduced L_d: d2 failed");
    for (size_t i = 0; i < n; ++i) d2[i] = g[k + i] + mdpsi[1][i];
  }
  if (a1 || a2) {
    gm_routh_shape o0, o1;
    if (gm_routh_shape_eval(&d->sys, d->mu, x0, &o0, NULL) != GM_OK ||
        gm_routh_shape_eval(&d->sys, d->mu, x1, &o1, NULL) != GM_OK)
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "reduced L_d: connection failed");
    for (size_t i = 0; i < n; ++i) {
      double m0 = 0.0, m1 = 0.0;
      for (size_t p = 0; p < k; ++p) {
        m0 += d->mu[p] * o0.conn[p * n + i];
        m1 += d->mu[p] * o1.conn[p * n + i];
      }
      if (a1) a1[i] = mdpsi[0][i] - m0;
      if (a2) a2[i] = mdpsi[1][i] + m1;
    }
  }
  return GM_OK;
}

/* the x_{k+1}-dependent part: D₁L̂_d(x, xp) − Â₁(x, xp) + F̂¹(x, xp) */
static gm_status forward_part(gm_routh_discrete *d, double h, const double *x, const double *xp,
                              double *out) {
  const size_t n = d->sys.n;
  double d1[GM_ROUTH_MAX_SHAPE], a1[GM_ROUTH_MAX_SHAPE], f[GM_ROUTH_MAX_SHAPE];
  gm_status st = gm_routh_reduced_lagrangian(d, h, x, xp, NULL, d1, NULL, a1, NULL, NULL);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < n; ++i) out[i] = d1[i] - a1[i];
  if (d->opts.force1) {
    if (d->opts.force1(d->opts.ctx, h, x, xp, f))
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "discrete routh: force1 failed");
    for (size_t i = 0; i < n; ++i) out[i] += f[i];
  }
  return GM_OK;
}

/* D₂L̂_d(xm, x) − Â₂(xm, x) + F̂²(xm, x) + λᵀDĝ(x) */
static gm_status backward_part(gm_routh_discrete *d, double h, const double *xm, const double *x,
                               const double *lambda, double *out) {
  const size_t n = d->sys.n, mc = d->opts.n_constraints;
  double d2[GM_ROUTH_MAX_SHAPE], a2[GM_ROUTH_MAX_SHAPE], f[GM_ROUTH_MAX_SHAPE];
  gm_status st = gm_routh_reduced_lagrangian(d, h, xm, x, NULL, NULL, d2, NULL, a2, NULL);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < n; ++i) out[i] = d2[i] - a2[i];
  if (d->opts.force2) {
    if (d->opts.force2(d->opts.ctx, h, xm, x, f))
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "discrete routh: force2 failed");
    for (size_t i = 0; i < n; ++i) out[i] += f[i];
  }
  if (mc > 0 && lambda) {
    double jac[GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE];
    if (d->opts.constraint_jacobian(d->opts.ctx, x, jac))
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "discrete routh: Dg failed");
    for (size_t i = 0; i < n; ++i)
      for (size_t c = 0; c < mc; ++c) out[i] += lambda[c] * jac[c * n + i];
  }
  return GM_OK;
}

gm_status gm_routh_discrete_residual(gm_routh_discrete *d, double h, const double *xm,
                                     const double *x, const double *xp, const double *lambda,
                                     double *res) {
  if (d == NULL || xm == NULL || x == NULL || xp == NULL || res == NULL) return GM_EINVAL;
  double fwd[GM_ROUTH_MAX_SHAPE];
  gm_status st = backward_part(d, h, xm, x, lambda, res);
  if (st == GM_OK) st = forward_part(d, h, x, xp, fwd);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < d->sys.n; ++i) res[i] += fwd[i];
  return GM_OK;
}

/* F(xp, λ) = [backward(λ) + forward(xp); ĝ(xp)] */
static gm_status step_residual(gm_routh_discrete *d, double h, const double *back0,
                               const double *x, const double *u, double *f) {
  const size_t n = d->sys.n, mc = d->opts.n_constraints;
  double fwd[GM_ROUTH_MAX_SHAPE];
  gm_status st = forward_part(d, h, x, u, fwd);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < n; ++i) f[i] = back0[i] + fwd[i];
  if (mc > 0) {
    double jac[GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE];
    if (d->opts.constraint_jacobian(d->opts.ctx, x, jac) ||
        d->opts.constraint(d->opts.ctx, u, f + n))
      return gm_fail(d->errmsg, sizeof d->errmsg, GM_ECALLBACK, "discrete routh: g failed");
    for (size_t i = 0; i < n; ++i)
      for (size_t c = 0; c < mc; ++c) f[i] += u[n + c] * jac[c * n + i];
  }
  return GM_OK;
}

gm_status gm_routh_discrete_step(gm_routh_discrete *d, double h, const double *xm,
                                 const double *x, double *xp, double *theta, double *lambda) {
  if (d == NULL || xm == NULL || x == NULL || xp == NULL || !(h > 0.0)) return GM_EINVAL;
  const size_t n = d->sys.n, mc = d->opts.n_constraints, m = n + mc;
  double back0[GM_ROUTH_MAX_SHAPE], u[2 * GM_ROUTH_MAX_SHAPE], f[2 * GM_ROUTH_MAX_SHAPE];
  double f2[2 * GM_ROUTH_MAX_SHAPE], jac[4 * GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE];
  gm_status st = backward_part(d, h, xm, x, NULL, back0);
  if (st != GM_OK) return st;
  memcpy(u, xp, n * sizeof(double));
  for (size_t c = 0; c < mc; ++c) u[n + c] = 0.0;
  double last = INFINITY;
  int ok = 0;
  for (int it = 0; it < 50 && !ok; ++it) {
    if ((st = step_residual(d, h, back0, x, u, f)) != GM_OK) return st;
    for (size_t c = 0; c < m; ++c) {
      const double uc = u[c], e = 1e-7 * (1.0 + fabs(uc));
      u[c] = uc + e;
      st = step_residual(d, h, back0, x, u, f2);
      u[c] = uc;
      if (st != GM_OK) return st;
      for (size_t i = 0; i < m; ++i) jac[i * m + c] = (f2[i] - f[i]) / e;
    }
    if (gm_routh_small_solve(m, jac, f, 1)) break;
    double nd = 0.0, nu = 0.0;
    for (size_t i = 0; i < m; ++i) {
      u[i] -= f[i];
      nd = fmax(nd, fabs(f[i]));
      nu = fmax(nu, fabs(u[i]));
    }
    if (!isfinite(nd)) break;
    if (nd <= 1e-15 * (1.0 + nu) || (nd >= last && nd <= 1e-11 * (1.0 + nu))) ok = 1;
    last = nd;
  }
  if (!ok)
    return gm_fail(d->errmsg, sizeof d->errmsg, GM_ENOCONV,
                   "discrete routh: Newton for x_{k+1} did not converge at x_k = (%g, ...)", x[0]);
  if (theta) {
    double psi[GM_ROUTH_MAX_GROUP];
    if ((st = gm_routh_psi(d, h, x, u, 0, psi)) != GM_OK) return st;
    for (size_t p = 0; p < d->sys.k; ++p) theta[p] += psi[p];
  }
  memcpy(xp, u, n * sizeof(double));
  if (lambda)
    for (size_t c = 0; c < mc; ++c) lambda[c] = u[n + c];
  return GM_OK;
}

gm_status gm_routh_holonomy(gm_routh_discrete *d, double h, size_t n_points, const double *loop,
                            double *angle) {
  if (d == NULL || loop == NULL || angle == NULL || n_points < 3 || !(h > 0.0))
    return GM_EINVAL;
  const size_t k = d->sys.k, n = d->sys.n;
  const double *first = loop, *last = loop + (n_points - 1) * n;
  double gap = 0.0, size = 0.0;
  for (size_t i = 0; i < n; ++i) {
    gap = fmax(gap, fabs(last[i] - first[i]));
    size = fmax(size, fabs(first[i]));
  }
  if (!(gap <= 1e-12 * (1.0 + size)))
    return gm_fail(d->errmsg, sizeof d->errmsg, GM_EINVAL,
                   "holonomy: the shape loop does not close: |x_N - x_0| = %.3g", gap);
  for (size_t p = 0; p < k; ++p) angle[p] = 0.0;
  for (size_t s = 0; s + 1 < n_points; ++s) {
    double psi[GM_ROUTH_MAX_GROUP];
    gm_status st = gm_routh_psi(d, h, loop + s * n, loop + (s + 1) * n, 0, psi);
    if (st != GM_OK) return st;
    for (size_t p = 0; p < k; ++p) angle[p] += psi[p];
  }
  return GM_OK;
}
