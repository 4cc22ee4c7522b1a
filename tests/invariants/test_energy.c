/* Long-time energy behaviour on Kepler (e = 0.6): Störmer–Verlet's error stays bounded over
 * 10⁶ steps while RK4's grows; the implicit midpoint rule keeps the harmonic oscillator's
 * quadratic energy to round-off. */
#include "test_util.h"

typedef struct {
  const gm_problem *problem;
  double energy0;
  double max_first_half, max_second_half;
  size_t half_step;
} energy_watch;

static int watch(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  energy_watch *w = ctx;
  double e = fabs(gm_problem_energy(w->problem, y) - w->energy0) / fabs(w->energy0);
  if (step <= w->half_step)
    w->max_first_half = fmax(w->max_first_half, e);
  else
    w->max_second_half = fmax(w->max_second_half, e);
  return 0;
}

static energy_watch run_energy(const char *method, const test_model *tm, double h, size_t steps) {
  energy_watch w = {tm->problem, gm_problem_energy(tm->problem, tm->y0), 0, 0, steps / 2};
  gm_integrator *it = test_integrator(gm_method_find(method), tm->problem, tm->t0, tm->y0);
  cr_assert_eq(gm_integrator_add_observer(it, watch, &w, 100), GM_OK);
  cr_assert_eq(gm_integrator_run(it, steps, h), GM_OK, "%s", gm_integrator_errmsg(it));
  gm_integrator_free(it);
  return w;
}

Test(energy, verlet_bounded_rk4_drifts_on_kepler) {
  test_model tm = test_model_make("kepler");
  const double h = 0.01;
  const size_t steps = 1000000; /* about 1600 orbits */
  energy_watch v = run_energy("verlet", &tm, h, steps);
  energy_watch r = run_energy("rk4", &tm, h, steps);
  /* Verlet: the error oscillates (O(h²) near pericentre) without growing. */
  cr_expect_lt(v.max_first_half, 1e-2);
  cr_expect_lt(v.max_second_half, 1.05 * v.max_first_half, "verlet drifts: %.3e then %.3e",
               v.max_first_half, v.max_second_half);
  /* RK4: a secular drift, larger in the second half by a clear factor. */
  cr_expect_gt(r.max_second_half, 1.5 * r.max_first_half, "rk4: %.3e then %.3e",
               r.max_first_half, r.max_second_half);
  gm_model_free(tm.model);
}

Test(energy, midpoint_keeps_quadratic_energy) {
  test_model tm = test_model_make("harmonic");
  energy_watch w = run_energy("midpoint", &tm, 0.1, 100000);
  cr_expect_leq(fmax(w.max_first_half, w.max_second_half), 1e-13, "midpoint energy error %.2e",
                fmax(w.max_first_half, w.max_second_half));
  gm_model_free(tm.model);
}

Test(energy, midpoint_keeps_kepler_angular_momentum) {
  test_model tm = test_model_make("kepler");
  gm_integrator *it = test_integrator(gm_method_find("midpoint"), tm.problem, tm.t0, tm.y0);
  gm_monitor *mon = NULL;
  cr_assert_eq(gm_monitor_create(tm.problem, tm.y0, &mon), GM_OK);
  cr_assert_eq(gm_integrator_add_observer(it, gm_monitor_observe, mon, 10), GM_OK);
  cr_assert_eq(gm_integrator_run(it, 20000, 0.05), GM_OK, "%s", gm_integrator_errmsg(it));
  cr_expect_leq(gm_monitor_max_invariant_drift(mon, 0), 1e-12, "angular momentum drift %.2e",
                gm_monitor_max_invariant_drift(mon, 0));
  gm_monitor_free(mon);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}
