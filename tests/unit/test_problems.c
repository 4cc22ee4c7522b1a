/* The problem library: analytic derivatives agree with finite differences, exact solutions
 * solve the equations and keep the invariants, and parameters are checked. */
#include "test_util.h"

/* Central difference of a scalar function of q or p, step 1e-6. */
static double fd_partial(double (*f)(void *, const double *), void *ctx, const double *x,
                         size_t n, size_t j) {
  double xp[32];
  memcpy(xp, x, n * sizeof *x);
  const double h = 1e-6;
  xp[j] = x[j] + h;
  double fp = f(ctx, xp);
  xp[j] = x[j] - h;
  double fm = f(ctx, xp);
  return (fp - fm) / (2 * h);
}

Test(problems, gradients_and_hessians_match_differences) {
  for (size_t k = 0; k < gm_model_count(); ++k) {
    test_model tm = test_model_make(gm_model_info_at(k)->name);
    const gm_problem *pb = tm.problem;
    if (pb->kind != GM_PROBLEM_SEPARABLE) {
      gm_model_free(tm.model);
      continue;
    }
    const size_t d = pb->dim;
    double q[32], p[32], g[32], g2[32], hess[1024];
    for (size_t i = 0; i < d; ++i) {
      q[i] = tm.y0[i] + 0.1 * (double)(i + 1);
      p[i] = tm.y0[d + i] - 0.07 * (double)(i + 1);
    }
    cr_assert_eq(pb->potential_gradient(pb->ctx, q, g), 0);
    cr_assert_eq(pb->potential_hessian(pb->ctx, q, hess), 0);
    for (size_t j = 0; j < d; ++j) {
      double fd = fd_partial(pb->potential, pb->ctx, q, d, j);
      cr_expect(fabs(fd - g[j]) < 1e-8 * fmax(1, fabs(g[j])), "%s dV/dq%zu: %.12g vs %.12g",
                gm_model_info_at(k)->name, j + 1, g[j], fd);
      double qp[32];
      memcpy(qp, q, d * sizeof *q);
      qp[j] += 1e-6;
      pb->potential_gradient(pb->ctx, qp, g2);
      for (size_t i = 0; i < d; ++i) {
        double fdh = (g2[i] - g[i]) / 1e-6;
        cr_expect(fabs(fdh - hess[i * d + j]) < 1e-5 * fmax(1, fabs(fdh)), "%s hessian",
                  gm_model_info_at(k)->name);
      }
    }
    cr_assert_eq(pb->kinetic_gradient(pb->ctx, p, g), 0);
    for (size_t j = 0; j < d; ++j)
      cr_expect(fabs(fd_partial(pb->kinetic, pb->ctx, p, d, j) - g[j]) < 1e-8, "dT/dp");
    gm_model_free(tm.model);
  }
}

/* The exact solution starts at y0, solves y' = J⁻¹∇H (checked by central differences in t)
 * and keeps the energy and the invariants. */
Test(problems, exact_solutions_solve_the_equations) {
  for (size_t k = 0; k < gm_model_count(); ++k) {
    const gm_model_info *info = gm_model_info_at(k);
    test_model tm = test_model_make(info->name);
    const gm_problem *pb = tm.problem;
    cr_expect_eq(pb->exact != NULL, info->has_exact, "%s", info->name);
    if (pb->exact == NULL) {
      gm_model_free(tm.model);
      continue;
    }
    const size_t d = pb->dim, n = tm.n;
    double y[32], yp[32], ym[32], grad[32];
    cr_assert_eq(pb->exact(pb->ctx, 0.0, y), 0);
    for (size_t i = 0; i < n; ++i) cr_expect(fabs(y[i] - tm.y0[i]) < 1e-14, "%s y(0)", info->name);
    double h0 = gm_problem_energy(pb, tm.y0);
    for (double t = 0.3; t < 20.0; t += 1.7) {
      const double dt = 1e-5;
      pb->exact(pb->ctx, t, y);
      pb->exact(pb->ctx, t + dt, yp);
      pb->exact(pb->ctx, t - dt, ym);
      pb->kinetic_gradient(pb->ctx, y + d, grad);
      for (size_t i = 0; i < d; ++i)
        cr_expect(fabs((yp[i] - ym[i]) / (2 * dt) - grad[i]) < 1e-7, "%s q' at t=%g", info->name, t);
      pb->potential_gradient(pb->ctx, y, grad);
      for (size_t i = 0; i < d; ++i)
        cr_expect(fabs((yp[d + i] - ym[d + i]) / (2 * dt) + grad[i]) < 1e-7, "%s p' at t=%g",
                  info->name, t);
      cr_expect(fabs(gm_problem_energy(pb, y) - h0) < 1e-13, "%s energy", info->name);
      for (size_t j = 0; j < pb->n_invariants; ++j)
        cr_expect(fabs(pb->invariants[j].value(pb->ctx, y) - pb->invariants[j].value(pb->ctx, tm.y0)) <
                      1e-13,
                  "%s invariant %s", info->name, pb->invariants[j].name);
    }
    gm_model_free(tm.model);
  }
}

Test(problems, info_matches_problem) {
  cr_assert_geq(gm_model_count(), 4);
  for (size_t k = 0; k < gm_model_count(); ++k) {
    const gm_model_info *info = gm_model_info_at(k);
    cr_expect_eq(gm_model_info_find(info->name), info);
    test_model tm = test_model_make(info->name);
    cr_expect_eq(tm.problem->dim, info->default_dim, "%s", info->name);
    cr_expect_eq(tm.problem->n_invariants, info->n_invariants, "%s", info->name);
    for (size_t j = 0; j < info->n_invariants; ++j)
      cr_expect_str_eq(tm.problem->invariants[j].name, info->invariant_names[j]);
    cr_expect_eq(gm_problem_validate(tm.problem, NULL), GM_OK);
    gm_model_free(tm.model);
  }
  cr_expect_null(gm_model_info_at(gm_model_count()));
}

Test(problems, kepler_defaults_and_parameters) {
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "e", 0.3), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK);
  double t0, y[4];
  gm_model_initial_state(m, &t0, y);
  cr_expect_float_eq(y[0], 0.7, 1e-15);
  cr_expect_float_eq(y[3], sqrt(1.3 / 0.7), 1e-15);
  cr_expect_float_eq(gm_problem_energy(gm_model_problem(m), y), -0.5, 1e-15);
  /* changing an initial value drops the exact solution, which assumed the default start */
  cr_expect_eq(gm_model_set(m, "p2", 1.2), GM_OK);
  cr_assert_eq(gm_model_build(m), GM_OK);
  cr_expect_null(gm_model_problem(m)->exact);
  gm_model_initial_state(m, &t0, y);
  cr_expect_eq(y[3], 1.2);
  gm_model_free(m);
}

/* First-order problems: the analytic Jacobian agrees with central differences of f. */
Test(problems, first_order_jacobians_match_differences) {
  for (size_t k = 0; k < gm_model_count(); ++k) {
    test_model tm = test_model_make(gm_model_info_at(k)->name);
    const gm_problem *pb = tm.problem;
    if (pb->kind != GM_PROBLEM_FIRST_ORDER) {
      gm_model_free(tm.model);
      continue;
    }
    const size_t n = tm.n;
    double y[32], yp[32], fp[32], fm[32], jac[1024];
    memcpy(y, tm.y0, n * sizeof *y);
    y[0] += 0.2;
    cr_assert_not_null(pb->rhs_jacobian);
    cr_assert_eq(pb->rhs_jacobian(pb->ctx, 0.0, y, jac), 0);
    for (size_t j = 0; j < n; ++j) {
      memcpy(yp, y, n * sizeof *y);
      yp[j] = y[j] + 1e-6;
      pb->rhs(pb->ctx, 0.0, yp, fp);
      yp[j] = y[j] - 1e-6;
      pb->rhs(pb->ctx, 0.0, yp, fm);
      for (size_t i = 0; i < n; ++i)
        cr_expect(fabs((fp[i] - fm[i]) / 2e-6 - jac[i * n + j]) < 1e-7, "%s jacobian (%zu,%zu)",
                  gm_model_info_at(k)->name, i, j);
    }
    gm_model_free(tm.model);
  }
}

/* Lotka–Volterra's invariant is kept by an accurate integration (RK4, small steps) and
 * splitting methods refuse the problem (it is not separable Hamiltonian). */
Test(problems, lotka_volterra_invariant_and_kind) {
  test_model tm = test_model_make("lotka-volterra");
  cr_expect_eq(tm.problem->kind, GM_PROBLEM_FIRST_ORDER);
  cr_expect(!test_accepts(gm_method_find("verlet"), tm.problem));
  gm_integrator *it = test_integrator(gm_method_find("rk4"), tm.problem, 0.0, tm.y0);
  gm_monitor *mon = NULL;
  cr_assert_eq(gm_monitor_create(tm.problem, tm.y0, &mon), GM_OK);
  cr_assert_eq(gm_integrator_add_observer(it, gm_monitor_observe, mon, 1), GM_OK);
  cr_assert_eq(gm_integrator_integrate(it, 20.0, 1e-3), GM_OK);
  cr_expect_lt(gm_monitor_max_invariant_drift(mon, 0), 1e-10, "%.2e",
               gm_monitor_max_invariant_drift(mon, 0));
  gm_monitor_free(mon);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}

Test(problems, singular_initial_state_is_an_error) {
  gm_model *m = NULL;
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "q1", 0.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL); /* q = 0: V = −inf */
  cr_expect(strstr(gm_model_errmsg(m), "energy") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  cr_assert_eq(gm_model_create("lotka-volterra", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "y1", -1.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL); /* log of a negative population */
  gm_model_free(m);
}

Test(problems, bad_parameters_are_errors) {
  gm_model *m = NULL;
  cr_expect_eq(gm_model_create("keppler", &m), GM_ENOTFOUND);
  cr_expect_null(m);
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "mass", 2.0), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "mass") != NULL, "%s", gm_model_errmsg(m));
  cr_expect_eq(gm_model_set(m, "q1", NAN), GM_EINVAL);
  cr_expect_eq(gm_model_set(m, "y1", 1.0), GM_EINVAL); /* Hamiltonian: q and p, not y */
  cr_expect_eq(gm_model_set(m, "q3", 1.0), GM_OK);     /* only known at build time ... */
  cr_expect_eq(gm_model_build(m), GM_EINVAL);          /* ... that kepler has 2 dof */
  cr_expect(strstr(gm_model_errmsg(m), "q3") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  cr_assert_eq(gm_model_create("kepler", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "e", 1.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL);
  cr_expect_null(gm_model_problem(m));
  gm_model_free(m);
  gm_model_free(NULL);
}
