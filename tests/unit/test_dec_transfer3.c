/* The support-volume transfer of 3-forms between unrelated tetrahedral meshes of one cube
 * (tetrahedron–tetrahedron clipping, src/dec/transfer_clip3.c): the total of a random 3-form is
 * kept to round-off, a constant density stays constant (which tests the clipped volumes
 * themselves), and meshes of different domains are refused naming the volumes. */
#include <stdio.h>
#include <string.h>

#include "dec_util.h"
#include "geomint/multigrid.h"

static gm_complex *cube(size_t nx, size_t ny, size_t nz, gm_box_pattern pattern, double jiggle,
                        double x1) {
  gm_mesh *m = NULL;
  gm_error err = {{0}};
  const double lo[3] = {0, 0, 0}, hi[3] = {x1, 1, 1};
  cr_assert_eq(gm_mesh_box(lo, hi, nx, ny, nz, pattern, &m, &err), GM_OK, "%s", err.message);
  if (jiggle > 0.0) {
    gm_complex *cx = test_complex(m);
    test_jiggle(m, cx, 1.0 / (double)nx, jiggle, nx * 31 + ny * 7 + nz);
    gm_complex_free(cx);
  }
  gm_complex *cx = test_complex(m);
  gm_mesh_free(m);
  return cx;
}

static double sum(size_t n, const double *x) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += x[i];
  return s;
}

/* Measured (360 → 300 jiggled tets, 384 → 320 grid-aligned): the overlap volume is 1 to
 * 4.4e-16 and 5.0e-15, the total of a random 3-form changes by 1.3e-15 and 0 (relative), a
 * constant density by at most 1.2e-14 and 1.0e-15 on one cell. */
Test(transfer3, totals_and_constant_density) {
  gm_complex *pairs[2][2] = {{cube(4, 3, 5, GM_BOX_KUHN, 0.2, 1.0), cube(3, 5, 4, GM_BOX_FIVE, 0.25, 1.0)},
                             {cube(4, 4, 4, GM_BOX_KUHN, 0.0, 1.0), cube(2, 4, 8, GM_BOX_FIVE, 0.0, 1.0)}};
  for (int p = 0; p < 2; ++p) {
    gm_complex *a = pairs[p][0], *b = pairs[p][1];
    gm_error err = {{0}};
    gm_csr *T = NULL;
    gm_transfer_report rep;
    cr_assert_eq(gm_dec_transfer(a, b, 3, &T, &rep, &err), GM_OK, "%s", err.message);
    const size_t na = gm_complex_count(a, 3), nb = gm_complex_count(b, 3);
    double *w = malloc(na * sizeof(double)), *tw = malloc(nb * sizeof(double));
    test_random_fill(na, w, 7 + (uint64_t)p);
    gm_csr_matvec(T, 1.0, w, 0.0, tw);
    const double s0 = sum(na, w), s1 = sum(nb, tw);
    /* a constant density 2: ⟨w, σ⟩ = 2 |σ| → 2 |τ| */
    gm_geometry *ga = NULL, *gb = NULL;
    cr_assert_eq(gm_geometry_create(a, NULL, &ga, &err), GM_OK);
    cr_assert_eq(gm_geometry_create(b, NULL, &gb, &err), GM_OK);
    const double *va = gm_geometry_primal_volumes(ga, 3), *vb = gm_geometry_primal_volumes(gb, 3);
    for (size_t i = 0; i < na; ++i) w[i] = 2.0 * va[i];
    gm_csr_matvec(T, 1.0, w, 0.0, tw);
    double dev = 0.0;
    for (size_t j = 0; j < nb; ++j) dev = fmax(dev, fabs(tw[j] / vb[j] - 2.0) / 2.0);
    printf("tets %zu -> %zu: %zu pairs, overlap - 1 = %.2e, total change %.2e, constant density "
           "off by %.2e\n",
           na, nb, rep.pairs, rep.volume_overlap - 1.0, fabs(s1 - s0) / fabs(s0), dev);
    cr_expect_leq(fabs(rep.volume_overlap - 1.0), 1e-14, "%.17g", rep.volume_overlap);
    cr_expect_leq(fabs(s1 - s0), 1e-13 * fabs(s0), "total %.17g -> %.17g", s0, s1);
    cr_expect_leq(dev, 6e-14, "%.3g", dev);
    free(w), free(tw);
    gm_csr_free(T);
    gm_geometry_free(ga), gm_geometry_free(gb);
    gm_complex_free(a), gm_complex_free(b);
  }
}

Test(transfer3, different_domains_refused) {
  gm_complex *a = cube(3, 3, 3, GM_BOX_KUHN, 0.0, 1.0), *b = cube(3, 3, 3, GM_BOX_FIVE, 0.0, 1.1);
  gm_error err = {{0}};
  gm_csr *T = NULL;
  cr_expect_eq(gm_dec_transfer(a, b, 3, &T, NULL, &err), GM_EINVAL);
  cr_expect_null(T);
  printf("%s\n", err.message);
  cr_expect_not_null(strstr(err.message, "volume |from| = 1.000000000000"), "%s", err.message);
  cr_expect_not_null(strstr(err.message, "|to| = 1.09999"), "%s", err.message);
  cr_expect_eq(gm_dec_transfer(a, b, 1, &T, NULL, &err), GM_EUNSUPPORTED);
  cr_expect_not_null(strstr(err.message, "top (3-)forms"), "%s", err.message);
  gm_complex_free(a), gm_complex_free(b);
}
