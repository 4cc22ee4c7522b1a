/* The integrator driver's contracts: errors with messages, exact final time, observers that
 * do not change results, statistics, failures that keep the last good state, compensated
 * summation, and the general Hamiltonian path (with and without a Hessian). */
#include "test_util.h"

/* H(q, p) = ½ p² (1 + q²) + ½ q²: not separable. */
static double nonsep_h(void *ctx, const double *q, const double *p) {
  (void)ctx;
  return 0.5 * p[0] * p[0] * (1 + q[0] * q[0]) + 0.5 * q[0] * q[0];
}
static int nonsep_hq(void *ctx, const double *q, const double *p, double *out) {
  (void)ctx;
  out[0] = p[0] * p[0] * q[0] + q[0];
  return 0;
}
static int nonsep_hp(void *ctx, const double *q, const double *p, double *out) {
  (void)ctx;
  out[0] = p[0] * (1 + q[0] * q[0]);
  return 0;
}
static int nonsep_hess(void *ctx, const double *q, const double *p, double *h) {
  (void)ctx;
  h[0] = p[0] * p[0] + 1; /* H_qq */
  h[1] = 2 * p[0] * q[0]; /* H_qp */
  h[2] = h[1];
  h[3] = 1 + q[0] * q[0]; /* H_pp */
  return 0;
}
static gm_problem nonseparable(int with_hessian) {
  gm_problem pb = {0};
  pb.kind = GM_PROBLEM_HAMILTONIAN;
  pb.dim = 1;
  pb.hamiltonian = nonsep_h;
  pb.dh_dq = nonsep_hq;
  pb.dh_dp = nonsep_hp;
  if (with_hessian) pb.hamiltonian_hessian = nonsep_hess;
  return pb;
}

/* y' = c, failing (returning 7) once t exceeds *fail_after. */
typedef struct {
  double c, fail_after;
} constant_ctx;
static int constant_rhs(void *ctx, double t, const double *y, double *f) {
  (void)y;
  const constant_ctx *k = ctx;
  if (t > k->fail_after) return 7;
  f[0] = k->c;
  return 0;
}
static gm_problem constant_problem(constant_ctx *ctx) {
  gm_problem pb = {0};
  pb.kind = GM_PROBLEM_FIRST_ORDER;
  pb.dim = 1;
  pb.ctx = ctx;
  pb.rhs = constant_rhs;
  return pb;
}

/* y' = y² + 1: the midpoint equation has no real solution for y = 0 and h > 1. */
static int tan_rhs(void *ctx, double t, const double *y, double *f) {
  (void)ctx;
  (void)t;
  f[0] = y[0] * y[0] + 1;
  return 0;
}

Test(integrator, create_errors_say_why) {
  gm_problem pb = nonseparable(1);
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_integrator_create(gm_method_find("verlet"), &pb, &it, &err), GM_EUNSUPPORTED);
  cr_expect_null(it);
  cr_expect(strstr(err.message, "verlet") && strstr(err.message, "hamiltonian") &&
                strstr(err.message, "separable"),
            "%s", err.message);
  cr_expect_eq(gm_integrator_create(NULL, &pb, &it, &err), GM_EINVAL);
  pb.dh_dq = NULL;
  cr_expect_eq(gm_integrator_create(gm_method_find("midpoint"), &pb, &it, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "dh_dq") != NULL, "%s", err.message);
  cr_expect_eq(gm_integrator_create(gm_method_find("rk4"), NULL, &it, NULL), GM_EINVAL);
  gm_integrator_free(NULL);
}

Test(integrator, bad_state_and_steps_are_rejected) {
  test_model tm = test_model_make("kepler");
  gm_integrator *it = test_integrator(gm_method_find("verlet"), tm.problem, 0.0, tm.y0);
  double bad[4] = {0.4, NAN, 0, 2};
  cr_expect_eq(gm_integrator_set_state(it, 0.0, bad), GM_EDOMAIN);
  cr_expect(strstr(gm_integrator_errmsg(it), "component 2") != NULL, "%s",
            gm_integrator_errmsg(it));
  cr_expect_eq(gm_integrator_state(it)[1], tm.y0[1]); /* unchanged */
  cr_expect_eq(gm_integrator_step(it, 0.0), GM_EINVAL);
  cr_expect_eq(gm_integrator_step(it, INFINITY), GM_EINVAL);
  cr_expect_eq(gm_integrator_integrate(it, 1.0, -0.1), GM_EINVAL);
  cr_expect_eq(gm_integrator_integrate(it, -1.0, 0.1), GM_EINVAL);
  cr_expect_eq(gm_integrator_add_observer(it, gm_monitor_observe, NULL, 0), GM_EINVAL);
  cr_expect_eq(gm_integrator_stats(it).steps, 0);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

Test(integrator, integrate_ends_exactly_at_t_end) {
  test_model tm = test_model_make("harmonic");
  gm_integrator *it = test_integrator(gm_method_find("verlet"), tm.problem, 0.0, tm.y0);
  cr_assert_eq(gm_integrator_integrate(it, 1.0, 0.3), GM_OK);
  cr_expect_eq(gm_integrator_time(it), 1.0);
  cr_expect_eq(gm_integrator_stats(it).steps, 4); /* four steps of 0.25 */
  /* 0.1 does not divide 1 in binary, yet 10 steps are taken, not 11 */
  cr_assert_eq(gm_integrator_integrate(it, 2.0, 0.1), GM_OK);
  cr_expect_eq(gm_integrator_time(it), 2.0);
  cr_expect_eq(gm_integrator_stats(it).steps, 14);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

typedef struct {
  size_t calls, steps[32];
  int fail_at;
} recorder;
static int record(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  (void)y;
  recorder *r = ctx;
  if (r->calls < 32) r->steps[r->calls] = step;
  r->calls++;
  return (r->fail_at >= 0 && (int)step == r->fail_at) ? 5 : 0;
}

Test(integrator, observers_see_due_steps_and_change_nothing) {
  test_model tm = test_model_make("kepler");
  gm_integrator *a = test_integrator(gm_method_find("rk4"), tm.problem, 0.0, tm.y0);
  gm_integrator *b = test_integrator(gm_method_find("rk4"), tm.problem, 0.0, tm.y0);
  recorder r = {0, {0}, -1};
  cr_assert_eq(gm_integrator_add_observer(a, record, &r, 3), GM_OK);
  cr_assert_eq(gm_integrator_run(a, 10, 0.01), GM_OK);
  cr_assert_eq(gm_integrator_run(b, 10, 0.01), GM_OK);
  size_t expected[] = {0, 3, 6, 9, 10};
  cr_assert_eq(r.calls, 5);
  for (size_t i = 0; i < 5; ++i) cr_expect_eq(r.steps[i], expected[i]);
  cr_expect_eq(memcmp(gm_integrator_state(a), gm_integrator_state(b), 4 * sizeof(double)), 0,
               "observation changed the result");
  gm_integrator_free(a);
  gm_integrator_free(b);
  gm_model_free(tm.model);
}

Test(integrator, observer_failure_stops_the_run) {
  test_model tm = test_model_make("kepler");
  gm_integrator *it = test_integrator(gm_method_find("verlet"), tm.problem, 0.0, tm.y0);
  recorder r = {0, {0}, 4};
  cr_assert_eq(gm_integrator_add_observer(it, record, &r, 2), GM_OK);
  cr_expect_eq(gm_integrator_run(it, 10, 0.01), GM_ECALLBACK);
  cr_expect_eq(gm_integrator_stats(it).steps, 4);
  cr_expect(strstr(gm_integrator_errmsg(it), "observer 1 returned 5") != NULL, "%s",
            gm_integrator_errmsg(it));
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

Test(integrator, callback_failure_keeps_last_good_state) {
  constant_ctx ctx = {1.0, 0.5};
  gm_problem pb = constant_problem(&ctx);
  double y0 = 0.0;
  gm_integrator *it = test_integrator(gm_method_find("rk4"), &pb, 0.0, &y0);
  cr_expect_eq(gm_integrator_run(it, 100, 0.1), GM_ECALLBACK);
  cr_expect(strstr(gm_integrator_errmsg(it), "rhs returned 7") != NULL, "%s",
            gm_integrator_errmsg(it));
  /* the step from 0.4 hits t = 0.45 > 0.5? no: its stages reach 0.5, the next step fails */
  cr_expect_float_eq(gm_integrator_time(it), 0.5, 1e-15);
  cr_expect_float_eq(gm_integrator_state(it)[0], 0.5, 1e-15);
  gm_integrator_free(it);
}

Test(integrator, newton_failure_is_reported) {
  gm_problem pb = {0};
  pb.kind = GM_PROBLEM_FIRST_ORDER;
  pb.dim = 1;
  pb.rhs = tan_rhs;
  double y0 = 0.0;
  gm_integrator *it = test_integrator(gm_method_find("midpoint"), &pb, 0.0, &y0);
  /* full Newton oscillates without converging */
  cr_assert_eq(gm_integrator_set_solver(it, GM_SOLVER_NEWTON), GM_OK);
  cr_expect_eq(gm_integrator_step(it, 2.0), GM_ENOCONV);
  cr_expect(strstr(gm_integrator_errmsg(it), "did not converge") != NULL, "%s",
            gm_integrator_errmsg(it));
  cr_expect(strstr(gm_integrator_errmsg(it), "t = 0") != NULL, "%s", gm_integrator_errmsg(it));
  /* simplified Newton runs away to infinity: also reported, never a silent NaN */
  cr_assert_eq(gm_integrator_set_solver(it, GM_SOLVER_SIMPLIFIED_NEWTON), GM_OK);
  gm_status st = gm_integrator_step(it, 2.0);
  cr_expect(st == GM_ENOCONV || st == GM_EDOMAIN, "%s", gm_strerror(st));
  cr_expect_eq(gm_integrator_stats(it).newton_failures, 2);
  cr_expect_eq(gm_integrator_state(it)[0], 0.0);
  cr_expect_eq(gm_integrator_time(it), 0.0);
  /* and a small step works, with a finite-difference Jacobian since none was given */
  cr_expect_eq(gm_integrator_step(it, 0.1), GM_OK);
  cr_expect_gt(gm_integrator_stats(it).fd_jacobians, 0);
  gm_integrator_free(it);
}

Test(integrator, force_evaluations_counted) {
  test_model tm = test_model_make("kepler");
  struct {
    const char *name;
    size_t per_step, extra;
  } cases[] = {{"verlet", 1, 1}, {"verlet-position", 1, 0}, {"symplectic-euler-a", 1, 0},
               {"symplectic-euler-b", 1, 0}, {"rk4", 4, 0}, {"euler", 1, 0}};
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    gm_integrator *it = test_integrator(gm_method_find(cases[i].name), tm.problem, 0, tm.y0);
    cr_assert_eq(gm_integrator_run(it, 100, 0.01), GM_OK);
    cr_expect_eq(gm_integrator_stats(it).force_evals, 100 * cases[i].per_step + cases[i].extra,
                 "%s: %zu", cases[i].name, gm_integrator_stats(it).force_evals);
    gm_integrator_free(it);
  }
  gm_model_free(tm.model);
}

Test(integrator, hamiltonian_path_with_and_without_hessian) {
  gm_problem with = nonseparable(1), without = nonseparable(0);
  double y0[2] = {0.8, -0.3};
  gm_integrator *a = test_integrator(gm_method_find("midpoint"), &with, 0.0, y0);
  gm_integrator *b = test_integrator(gm_method_find("midpoint"), &without, 0.0, y0);
  /* the Jacobian paths: Newton (the default solver is fixed-point) */
  cr_assert_eq(gm_integrator_set_solver(a, GM_SOLVER_SIMPLIFIED_NEWTON), GM_OK);
  cr_assert_eq(gm_integrator_set_solver(b, GM_SOLVER_SIMPLIFIED_NEWTON), GM_OK);
  cr_assert_eq(gm_integrator_run(a, 200, 0.05), GM_OK, "%s", gm_integrator_errmsg(a));
  cr_assert_eq(gm_integrator_run(b, 200, 0.05), GM_OK, "%s", gm_integrator_errmsg(b));
  for (size_t i = 0; i < 2; ++i)
    cr_expect(fabs(gm_integrator_state(a)[i] - gm_integrator_state(b)[i]) < 1e-12);
  cr_expect_eq(gm_integrator_stats(a).fd_jacobians, 0);
  cr_expect_gt(gm_integrator_stats(b).fd_jacobians, 0);
  cr_expect_gt(gm_integrator_stats(a).newton_iterations, 200);
  /* RK4 takes the same Hamiltonian through its first-order view */
  gm_integrator *c = test_integrator(gm_method_find("rk4"), &with, 0.0, y0);
  cr_assert_eq(gm_integrator_run(c, 200, 0.05), GM_OK);
  for (size_t i = 0; i < 2; ++i)
    cr_expect(fabs(gm_integrator_state(a)[i] - gm_integrator_state(c)[i]) < 1e-2);
  gm_integrator_free(a);
  gm_integrator_free(b);
  gm_integrator_free(c);
}

/* y' = 0.1 with explicit Euler is exact in exact arithmetic: what remains is round-off, which
 * compensated summation removes. */
Test(integrator, compensated_summation_removes_round_off) {
  constant_ctx ctx = {0.1, INFINITY};
  gm_problem pb = constant_problem(&ctx);
  double y0 = 1.0, err[2];
  for (int comp = 0; comp < 2; ++comp) {
    gm_integrator *it = test_integrator(gm_method_find("euler"), &pb, 0.0, &y0);
    cr_assert_eq(gm_integrator_set_compensated(it, comp), GM_OK);
    cr_assert_eq(gm_integrator_run(it, 1000000, 1e-3), GM_OK);
    err[comp] = fabs(gm_integrator_state(it)[0] - (1.0 + 0.1 * 1e-3 * 1e6));
    gm_integrator_free(it);
  }
  cr_expect_gt(err[0], 1e-12, "plain summation should show round-off: %.2e", err[0]);
  cr_expect_lt(err[1], 1e-3 * err[0], "compensated %.2e vs plain %.2e", err[1], err[0]);
}

Test(integrator, runs_are_bitwise_reproducible) {
  test_model tm = test_model_make("henon-heiles");
  double first[4];
  for (int k = 0; k < 2; ++k) {
    gm_integrator *it = test_integrator(gm_method_find("midpoint"), tm.problem, 0.0, tm.y0);
    cr_assert_eq(gm_integrator_run(it, 1000, 0.05), GM_OK);
    if (k == 0)
      memcpy(first, gm_integrator_state(it), sizeof first);
    else
      cr_expect_eq(memcmp(first, gm_integrator_state(it), sizeof first), 0);
    gm_integrator_free(it);
  }
  gm_model_free(tm.model);
}
