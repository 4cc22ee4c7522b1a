/* Rigid-body problems: analytic gradients against differences, the canonical chart, the
 * closed-form period, and bad input (non-orthogonal R, non-positive or singular inertia, NaN). */
#include "test_util.h"

static const char *const rigid_problems[] = {"rigid-body", "heavy-top", "pendulum-3d",
                                             "satellite", "central-body"};
#define N_RIGID (sizeof rigid_problems / sizeof rigid_problems[0])

/* A generic state near the initial one: R0 exp(0.3, −0.2, 0.5), x and momenta shifted. */
static void generic_state(const test_model *tm, double *y) {
  const double w[3] = {0.3, -0.2, 0.5};
  double e[9];
  memcpy(y, tm->y0, tm->n * sizeof *y);
  gm_so3_exp(w, e);
  gm_mat3_mul(tm->y0, e, y);
  for (size_t i = 9; i < tm->n; ++i) y[i] += 0.05 * (double)(i % 4) - 0.07;
}

Test(problems_rigid, potential_gradients_match_differences) {
  for (size_t k = 0; k < N_RIGID; ++k) {
    test_model tm = test_model_make(rigid_problems[k]);
    const gm_problem *pb = tm.problem;
    if (pb->rigid_potential == NULL) {
      gm_model_free(tm.model);
      continue;
    }
    const size_t nt = pb->dim - 3;
    double y[18], g[3], fx[3] = {0, 0, 0};
    generic_state(&tm, y);
    const double *x = nt ? y + 9 : NULL;
    cr_assert_eq(pb->rigid_potential_gradient(pb->ctx, y, x, g, nt ? fx : NULL), 0);
    const double h = 1e-5;
    for (int a = 0; a < 3; ++a) { /* d/dε V(R exp(ε e_a)) */
      double eta[3] = {0, 0, 0}, e[9], rp[9], rm[9];
      eta[a] = h;
      gm_so3_exp(eta, e);
      gm_mat3_mul(y, e, rp);
      eta[a] = -h;
      gm_so3_exp(eta, e);
      gm_mat3_mul(y, e, rm);
      double fd = (pb->rigid_potential(pb->ctx, rp, x) - pb->rigid_potential(pb->ctx, rm, x)) /
                  (2 * h);
      cr_expect(fabs(fd - g[a]) <= 1e-8 * (1 + fabs(g[a])), "%s: g%d analytic %.12g, diff %.12g",
                rigid_problems[k], a + 1, g[a], fd);
    }
    for (size_t a = 0; a < nt; ++a) {
      double xp[3], xm[3];
      memcpy(xp, x, sizeof xp);
      memcpy(xm, x, sizeof xm);
      xp[a] += h;
      xm[a] -= h;
      double fd = (pb->rigid_potential(pb->ctx, y, xp) - pb->rigid_potential(pb->ctx, y, xm)) /
                  (2 * h);
      cr_expect(fabs(fd - fx[a]) <= 1e-8 * (1 + fabs(fx[a])),
                "%s: dV/dx%zu analytic %.12g, diff %.12g", rigid_problems[k], a + 1, fx[a], fd);
    }
    gm_model_free(tm.model);
  }
}

Test(problems_rigid, canonical_chart_round_trip) {
  for (size_t k = 0; k < N_RIGID; ++k) {
    test_model tm = test_model_make(rigid_problems[k]);
    const gm_problem *pb = tm.problem;
    const size_t nc = gm_problem_chart_dim(pb);
    cr_expect_eq(nc, 2 * pb->dim, "%s: chart dimension %zu", rigid_problems[k], nc);
    double y[18], z[12], back[18], z0[12];
    generic_state(&tm, y);
    cr_assert_eq(gm_problem_to_chart(pb, tm.y0, y, z), GM_OK);
    cr_assert_eq(gm_problem_from_chart(pb, tm.y0, z, back), GM_OK);
    for (size_t i = 0; i < tm.n; ++i)
      cr_expect(fabs(back[i] - y[i]) <= 1e-15 * (1 + fabs(y[i])), "%s: component %zu",
                rigid_problems[k], i);
    cr_assert_eq(gm_problem_to_chart(pb, y, y, z0), GM_OK);
    for (size_t i = 0; i < nc; ++i) cr_expect(fabs(z0[i]) <= 1e-16);
    cr_expect_leq(gm_problem_state_defect(pb, y), 1e-15);
    gm_model_free(tm.model);
  }
}

Test(problems_rigid, chart_momenta_are_canonical) {
  /* For the free body, H in chart coordinates (ξ, p_ξ) must generate the body's flow:
   * dξ/dt at ξ = 0 is ∂H/∂p_ξ = Ω = J⁻¹Π (differences of H through the chart). */
  test_model tm = test_model_make("rigid-body");
  const gm_problem *pb = tm.problem;
  double z[6] = {0}, y[12], grad[6];
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    z[i] = h;
    gm_problem_from_chart(pb, tm.y0, z, y);
    double hp = gm_problem_energy(pb, y);
    z[i] = -h;
    gm_problem_from_chart(pb, tm.y0, z, y);
    double hm = gm_problem_energy(pb, y);
    z[i] = 0;
    grad[i] = (hp - hm) / (2 * h);
  }
  /* ∂H/∂p_ξ at the base is Ω (dexp_0 = I) */
  const double *pi = tm.y0 + 9;
  double omega[3] = {pi[0] / 1.0, pi[1] / 2.0, pi[2] / 3.0};
  for (int a = 0; a < 3; ++a)
    cr_expect(fabs(grad[3 + a] - omega[a]) < 1e-9, "dH/dp%d = %.12g, Omega = %.12g", a, grad[3 + a],
              omega[a]);
  gm_model_free(tm.model);
}

Test(problems_rigid, closed_form_period) {
  /* symmetric cases: the period of Π for a body spinning off an axis of a nearly symmetric
   * body is 2π/|ω_prec| with the precession rate (I3 − I1)Ω3/I1 (Landau & Lifshitz §33) */
  const double inertia[3] = {1.0, 1.0 + 1e-9, 3.0}, pi[3] = {0.01, 0.0, 3.0};
  double t = gm_free_rigid_body_period(inertia, pi);
  double prec = (3.0 - 1.0) * (3.0 / 3.0) / 1.0;
  cr_expect(fabs(t - 2 * 3.14159265358979323846 / prec) < 1e-6, "period %.12g", t);
  const double eq[3] = {1, 1, 3};
  cr_expect(isnan(gm_free_rigid_body_period(eq, pi)));
  const double steady[3] = {0, 1, 0}, in[3] = {1, 2, 3};
  cr_expect(isnan(gm_free_rigid_body_period(in, steady)));
}

Test(problems_rigid, bad_input) {
  gm_model *m = NULL;
  /* a non-orthogonal R: the message names |R^T R - I| and its value */
  cr_assert_eq(gm_model_create("rigid-body", &m), GM_OK);
  cr_assert_eq(gm_model_set(m, "y1", 1.001), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "|R^T R - I|") != NULL, "%s", gm_model_errmsg(m));
  cr_expect(strstr(gm_model_errmsg(m), "0.002") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  /* non-positive inertia */
  cr_assert_eq(gm_model_create("rigid-body", &m), GM_OK);
  cr_assert_eq(gm_model_set(m, "I2", 0.0), GM_OK);
  cr_expect_eq(gm_model_build(m), GM_EINVAL);
  cr_expect(strstr(gm_model_errmsg(m), "I2 must be positive") != NULL, "%s", gm_model_errmsg(m));
  gm_model_free(m);
  /* NaN parameters are refused when set */
  cr_assert_eq(gm_model_create("heavy-top", &m), GM_OK);
  cr_expect_eq(gm_model_set(m, "mgl", NAN), GM_EINVAL);
  gm_model_free(m);

  /* a hand-made problem: singular J, then indefinite J, then a good one with bad states */
  gm_problem pb;
  memset(&pb, 0, sizeof pb);
  pb.kind = GM_PROBLEM_RIGID_BODY;
  pb.dim = 3;
  const double singular[9] = {1, 0, 0, 0, 1, 1, 0, 1, 1};
  memcpy(pb.inertia, singular, sizeof singular);
  gm_error err = {{0}};
  gm_integrator *it = NULL;
  const gm_method *lgvi = gm_method_find("lgvi");
  cr_assert_not_null(lgvi);
  cr_expect_eq(gm_integrator_create(lgvi, &pb, &it, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "positive definite") != NULL, "%s", err.message);
  const double indefinite[9] = {1, 0, 0, 0, -2, 0, 0, 0, 3};
  memcpy(pb.inertia, indefinite, sizeof indefinite);
  cr_expect_eq(gm_integrator_create(lgvi, &pb, &it, &err), GM_EINVAL);
  const double asym[9] = {1, 0.1, 0, 0, 2, 0, 0, 0, 3};
  memcpy(pb.inertia, asym, sizeof asym);
  cr_expect_eq(gm_integrator_create(lgvi, &pb, &it, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "symmetric") != NULL, "%s", err.message);
  const double full[9] = {2, 0.3, 0, 0.3, 1, 0.1, 0, 0.1, 3}; /* not diagonal, SPD */
  memcpy(pb.inertia, full, sizeof full);
  cr_assert_eq(gm_integrator_create(lgvi, &pb, &it, &err), GM_OK, "%s", err.message);
  double y[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1, 0.2, 0.3};
  cr_expect_eq(gm_integrator_set_state(it, 0.0, y), GM_OK);
  y[1] = 1e-6; /* off SO(3) */
  cr_expect_eq(gm_integrator_set_state(it, 0.0, y), GM_EINVAL);
  cr_expect(strstr(gm_integrator_errmsg(it), "|R^T R - I| = 1.41e-06") != NULL, "%s",
            gm_integrator_errmsg(it));
  y[1] = 0;
  y[10] = NAN;
  cr_expect_eq(gm_integrator_set_state(it, 0.0, y), GM_EDOMAIN);
  gm_integrator_free(it);
  /* the body-axis splitting needs principal axes */
  cr_expect_eq(gm_integrator_create(gm_method_find("rigid-splitting"), &pb, &it, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "diagonal inertia") != NULL, "%s", err.message);
  /* rigid rows refuse other kinds, other rows refuse rigid bodies */
  test_model kep = test_model_make("kepler");
  cr_expect_eq(gm_integrator_create(lgvi, kep.problem, &it, &err), GM_EUNSUPPORTED);
  memcpy(pb.inertia, full, sizeof full);
  cr_expect_eq(gm_integrator_create(gm_method_find("rk4"), &pb, &it, &err), GM_EUNSUPPORTED);
  gm_model_free(kep.model);
}
