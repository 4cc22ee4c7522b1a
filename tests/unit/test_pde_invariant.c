/* Invariant schemes: the table, and bad input as an error with a message. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geomint/pde.h"

static gm_inv_front front = {1.0, 0.0, 0.0, 5e-3};

static gm_inv_run_spec spec(const char *scheme, const gm_inv_group *g) {
  gm_inv_run_spec s = gm_inv_run_spec_defaults();
  cr_assert_eq(gm_inv_scheme_find(scheme, &s.scheme), GM_OK);
  s.frame_group = g;
  s.nu = front.nu;
  s.n = 201;
  s.x_left = -2.0;
  s.h = 0.02;
  s.k = 0.01;
  s.n_steps = 10;
  s.exact = gm_inv_burgers_front;
  s.exact_ctx = &front;
  return s;
}

static void expect(const gm_inv_run_spec *s, gm_status want, const char *needle) {
  gm_error err = {{0}};
  double u[400];
  gm_status st = gm_inv_run(s, NULL, NULL, u, NULL, &err);
  cr_assert_eq(st, want, "expected %d got %d (%s)", want, st, err.message);
  cr_assert(strstr(err.message, needle) != NULL, "message '%s' lacks '%s'", err.message, needle);
}

static double nan_data(double t, double x, const void *ctx) {
  (void)ctx;
  return x > 0.51 && t >= 0.0 ? NAN : 0.0;
}

Test(pde_invariant, table) {
  cr_assert_eq(gm_inv_scheme_count(), 4);
  for (size_t i = 0; i < gm_inv_scheme_count(); i++) {
    const gm_inv_scheme *s = gm_inv_scheme_at(i), *f = NULL;
    cr_assert_eq(gm_inv_scheme_find(s->name, &f), GM_OK);
    cr_assert_eq(s, f);
  }
  cr_assert_null(gm_inv_scheme_at(4));
  const gm_inv_scheme *s;
  cr_assert_eq(gm_inv_scheme_find("upwind", &s), GM_ENOTFOUND);
}

Test(pde_invariant, bad_input) {
  gm_inv_run_spec s = spec("ftcs", &gm_inv_burgers_g0);
  s.nu = -1e-3;
  expect(&s, GM_EINVAL, "viscosity nu = -0.001");
  s = spec("ftcs", NULL);
  s.nu = NAN;
  expect(&s, GM_EINVAL, "must be finite and >= 0");
  /* FTCS: k <= min(h²/(2ν), 2ν/max|u|²) = min(0.04, 0.01): k = 0.02 is above 0.01 */
  s = spec("ftcs", NULL);
  s.k = 0.02;
  expect(&s, GM_EINVAL, "above the stability bound 0.01 of ftcs");
  s = spec("lax-wendroff", &gm_inv_burgers_g0);
  s.k = 0.03; /* h²/(ν + √(ν² + h²)) = 0.0156 */
  expect(&s, GM_EINVAL, "above the stability bound 0.0156");
  s = spec("ftcs", NULL);
  s.exact = nan_data;
  expect(&s, GM_EDOMAIN, "not finite at (t, x) = (0, 0.52)");
  s = spec("ftcs", NULL);
  s.h = 0.0;
  expect(&s, GM_EINVAL, "h, k must be finite and > 0");
  s = spec("ftcs", NULL);
  s.n = 2;
  expect(&s, GM_EINVAL, "2 points per layer");
  s = spec("heat-ftcs", &gm_inv_burgers_g0);
  expect(&s, GM_EINVAL, "group burgers-g0 acts on the burgers equation, scheme heat-ftcs");
  /* The projection frame needs 1 + k D₁u > 0: the front's slope is −Δ²/(8ν) = −25 at its
   * centre, D₁u = −19.0 at x = 0 on h = 0.02, so k = 0.06 (stability check off) has no frame
   * there. */
  s = spec("ftcs", &gm_inv_burgers_g0);
  s.k = 0.06;
  s.check_stability = 0;
  expect(&s, GM_EDOMAIN, "frame does not exist at (t, x) = (0, ");
  expect(&s, GM_EDOMAIN, "1 + k u_x = -0.");
}

/* The stability check sees the velocity relative to the mesh: u for the standard form,
 * u − σ/k for the invariant one, so a boost that the standard FTCS refuses passes. */
Test(pde_invariant, bound_is_galilean_for_the_invariant_form) {
  double a[4] = {0, 0, 0, 1.0};
  gm_inv_run_spec s = spec("ftcs", NULL);
  s.k = 0.005;
  s.transform_group = &gm_inv_burgers_g0;
  s.transform_a = a;
  expect(&s, GM_EINVAL, "above the stability bound 0.0025");
  s.frame_group = &gm_inv_burgers_g0;
  gm_error err = {{0}};
  double u[201];
  cr_assert_eq(gm_inv_run(&s, NULL, NULL, u, NULL, &err), GM_OK, "%s", err.message);
}
