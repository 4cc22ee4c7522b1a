/* RSPRK (seed 001 eq. 2.5.14) and the SPRK on the classical Routhian (seed 001 eq. 2.7.5) for a
 * mechanical system with an abelian symmetry (include/geomint/reduction.h). With the Routhian
 * R̂^μ = ½ẋᵀKẋ − V_μ the stage relations are S_i = K(X_i)Ẋ_i and
 *   Ṡ_j = ∂R̂^μ/∂x(X_j, Ẋ_j) − i_{Ẋ_j}β_μ,  (i_vβ)_l = v^i β_il  (Routh equations 2.5.10),
 * plus the connection bracket of 2.5.14b/d, (μ ∂A/∂x ẋ)_l = μ_a ∂A^a_l/∂x^m ẋ^m (notes §1D). On
 * R̂_c = R̂^μ + μAẋ: Y_i = K Ẋ_i + μA(X_i), Ẏ_j = ∂R̂^μ/∂x + μ_a ∂_lA^a_m Ẋ^m. Adding the bracket to
 * −i_Ẋβ gives exactly that last term, so the schemes agree under σ (docs/reduction.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "reduction/internal.h"

struct gm_rsprk {
  gm_routh_system sys;
  gm_routh_form form;
  size_t s;
  double mu[GM_ROUTH_MAX_GROUP];
  double *a, *b, *abar, *bbar;
  /* work, allocated at create: stage velocities, residual, Jacobian, per-stage data */
  double *v, *r, *r2, *jac, *dv, *zdot, *thdot, *conn_stage;
  gm_routh_shape *sh;
  char errmsg[GM_ERRMSG_SIZE];
};

void gm_rsprk_free(gm_rsprk *r) {
  if (r == NULL) return;
  free(r->a);
  free(r->v);
  free(r->sh);
  free(r);
}

const char *gm_rsprk_errmsg(const gm_rsprk *r) { return r ? r->errmsg : ""; }

gm_status gm_rsprk_create(const gm_routh_system *sys, const gm_tableau *t, gm_routh_form form,
                          const double *mu, gm_rsprk **out, gm_error *err) {
  if (out) *out = NULL;
  gm_status st = gm_routh_check(sys, err);
  if (st != GM_OK) return st;
  if (out == NULL || mu == NULL || t == NULL || t->a == NULL || t->b == NULL ||
      t->a_bar == NULL || t->b_bar == NULL || t->n_stages < 1 || t->n_stages > 16)
    return gm_error_set(err, GM_EINVAL,
                        "rsprk: need a partitioned tableau (a, b, a_bar, b_bar; 1..16 stages)");
  if (form != GM_ROUTH_RSPRK && form != GM_ROUTH_CLASSICAL)
    return gm_error_set(err, GM_EINVAL, "rsprk: unknown form");
  const size_t s = t->n_stages, n = sys->n, m = s * n;
  gm_rsprk *r = calloc(1, sizeof *r);
  if (r == NULL) return gm_error_set(err, GM_ENOMEM, "rsprk: out of memory");
  r->sys = *sys;
  r->form = form;
  r->s = s;
  memcpy(r->mu, mu, sys->k * sizeof(double));
  r->a = malloc((2 * s * s + 2 * s) * sizeof(double));
  r->v = malloc((4 * m + m * m + s * n + s * sys->k + s * sys->k * n) * sizeof(double));
  r->sh = malloc(s * sizeof(gm_routh_shape));
  if (!r->a || !r->v || !r->sh) {
    gm_rsprk_free(r);
    return gm_error_set(err, GM_ENOMEM, "rsprk: out of memory");
  }
  r->abar = r->a + s * s;
  r->b = r->abar + s * s;
  r->bbar = r->b + s;
  memcpy(r->a, t->a, s * s * sizeof(double));
  memcpy(r->abar, t->a_bar, s * s * sizeof(double));
  memcpy(r->b, t->b, s * sizeof(double));
  memcpy(r->bbar, t->b_bar, s * sizeof(double));
  r->r = r->v + m;
  r->r2 = r->r + m;
  r->dv = r->r2 + m;
  r->jac = r->dv + m;
  r->zdot = r->jac + m * m;
  r->thdot = r->zdot + s * n;
  r->conn_stage = r->thdot + s * sys->k;
  *out = r;
  return GM_OK;
}

/* Stage data for stage velocities v: per stage the shape point, ż_j (Ṡ_j plus the bracket for
 * RSPRK, Ẏ_j for the classical form) and Θ̇_j. */
static int stage_data(gm_rsprk *r, double h, const double *x0, const double *v) {
  const size_t s = r->s, n = r->sys.n, k = r->sys.k;
  for (size_t j = 0; j < s; ++j) {
    double X[GM_ROUTH_MAX_SHAPE];
    for (size_t i = 0; i < n; ++i) {
      double t = x0[i];
      for (size_t m = 0; m < s; ++m) t += h * r->a[j * s + m] * v[m * n + i];
      X[i] = t;
    }
    gm_routh_shape *o = &r->sh[j];
    if (gm_routh_shape_eval(&r->sys, r->mu, X, o, NULL) != GM_OK) return 1;
    const double *vj = v + j * n;
    for (size_t l = 0; l < n; ++l) {
      double t = -o->amended_grad[l];
      for (size_t i = 0; i < n; ++i)
        for (size_t q = 0; q < n; ++q) t += 0.5 * vj[i] * o->dkinetic[(l * n + i) * n + q] * vj[q];
      /* RSPRK: −(i_vβ)_l + μ_a ∂_mA^a_l v^m = μ_a ∂_lA^a_m v^m (the sum the bracket and the
       * magnetic term make, written out term by term as the thesis has them) */
      double mag = 0.0, bracket = 0.0, classical = 0.0;
      for (size_t p = 0; p < k; ++p)
        for (size_t i = 0; i < n; ++i) {
          const double dil = o->dconn[(p * n + l) * n + i], dli = o->dconn[(p * n + i) * n + l];
          mag += vj[i] * r->mu[p] * (dil - dli); /* v^i β_il, β_il = μ(∂_iA_l − ∂_lA_i) */
          bracket += r->mu[p] * dil * vj[i];
          classical += r->mu[p] * dli * vj[i];
        }
      r->zdot[j * n + l] = t + (r->form == GM_ROUTH_RSPRK ? bracket - mag : classical);
    }
    for (size_t p = 0; p < k; ++p) {
      double t = o->inertia_inv_mu[p];
      for (size_t i = 0; i < n; ++i) t -= o->conn[p * n + i] * vj[i];
      r->thdot[j * k + p] = t;
    }
  }
  return 0;
}

/* residual_i = z0 + h Σ ā_ij ż_j [− μ(A(X_i) − A(x0))] − (K_iẊ_i [+ μA(X_i)]) */
static int residual(gm_rsprk *r, double h, const double *x0, const double *z0,
                    const double *conn0, const double *v, double *res) {
  const size_t s = r->s, n = r->sys.n, k = r->sys.k;
  if (stage_data(r, h, x0, v)) return 1;
  for (size_t i = 0; i < s; ++i) {
    const gm_routh_shape *o = &r->sh[i];
    for (size_t l = 0; l < n; ++l) {
      double t = z0[l];
      for (size_t j = 0; j < s; ++j) t += h * r->abar[i * s + j] * r->zdot[j * n + l];
      double ma = 0.0;
      for (size_t p = 0; p < k; ++p) ma += r->mu[p] * o->conn[p * n + l];
      if (r->form == GM_ROUTH_RSPRK) {
        for (size_t p = 0; p < k; ++p) t += r->mu[p] * conn0[p * n + l];
        t -= ma;
      } else {
        t -= ma;
      }
      for (size_t q = 0; q < n; ++q) t -= o->kinetic[l * n + q] * v[i * n + q];
      res[i * n + l] = t;
    }
  }
  return 0;
}

gm_status gm_rsprk_step(gm_rsprk *r, double h, double *x, double *z, double *theta) {
  if (r == NULL || x == NULL || z == NULL) return GM_EINVAL;
  const size_t s = r->s, n = r->sys.n, k = r->sys.k, m = s * n;
  gm_routh_shape o0;
  if (gm_routh_shape_eval(&r->sys, r->mu, x, &o0, NULL) != GM_OK)
    return gm_fail(r->errmsg, sizeof r->errmsg, GM_ECALLBACK, "rsprk: shape evaluation failed");
  /* initial guess: Ẋ = K(x0)⁻¹ s0 on every stage */
  double v0[GM_ROUTH_MAX_SHAPE], kk[GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE];
  for (size_t l = 0; l < n; ++l) {
    v0[l] = z[l];
    if (r->form == GM_ROUTH_CLASSICAL)
      for (size_t p = 0; p < k; ++p) v0[l] -= r->mu[p] * o0.conn[p * n + l];
  }
  memcpy(kk, o0.kinetic, n * n * sizeof(double));
  if (gm_routh_small_solve(n, kk, v0, 1))
    return gm_fail(r->errmsg, sizeof r->errmsg, GM_ESINGULAR, "rsprk: K(x) is singular");
  for (size_t j = 0; j < s; ++j) memcpy(r->v + j * n, v0, n * sizeof(double));
  double last = INFINITY;
  int ok = 0;
  for (int it = 0; it < 60 && !ok; ++it) {
    if (residual(r, h, x, z, o0.conn, r->v, r->r)) break;
    for (size_t c = 0; c < m; ++c) {
      const double vc = r->v[c], d = 1e-7 * (1.0 + fabs(vc));
      r->v[c] = vc + d;
      int bad = residual(r, h, x, z, o0.conn, r->v, r->r2);
      r->v[c] = vc;
      if (bad) return gm_fail(r->errmsg, sizeof r->errmsg, GM_ECALLBACK, "rsprk: callback failed");
      for (size_t i = 0; i < m; ++i) r->jac[i * m + c] = (r->r2[i] - r->r[i]) / d;
    }
    memcpy(r->dv, r->r, m * sizeof(double));
    if (gm_routh_small_solve(m, r->jac, r->dv, 1)) break;
    double nd = 0.0, nv = 0.0;
    for (size_t i = 0; i < m; ++i) {
      r->v[i] -= r->dv[i];
      nd = fmax(nd, fabs(r->dv[i]));
      nv = fmax(nv, fabs(r->v[i]));
    }
    if (!isfinite(nd)) break;
    if (nd <= 1e-15 * (1.0 + nv) || (nd >= last && nd <= 1e-12 * (1.0 + nv))) ok = 1;
    last = nd;
  }
  if (!ok || stage_data(r, h, x, r->v))
    return gm_fail(r->errmsg, sizeof r->errmsg, GM_ENOCONV,
                   "rsprk: stage equations did not converge at x = (%g, ...), h = %g", x[0], h);
  double x1[GM_ROUTH_MAX_SHAPE];
  for (size_t l = 0; l < n; ++l) {
    double t = x[l];
    for (size_t j = 0; j < s; ++j) t += h * r->b[j] * r->v[j * n + l];
    x1[l] = t;
  }
  gm_routh_shape o1;
  if (r->form == GM_ROUTH_RSPRK && gm_routh_shape_eval(&r->sys, r->mu, x1, &o1, NULL) != GM_OK)
    return gm_fail(r->errmsg, sizeof r->errmsg, GM_ECALLBACK, "rsprk: shape evaluation failed");
  for (size_t l = 0; l < n; ++l) {
    double t = z[l];
    for (size_t j = 0; j < s; ++j) t += h * r->bbar[j] * r->zdot[j * n + l];
    if (r->form == GM_ROUTH_RSPRK)
      for (size_t p = 0; p < k; ++p) t -= r->mu[p] * (o1.conn[p * n + l] - o0.conn[p * n + l]);
    z[l] = t;
  }
  if (theta)
    for (size_t p = 0; p < k; ++p)
      for (size_t j = 0; j < s; ++j) theta[p] += h * r->b[j] * r->thdot[j * k + p];
  memcpy(x, x1, n * sizeof(double));
  return GM_OK;
}
