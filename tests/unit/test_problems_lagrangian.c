/* The Lagrangian problems: ∂L/∂q, ∂L/∂v and the second derivatives against central differences
 * of L, constraint Jacobians against differences of g, invariance of L under the declared
 * symmetry, the initial state on the constraint with a tangent momentum, and the damped
 * oscillator's exact solution. */
#include "test_util.h"

static const char *const lagrangian_models[] = {"spherical-pendulum", "double-spherical-pendulum",
                                                "spring-pendulum", "j2-satellite",
                                                "damped-oscillator"};

static void check_derivatives(const char *name) {
  test_model tm = test_model_make(name);
  const gm_problem *pb = tm.problem;
  cr_assert_eq(pb->kind, GM_PROBLEM_LAGRANGIAN);
  const size_t d = pb->dim, n2 = 2 * d;
  double x[12], lq[6], lv[6], gp[12], gm[12], h[144];
  for (size_t i = 0; i < n2; ++i) x[i] = tm.y0[i] + 0.03 * (double)((5 * i) % 7 + 1);
  double *q = x, *v = x + d;
  cr_assert_eq(pb->dl_dq(pb->ctx, q, v, lq), 0);
  cr_assert_eq(pb->dl_dv(pb->ctx, q, v, lv), 0);
  cr_assert_eq(pb->lagrangian_hessian(pb->ctx, q, v, h), 0);
  for (size_t j = 0; j < n2; ++j) {
    const double step = 1e-6, x0 = x[j];
    x[j] = x0 + step;
    double lp = pb->lagrangian(pb->ctx, q, v);
    pb->dl_dq(pb->ctx, q, v, gp);
    pb->dl_dv(pb->ctx, q, v, gp + d);
    x[j] = x0 - step;
    double lm = pb->lagrangian(pb->ctx, q, v);
    pb->dl_dq(pb->ctx, q, v, gm);
    pb->dl_dv(pb->ctx, q, v, gm + d);
    x[j] = x0;
    double an = j < d ? lq[j] : lv[j - d], fd = (lp - lm) / (2 * step);
    cr_expect(fabs(an - fd) <= 1e-6 * (1 + fabs(an)), "%s: dL/dx%zu %.12g vs %.12g", name, j, an,
              fd);
    for (size_t i = 0; i < n2; ++i) {
      double fdh = (gp[i] - gm[i]) / (2 * step);
      cr_expect(fabs(h[i * n2 + j] - fdh) <= 1e-5 * (1 + fabs(fdh)),
                "%s: Hessian (%zu,%zu) %.12g vs %.12g", name, i, j, h[i * n2 + j], fdh);
    }
  }
  /* constraints: g(q0) = 0, momentum tangent (G M⁻¹ p = 0, here with M diagonal blocks:
   * checked through the velocity G v = 0), Jacobian by differences */
  if (pb->n_constraints > 0) {
    const size_t m = pb->n_constraints;
    double g[2], jac[12], vel[6];
    cr_assert_eq(gm_constraint_residual(pb, tm.y0) <= 1e-15, 1, "%s: g(q0)", name);
    cr_assert_eq(gm_lagrangian_velocity(pb, tm.y0, tm.y0 + d, vel), GM_OK);
    cr_assert_eq(pb->constraint_jacobian(pb->ctx, tm.y0, jac), 0);
    for (size_t a = 0; a < m; ++a) {
      double gv = 0.0;
      for (size_t k = 0; k < d; ++k) gv += jac[a * d + k] * vel[k];
      cr_expect(fabs(gv) < 1e-14, "%s: initial velocity not tangent (%.2e)", name, gv);
    }
    cr_assert_eq(pb->constraint_jacobian(pb->ctx, q, jac), 0);
    for (size_t j = 0; j < d; ++j) {
      const double step = 1e-6, x0 = q[j];
      double gpl[2], gmi[2];
      q[j] = x0 + step;
      pb->constraint(pb->ctx, q, gpl);
      q[j] = x0 - step;
      pb->constraint(pb->ctx, q, gmi);
      q[j] = x0;
      for (size_t a = 0; a < m; ++a)
        cr_expect(fabs((gpl[a] - gmi[a]) / (2 * step) - jac[a * d + j]) < 1e-8, "%s: dg", name);
    }
    (void)g;
    /* Σ_a λ_a ∇²g_a against central differences of the constraint Jacobian (issue 17: the
     * pendulums had none, so every Newton Jacobian was a finite-difference one) */
    cr_assert_not_null(pb->constraint_hessian, "%s: no analytic constraint Hessian", name);
    const double lam[2] = {0.7, -1.3};
    double ch[36], jp[12], jm[12];
    cr_assert_eq(pb->constraint_hessian(pb->ctx, q, lam, ch), 0);
    for (size_t j = 0; j < d; ++j) {
      const double step = 1e-6, x0 = q[j];
      q[j] = x0 + step;
      pb->constraint_jacobian(pb->ctx, q, jp);
      q[j] = x0 - step;
      pb->constraint_jacobian(pb->ctx, q, jm);
      q[j] = x0;
      for (size_t k = 0; k < d; ++k) {
        double fd = 0.0;
        for (size_t a = 0; a < m; ++a) fd += lam[a] * (jp[a * d + k] - jm[a * d + k]) / (2 * step);
        cr_expect(fabs(ch[k * d + j] - fd) < 1e-8, "%s: constraint Hessian (%zu,%zu) %.12g vs %.12g",
                  name, k, j, ch[k * d + j], fd);
      }
    }
  }
  /* symmetry: L(R_ε q, R_ε v) = L(q, v) to O(ε²) for the generator ξ_Q (linear: ξ_Q(v) for v) */
  for (size_t k = 0; k < pb->n_symmetries; ++k) {
    double xq[6], xv[6], y[12], z[12];
    pb->symmetries[k].generator(pb->ctx, q, xq);
    pb->symmetries[k].generator(pb->ctx, v, xv);
    const double eps = 1e-4; /* dL/dε at ε = 0 by central differences: O(ε²) */
    for (size_t i = 0; i < d; ++i) {
      y[i] = q[i] + eps * xq[i];
      y[d + i] = v[i] + eps * xv[i];
      z[i] = q[i] - eps * xq[i];
      z[d + i] = v[i] - eps * xv[i];
    }
    double dl = (pb->lagrangian(pb->ctx, y, y + d) - pb->lagrangian(pb->ctx, z, z + d)) / (2 * eps);
    cr_expect(fabs(dl) < 1e-6, "%s: L not invariant under %s (%.2e)", name,
              pb->symmetries[k].name, dl);
    cr_expect(fabs(gm_noether_momentum(pb, k, tm.y0) -
                   pb->invariants[k].value(pb->ctx, tm.y0)) < 1e-14,
              "%s: the invariant is the Noether momentum", name);
  }
  gm_model_free(tm.model);
}

Test(problems_lagrangian, derivatives_constraints_symmetries) {
  for (size_t i = 0; i < sizeof lagrangian_models / sizeof lagrangian_models[0]; ++i)
    check_derivatives(lagrangian_models[i]);
}

/* Every Lagrangian model of the library is listed above. */
Test(problems_lagrangian, all_listed) {
  size_t n = 0;
  for (size_t k = 0; k < gm_model_count(); ++k)
    if (gm_model_info_at(k)->kind == GM_PROBLEM_LAGRANGIAN) ++n;
  cr_expect_eq(n, sizeof lagrangian_models / sizeof lagrangian_models[0]);
}

/* q' = p/m and p' = −k q − c p/m along the exact solution (central differences in t). */
Test(problems_lagrangian, damped_oscillator_exact_solution) {
  test_model tm = test_model_make("damped-oscillator");
  const gm_problem *pb = tm.problem;
  double y[2], yp[2], ym[2];
  pb->exact(pb->ctx, 0.0, y);
  cr_expect(fabs(y[0] - tm.y0[0]) < 1e-15 && fabs(y[1] - tm.y0[1]) < 1e-15);
  for (double t = 0.3; t < 10.0; t += 1.3) {
    const double dt = 1e-5;
    pb->exact(pb->ctx, t, y);
    pb->exact(pb->ctx, t + dt, yp);
    pb->exact(pb->ctx, t - dt, ym);
    cr_expect(fabs((yp[0] - ym[0]) / (2 * dt) - y[1]) < 1e-8, "q' at %g", t);
    cr_expect(fabs((yp[1] - ym[1]) / (2 * dt) - (-y[0] - 0.1 * y[1])) < 1e-8, "p' at %g", t);
  }
  gm_model_free(tm.model);
}

/* The pendulums' constraint Hessians are analytic: a constrained Galerkin run makes no
 * finite-difference Jacobian (before: 3941 and 4550 in 1000 steps), and lands where the run with
 * differences of the constraint Jacobian lands. */
Test(problems_lagrangian, constrained_runs_use_no_finite_differences) {
  const char *names[] = {"spherical-pendulum", "double-spherical-pendulum"};
  for (size_t i = 0; i < 2; ++i) {
    test_model tm = test_model_make(names[i]);
    gm_problem fd = *tm.problem;
    fd.constraint_hessian = NULL;
    const gm_method *m = gm_method_find("vi-galerkin-gauss-2");
    cr_assert_not_null(m);
    gm_integrator *a = test_integrator(m, tm.problem, tm.t0, tm.y0);
    gm_integrator *b = test_integrator(m, &fd, tm.t0, tm.y0);
    cr_assert_eq(gm_integrator_integrate(a, 2.0, 0.01), GM_OK, "%s", gm_integrator_errmsg(a));
    cr_assert_eq(gm_integrator_integrate(b, 2.0, 0.01), GM_OK, "%s", gm_integrator_errmsg(b));
    gm_stats sa = gm_integrator_stats(a), sb = gm_integrator_stats(b);
    cr_expect_gt(sa.jacobian_evals, 0, "%s", names[i]);
    cr_expect_eq(sa.fd_jacobians, 0, "%s: %zu finite-difference Jacobians", names[i], sa.fd_jacobians);
    cr_expect_gt(sb.fd_jacobians, 0, "%s", names[i]);
    const double *ya = gm_integrator_state(a), *yb = gm_integrator_state(b);
    double diff = 0.0;
    for (size_t k = 0; k < tm.n; ++k) diff = fmax(diff, fabs(ya[k] - yb[k]));
    cr_expect_lt(diff, 1e-9, "%s: analytic and difference Hessians differ by %.2e", names[i], diff);
    gm_integrator_free(a);
    gm_integrator_free(b);
    gm_model_free(tm.model);
  }
}
