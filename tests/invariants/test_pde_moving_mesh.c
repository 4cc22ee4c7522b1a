/* The space–time adaptive variational integrator of the wave equation (seed 004 (62), (66),
 * (67a)–(67c); geomint/pde_moving_mesh.h) on a travelling Gaussian pulse u = exp(−(x − 10 − t)²)
 * on [0, 20) periodic: the seed's equations give a singular Newton matrix; the time-adaptive
 * regularisation keeps the discrete energy to the Newton tolerance over 10⁴ steps; its order
 * against d'Alembert; Dirichlet ends; observers; bad input. Measured values in comments. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geomint/pde.h"

#define LEN 20.0

static double pulse(double x, const void *ctx) {
  (void)ctx;
  double y = fmod(x, LEN);
  if (y < 0.0) y += LEN;
  y -= 0.5 * LEN;
  return exp(-y * y);
}
static double pulse_dx(double x) {
  double y = fmod(x, LEN);
  if (y < 0.0) y += LEN;
  y -= 0.5 * LEN;
  return -2.0 * y * exp(-y * y);
}

/* n nodes on the uniform grid (or Dirichlet: n nodes over [0, 20]), right-travelling data */
static gm_moving_mesh *make(size_t n, gm_moving_mesh_kind kind, double alpha, int dirichlet,
                            double cfl) {
  double *x = malloc(n * sizeof *x), *u0 = malloc(n * sizeof *u0), *ut = malloc(n * sizeof *ut);
  gm_error err = {0};
  cr_assert_eq(gm_moving_mesh_equidistribute(n, 0.0, LEN, alpha, dirichlet, pulse, NULL, 64 * n,
                                             x, &err),
               GM_OK, "%s", err.message);
  for (size_t j = 0; j < n; j++) {
    u0[j] = pulse(x[j], NULL);
    ut[j] = -pulse_dx(x[j]);
  }
  gm_moving_mesh_options o = gm_moving_mesh_options_defaults();
  o.kind = kind;
  o.alpha = alpha;
  o.dirichlet = dirichlet;
  o.dt = cfl * gm_moving_mesh_dt_bound(n, x, LEN, dirichlet);
  gm_moving_mesh *m = NULL;
  cr_assert_eq(gm_moving_mesh_create(n, x, LEN, u0, ut, &o, &m, &err), GM_OK, "%s", err.message);
  free(x);
  free(u0);
  free(ut);
  return m;
}

static double max_error(const gm_moving_mesh *m) {
  const double *x = gm_moving_mesh_x(m), *u = gm_moving_mesh_u(m);
  double t = gm_moving_mesh_time(m), e = 0.0;
  for (size_t j = 0; j < gm_moving_mesh_n(m); j++) e = fmax(e, fabs(u[j] - pulse(x[j] - t, NULL)));
  return e;
}

Test(moving_mesh, seed_equations_are_singular) {
  /* cond of the row-scaled Newton matrix at the first step's start: seed 3.8e17 (n = 40),
   * time-adaptive 54 (n = 40) */
  gm_error err = {0};
  double smin, cond;
  gm_moving_mesh *m = make(40, GM_MOVING_MESH_SEED, 0.0, 0, 0.5);
  cr_assert_eq(gm_moving_mesh_conditioning(m, &smin, &cond, &err), GM_OK, "%s", err.message);
  cr_log_info("seed n = 40: sigma_min %.3e cond %.3e", smin, cond);
  cr_expect_gt(cond, 1e14, "seed cond %g", cond);
  cr_expect_eq(gm_moving_mesh_advance(m, 1, &err), GM_ESINGULAR, "%s", err.message);
  cr_expect_eq(gm_moving_mesh_get_stats(m).failed_steps, 1);
  gm_moving_mesh_free(m);
  m = make(40, GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 0, 0.5);
  cr_assert_eq(gm_moving_mesh_conditioning(m, &smin, &cond, &err), GM_OK, "%s", err.message);
  cr_log_info("time-adaptive n = 40: sigma_min %.3e cond %.3e", smin, cond);
  cr_expect_lt(cond, 300.0, "time-adaptive cond %g", cond);
  gm_moving_mesh_free(m);
}

Test(moving_mesh, energy_over_1e4_steps) {
  /* n = 100, Δt⁰ = h/2: measured max per-step |Eⁿ − E^{n−1}| 7.7e-13 (= the largest Newton
   * residual), |E − E⁰|/E⁰ 3.9e-11 after 10⁴ steps (t = 985.8), 5.28 Newton iterations per
   * step; momentum (not imposed) max |P − P⁰|/|P⁰| 8.2e-5 */
  gm_error err = {0};
  gm_moving_mesh *m = make(100, GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 0, 0.5);
  double e0 = gm_moving_mesh_energy(m), p0 = gm_moving_mesh_momentum(m), e_prev = e0;
  double step_max = 0.0, p_max = 0.0;
  for (size_t s = 0; s < 10000; s++) {
    cr_assert_eq(gm_moving_mesh_advance(m, 1, &err), GM_OK, "%s", err.message);
    double e = gm_moving_mesh_energy(m);
    step_max = fmax(step_max, fabs(e - e_prev));
    e_prev = e;
    p_max = fmax(p_max, fabs(gm_moving_mesh_momentum(m) - p0));
  }
  gm_moving_mesh_stats st = gm_moving_mesh_get_stats(m);
  double drift = fabs(gm_moving_mesh_energy(m) - e0) / e0;
  cr_log_info("t %.4f, per-step |dE| %.3e, |E - E0|/E0 %.3e, max |P - P0|/|P0| %.3e, "
              "max residual %.3e, %.2f Newton iterations per step", gm_moving_mesh_time(m),
              step_max, drift, p_max / fabs(p0), st.max_residual,
              (double)st.newton_iterations / (double)st.steps);
  cr_expect_eq(st.failed_steps, 0);
  cr_expect_lt(st.max_residual, 3e-12);
  cr_expect_lt(step_max, 3e-12, "per-step energy change %g", step_max);
  cr_expect_lt(drift, 2e-10, "energy drift %g", drift);
  cr_expect_lt(p_max / fabs(p0), 3e-4, "momentum drift %g", p_max / fabs(p0));
  cr_expect_gt(gm_moving_mesh_time(m), 900.0);
  gm_moving_mesh_free(m);
}

Test(moving_mesh, order_against_dalembert) {
  /* max error at t ≈ 4: n = 100, 200, 400 (Δt⁰ = h/2): 2.19e-2, 5.28e-3, 1.31e-3, orders 2.05,
   * 2.01 (docs/pde.md: 2) */
  double e[3];
  for (int k = 0; k < 3; k++) {
    size_t n = (size_t)100 << k;
    gm_error err = {0};
    gm_moving_mesh *m = make(n, GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 0, 0.5);
    cr_assert_eq(gm_moving_mesh_advance(m, 2 * n / 5, &err), GM_OK, "%s", err.message);
    e[k] = max_error(m);
    gm_moving_mesh_free(m);
  }
  double p = log2(e[1] / e[2]);
  cr_log_info("errors %.3e %.3e %.3e, orders %.3f %.3f", e[0], e[1], e[2], log2(e[0] / e[1]), p);
  cr_expect(fabs(p - 2.0) <= 0.2, "order %g", p);
}

Test(moving_mesh, dirichlet_ends_and_equidistribute) {
  /* Dirichlet, n = 64: the ends stay, E to the tolerance until the pulse reaches the wall
   * (t ≈ 9.4: the energy equation then loses its root, docs/pde.md). EQUIDISTRIBUTE with α = 0
   * on Dirichlet ends (the grid cannot move) also runs. */
  gm_error err = {0};
  gm_moving_mesh *m = make(64, GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 1, 0.5);
  double e0 = gm_moving_mesh_energy(m);
  cr_assert_eq(gm_moving_mesh_advance(m, 40, &err), GM_OK, "%s", err.message);
  const double *x = gm_moving_mesh_x(m), *u = gm_moving_mesh_u(m);
  cr_expect_eq(x[0], 0.0);
  cr_expect_eq(x[63], LEN);
  cr_expect_eq(u[0], pulse(0.0, NULL));
  cr_expect_lt(fabs(gm_moving_mesh_energy(m) - e0) / e0, 1e-12);
  gm_moving_mesh_free(m);
  m = make(64, GM_MOVING_MESH_EQUIDISTRIBUTE, 0.0, 1, 0.5);
  e0 = gm_moving_mesh_energy(m);
  cr_assert_eq(gm_moving_mesh_advance(m, 20, &err), GM_OK, "%s", err.message);
  cr_expect_lt(fabs(gm_moving_mesh_energy(m) - e0) / e0, 1e-12);
  gm_moving_mesh_free(m);
}

static int count_steps(const gm_moving_mesh *m, void *ctx) {
  (void)m;
  ++*(size_t *)ctx;
  return 0;
}

Test(moving_mesh, observer_and_bad_input) {
  gm_error err = {0};
  gm_moving_mesh *m = make(32, GM_MOVING_MESH_TIME_ADAPTIVE, 0.0, 0, 0.5);
  size_t calls = 0;
  cr_assert_eq(gm_moving_mesh_set_observer(m, 1, count_steps, &calls, &err), GM_OK);
  cr_assert_eq(gm_moving_mesh_advance(m, 7, &err), GM_OK, "%s", err.message);
  cr_expect_eq(calls, 7);
  gm_moving_mesh_free(m);

  double x[8], u[8], ut[8];
  for (size_t j = 0; j < 8; j++) {
    x[j] = 2.5 * (double)j;
    u[j] = ut[j] = 0.0;
  }
  gm_moving_mesh_options o = gm_moving_mesh_options_defaults();
  o.dt = 3.0; /* above min dx = 2.5 */
  cr_expect_eq(gm_moving_mesh_create(8, x, LEN, u, ut, &o, &m, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "2.5") != NULL, "%s", err.message);
  o.dt = 1.0;
  cr_expect_eq(gm_moving_mesh_create(3, x, LEN, u, ut, &o, &m, &err), GM_EINVAL);
  u[3] = NAN;
  cr_expect_eq(gm_moving_mesh_create(8, x, LEN, u, ut, &o, &m, &err), GM_EDOMAIN);
  cr_expect(strstr(err.message, "node 3") != NULL, "%s", err.message);
  u[3] = 0.0;
  o.dt = NAN;
  cr_expect_eq(gm_moving_mesh_create(8, x, LEN, u, ut, &o, &m, &err), GM_EINVAL);
  o.dt = 1.0;
  o.alpha = -1.0;
  cr_expect_eq(gm_moving_mesh_create(8, x, LEN, u, ut, &o, &m, &err), GM_EINVAL);
  o.alpha = 0.0;
  x[4] = x[3];
  cr_expect_eq(gm_moving_mesh_create(8, x, LEN, u, ut, &o, &m, &err), GM_EINVAL);
  cr_expect(m == NULL);
}
