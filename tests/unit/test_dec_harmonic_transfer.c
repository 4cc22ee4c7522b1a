/* A harmonic form stays harmonic under the nested transfer: on an annulus (b_1 = 1) the Whitney
 * prolongation P_1 of the coarse harmonic 1-form h is closed to round-off (P is a cochain map:
 * d P = P d), so its class is kept and its Hodge decomposition on the fine mesh has no coexact
 * part; what is not exactly harmonic is an exact part (P does not commute with δ), measured here
 * and shrinking under refinement (first order). */
#include <stdio.h>
#include <string.h>

#include "dec_util.h"
#include "geomint/multigrid.h"

static double star_norm(const gm_geometry *g, size_t k, size_t n, const double *a) {
  const double *s = gm_geometry_hodge_star(g, k);
  double r = 0.0;
  for (size_t i = 0; i < n; ++i) r += s[i] * a[i] * a[i];
  return sqrt(r);
}

/* Measured (annulus 1 < r < 2, 4 × 32 acute coarse triangles, refined once and twice): max |d P h|
 * / max |P h| 9.1e-15 and 2.0e-16; coexact part 2.7e-15 and 6.7e-17 of |P h| (⋆-norms); exact
 * part 0.0732 and 0.0383 (first order), harmonic part 0.9973 and 0.9993. */
Test(harmonic_transfer, annulus_whitney_prolongation) {
  gm_error err = {{0}};
  gm_mesh *m0 = NULL;
  cr_assert_eq(gm_mesh_annulus(1.0, 2.0, 4, 32, &m0, &err), GM_OK, "%s", err.message);
  gm_complex *c0 = test_complex(m0);
  gm_geometry *g0 = NULL;
  cr_assert_eq(gm_geometry_create(c0, NULL, &g0, &err), GM_OK, "%s", err.message);
  size_t nh = 0;
  double *h = NULL;
  cr_assert_eq(gm_dec_harmonic_basis(g0, 1, &nh, &h, &err), GM_OK, "%s", err.message);
  cr_assert_eq(nh, 1);
  gm_mesh *mc = m0;
  gm_complex *cc = c0;
  double *hc = h, exact_prev = 0.0;
  for (int level = 1; level <= 2; ++level) {
    gm_mesh *mf = NULL;
    cr_assert_eq(gm_mesh_refine(mc, 0, &mf, &err), GM_OK, "%s", err.message);
    gm_complex *cf = test_complex(mf);
    gm_refinement *r = NULL;
    gm_csr *P = NULL;
    cr_assert_eq(gm_refinement_create(cc, cf, &r, &err), GM_OK, "%s", err.message);
    cr_assert_eq(gm_refinement_prolongation(r, 1, &P, &err), GM_OK, "%s", err.message);
    const size_t ne = gm_complex_count(cf, 1), nf = gm_complex_count(cf, 2);
    double *ph = malloc(ne * sizeof(double)), *dph = malloc(nf * sizeof(double));
    double *ex = malloc(ne * sizeof(double)), *co = malloc(ne * sizeof(double)),
           *ha = malloc(ne * sizeof(double));
    gm_csr_matvec(P, 1.0, hc, 0.0, ph);
    gm_csr_matvec(gm_complex_d(cf, 1), 1.0, ph, 0.0, dph);
    gm_geometry *gf = NULL;
    cr_assert_eq(gm_geometry_create(cf, NULL, &gf, &err), GM_OK, "%s", err.message);
    gm_hodge_decomposition *hd = NULL;
    cr_assert_eq(gm_hodge_decomposition_create(gf, 1, &hd, &err), GM_OK, "%s", err.message);
    cr_assert_eq(gm_hodge_decomposition_apply(hd, ph, ex, co, ha), GM_OK);
    const double n = star_norm(gf, 1, ne, ph);
    double dmax = 0.0, pmax = 0.0;
    for (size_t f = 0; f < nf; ++f) dmax = fmax(dmax, fabs(dph[f]));
    for (size_t e = 0; e < ne; ++e) pmax = fmax(pmax, fabs(ph[e]));
    const double exact = star_norm(gf, 1, ne, ex) / n, coexact = star_norm(gf, 1, ne, co) / n;
    printf("annulus level %d: %zu edges, |d P h|max / |P h|max = %.2e, exact part %.4f, coexact "
           "part %.2e, harmonic part %.4f (of |P h|)\n",
           level, ne, dmax / pmax, exact, coexact, star_norm(gf, 1, ne, ha) / n);
    cr_expect_leq(dmax, 5e-14 * pmax, "%.3g", dmax / pmax);
    cr_expect_leq(coexact, 3e-14, "%.3g", coexact);
    cr_expect_leq(exact, level == 1 ? 0.15 : 0.6 * exact_prev, "%.4f", exact);
    exact_prev = exact;
    gm_hodge_decomposition_free(hd);
    gm_geometry_free(gf);
    free(dph), free(ex), free(co);
    gm_csr_free(P);
    gm_refinement_free(r);
    if (hc != h) free(hc);
    hc = ha; /* the fine harmonic form, prolonged again on the next level */
    free(ph);
    if (cc != c0) gm_complex_free(cc);
    if (mc != m0) gm_mesh_free(mc);
    mc = mf, cc = cf;
  }
  if (hc != h) free(hc);
  gm_complex_free(cc), gm_mesh_free(mc);
  free(h);
  gm_geometry_free(g0);
  gm_complex_free(c0);
  gm_mesh_free(m0);
}
