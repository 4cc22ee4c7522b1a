/* Symmetric methods are time reversible: a step of h followed by a step of −h returns to the
 * start (to 1e-13); non-symmetric rows do not (so the check can fail). */
#include "test_util.h"

static double reversal_error(const gm_method *m, const test_model *tm, double h) {
  gm_integrator *it = test_integrator(m, tm->problem, tm->t0, tm->y0);
  cr_assert_eq(gm_integrator_step(it, h), GM_OK, "%s", gm_integrator_errmsg(it));
  cr_assert_eq(gm_integrator_step(it, -h), GM_OK, "%s", gm_integrator_errmsg(it));
  const double *y = gm_integrator_state(it);
  double e = 0.0;
  for (size_t i = 0; i < tm->n; ++i) e = fmax(e, fabs(y[i] - tm->y0[i]));
  gm_integrator_free(it);
  return e;
}

static void check_model(const char *name, test_model tm, double h) {
  for (size_t i = 0; i < gm_method_count(); ++i) {
    const gm_method *m = gm_method_at(i);
    if (!test_accepts(m, tm.problem)) continue;
    double e = reversal_error(m, &tm, h);
    if (m->flags & GM_SYMMETRIC)
      cr_expect_leq(e, 1e-13, "%s on %s: returns with error %.2e", m->name, name, e);
    else
      cr_expect_gt(e, 1e-8, "%s on %s is not symmetric, yet returns to %.2e", m->name, name, e);
  }
  gm_model_free(tm.model);
}

static void check_problem(const char *name, double h) { check_model(name, test_model_make(name), h); }

Test(reversible, kepler) { check_problem("kepler", 0.05); }
Test(reversible, henon_heiles) { check_problem("henon-heiles", 0.1); }
/* split potentials (issue 12) */
Test(reversible, diatomic_chain) { check_problem("diatomic-chain", 0.05); }
Test(reversible, stiff_spring_pendulum) {
  check_model("stiff-spring-pendulum", test_model_with("stiff-spring-pendulum", "k", 400.0), 0.05);
}
