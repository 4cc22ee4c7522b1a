/* Hodge decomposition: parts sum to the input, are mutually ⋆-orthogonal to round-off, the exact
 * part is closed, the coexact part co-closed, the harmonic part both; harmonic spaces have the
 * dimension of the Betti numbers (annulus b1 = 1, torus b1 = 2, sphere b2 = 1); d∘d = 0 and ⋆⋆. */
#include <string.h>

#include "dec_util.h"

static void check_decomposition(const gm_geometry *g, size_t k, uint64_t seed) {
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t nk = gm_complex_count(cx, k), n = gm_complex_dim(cx);
  const double *w = gm_geometry_hodge_star(g, k);
  double *a = malloc(nk * sizeof(double)), *ex = malloc(nk * sizeof(double)),
         *co = malloc(nk * sizeof(double)), *h = malloc(nk * sizeof(double));
  test_random_fill(nk, a, seed);
  gm_hodge_decomposition *hd = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_hodge_decomposition_create(g, k, &hd, &err), GM_OK, "%s", err.message);
  cr_assert_eq(gm_hodge_decomposition_apply(hd, a, ex, co, h), GM_OK);
  double na = sqrt(test_wdot(nk, w, a, a));
  double s = 0.0;
  for (size_t i = 0; i < nk; ++i) s = fmax(s, fabs(ex[i] + co[i] + h[i] - a[i]));
  cr_expect_leq(s, 1e-13 * test_max_abs(nk, a));
  double e_c = test_wdot(nk, w, ex, co), e_h = test_wdot(nk, w, ex, h), c_h = test_wdot(nk, w, co, h);
  cr_expect_leq(fabs(e_c), 1e-12 * na * na, "(exact, coexact) = %.3g", e_c);
  cr_expect_leq(fabs(e_h), 1e-12 * na * na, "(exact, harmonic) = %.3g", e_h);
  cr_expect_leq(fabs(c_h), 1e-12 * na * na, "(coexact, harmonic) = %.3g", c_h);
  /* d of the harmonic and exact parts vanish; so does δ (d_{k−1}ᵀ ⋆) of harmonic and coexact */
  if (k < n) {
    size_t m = gm_complex_count(cx, k + 1);
    double *dh = malloc(m * sizeof(double));
    gm_csr_matvec(gm_complex_d(cx, k), 1.0, h, 0.0, dh);
    cr_expect_leq(test_max_abs(m, dh), 1e-11 * test_max_abs(nk, a), "|d h| = %.3g", test_max_abs(m, dh));
    gm_csr_matvec(gm_complex_d(cx, k), 1.0, ex, 0.0, dh);
    cr_expect_leq(test_max_abs(m, dh), 1e-11 * test_max_abs(nk, a));
    free(dh);
  }
  if (k >= 1) {
    size_t m = gm_complex_count(cx, k - 1);
    double *sh = malloc(m * sizeof(double)), *t = malloc(nk * sizeof(double));
    for (size_t i = 0; i < nk; ++i) t[i] = w[i] * h[i];
    gm_csr_matvec_transpose(gm_complex_d(cx, k - 1), 1.0, t, 0.0, sh);
    double scale = test_max_abs(nk, w) * test_max_abs(nk, a);
    cr_expect_leq(test_max_abs(m, sh), 1e-11 * scale, "|δ h| = %.3g", test_max_abs(m, sh));
    free(sh), free(t);
  }
  gm_hodge_decomposition_free(hd);
  free(a), free(ex), free(co), free(h);
}

static void check_harmonic_dimension(const gm_geometry *g, size_t k, size_t expected) {
  size_t count = 0;
  double *basis = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_dec_harmonic_basis(g, k, &count, &basis, &err), GM_OK, "%s", err.message);
  cr_expect_eq(count, expected);
  const gm_complex *cx = gm_geometry_complex(g);
  const size_t nk = gm_complex_count(cx, k);
  const double *w = gm_geometry_hodge_star(g, k);
  /* orthonormal */
  for (size_t i = 0; i < count; ++i)
    for (size_t j = 0; j < count; ++j)
      cr_expect(fabs(test_wdot(nk, w, basis + i * nk, basis + j * nk) - (i == j)) <= 1e-12);
  /* and complete: the harmonic part of one more random cochain lies in their span */
  if (count > 0) {
    gm_hodge_decomposition *hd = NULL;
    cr_assert_eq(gm_hodge_decomposition_create(g, k, &hd, NULL), GM_OK);
    double *a = malloc(nk * sizeof(double)), *h = malloc(nk * sizeof(double));
    test_random_fill(nk, a, 77);
    cr_assert_eq(gm_hodge_decomposition_apply(hd, a, NULL, NULL, h), GM_OK);
    double n0 = sqrt(test_wdot(nk, w, h, h));
    for (size_t i = 0; i < count; ++i) {
      double c = test_wdot(nk, w, h, basis + i * nk);
      for (size_t q = 0; q < nk; ++q) h[q] -= c * basis[i * nk + q];
    }
    cr_expect_leq(sqrt(test_wdot(nk, w, h, h)), 1e-10 * n0, "harmonic space larger than b_%zu", k);
    free(a), free(h);
    gm_hodge_decomposition_free(hd);
  }
  free(basis);
}

Test(dec_hodge, annulus_one_forms) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_annulus(0.5, 1.0, 6, 40, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  for (size_t k = 0; k <= 2; ++k) check_decomposition(g, k, 100 + k);
  check_harmonic_dimension(g, 0, 1);
  check_harmonic_dimension(g, 1, 1);
  check_harmonic_dimension(g, 2, 0);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
}

Test(dec_hodge, torus_and_sphere) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_torus(2.0, 0.8, 24, 12, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  check_decomposition(g, 1, 7);
  check_harmonic_dimension(g, 1, 2);
  check_harmonic_dimension(g, 2, 1);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
  cr_assert_eq(gm_mesh_icosphere(1.0, 2, &m, NULL), GM_OK);
  cx = test_complex(m);
  g = test_geometry(cx);
  check_decomposition(g, 1, 8);
  check_harmonic_dimension(g, 1, 0);
  check_harmonic_dimension(g, 2, 1);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
}

Test(dec_hodge, three_dimensional_ball_with_cavity) {
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_box(lo, hi, 4, 4, 4, GM_BOX_FIVE, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  gm_geometry *g = test_geometry(cx);
  /* five-tetrahedra cubes are not well-centred: some stars are not positive, and the
   * decomposition says so instead of returning garbage */
  gm_hodge_decomposition *hd = NULL;
  gm_error err = {{0}};
  gm_status st = gm_hodge_decomposition_create(g, 1, &hd, &err);
  if (gm_geometry_negative_duals(g, 1) > 0) {
    cr_expect_eq(st, GM_EDOMAIN);
    cr_expect(strstr(err.message, "positive Hodge star") != NULL, "%s", err.message);
  } else {
    cr_expect_eq(st, GM_OK);
    gm_hodge_decomposition_free(hd);
  }
  /* 0-forms and 3-forms have positive stars here */
  check_decomposition(g, 0, 3);
  check_decomposition(g, 3, 4);
  gm_geometry_free(g), gm_complex_free(cx), gm_mesh_free(m);
}
