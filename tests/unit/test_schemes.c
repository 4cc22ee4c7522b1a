/* Schemes: compositions of other basic methods, the solvers of implicit stages, and what is
 * refused with a message. */
#include "test_util.h"

static gm_status make(const char *method, const char *basic, gm_solver solver,
                      const gm_problem *pb, gm_integrator **it, gm_error *err) {
  const gm_scheme s = {gm_method_find(method), basic ? gm_method_find(basic) : NULL, solver, 0};
  return gm_integrator_create_scheme(&s, pb, it, err);
}

/* Sixth-order composition of the implicit midpoint rule for a non-separable H (point vortices,
 * seed 004's rotated pairs), against a Gauss reference run. */
Test(schemes, composition_of_midpoint_reaches_its_order) {
  test_model tm = test_model_with("point-vortices", "config", 1.0);
  cr_assert_eq(tm.problem->kind, GM_PROBLEM_HAMILTONIAN);
  const char *compositions[] = {"yoshida-4", "suzuki-4", "yoshida-6", "kahan-li-6"};
  for (size_t i = 0; i < 4; ++i) {
    const gm_method *m = gm_method_find(compositions[i]);
    const gm_scheme s = {m, gm_method_find("midpoint"), GM_SOLVER_DEFAULT, 0};
    gm_order_result r;
    gm_error err = {{0}};
    cr_assert_eq(gm_order_measure(&s, tm.problem, tm.t0, tm.y0, 2.0, 0.2, 5, 1.5,
                                  gm_method_find("gauss-8"), &r, &err),
                 GM_OK, "%s", err.message);
    cr_expect(fabs(r.order - m->order) <= 0.3, "%s of midpoint: order %.3f", m->name, r.order);
  }
  gm_model_free(tm.model);
}

/* A composition of midpoint is symmetric and keeps the quadratic angular impulse of the
 * vortices; Verlet cannot be its basic method there. */
Test(schemes, composition_of_midpoint_is_symmetric) {
  test_model tm = test_model_with("point-vortices", "config", 1.0);
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_assert_eq(make("yoshida-6", "midpoint", GM_SOLVER_DEFAULT, tm.problem, &it, &err), GM_OK,
               "%s", err.message);
  cr_assert_eq(gm_integrator_set_state(it, tm.t0, tm.y0), GM_OK);
  cr_assert_eq(gm_integrator_step(it, 0.1), GM_OK, "%s", gm_integrator_errmsg(it));
  cr_assert_eq(gm_integrator_step(it, -0.1), GM_OK);
  for (size_t i = 0; i < tm.n; ++i)
    cr_expect(fabs(gm_integrator_state(it)[i] - tm.y0[i]) < 1e-13, "component %zu", i);
  cr_expect_gt(gm_integrator_stats(it).fixed_point_iterations, 0); /* midpoint's default */
  cr_expect_eq(gm_integrator_solver(it), GM_SOLVER_FIXED_POINT);
  gm_integrator_free(it);
  /* the default basic (verlet-position) needs a separable H */
  cr_expect_eq(gm_integrator_create(gm_method_find("yoshida-6"), tm.problem, &it, &err),
               GM_EUNSUPPORTED);
  cr_expect(strstr(err.message, "verlet") && strstr(err.message, "midpoint"), "%s", err.message);
  gm_model_free(tm.model);
}

Test(schemes, basic_methods_are_checked) {
  test_model tm = test_model_make("kepler");
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  /* not symmetric */
  cr_expect_eq(make("yoshida-6", "symplectic-euler-a", 0, tm.problem, &it, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "symmetric") != NULL, "%s", err.message);
  /* symmetric but of order 4 */
  cr_expect_eq(make("yoshida-6", "gauss-2", 0, tm.problem, &it, &err), GM_EINVAL);
  /* a composition cannot be a basic method */
  cr_expect_eq(make("yoshida-6", "yoshida-4", 0, tm.problem, &it, &err), GM_EINVAL);
  /* a method that is not a composition takes no basic method */
  cr_expect_eq(make("verlet", "midpoint", 0, tm.problem, &it, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "not a composition") != NULL, "%s", err.message);
  cr_expect_null(it);
  /* verlet-position as basic: a different merged operation list, same order */
  cr_assert_eq(make("yoshida-6", "verlet-position", 0, tm.problem, &it, &err), GM_OK);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

/* Composed with Verlet, the kicks between basic steps merge: one force per basic step. */
Test(schemes, composition_of_verlet_merges_kicks) {
  test_model tm = test_model_make("kepler");
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_assert_eq(make("yoshida-6", "verlet", 0, tm.problem, &it, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_integrator_set_state(it, tm.t0, tm.y0), GM_OK);
  cr_assert_eq(gm_integrator_run(it, 100, 0.01), GM_OK);
  /* 7 basic steps, FSAL across steps: 7 forces per step, plus the first */
  cr_expect_eq(gm_integrator_stats(it).force_evals, 701);
  gm_integrator_free(it);
  /* the default basic, position Verlet: its drifts merge, 7 kicks a step, nothing to share */
  it = test_integrator(gm_method_find("yoshida-6"), tm.problem, tm.t0, tm.y0);
  cr_assert_eq(gm_integrator_run(it, 100, 0.01), GM_OK);
  cr_expect_eq(gm_integrator_stats(it).force_evals, 700);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

/* Every solver of the Gauss stage equations gives the same trajectory to round-off. */
Test(schemes, solvers_agree) {
  test_model tm = test_model_make("kepler");
  const gm_solver solvers[] = {GM_SOLVER_NEWTON, GM_SOLVER_SIMPLIFIED_NEWTON, GM_SOLVER_FIXED_POINT,
                               GM_SOLVER_FIXED_POINT_POSITIONS};
  double first[4];
  for (size_t k = 0; k < 4; ++k) {
    gm_integrator *it = NULL;
    gm_error err = {{0}};
    cr_assert_eq(make("gauss-3", NULL, solvers[k], tm.problem, &it, &err), GM_OK, "%s",
                 err.message);
    cr_assert_eq(gm_integrator_set_state(it, tm.t0, tm.y0), GM_OK);
    cr_assert_eq(gm_integrator_run(it, 200, 0.05), GM_OK, "%s", gm_integrator_errmsg(it));
    gm_stats st = gm_integrator_stats(it);
    if (solvers[k] == GM_SOLVER_FIXED_POINT || solvers[k] == GM_SOLVER_FIXED_POINT_POSITIONS)
      cr_expect_gt(st.fixed_point_iterations, 200, "%s", gm_solver_name(solvers[k]));
    else
      cr_expect_gt(st.newton_iterations, 200, "%s", gm_solver_name(solvers[k]));
    const double *y = gm_integrator_state(it);
    if (k == 0) memcpy(first, y, sizeof first);
    for (size_t i = 0; i < 4; ++i)
      cr_expect(fabs(y[i] - first[i]) < 1e-12, "%s differs from newton by %.2e",
                gm_solver_name(solvers[k]), fabs(y[i] - first[i]));
    gm_integrator_free(it);
  }
  gm_model_free(tm.model);
}

Test(schemes, solvers_refused_where_they_do_not_apply) {
  test_model kepler = test_model_make("kepler");
  test_model vortices = test_model_make("point-vortices");
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  /* explicit methods have no stage equations */
  cr_expect_eq(make("rk4", NULL, GM_SOLVER_FIXED_POINT, kepler.problem, &it, &err),
               GM_EUNSUPPORTED);
  /* positions only: a non-separable problem, or a partitioned method, cannot */
  cr_expect_eq(make("gauss-2", NULL, GM_SOLVER_FIXED_POINT_POSITIONS, vortices.problem, &it, &err),
               GM_EUNSUPPORTED);
  cr_expect(strstr(err.message, "quadratic") != NULL, "%s", err.message);
  cr_expect_eq(make("lobatto-iiia-iiib-3", NULL, GM_SOLVER_FIXED_POINT_POSITIONS, kepler.problem,
                    &it, &err),
               GM_EUNSUPPORTED);
  cr_expect_null(it);
  /* the default solver is fine for an explicit method */
  cr_expect_eq(make("rk4", NULL, GM_SOLVER_DEFAULT, kepler.problem, &it, &err), GM_OK);
  gm_integrator_free(it);
  gm_model_free(kepler.model);
  gm_model_free(vortices.model);
}

/* Compensated summation changes only round-off, for every family. */
Test(schemes, compensated_summation_for_every_family) {
  test_model tm = test_model_make("kepler");
  const char *methods[] = {"rk4", "verlet", "yoshida-6", "gauss-2", "lobatto-iiia-iiib-3"};
  for (size_t i = 0; i < 5; ++i) {
    double y[2][4];
    for (int comp = 0; comp < 2; ++comp) {
      gm_integrator *it = NULL;
      gm_error err;
      const gm_scheme s = {gm_method_find(methods[i]), NULL, GM_SOLVER_DEFAULT, comp};
      cr_assert_eq(gm_integrator_create_scheme(&s, tm.problem, &it, &err), GM_OK, "%s",
                   err.message);
      cr_assert_eq(gm_integrator_set_state(it, tm.t0, tm.y0), GM_OK);
      cr_assert_eq(gm_integrator_run(it, 1000, 0.01), GM_OK, "%s", gm_integrator_errmsg(it));
      memcpy(y[comp], gm_integrator_state(it), sizeof y[comp]);
      gm_integrator_free(it);
    }
    for (size_t k = 0; k < 4; ++k)
      cr_expect(fabs(y[0][k] - y[1][k]) < 1e-11, "%s: compensated differs by %.2e", methods[i],
                fabs(y[0][k] - y[1][k]));
  }
  gm_model_free(tm.model);
}
