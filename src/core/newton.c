/* Newton's method for F(x) = 0: full (Jacobian every iteration) or simplified (Jacobian once per
 * solve), with an analytic or a one-sided finite-difference Jacobian. All memory is taken in
 * gm_newton_create; gm_newton_solve allocates nothing, so it can run inside integration steps. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"

/* Increments below this (relative to 1 + max|x|) are at the level of round-off in x: if they stop
 * decreasing there, further iterations cannot improve x and the iteration has converged. */
#define GM_NEWTON_ROUNDOFF_FLOOR 1e-12

struct gm_newton {
  size_t n;
  gm_newton_options options;
  double *residual;  /* F(x) at the current iterate */
  double *jacobian;  /* n×n, row-major; LU factors after factoring */
  int *pivots;       /* n */
  double *increment; /* n: Newton step, x <- x - increment */
  double *fd_x;      /* n: perturbed point of the finite-difference Jacobian */
  double *fd_f;      /* n: F at the perturbed point */
  size_t iterations, residual_evals, jacobian_evals;
  double residual_norm;
  char errmsg[GM_ERRMSG_SIZE];
};

/* Per-solve state passed between the small steps of gm_newton_solve. */
typedef struct solve_call {
  gm_newton *nw;
  gm_residual_fn residual;
  gm_jacobian_fn jacobian;
  void *ctx;
} solve_call;

gm_newton_options gm_newton_defaults(void) {
  gm_newton_options o;
  o.max_iterations = 30;
  o.residual_tol = 0.0;
  o.increment_tol = 1e-14;
  o.simplified = 0;
  o.fd_relative_step = 1e-7;
  return o;
}

static int options_valid(const gm_newton_options *o) {
  return o->max_iterations > 0 && isfinite(o->residual_tol) && o->residual_tol >= 0.0 &&
         isfinite(o->increment_tol) && o->increment_tol >= 0.0 && isfinite(o->fd_relative_step) &&
         o->fd_relative_step > 0.0;
}

gm_status gm_newton_create(size_t n, const gm_newton_options *options, gm_newton **out) {
  if (out == NULL) return GM_EINVAL;
  *out = NULL;
  gm_newton_options opt = options != NULL ? *options : gm_newton_defaults();
  /* n must fit LAPACK's int, and n*n doubles must fit size_t. */
  if (n == 0 || n > (size_t)INT_MAX || n > ((size_t)-1) / sizeof(double) / n) return GM_EINVAL;
  if (!options_valid(&opt)) return GM_EINVAL;
  gm_newton *nw = calloc(1, sizeof *nw);
  if (nw == NULL) return GM_ENOMEM;
  nw->n = n;
  nw->options = opt;
  nw->residual = malloc(n * sizeof(double));
  nw->jacobian = malloc(n * n * sizeof(double));
  nw->pivots = malloc(n * sizeof(int));
  nw->increment = malloc(n * sizeof(double));
  nw->fd_x = malloc(n * sizeof(double));
  nw->fd_f = malloc(n * sizeof(double));
  if (!nw->residual || !nw->jacobian || !nw->pivots || !nw->increment || !nw->fd_x || !nw->fd_f) {
    gm_newton_free(nw);
    return GM_ENOMEM;
  }
  *out = nw;
  return GM_OK;
}

void gm_newton_free(gm_newton *newton) {
  if (newton == NULL) return;
  free(newton->residual);
  free(newton->jacobian);
  free(newton->pivots);
  free(newton->increment);
  free(newton->fd_x);
  free(newton->fd_f);
  free(newton);
}

/* out = F(x); every call of the user's residual is counted, finite differences included. */
static gm_status eval_residual(const solve_call *c, const double *x, double *out) {
  gm_newton *nw = c->nw;
  nw->residual_evals++;
  int rc = c->residual(c->ctx, x, out);
  if (rc != 0)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_ECALLBACK,
                   "residual callback returned %d (Newton iteration %zu)", rc, nw->iterations);
  size_t bad = gm_first_nonfinite(nw->n, out);
  if (bad < nw->n)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_EDOMAIN,
                   "residual component %zu is %g (Newton iteration %zu)", bad, out[bad],
                   nw->iterations);
  return GM_OK;
}

/* Residual at x into nw->residual, and its norm. */
static gm_status update_residual(const solve_call *c, const double *x) {
  gm_status s = eval_residual(c, x, c->nw->residual);
  if (s == GM_OK) c->nw->residual_norm = gm_norm_inf(c->nw->n, c->nw->residual);
  return s;
}

/* One-sided differences, column by column; needs F(x) in nw->residual. */
static gm_status fd_jacobian(const solve_call *c, const double *x) {
  gm_newton *nw = c->nw;
  size_t n = nw->n;
  memcpy(nw->fd_x, x, n * sizeof *x);
  for (size_t j = 0; j < n; ++j) {
    double xj = x[j];
    nw->fd_x[j] = xj + nw->options.fd_relative_step * fmax(fabs(xj), 1.0);
    double h = nw->fd_x[j] - xj; /* the step actually taken, exact in floating point */
    gm_status s = eval_residual(c, nw->fd_x, nw->fd_f);
    if (s != GM_OK) return s;
    for (size_t i = 0; i < n; ++i) nw->jacobian[i * n + j] = (nw->fd_f[i] - nw->residual[i]) / h;
    nw->fd_x[j] = xj;
  }
  return GM_OK;
}

/* Evaluate the Jacobian at x (F(x) must be in nw->residual) and factor it. */
static gm_status jacobian_factor(const solve_call *c, const double *x) {
  gm_newton *nw = c->nw;
  size_t n = nw->n;
  nw->jacobian_evals++;
  if (c->jacobian != NULL) {
    int rc = c->jacobian(c->ctx, x, nw->jacobian);
    if (rc != 0)
      return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_ECALLBACK,
                     "jacobian callback returned %d (Newton iteration %zu)", rc, nw->iterations);
  } else {
    gm_status s = fd_jacobian(c, x);
    if (s != GM_OK) return s;
  }
  size_t bad = gm_first_nonfinite(n * n, nw->jacobian);
  if (bad < n * n)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_EDOMAIN,
                   "Jacobian entry (%zu, %zu) is %g (Newton iteration %zu)", bad / n, bad % n,
                   nw->jacobian[bad], nw->iterations);
  gm_status s = gm_lu_factor(n, nw->jacobian, nw->pivots);
  if (s == GM_ESINGULAR)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, s,
                   "Jacobian is singular (Newton iteration %zu, residual %.1e)", nw->iterations,
                   nw->residual_norm);
  if (s != GM_OK)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, s, "LU factorization of the Jacobian failed: %s",
                   gm_strerror(s));
  return GM_OK;
}

/* x <- x - J⁻¹ F(x); returns max|dx| in *dx_norm. */
static gm_status newton_update(const solve_call *c, double *x, double *dx_norm) {
  gm_newton *nw = c->nw;
  size_t n = nw->n;
  memcpy(nw->increment, nw->residual, n * sizeof *x);
  gm_status s = gm_lu_solve(n, nw->jacobian, nw->pivots, nw->increment);
  if (s != GM_OK)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, s, "solving for the Newton increment failed: %s",
                   gm_strerror(s));
  for (size_t i = 0; i < n; ++i) x[i] -= nw->increment[i];
  *dx_norm = gm_norm_inf(n, nw->increment);
  size_t bad = gm_first_nonfinite(n, x);
  if (bad < n)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_EDOMAIN,
                   "Newton iterate component %zu is %g (iteration %zu)", bad, x[bad],
                   nw->iterations);
  return GM_OK;
}

static int residual_converged(const gm_newton *nw) {
  return nw->options.residual_tol > 0.0 && nw->residual_norm <= nw->options.residual_tol;
}

gm_status gm_newton_solve(gm_newton *newton, gm_residual_fn residual, gm_jacobian_fn jacobian,
                          void *ctx, double *x) {
  if (newton == NULL) return GM_EINVAL;
  gm_newton *nw = newton;
  nw->iterations = nw->residual_evals = nw->jacobian_evals = 0;
  nw->residual_norm = NAN;
  nw->errmsg[0] = '\0';
  if (residual == NULL || x == NULL)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_EINVAL,
                   "Newton solve needs a residual function and a starting point");
  size_t bad = gm_first_nonfinite(nw->n, x);
  if (bad < nw->n)
    return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_EDOMAIN,
                   "Newton starting point component %zu is %g", bad, x[bad]);
  const solve_call c = {nw, residual, jacobian, ctx};
  const gm_newton_options *o = &nw->options;

  gm_status s = update_residual(&c, x);
  if (s != GM_OK || residual_converged(nw)) return s;
  if (o->simplified && (s = jacobian_factor(&c, x)) != GM_OK) return s;

  double dx_norm = INFINITY, previous_dx_norm = INFINITY;
  while (nw->iterations < o->max_iterations) {
    if (!o->simplified && (s = jacobian_factor(&c, x)) != GM_OK) return s;
    previous_dx_norm = dx_norm;
    if ((s = newton_update(&c, x, &dx_norm)) != GM_OK) return s;
    nw->iterations++;
    /* The residual at the new iterate is needed next anyway, and makes the reported norm honest. */
    if ((s = update_residual(&c, x)) != GM_OK) return s;
    double scale = 1.0 + gm_norm_inf(nw->n, x);
    if (residual_converged(nw) || dx_norm <= o->increment_tol * scale) return GM_OK;
    if (dx_norm <= GM_NEWTON_ROUNDOFF_FLOOR * scale && dx_norm >= previous_dx_norm) return GM_OK;
  }
  return gm_fail(nw->errmsg, sizeof nw->errmsg, GM_ENOCONV,
                 "Newton did not converge in %zu iterations: residual %.1e, last increment %.1e",
                 nw->iterations, nw->residual_norm, dx_norm);
}

size_t gm_newton_iterations(const gm_newton *newton) { return newton ? newton->iterations : 0; }
size_t gm_newton_residual_evals(const gm_newton *newton) {
  return newton ? newton->residual_evals : 0;
}
size_t gm_newton_jacobian_evals(const gm_newton *newton) {
  return newton ? newton->jacobian_evals : 0;
}
double gm_newton_residual_norm(const gm_newton *newton) {
  return newton ? newton->residual_norm : NAN;
}
const char *gm_newton_errmsg(const gm_newton *newton) { return newton ? newton->errmsg : ""; }
