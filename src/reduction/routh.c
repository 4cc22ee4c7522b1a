/* Routh reduction by an abelian symmetry: shape quantities of a mechanical Lagrangian in a
 * trivialisation q = (θ, x), and the reduced steppers RSPRK (seed 001 eq. 2.5.14) and SPRK on
 * the classical Routhian (seed 001 eq. 2.7.5). Derivations in docs/reduction.md. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/reduction.h"
#include "reduction/internal.h"

#define MAXN (GM_ROUTH_MAX_GROUP + GM_ROUTH_MAX_SHAPE)

int gm_routh_small_solve(size_t n, double *a, double *b, size_t nrhs) {
  for (size_t c = 0; c < n; ++c) {
    size_t piv = c;
    for (size_t r = c + 1; r < n; ++r)
      if (fabs(a[r * n + c]) > fabs(a[piv * n + c])) piv = r;
    if (!(fabs(a[piv * n + c]) > 0.0)) return 1;
    if (piv != c) {
      for (size_t j = 0; j < n; ++j) {
        double t = a[c * n + j];
        a[c * n + j] = a[piv * n + j];
        a[piv * n + j] = t;
      }
      for (size_t j = 0; j < nrhs; ++j) {
        double t = b[c * nrhs + j];
        b[c * nrhs + j] = b[piv * nrhs + j];
        b[piv * nrhs + j] = t;
      }
    }
    for (size_t r = c + 1; r < n; ++r) {
      const double f = a[r * n + c] / a[c * n + c];
      if (f == 0.0) continue;
      for (size_t j = c; j < n; ++j) a[r * n + j] -= f * a[c * n + j];
      for (size_t j = 0; j < nrhs; ++j) b[r * nrhs + j] -= f * b[c * nrhs + j];
    }
  }
  for (size_t c = n; c-- > 0;)
    for (size_t j = 0; j < nrhs; ++j) {
      double v = b[c * nrhs + j];
      for (size_t m = c + 1; m < n; ++m) v -= a[c * n + m] * b[m * nrhs + j];
      b[c * nrhs + j] = v / a[c * n + c];
    }
  return 0;
}

gm_status gm_routh_check(const gm_routh_system *sys, gm_error *err) {
  if (sys == NULL || sys->metric == NULL || sys->potential == NULL || sys->potential_dx == NULL)
    return gm_error_set(err, GM_EINVAL, "routh: the system needs metric, potential and potential_dx");
  if (sys->k < 1 || sys->k > GM_ROUTH_MAX_GROUP || sys->n < 1 || sys->n > GM_ROUTH_MAX_SHAPE)
    return gm_error_set(err, GM_EINVAL, "routh: need 1 <= k <= %d and 1 <= n <= %d (got %zu, %zu)",
                        GM_ROUTH_MAX_GROUP, GM_ROUTH_MAX_SHAPE, sys->k, sys->n);
  return GM_OK;
}

/* ∂M/∂x_l by the callback or by central differences */
int gm_routh_metric_dx(const gm_routh_system *sys, const double *x, double *dm) {
  const size_t n = sys->n, nn = (sys->k + n) * (sys->k + n);
  if (sys->metric_dx) return sys->metric_dx(sys->ctx, x, dm);
  double xp[GM_ROUTH_MAX_SHAPE], mp[MAXN * MAXN], mm[MAXN * MAXN];
  memcpy(xp, x, n * sizeof(double));
  for (size_t l = 0; l < n; ++l) {
    const double d = 1e-5 * (1.0 + fabs(x[l]));
    xp[l] = x[l] + d;
    if (sys->metric(sys->ctx, xp, mp)) return 1;
    xp[l] = x[l] - d;
    if (sys->metric(sys->ctx, xp, mm)) return 1;
    xp[l] = x[l];
    for (size_t i = 0; i < nn; ++i) dm[l * nn + i] = (mp[i] - mm[i]) / (2.0 * d);
  }
  return 0;
}

gm_status gm_routh_shape_eval(const gm_routh_system *sys, const double *mu, const double *x,
                              gm_routh_shape *o, gm_error *err) {
  const size_t k = sys->k, n = sys->n, N = k + n, nn = N * N;
  double m[MAXN * MAXN], dm[GM_ROUTH_MAX_SHAPE * MAXN * MAXN], a[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_GROUP];
  if (sys->metric(sys->ctx, x, m) || gm_routh_metric_dx(sys, x, dm) ||
      sys->potential_dx(sys->ctx, x, o->amended_grad))
    return gm_error_set(err, GM_ECALLBACK, "routh: a callback failed at the shape point");
  o->amended = sys->potential(sys->ctx, x);
  if (!isfinite(o->amended)) return gm_error_set(err, GM_EDOMAIN, "routh: V(x) is not finite");
  /* A = 𝕀⁻¹B and w = 𝕀⁻¹μ in one solve: right-hand sides [B | μ] */
  double rhs[GM_ROUTH_MAX_GROUP * (GM_ROUTH_MAX_SHAPE + 1)];
  for (size_t p = 0; p < k; ++p) {
    for (size_t q = 0; q < k; ++q) o->inertia[p * k + q] = a[p * k + q] = m[p * N + q];
    for (size_t i = 0; i < n; ++i) rhs[p * (n + 1) + i] = m[p * N + k + i];
    rhs[p * (n + 1) + n] = mu[p];
  }
  if (gm_routh_small_solve(k, a, rhs, n + 1))
    return gm_error_set(err, GM_ESINGULAR, "routh: the locked inertia is singular");
  for (size_t p = 0; p < k; ++p) {
    for (size_t i = 0; i < n; ++i) o->conn[p * n + i] = rhs[p * (n + 1) + i];
    o->inertia_inv_mu[p] = rhs[p * (n + 1) + n];
  }
  /* K = M_xx − BᵀA */
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) {
      double v = m[(k + i) * N + k + j];
      for (size_t p = 0; p < k; ++p) v -= m[p * N + k + i] * o->conn[p * n + j];
      o->kinetic[i * n + j] = v;
    }
  for (size_t p = 0; p < k; ++p) o->amended += 0.5 * mu[p] * o->inertia_inv_mu[p];
  for (size_t l = 0; l < n; ++l) {
    const double *d = dm + l * nn;
    /* ∂_lA = 𝕀⁻¹(∂_lB − ∂_l𝕀 A) */
    double r[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_SHAPE];
    for (size_t p = 0; p < k; ++p) {
      for (size_t q = 0; q < k; ++q) a[p * k + q] = m[p * N + q];
      for (size_t i = 0; i < n; ++i) {
        double v = d[p * N + k + i];
        for (size_t q = 0; q < k; ++q) v -= d[p * N + q] * o->conn[q * n + i];
        r[p * n + i] = v;
      }
    }
    if (gm_routh_small_solve(k, a, r, n))
      return gm_error_set(err, GM_ESINGULAR, "routh: the locked inertia is singular");
    for (size_t p = 0; p < k; ++p)
      for (size_t i = 0; i < n; ++i) o->dconn[(p * n + i) * n + l] = r[p * n + i];
    /* ∂_l V_μ = ∂_l V − ½ wᵀ ∂_l𝕀 w */
    for (size_t p = 0; p < k; ++p)
      for (size_t q = 0; q < k; ++q)
        o->amended_grad[l] -= 0.5 * o->inertia_inv_mu[p] * d[p * N + q] * o->inertia_inv_mu[q];
    /* ∂_lK = ∂_lM_xx − ∂_lBᵀA − Bᵀ∂_lA */
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j) {
        double v = d[(k + i) * N + k + j];
        for (size_t p = 0; p < k; ++p)
          v -= d[p * N + k + i] * o->conn[p * n + j] + m[p * N + k + i] * r[p * n + j];
        o->dkinetic[(l * n + i) * n + j] = v;
      }
  }
  return GM_OK;
}

gm_status gm_routh_connection(const gm_routh_system *sys, const double *mu, const double *x,
                              double *locked_inertia, double *conn, double *kinetic, double *dconn,
                              double *amended, double *amended_grad, gm_error *err) {
  gm_status st = gm_routh_check(sys, err);
  if (st != GM_OK) return st;
  if (mu == NULL || x == NULL) return gm_error_set(err, GM_EINVAL, "routh: mu and x are required");
  gm_routh_shape o;
  st = gm_routh_shape_eval(sys, mu, x, &o, err);
  if (st != GM_OK) return st;
  const size_t k = sys->k, n = sys->n;
  if (locked_inertia) memcpy(locked_inertia, o.inertia, k * k * sizeof(double));
  if (conn) memcpy(conn, o.conn, k * n * sizeof(double));
  if (kinetic) memcpy(kinetic, o.kinetic, n * n * sizeof(double));
  if (dconn) memcpy(dconn, o.dconn, k * n * n * sizeof(double));
  if (amended) *amended = o.amended;
  if (amended_grad) memcpy(amended_grad, o.amended_grad, n * sizeof(double));
  return GM_OK;
}

void gm_routh_beta(size_t k, size_t n, const double *mu, const double *dconn, double *beta) {
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) {
      double v = 0.0;
      for (size_t p = 0; p < k; ++p)
        v += mu[p] * (dconn[(p * n + j) * n + i] - dconn[(p * n + i) * n + j]);
      beta[i * n + j] = v;
    }
}

gm_status gm_routh_magnetic(const gm_routh_system *sys, const double *mu, const double *x,
                            double *beta, gm_error *err) {
  double dconn[GM_ROUTH_MAX_GROUP * GM_ROUTH_MAX_SHAPE * GM_ROUTH_MAX_SHAPE];
  gm_status st = gm_routh_connection(sys, mu, x, NULL, NULL, NULL, dconn, NULL, NULL, err);
  if (st != GM_OK) return st;
  gm_routh_beta(sys->k, sys->n, mu, dconn, beta);
  return GM_OK;
}

double gm_routh_energy(const gm_routh_system *sys, const double *mu, const double *x,
                       const double *s) {
  gm_routh_shape o;
  if (gm_routh_check(sys, NULL) != GM_OK || gm_routh_shape_eval(sys, mu, x, &o, NULL) != GM_OK)
    return NAN;
  const size_t n = sys->n;
  double v[GM_ROUTH_MAX_SHAPE];
  memcpy(v, s, n * sizeof(double));
  if (gm_routh_small_solve(n, o.kinetic, v, 1)) return NAN;
  double e = o.amended;
  for (size_t i = 0; i < n; ++i) e += 0.5 * s[i] * v[i];
  return e;
}

gm_status gm_routh_reduce_momentum(const gm_routh_system *sys, const double *mu, const double *x,
                                   const double *p_theta, const double *p_x, double *s,
                                   gm_error *err) {
  gm_routh_shape o;
  gm_status st = gm_routh_check(sys, err);
  if (st != GM_OK) return st;
  for (size_t p = 0; p < sys->k; ++p)
    if (!(fabs(p_theta[p] - mu[p]) <= 1e-12 * (1.0 + fabs(mu[p]))))
      return gm_error_set(err, GM_EINVAL,
                          "routh: mu inconsistent with the initial state: p_theta[%zu] = %.17g, "
                          "mu[%zu] = %.17g",
                          p, p_theta[p], p, mu[p]);
  st = gm_routh_shape_eval(sys, mu, x, &o, err);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < sys->n; ++i) {
    double v = p_x[i];
    for (size_t p = 0; p < sys->k; ++p) v -= mu[p] * o.conn[p * sys->n + i];
    s[i] = v;
  }
  return GM_OK;
}

gm_status gm_routh_lift_momentum(const gm_routh_system *sys, const double *mu, const double *x,
                                 const double *s, double *p_x, gm_error *err) {
  gm_routh_shape o;
  gm_status st = gm_routh_check(sys, err);
  if (st == GM_OK) st = gm_routh_shape_eval(sys, mu, x, &o, err);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < sys->n; ++i) {
    double v = s[i];
    for (size_t p = 0; p < sys->k; ++p) v += mu[p] * o.conn[p * sys->n + i];
    p_x[i] = v;
  }
  return GM_OK;
}

gm_status gm_routh_full_rhs(const gm_routh_system *sys, const double *y, double *dy,
                            gm_error *err) {
  gm_status st = gm_routh_check(sys, err);
  if (st != GM_OK) return st;
  const size_t k = sys->k, n = sys->n, N = k + n, nn = N * N;
  const double *x = y + k, *p = y + N;
  double m[MAXN * MAXN], dm[GM_ROUTH_MAX_SHAPE * MAXN * MAXN], v[MAXN], g[GM_ROUTH_MAX_SHAPE];
  if (sys->metric(sys->ctx, x, m) || gm_routh_metric_dx(sys, x, dm) ||
      sys->potential_dx(sys->ctx, x, g))
    return gm_error_set(err, GM_ECALLBACK, "routh: a callback failed");
  memcpy(v, p, N * sizeof(double));
  if (gm_routh_small_solve(N, m, v, 1))
    return gm_error_set(err, GM_ESINGULAR, "routh: the metric is singular");
  memcpy(dy, v, N * sizeof(double));
  for (size_t a = 0; a < k; ++a) dy[N + a] = 0.0;
  /* ṗ_x = ½ vᵀ ∂_lM v − ∂_lV (L = ½vᵀMv − V, p = Mv) */
  for (size_t l = 0; l < n; ++l) {
    double t = 0.0;
    for (size_t i = 0; i < N; ++i)
      for (size_t j = 0; j < N; ++j) t += v[i] * dm[l * nn + i * N + j] * v[j];
    dy[N + k + l] = 0.5 * t - g[l];
  }
  return GM_OK;
}
