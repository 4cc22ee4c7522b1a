/* The Lie group rows: Crouch–Grossman's coefficients satisfy the order-3 conditions of
 * frozen-flow methods, the DEP rows are the reduced form of the Galerkin rows, and rows refuse
 * what they cannot integrate. */
#include "test_util.h"

Test(lie_methods, crouch_grossman_order_3_conditions) {
  const gm_method *m = gm_method_find("crouch-grossman-3");
  cr_assert_not_null(m);
  gm_tableau *t = NULL;
  cr_assert_eq(gm_method_tableau(m, &t), GM_OK);
  const size_t s = t->n_stages;
  const double *a = t->a, *b = t->b, *c = t->c;
  double sb = 0, sbc = 0, sbc2 = 0, sbac = 0, cg = 0;
  for (size_t i = 0; i < s; ++i) {
    double row = 0;
    for (size_t j = 0; j < s; ++j) row += a[i * s + j];
    cr_expect(fabs(row - c[i]) < 1e-15, "row sum %zu", i);
    sb += b[i];
    sbc += b[i] * c[i];
    sbc2 += b[i] * c[i] * c[i];
    for (size_t j = 0; j < s; ++j) sbac += b[i] * a[i * s + j] * c[j];
    cg += b[i] * b[i] * c[i];
    for (size_t j = i + 1; j < s; ++j) cg += 2 * b[i] * c[i] * b[j];
  }
  cr_expect(fabs(sb - 1) < 1e-15 && fabs(sbc - 0.5) < 1e-15 && fabs(sbc2 - 1.0 / 3) < 1e-15 &&
            fabs(sbac - 1.0 / 6) < 1e-15);
  /* the extra condition of Crouch–Grossman methods (Owren & Marthinsen 1999) */
  cr_expect(fabs(cg - 1.0 / 3) < 1e-15, "sum b_i^2 c_i + 2 sum_{i<j} b_i c_i b_j = %.17g", cg);
  gm_tableau_free(t);
}

Test(lie_methods, dep_is_the_reduced_galerkin_integrator) {
  test_model tm = test_model_make("rigid-body");
  static const char *const pairs[][2] = {
      {"dep-1", "lgvi-galerkin-1"}, {"dep-2", "lgvi-galerkin-2"}, {"dep-3", "lgvi-galerkin-3"}};
  for (size_t k = 0; k < 3; ++k) {
    gm_integrator *a = test_integrator(gm_method_find(pairs[k][0]), tm.problem, tm.t0, tm.y0);
    gm_integrator *b = test_integrator(gm_method_find(pairs[k][1]), tm.problem, tm.t0, tm.y0);
    cr_assert_eq(gm_integrator_run(a, 200, 0.1), GM_OK);
    cr_assert_eq(gm_integrator_run(b, 200, 0.1), GM_OK);
    double e = 0;
    for (size_t i = 0; i < tm.n; ++i)
      e = fmax(e, fabs(gm_integrator_state(a)[i] - gm_integrator_state(b)[i]));
    cr_expect_leq(e, 1e-14, "%s vs %s: %.2e", pairs[k][0], pairs[k][1], e);
    /* the reduced equations never evaluate the (absent) potential */
    cr_expect_eq(gm_integrator_stats(a).force_evals, 0);
    gm_integrator_free(a);
    gm_integrator_free(b);
  }
  /* a body in a field has no left-invariant Lagrangian */
  test_model top = test_model_make("heavy-top");
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_integrator_create(gm_method_find("dep-2"), top.problem, &it, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "free body") != NULL, "%s", err.message);
  gm_model_free(top.model);
  gm_model_free(tm.model);
}

Test(lie_methods, free_body_midpoint_galerkin_rotates_pi) {
  /* s = 1: Π_{k+1} = exp(−ξ̂_k) Π_k and R_{k+1} = R_k exp(ξ̂_k): R Π is kept exactly */
  test_model tm = test_model_make("rigid-body");
  gm_integrator *it = test_integrator(gm_method_find("lgvi-galerkin-1"), tm.problem, tm.t0, tm.y0);
  cr_assert_eq(gm_integrator_step(it, 0.3), GM_OK);
  const double *y = gm_integrator_state(it);
  double xi[3], f[9], back[3];
  gm_so3_log(y, xi); /* R0 = I */
  gm_so3_exp(xi, f);
  gm_mat3_vec(f, y + 9, back); /* exp(ξ̂) Π1 = Π0 */
  for (int a = 0; a < 3; ++a) cr_expect(fabs(back[a] - tm.y0[9 + a]) < 1e-15);
  gm_integrator_free(it);
  gm_model_free(tm.model);
}
