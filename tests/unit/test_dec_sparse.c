/* Sparse CSR matrices and the CHOLMOD / UMFPACK wrappers. */
#include <string.h>

#include "dec_util.h"

Test(dec_sparse, triplets_transpose_multiply_add) {
  const size_t r[] = {0, 1, 0, 2, 1, 0}, c[] = {1, 0, 1, 2, 2, 0};
  const double v[] = {1, 2, 3, 4, 5, 6};
  gm_csr *a = NULL, *t = NULL, *p = NULL, *s = NULL;
  cr_assert_eq(gm_csr_from_triplets(3, 3, 6, r, c, v, &a, NULL), GM_OK);
  cr_expect_eq(gm_csr_nnz(a), 5); /* (0,1) summed */
  cr_expect_eq(gm_csr_get(a, 0, 1), 4.0);
  cr_assert_eq(gm_csr_transpose(a, &t), GM_OK);
  cr_expect_eq(gm_csr_get(t, 1, 0), 4.0);
  cr_expect_eq(gm_csr_get(t, 2, 1), 5.0);
  cr_assert_eq(gm_csr_multiply(a, t, &p), GM_OK); /* A Aᵀ is symmetric */
  cr_expect_eq(gm_csr_asymmetry(p), 0.0);
  /* (A Aᵀ)_00 = 6² + 4² */
  cr_expect_eq(gm_csr_get(p, 0, 0), 52.0);
  cr_assert_eq(gm_csr_add(2.0, a, -1.0, t, &s), GM_OK);
  cr_expect_eq(gm_csr_get(s, 1, 0), 2.0 * 2.0 - 4.0);
  double x[3] = {1, 2, 3}, y[3];
  gm_csr_matvec(a, 1.0, x, 0.0, y);
  cr_expect_eq(y[0], 6.0 + 8.0);
  cr_expect_eq(y[1], 2.0 + 15.0);
  gm_error err = {{0}};
  const size_t bad[] = {5};
  cr_expect_eq(gm_csr_from_triplets(3, 3, 1, bad, c, v, &a, &err), GM_EINVAL);
  cr_expect(strstr(err.message, "triplet 0") != NULL, "%s", err.message);
  gm_csr_free(a), gm_csr_free(t), gm_csr_free(p), gm_csr_free(s);
}

Test(dec_sparse, cholmod_and_umfpack_solve) {
  const size_t n = 200;
  size_t *r = malloc(3 * n * sizeof(size_t)), *c = malloc(3 * n * sizeof(size_t));
  double *v = malloc(3 * n * sizeof(double));
  size_t w = 0;
  for (size_t i = 0; i < n; ++i) {
    r[w] = i, c[w] = i, v[w++] = 2.5;
    if (i > 0) r[w] = i, c[w] = i - 1, v[w++] = -1.0;
    if (i + 1 < n) r[w] = i, c[w] = i + 1, v[w++] = -1.0;
  }
  gm_csr *a = NULL;
  cr_assert_eq(gm_csr_from_triplets(n, n, w, r, c, v, &a, NULL), GM_OK);
  double *x = malloc(n * sizeof(double)), *b = malloc(n * sizeof(double)), *y = malloc(n * sizeof(double));
  test_random_fill(n, x, 1);
  gm_csr_matvec(a, 1.0, x, 0.0, b);
  gm_sparse_cholesky *ch = NULL;
  cr_assert_eq(gm_sparse_cholesky_create(a, &ch, NULL), GM_OK);
  cr_assert_eq(gm_sparse_cholesky_solve(ch, b, y), GM_OK);
  for (size_t i = 0; i < n; ++i) cr_expect(fabs(y[i] - x[i]) <= 1e-13);
  gm_sparse_cholesky_free(ch);
  /* UMFPACK on a non-symmetric perturbation */
  a->val[1] += 0.3;
  gm_csr_matvec(a, 1.0, x, 0.0, b);
  gm_sparse_lu *lu = NULL;
  cr_assert_eq(gm_sparse_lu_create(a, &lu, NULL), GM_OK);
  cr_assert_eq(gm_sparse_lu_solve(lu, b, y), GM_OK);
  for (size_t i = 0; i < n; ++i) cr_expect(fabs(y[i] - x[i]) <= 1e-13);
  gm_sparse_lu_free(lu);
  /* indefinite: CHOLMOD refuses with the column */
  gm_csr_scale(a, -1.0);
  gm_error err = {{0}};
  gm_status cst = gm_sparse_cholesky_create(a, &ch, &err);
  cr_expect_eq(cst, GM_ESINGULAR, "status %d: %s", (int)cst, err.message);
  cr_expect(strstr(err.message, "not positive definite") != NULL, "%s", err.message);
  /* singular: UMFPACK says so */
  for (size_t p = a->row_start[0]; p < a->row_start[1]; ++p) a->val[p] = 0.0;
  cr_expect_eq(gm_sparse_lu_create(a, &lu, &err), GM_ESINGULAR);
  free(r), free(c), free(v), free(x), free(b), free(y);
  gm_csr_free(a);
}
