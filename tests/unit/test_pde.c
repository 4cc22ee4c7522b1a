/* pde contracts: the scheme table, bad input is an error with a message, observers. */
#include "pde_util.h"

static void expect_error(const char *scheme, size_t n, double h, double dt, int nan_data,
                         gm_status want, const char *needle) {
  gm_pde_equation eq = gm_pde_sine_gordon();
  const gm_pde_scheme *s = NULL;
  cr_assert_eq(gm_pde_scheme_find(scheme, &s), GM_OK);
  gm_pde_grid g = {n, h, 0.0, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  double *s0 = calloc(3 * n, sizeof *s0);
  if (nan_data) s0[3 * (n / 2) + 1] = NAN;
  gm_pde *p = (gm_pde *)0x1;
  gm_error err = {{0}};
  gm_status st = gm_pde_create(&g, &eq, s, &o, s0, &p, &err);
  free(s0);
  cr_assert_eq(st, want, "%s: expected %d got %d (%s)", scheme, want, st, err.message);
  cr_assert_null(p);
  cr_assert(strstr(err.message, needle) != NULL, "message '%s' lacks '%s'", err.message, needle);
}

Test(pde, bad_input_is_an_error) {
  expect_error("preissmann", 100, 0.1, 0.05, 0, GM_EINVAL, "odd number of grid points");
  expect_error("ms", 100, 0.1, 0.0, 0, GM_EINVAL, "dt must be finite and > 0");
  expect_error("euler-box", 100, 0.1, -0.1, 0, GM_EINVAL, "dt must be finite and > 0");
  expect_error("ec", 100, 0.1, NAN, 0, GM_EINVAL, "dt must be finite and > 0");
  expect_error("lf", 100, 0.1, 0.11, 0, GM_EINVAL, "CFL");
  expect_error("ms", 100, 0.1, 0.05, 1, GM_EDOMAIN, "not finite at point 50");
  expect_error("preissmann", 101, 0.1, 0.05, 1, GM_EDOMAIN, "not finite");
  expect_error("ms", 3, 0.1, 0.05, 0, GM_EINVAL, "n >= 4");
  expect_error("ms", 100, 0.0, 0.05, 0, GM_EINVAL, "grid spacing");
}

Test(pde, lf_at_the_cfl_bound_is_accepted) {
  gm_pde *p = pde_breather_solver("lf", 200, 0.2, 0); /* h = 0.2 */
  gm_pde_free(p);
  gm_pde_free(NULL);
}

Test(pde, equation_must_be_skew) {
  gm_pde_equation eq = gm_pde_sine_gordon();
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_equation_check(&eq, &err), GM_OK);
  eq.W[1 * 3 + 0] = 2.0;
  cr_assert_eq(gm_pde_equation_check(&eq, &err), GM_EINVAL);
  cr_assert(strstr(err.message, "skew") != NULL, "%s", err.message);
  eq = gm_pde_sine_gordon();
  eq.V = NULL;
  cr_assert_eq(gm_pde_equation_check(&eq, &err), GM_EINVAL);
}

Test(pde, scheme_table) {
  cr_assert_eq(gm_pde_scheme_count(), 8);
  for (size_t i = 0; i < gm_pde_scheme_count(); i++) {
    const gm_pde_scheme *s = gm_pde_scheme_at(i), *f = NULL;
    cr_assert_not_null(s->reference);
    cr_assert_not_null(s->law);
    cr_assert(s->order_t >= 1 && s->order_x >= 1);
    cr_assert_eq(gm_pde_scheme_find(s->name, &f), GM_OK);
    cr_assert_eq(f, s);
  }
  cr_assert_null(gm_pde_scheme_at(8));
  const gm_pde_scheme *f = NULL;
  cr_assert_eq(gm_pde_scheme_find("box", &f), GM_ENOTFOUND);
}

static int count_obs(const gm_pde *p, void *ctx) {
  (void)p;
  return ++*(int *)ctx >= 3;
}

Test(pde, observers_and_stop) {
  gm_pde *p = pde_breather_solver("ms", 100, 0.2, 0);
  gm_error err = {{0}};
  int calls = 0;
  cr_assert_eq(gm_pde_add_observer(p, 0, count_obs, &calls, &err), GM_EINVAL);
  cr_assert_eq(gm_pde_add_observer(p, 5, count_obs, &calls, &err), GM_OK);
  cr_assert_eq(gm_pde_advance(p, 100, &err), GM_ECALLBACK);
  cr_assert_eq(calls, 3);
  cr_assert_eq(gm_pde_steps(p), 15);
  cr_assert(strstr(err.message, "step 15") != NULL, "%s", err.message);
  gm_pde_free(p);
}

Test(pde, hessian_by_differences_is_counted) {
  /* the same Preissmann run with the analytic and the finite-difference Hessian */
  gm_pde_equation eq = gm_pde_sine_gordon();
  eq.hessian = NULL;
  const gm_pde_scheme *s = NULL;
  gm_pde_scheme_find("preissmann", &s);
  gm_pde_grid g = {101, 2.0 * PDE_L / 101, -PDE_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = 0.2;
  o.track_variations = 1;
  double *s0 = pde_breather_data(101);
  gm_pde *p = NULL, *q = pde_breather_solver("preissmann", 101, 0.2, 0);
  gm_error err = {{0}};
  cr_assert_eq(gm_pde_create(&g, &eq, s, &o, s0, &p, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_pde_advance(p, 20, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_pde_advance(q, 20, &err), GM_OK, "%s", err.message);
  cr_assert(gm_pde_get_stats(p).hessian_fd_evaluations > 0);
  cr_assert_eq(gm_pde_get_stats(q).hessian_fd_evaluations, 0);
  cr_assert(gm_pde_ms_residual(p, NULL) <= 1e-12, "%.3e", gm_pde_ms_residual(p, NULL));
  double d = 0.0;
  for (size_t i = 0; i < 303; i++) d = fmax(d, fabs(gm_pde_state(p)[i] - gm_pde_state(q)[i]));
  cr_assert(d < 1e-10, "FD Hessian changes the solution by %.3e", d);
  free(s0);
  gm_pde_free(p);
  gm_pde_free(q);
}
