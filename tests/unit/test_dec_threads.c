/* The complex and its geometry do not depend on the number of OpenMP threads (bit for bit), and
 * the dual volumes built from the stored circumcenters equal, bit for bit, the sums of the pieces
 * recomputed tetrahedron by tetrahedron (gm_geometry_dual_pieces, the direct formula). */
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "dec_util.h"

/* A 24³ Kuhn box (82 944 tetrahedra: enough for the parallel loops to engage) with vertices moved
 * by up to 0.2 h (fixed seed), so circumcenters leave their simplices and some duals are
 * negative; every 5th tetrahedron is given with two vertices swapped. */
static gm_mesh *jittered_box(void) {
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  const size_t n = 24;
  gm_mesh *m = NULL;
  cr_assert_eq(gm_mesh_box(lo, hi, n, n, n, GM_BOX_KUHN, &m, NULL), GM_OK);
  uint64_t seed = 7;
  const double h = 1.0 / (double)n;
  for (size_t v = 0; v < m->n_vertices; ++v)
    for (size_t j = 0; j < 3; ++j) {
      double x = m->x[3 * v + j];
      if (x > 0.0 && x < 1.0) m->x[3 * v + j] = x + 0.2 * h * test_random(&seed);
    }
  for (size_t t = 0; t < m->n_cells; t += 5) {
    size_t s = m->cells[4 * t];
    m->cells[4 * t] = m->cells[4 * t + 1];
    m->cells[4 * t + 1] = s;
  }
  return m;
}

typedef struct {
  gm_complex *cx;
  gm_geometry *g;
} built;

static built build(const gm_mesh *m, int threads) {
#ifdef _OPENMP
  omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  built b;
  b.cx = test_complex(m);
  b.g = test_geometry(b.cx);
  return b;
}

static void expect_same_bits(const void *a, const void *b, size_t bytes, const char *what) {
  cr_expect(memcmp(a, b, bytes) == 0, "%s differs between 1 and 2 threads", what);
}

Test(dec_threads, complex_and_geometry_are_bitwise_independent_of_thread_count) {
  gm_mesh *m = jittered_box();
  built one = build(m, 1), two = build(m, 2);
#ifdef _OPENMP
  omp_set_num_threads(omp_get_num_procs());
#endif
  const size_t n = 3;
  for (size_t k = 0; k <= n; ++k) {
    const size_t c = gm_complex_count(one.cx, k);
    cr_assert_eq(c, gm_complex_count(two.cx, k));
    expect_same_bits(gm_complex_simplices(one.cx, k), gm_complex_simplices(two.cx, k),
                     c * (k + 1) * sizeof(size_t), "simplices");
    if (k >= 1)
      expect_same_bits(gm_complex_faces(one.cx, k), gm_complex_faces(two.cx, k),
                       c * (k + 1) * sizeof(size_t), "faces");
    if (k < n) {
      const gm_csr *d1 = gm_complex_d(one.cx, k), *d2 = gm_complex_d(two.cx, k);
      cr_assert_eq(gm_csr_nnz(d1), gm_csr_nnz(d2));
      expect_same_bits(d1->col, d2->col, gm_csr_nnz(d1) * sizeof(size_t), "d columns");
      expect_same_bits(d1->val, d2->val, gm_csr_nnz(d1) * sizeof(double), "d values");
    }
    expect_same_bits(gm_geometry_centers(one.g, k), gm_geometry_centers(two.g, k),
                     3 * c * sizeof(double), "circumcenters");
    expect_same_bits(gm_geometry_primal_volumes(one.g, k), gm_geometry_primal_volumes(two.g, k),
                     c * sizeof(double), "primal volumes");
    expect_same_bits(gm_geometry_dual_volumes(one.g, k), gm_geometry_dual_volumes(two.g, k),
                     c * sizeof(double), "dual volumes");
    expect_same_bits(gm_geometry_hodge_star(one.g, k), gm_geometry_hodge_star(two.g, k),
                     c * sizeof(double), "Hodge star");
    if (k < n)
      expect_same_bits(gm_geometry_boundary_dual_volumes(one.g, k),
                       gm_geometry_boundary_dual_volumes(two.g, k), c * sizeof(double),
                       "boundary dual volumes");
    cr_expect_eq(gm_geometry_negative_duals(one.g, k), gm_geometry_negative_duals(two.g, k));
  }
  const size_t nt = gm_complex_count(one.cx, n);
  expect_same_bits(gm_complex_orientation(one.cx), gm_complex_orientation(two.cx), nt,
                   "orientation");
  cr_expect_eq(gm_complex_reoriented_count(one.cx), gm_complex_reoriented_count(two.cx));
  /* the jitter makes some simplices not well-centred: the signs matter in this test */
  cr_expect_gt(gm_geometry_negative_duals(one.g, 1), 0);
  /* every tetrahedron positively oriented after orientation, whatever order it was given in */
  cr_expect_eq(gm_geometry_inverted_count(one.g), 0);
  cr_expect_gt(gm_complex_reoriented_count(one.cx), nt / 10);
  gm_mesh_free(m);
  gm_geometry_free(two.g);
  gm_complex_free(two.cx);

  /* the same dual volumes from the direct per-tetrahedron formula, summed in the same order */
  double *sum[3];
  for (size_t k = 0; k < n; ++k) sum[k] = calloc(gm_complex_count(one.cx, k), sizeof(double));
  for (size_t T = 0; T < nt; ++T) {
    size_t idx[3][6];
    double pieces[3][6];
    for (size_t k = 0; k < n; ++k) {
      gm_complex_local_faces(one.cx, T, k, idx[k]);
      gm_geometry_dual_pieces(one.g, T, k, pieces[k]);
    }
    const size_t *tv = gm_complex_simplices(one.cx, n) + 4 * T;
    /* the geometry pass adds the pieces of the subsets s of the 4 positions in increasing
     * bitmask order; local_faces lists them lexicographically: match them by vertex set */
    for (unsigned s = 1; s < 15; ++s) {
      size_t want[4], k = 0;
      for (unsigned b = 0; b < 4; ++b)
        if (s & (1u << b)) want[k++] = tv[b];
      --k;
      const size_t f = gm_complex_find(one.cx, k, want);
      const size_t nl = k == 1 ? 6 : 4;
      size_t q = 0;
      while (q < nl && idx[k][q] != f) ++q;
      cr_assert_lt(q, nl);
      sum[k][f] += pieces[k][q];
    }
  }
  for (size_t k = 0; k < n; ++k) {
    expect_same_bits(sum[k], gm_geometry_dual_volumes(one.g, k),
                     gm_complex_count(one.cx, k) * sizeof(double),
                     "dual volumes vs the direct formula");
    free(sum[k]);
  }
  gm_geometry_free(one.g);
  gm_complex_free(one.cx);
}
