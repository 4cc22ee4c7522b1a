/* Simplicial complexes: faces, orientation, d∘d = 0, boundary, Euler characteristic, Betti
 * numbers of disk, annulus, sphere, torus and 3-D balls with a cavity or a tunnel; bad input. */
#include <string.h>

#include "dec_util.h"

static void check_dd_zero(const gm_complex *cx) {
  for (size_t k = 0; k + 1 < gm_complex_dim(cx); ++k) {
    gm_csr *dd = NULL;
    cr_assert_eq(gm_csr_multiply(gm_complex_d(cx, k + 1), gm_complex_d(cx, k), &dd), GM_OK);
    /* entries are sums of ±1: exactly zero, not merely small */
    cr_expect_eq(gm_csr_max_abs(dd), 0.0, "d_%zu d_%zu has entry %g", k + 1, k, gm_csr_max_abs(dd));
    gm_csr_free(dd);
  }
}

static void check_betti(const gm_mesh *m, long chi, size_t b0, size_t b1, size_t b2) {
  gm_complex *cx = test_complex(m);
  check_dd_zero(cx);
  cr_expect_eq(gm_complex_euler_characteristic(cx), chi, "chi = %ld, expected %ld",
               gm_complex_euler_characteristic(cx), chi);
  size_t b[4];
  cr_assert_eq(gm_complex_betti_numbers(cx, b), GM_OK);
  cr_expect_eq(b[0], b0, "b0 = %zu", b[0]);
  cr_expect_eq(b[1], b1, "b1 = %zu", b[1]);
  cr_expect_eq(b[2], b2, "b2 = %zu", b[2]);
  cr_expect_eq(b[3], 0);
  gm_complex_free(cx);
}

Test(dec_complex, counts_and_faces_of_a_single_tetrahedron) {
  const double x[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const size_t t[] = {0, 1, 2, 3};
  gm_complex *cx = NULL;
  cr_assert_eq(gm_complex_create(3, 4, x, 3, 1, t, &cx, NULL), GM_OK);
  cr_expect_eq(gm_complex_count(cx, 1), 6);
  cr_expect_eq(gm_complex_count(cx, 2), 4);
  /* edges in lexicographic order */
  const size_t *e = gm_complex_simplices(cx, 1);
  const size_t expect[] = {0, 1, 0, 2, 0, 3, 1, 2, 1, 3, 2, 3};
  cr_expect_eq(memcmp(e, expect, sizeof expect), 0);
  /* face i of the tetrahedron is opposite vertex i */
  const size_t *f = gm_complex_faces(cx, 3);
  const size_t *tri = gm_complex_simplices(cx, 2);
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 3; ++j) cr_expect_neq(tri[3 * f[i] + j], i);
  cr_expect_eq(gm_complex_orientation(cx)[0], 1);
  cr_expect_eq(gm_complex_boundary_count(cx, 2), 4);
  size_t q[3] = {3, 1, 2};
  cr_expect_eq(gm_complex_find(cx, 2, q), f[0]);
  size_t all[4] = {3, 2, 1, 0};
  cr_expect_eq(gm_complex_find(cx, 3, all), 0);
  check_dd_zero(cx);
  gm_complex_free(cx);
}

Test(dec_complex, orientation_is_made_consistent) {
  /* a square of two triangles, the second given clockwise */
  const double x[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const size_t t[] = {0, 1, 2, 0, 3, 2};
  gm_complex *cx = NULL;
  cr_assert_eq(gm_complex_create(2, 4, x, 2, 2, t, &cx, NULL), GM_OK);
  cr_expect_eq(gm_complex_reoriented_count(cx), 1);
  /* interior edge (0,2): the two triangles induce opposite orientations, so column sums of d_1
   * vanish on interior edges */
  const gm_csr *d1 = gm_complex_d(cx, 1);
  size_t e02[2] = {0, 2};
  size_t e = gm_complex_find(cx, 1, e02);
  cr_expect_eq(gm_csr_get(d1, 0, e) + gm_csr_get(d1, 1, e), 0.0);
  cr_expect_eq(gm_complex_boundary_count(cx, 1), 4);
  gm_complex_free(cx);
}

Test(dec_complex, betti_numbers_of_standard_shapes) {
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_rectangle(0, 1, 0, 1, 7, 5, GM_DIAGONAL_ALTERNATE, &m, NULL), GM_OK);
  check_betti(m, 1, 1, 0, 0); /* disk */
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_annulus(0.5, 1.0, 4, 24, &m, NULL), GM_OK);
  check_betti(m, 0, 1, 1, 0);
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_icosphere(1.0, 2, &m, NULL), GM_OK);
  check_betti(m, 2, 1, 0, 1);
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_torus(2.0, 0.7, 16, 9, &m, NULL), GM_OK);
  check_betti(m, 0, 1, 2, 1);
  gm_mesh_free(m);
}

static int outside_cavity(void *ctx, const double *c) {
  (void)ctx;
  return !(fabs(c[0] - 0.5) < 0.12 && fabs(c[1] - 0.5) < 0.12 && fabs(c[2] - 0.5) < 0.12);
}

static int outside_tunnel(void *ctx, const double *c) {
  (void)ctx;
  return !(fabs(c[0] - 0.5) < 0.12 && fabs(c[1] - 0.5) < 0.12);
}

Test(dec_complex, betti_numbers_of_3d_balls_with_holes) {
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_box(lo, hi, 5, 5, 5, GM_BOX_KUHN, &m, NULL), GM_OK);
  check_betti(m, 1, 1, 0, 0); /* ball */
  cr_assert_eq(gm_mesh_filter(m, outside_cavity, NULL), GM_OK);
  check_betti(m, 2, 1, 0, 1); /* ball with a cavity: χ = 1 − 0 + 1 */
  gm_mesh_free(m);
  cr_assert_eq(gm_mesh_box(lo, hi, 5, 5, 5, GM_BOX_FIVE, &m, NULL), GM_OK);
  cr_assert_eq(gm_mesh_filter(m, outside_tunnel, NULL), GM_OK);
  check_betti(m, 0, 1, 1, 0); /* solid torus: a ball with a tunnel */
  gm_mesh_free(m);
}

Test(dec_complex, one_dimensional_complexes) {
  /* a closed polygon in R^2: b0 = 1, b1 = 1 */
  const size_t n = 6;
  double x[12];
  size_t e[12];
  for (size_t i = 0; i < n; ++i) {
    x[2 * i] = cos(2 * TEST_PI * (double)i / (double)n);
    x[2 * i + 1] = sin(2 * TEST_PI * (double)i / (double)n);
    e[2 * i] = i;
    e[2 * i + 1] = (i + 1) % n;
  }
  gm_complex *cx = NULL;
  cr_assert_eq(gm_complex_create(2, n, x, 1, n, e, &cx, NULL), GM_OK);
  size_t b[4];
  cr_assert_eq(gm_complex_betti_numbers(cx, b), GM_OK);
  cr_expect_eq(b[0], 1);
  cr_expect_eq(b[1], 1);
  cr_expect_eq(gm_complex_boundary_count(cx, 0), 0);
  gm_complex_free(cx);
}

Test(dec_complex, bad_input_is_an_error_with_a_message) {
  const double x[] = {0, 0, 1, 0, 1, 1, 0, 1, 0.5, 0.5};
  gm_complex *cx = NULL;
  gm_error err = {{0}};
  const size_t out_of_range[] = {0, 1, 7};
  cr_expect_eq(gm_complex_create(2, 5, x, 2, 1, out_of_range, &cx, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "out of range") != NULL, "%s", err.message);
  const size_t repeated[] = {0, 1, 1};
  cr_expect_eq(gm_complex_create(2, 5, x, 2, 1, repeated, &cx, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "repeats") != NULL, "%s", err.message);
  /* three triangles on the edge (0,1): not a manifold */
  const size_t fan[] = {0, 1, 2, 0, 1, 3, 0, 1, 4, 2, 3, 4};
  cr_expect_eq(gm_complex_create(2, 5, x, 2, 3, fan, &cx, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "non-manifold") != NULL, "%s", err.message);
  const size_t unused[] = {0, 1, 2};
  cr_expect_eq(gm_complex_create(2, 5, x, 2, 1, unused, &cx, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "not used") != NULL, "%s", err.message);
  const size_t dup[] = {0, 1, 2, 2, 1, 0, 0, 2, 3, 4, 0, 3};
  (void)dup;
  double nan_x[10];
  memcpy(nan_x, x, sizeof nan_x);
  nan_x[3] = NAN;
  const size_t ok[] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};
  cr_expect_eq(gm_complex_create(2, 5, nan_x, 2, 4, ok, &cx, &err), GM_EDOMAIN);
  cr_expect(strstr(err.message, "vertex 1") != NULL, "%s", err.message);
  cr_expect_null(cx);
}

Test(dec_complex, moebius_strip_is_not_orientable) {
  /* a strip of 5 quads (10 triangles) closed with a half twist */
  const size_t n = 5;
  double x[3 * 2 * 5];
  for (size_t i = 0; i < n; ++i) {
    double th = 2 * TEST_PI * (double)i / (double)n, tw = th / 2;
    for (int s = 0; s < 2; ++s) {
      double w = s ? 0.3 : -0.3;
      x[3 * (2 * i + (size_t)s)] = (1 + w * cos(tw)) * cos(th);
      x[3 * (2 * i + (size_t)s) + 1] = (1 + w * cos(tw)) * sin(th);
      x[3 * (2 * i + (size_t)s) + 2] = w * sin(tw);
    }
  }
  size_t t[3 * 2 * 5];
  for (size_t i = 0; i < n; ++i) {
    size_t a = 2 * i, b = 2 * i + 1, c, d;
    if (i + 1 < n) {
      c = 2 * (i + 1), d = 2 * (i + 1) + 1;
    } else { /* the twist swaps the two sides */
      c = 1, d = 0;
    }
    size_t *q = t + 6 * i;
    q[0] = a, q[1] = c, q[2] = b, q[3] = b, q[4] = c, q[5] = d;
  }
  gm_complex *cx = NULL;
  gm_error err = {{0}};
  cr_expect_eq(gm_complex_create(3, 2 * n, x, 2, 2 * n, t, &cx, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "not orientable") != NULL, "%s", err.message);
}

Test(dec_complex, boundary_matrices_are_transposes_of_d) {
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 2, 1};
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_box(lo, hi, 2, 3, 2, GM_BOX_KUHN, &m, NULL), GM_OK);
  gm_complex *cx = test_complex(m);
  for (size_t k = 1; k <= 3; ++k) {
    gm_csr *b = NULL;
    cr_assert_eq(gm_complex_boundary_matrix(cx, k, &b), GM_OK);
    const gm_csr *d = gm_complex_d(cx, k - 1);
    cr_expect_eq(b->n_rows, d->n_cols);
    for (size_t i = 0; i < d->n_rows; ++i)
      for (size_t p = d->row_start[i]; p < d->row_start[i + 1]; ++p)
        cr_expect_eq(gm_csr_get(b, d->col[p], i), d->val[p]);
    gm_csr_free(b);
  }
  /* the boundary of the boundary is empty: c = ∂_3(all tetrahedra) lies on the boundary faces
   * and ∂_2 c = 0 exactly */
  size_t nf = gm_complex_count(cx, 2), ne = gm_complex_count(cx, 1);
  double *ones = malloc(gm_complex_count(cx, 3) * sizeof(double));
  double *c = calloc(nf, sizeof(double)), *dc = calloc(ne, sizeof(double));
  for (size_t t = 0; t < gm_complex_count(cx, 3); ++t) ones[t] = 1.0;
  gm_csr_matvec_transpose(gm_complex_d(cx, 2), 1.0, ones, 0.0, c);
  const unsigned char *bf = gm_complex_boundary_mask(cx, 2);
  for (size_t f = 0; f < nf; ++f) cr_expect_eq(fabs(c[f]), bf[f] ? 1.0 : 0.0);
  gm_csr_matvec_transpose(gm_complex_d(cx, 1), 1.0, c, 0.0, dc);
  cr_expect_eq(test_max_abs(ne, dc), 0.0);
  gm_complex_free(cx);
  gm_mesh_free(m);
  free(ones), free(c), free(dc);
}
