/* Every method row reaches its declared order (±0.2) on nonlinear problems. The error at the
 * final time is measured against Kepler's exact solution, and for the pendulum against a
 * reference run; the fit skips errors at round-off. */
#include "test_util.h"

static void check_orders(const char *problem, double t_end) {
  test_model tm = test_model_make(problem);
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!test_accepts(m, tm.problem)) continue;
    /* steps in the asymptotic range and above round-off for the method's order */
    double dt0 = m->order >= 4 ? 0.1 : (m->order >= 2 ? 0.04 : 0.01);
    gm_order_result r;
    gm_error err = {{0}};
    cr_assert_eq(gm_order_measure(m, tm.problem, tm.t0, tm.y0, t_end, dt0, 5, NULL, &r, &err),
                 GM_OK, "%s on %s: %s", m->name, problem, err.message);
    cr_expect_geq(r.n_fitted, 3, "%s on %s: only %zu levels fitted", m->name, problem, r.n_fitted);
    cr_expect(fabs(r.order - m->order) <= 0.2, "%s on %s: measured order %.3f, declared %d",
              m->name, problem, r.order, m->order);
  }
  gm_model_free(tm.model);
}

Test(order, every_method_on_kepler) { check_orders("kepler", 2.0); }
Test(order, every_method_on_pendulum) { check_orders("pendulum", 3.0); }
