/* Newton's method: convergence with analytic and finite-difference Jacobians, quadratic rate,
 * simplified Newton, statistics, and every failure path with its message. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geomint/core.h"

/* x² + y² = 4, x = y: root (√2, √2) from a start in the positive quadrant. Records the residual
 * norm at every call so the convergence rate can be checked. */
typedef struct circle_ctx {
  double norms[64];
  size_t n_calls;
  int fail_residual_at; /* call number (1-based) that fails, 0: never */
  int fail_jacobian;
  int nan_at;
} circle_ctx;

static int circle_residual(void *ctx, const double *x, double *f) {
  circle_ctx *c = ctx;
  c->n_calls++;
  if (c->fail_residual_at > 0 && (size_t)c->fail_residual_at == c->n_calls) return 7;
  f[0] = x[0] * x[0] + x[1] * x[1] - 4.0;
  f[1] = x[0] - x[1];
  if (c->nan_at > 0 && (size_t)c->nan_at == c->n_calls) f[1] = NAN;
  if (c->n_calls <= 64) c->norms[c->n_calls - 1] = fmax(fabs(f[0]), fabs(f[1]));
  return 0;
}

static int circle_jacobian(void *ctx, const double *x, double *j) {
  circle_ctx *c = ctx;
  if (c->fail_jacobian) return -3;
  j[0] = 2.0 * x[0];
  j[1] = 2.0 * x[1];
  j[2] = 1.0;
  j[3] = -1.0;
  return 0;
}

static gm_newton *make(size_t n, const gm_newton_options *o) {
  gm_newton *nw = NULL;
  cr_assert_eq(gm_newton_create(n, o, &nw), GM_OK);
  cr_assert_not_null(nw);
  return nw;
}

static void assert_at_root(const double *x) {
  cr_assert(fabs(x[0] - sqrt(2.0)) <= 4e-16 && fabs(x[1] - sqrt(2.0)) <= 4e-16,
            "x = (%.17g, %.17g)", x[0], x[1]);
}

Test(newton, defaults) {
  gm_newton_options o = gm_newton_defaults();
  cr_assert_eq(o.max_iterations, 30);
  cr_assert(o.residual_tol == 0.0 && o.increment_tol == 1e-14 && o.simplified == 0 &&
            o.fd_relative_step == 1e-7);
  gm_newton_free(NULL);
  gm_newton *nw = (gm_newton *)1;
  cr_assert_eq(gm_newton_create(0, NULL, &nw), GM_EINVAL);
  cr_assert_null(nw);
  cr_assert_eq(gm_newton_create(2, NULL, NULL), GM_EINVAL);
  o.fd_relative_step = 0.0;
  cr_assert_eq(gm_newton_create(2, &o, &nw), GM_EINVAL);
}

Test(newton, analytic_jacobian_converges_quadratically) {
  gm_newton *nw = make(2, NULL);
  circle_ctx c = {0};
  double x[2] = {1.0, 0.5};
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &c, x), GM_OK, "%s",
               gm_newton_errmsg(nw));
  assert_at_root(x);
  size_t it = gm_newton_iterations(nw);
  cr_assert(it >= 4 && it <= 7, "iterations %zu", it);
  cr_assert_eq(gm_newton_jacobian_evals(nw), it);
  cr_assert_eq(gm_newton_residual_evals(nw), it + 1);
  cr_assert_eq(c.n_calls, it + 1);
  cr_assert(gm_newton_residual_norm(nw) <= 1e-15);
  cr_assert(gm_newton_residual_norm(nw) == c.norms[c.n_calls - 1], "reported norm is the last one");
  cr_assert_str_empty(gm_newton_errmsg(nw));
  /* Quadratic rate: r_{k+1} <= C r_k² while above round-off. */
  size_t n_checked = 0;
  for (size_t k = 1; k < c.n_calls; ++k) {
    if (c.norms[k] < 1e-13) break;
    cr_assert(c.norms[k] <= 2.0 * c.norms[k - 1] * c.norms[k - 1], "r_%zu = %g, r_%zu = %g", k,
              c.norms[k], k - 1, c.norms[k - 1]);
    n_checked++;
  }
  cr_assert(n_checked >= 2, "the rate was checked on %zu steps only", n_checked);
  gm_newton_free(nw);
}

Test(newton, finite_difference_jacobian) {
  gm_newton *nw = make(2, NULL);
  circle_ctx c = {0};
  double x[2] = {1.0, 0.5};
  cr_assert_eq(gm_newton_solve(nw, circle_residual, NULL, &c, x), GM_OK, "%s",
               gm_newton_errmsg(nw));
  assert_at_root(x);
  size_t it = gm_newton_iterations(nw);
  cr_assert(it <= 8, "iterations %zu", it);
  cr_assert_eq(gm_newton_jacobian_evals(nw), it);
  /* One residual per iterate plus n per finite-difference Jacobian. */
  cr_assert_eq(gm_newton_residual_evals(nw), it + 1 + 2 * it);
  cr_assert_eq(c.n_calls, gm_newton_residual_evals(nw));
  cr_assert(gm_newton_residual_norm(nw) <= 1e-15);
  gm_newton_free(nw);
}

Test(newton, simplified_newton_converges_with_one_jacobian) {
  gm_newton_options o = gm_newton_defaults();
  o.simplified = 1;
  o.max_iterations = 100;
  gm_newton *nw = make(2, &o);
  circle_ctx c = {0};
  double x[2] = {1.3, 1.5};
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &c, x), GM_OK, "%s",
               gm_newton_errmsg(nw));
  cr_assert(fabs(x[0] - sqrt(2.0)) <= 1e-14 && fabs(x[1] - sqrt(2.0)) <= 1e-14);
  cr_assert_eq(gm_newton_jacobian_evals(nw), 1);
  cr_assert(gm_newton_iterations(nw) > 5, "linear convergence needs more iterations");
  gm_newton_free(nw);
}

Test(newton, residual_tolerance_stops_early) {
  gm_newton_options o = gm_newton_defaults();
  o.residual_tol = 1e-6;
  gm_newton *nw = make(2, &o);
  circle_ctx c = {0};
  double x[2] = {1.0, 0.5};
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &c, x), GM_OK);
  cr_assert(gm_newton_residual_norm(nw) <= 1e-6);
  cr_assert(gm_newton_residual_norm(nw) > 1e-16, "stopped as soon as the tolerance was met");
  /* Already at a root: no iteration at all. */
  x[0] = x[1] = sqrt(2.0);
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &c, x), GM_OK);
  cr_assert_eq(gm_newton_iterations(nw), 0);
  cr_assert_eq(gm_newton_jacobian_evals(nw), 0);
  cr_assert_eq(gm_newton_residual_evals(nw), 1);
  gm_newton_free(nw);
}

/* x² + 1 = 0 has no real root; |dx| = (x²+1)/|2x| >= 1 forever. */
static int no_root(void *ctx, const double *x, double *f) {
  (void)ctx;
  f[0] = x[0] * x[0] + 1.0;
  return 0;
}

Test(newton, no_root_is_enoconv_with_message) {
  gm_newton *nw = make(1, NULL);
  double x = 0.5;
  cr_assert_eq(gm_newton_solve(nw, no_root, NULL, NULL, &x), GM_ENOCONV);
  cr_assert_eq(gm_newton_iterations(nw), 30);
  const char *msg = gm_newton_errmsg(nw);
  cr_assert(strstr(msg, "did not converge in 30 iterations") != NULL, "message: %s", msg);
  cr_assert(strstr(msg, "residual") != NULL && strstr(msg, "increment") != NULL, "message: %s",
            msg);
  cr_assert(gm_newton_residual_norm(nw) >= 1.0);
  gm_newton_free(nw);
}

Test(newton, failing_callbacks) {
  gm_newton *nw = make(2, NULL);
  circle_ctx c = {0};
  c.fail_residual_at = 3;
  double x[2] = {1.0, 0.5};
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &c, x), GM_ECALLBACK);
  const char *msg = gm_newton_errmsg(nw);
  cr_assert(strstr(msg, "residual") != NULL && strstr(msg, "7") != NULL, "message: %s", msg);

  circle_ctx cj = {0};
  cj.fail_jacobian = 1;
  x[0] = 1.0;
  x[1] = 0.5;
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &cj, x), GM_ECALLBACK);
  msg = gm_newton_errmsg(nw);
  cr_assert(strstr(msg, "jacobian") != NULL && strstr(msg, "-3") != NULL, "message: %s", msg);

  /* A later successful solve clears the message. */
  circle_ctx ok = {0};
  x[0] = 1.0;
  x[1] = 0.5;
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &ok, x), GM_OK);
  cr_assert_str_empty(gm_newton_errmsg(nw));
  gm_newton_free(nw);
}

Test(newton, nan_residual_is_edomain) {
  gm_newton *nw = make(2, NULL);
  circle_ctx c = {0};
  c.nan_at = 2;
  double x[2] = {1.0, 0.5};
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &c, x), GM_EDOMAIN);
  cr_assert(strstr(gm_newton_errmsg(nw), "residual") != NULL, "message: %s", gm_newton_errmsg(nw));
  double bad[2] = {NAN, 0.0};
  cr_assert_eq(gm_newton_solve(nw, circle_residual, circle_jacobian, &c, bad), GM_EDOMAIN);
  cr_assert_eq(gm_newton_solve(nw, NULL, NULL, NULL, x), GM_EINVAL);
  gm_newton_free(nw);
}

/* F(x) = x0 + x1 - 1 twice: a singular Jacobian. */
static int rank_deficient(void *ctx, const double *x, double *f) {
  (void)ctx;
  f[0] = f[1] = x[0] + x[1] - 1.0;
  return 0;
}

static int rank_deficient_jacobian(void *ctx, const double *x, double *j) {
  (void)ctx;
  (void)x;
  j[0] = j[1] = j[2] = j[3] = 1.0;
  return 0;
}

Test(newton, singular_jacobian) {
  gm_newton *nw = make(2, NULL);
  double x[2] = {3.0, 0.0};
  cr_assert_eq(gm_newton_solve(nw, rank_deficient, rank_deficient_jacobian, NULL, x), GM_ESINGULAR);
  cr_assert(strstr(gm_newton_errmsg(nw), "singular") != NULL);
  gm_newton_free(nw);
}

/* A larger system: F_i = x_i³ + x_i - c_i + 0.1 (x_{i-1} + x_{i+1}), with a root built in. */
enum { BIG = 12 };
static int chain(void *ctx, const double *x, double *f) {
  const double *root = ctx;
  for (size_t i = 0; i < BIG; ++i) {
    double l = i > 0 ? x[i - 1] - root[i - 1] : 0.0, r = i + 1 < BIG ? x[i + 1] - root[i + 1] : 0.0;
    f[i] = x[i] * x[i] * x[i] + x[i] - (root[i] * root[i] * root[i] + root[i]) + 0.1 * (l + r);
  }
  return 0;
}

Test(newton, finite_differences_on_a_larger_system) {
  double root[BIG], x[BIG];
  for (size_t i = 0; i < BIG; ++i) {
    root[i] = sin((double)i + 0.5) * 3.0;
    x[i] = root[i] + 0.3 * cos((double)i);
  }
  gm_newton *nw = make(BIG, NULL);
  cr_assert_eq(gm_newton_solve(nw, chain, NULL, root, x), GM_OK, "%s", gm_newton_errmsg(nw));
  for (size_t i = 0; i < BIG; ++i) cr_assert(fabs(x[i] - root[i]) <= 1e-13, "x[%zu]", i);
  cr_assert(gm_newton_iterations(nw) <= 10, "iterations %zu", gm_newton_iterations(nw));
  gm_newton_free(nw);
}
