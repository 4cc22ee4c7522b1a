/* Dense linear algebra on row-major matrices, through LAPACKE.
 *
 * LU: a row-major n×n array is, read column-major, the transpose Aᵀ. We factor Aᵀ = P L U in
 * LAPACK's native column-major layout and solve A x = (Aᵀ)ᵀ x = b with trans = 'T'. This is the
 * same partial-pivoting LU (on the columns of A instead of its rows), but it avoids the transposed
 * copy that LAPACKE's LAPACK_ROW_MAJOR wrappers allocate on every call: the Newton solver calls
 * these functions inside integration steps, where nothing may be allocated (DESIGN §3).
 *
 * Systems up to n = SMALL_LU (the stage equations of implicit integrators) are factored here
 * instead: row-major Gaussian elimination with partial pivoting (Golub & Van Loan, Matrix
 * Computations, 4th ed. (2013), Algorithm 3.4.1). At these sizes LAPACK's call overhead and
 * OpenBLAS's threads are most of the cost (measured: a 16×16 factorization and its solves per
 * gauss-4 step took 3× longer through OpenBLAS; 5000 factorizations of 144×144 took 3.5 s of
 * thread start-up and waiting on two cores). Which path factors a matrix depends only on n, so
 * factors and pivots always meet the matching solve. */
#include <lapacke.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include "core/internal.h"

/* The public API passes pivots as int*, handed straight to LAPACK. */
_Static_assert(sizeof(lapack_int) == sizeof(int), "geomint needs a LAPACK with 32-bit integers");

static int size_ok(size_t n) { return n > 0 && n <= (size_t)INT_MAX; }

static int all_finite(size_t count, const double *x) {
  return gm_first_nonfinite(count, x) == count;
}

/* The upper triangle (i <= j) of a row-major n×n matrix is finite. */
static int upper_finite(size_t n, const double *a) {
  for (size_t i = 0; i < n; ++i)
    if (!all_finite(n - i, a + i * n + i)) return 0;
  return 1;
}

static gm_status from_lapack_info(lapack_int info) {
  if (info == 0) return GM_OK;
  if (info == LAPACK_WORK_MEMORY_ERROR || info == LAPACK_TRANSPOSE_MEMORY_ERROR) return GM_ENOMEM;
  return GM_ELAPACK;
}

#define SMALL_LU 256

/* PA = LU in place (unit lower L below the diagonal); ipiv[k] = row swapped with row k. */
static gm_status small_lu_factor(size_t n, double *a, int *ipiv) {
  for (size_t k = 0; k < n; ++k) {
    size_t p = k;
    double big = fabs(a[k * n + k]);
    for (size_t i = k + 1; i < n; ++i)
      if (fabs(a[i * n + k]) > big) {
        big = fabs(a[i * n + k]);
        p = i;
      }
    ipiv[k] = (int)p;
    if (big == 0.0) return GM_ESINGULAR;
    if (p != k)
      for (size_t j = 0; j < n; ++j) {
        double t = a[k * n + j];
        a[k * n + j] = a[p * n + j];
        a[p * n + j] = t;
      }
    const double inv = 1.0 / a[k * n + k];
    for (size_t i = k + 1; i < n; ++i) {
      double l = a[i * n + k] * inv;
      a[i * n + k] = l;
      if (l == 0.0) continue;
      for (size_t j = k + 1; j < n; ++j) a[i * n + j] -= l * a[k * n + j];
    }
  }
  return GM_OK;
}

static void small_lu_solve(size_t n, const double *lu, const int *ipiv, double *b) {
  for (size_t k = 0; k < n; ++k) {
    size_t p = (size_t)ipiv[k];
    if (p != k) {
      double t = b[k];
      b[k] = b[p];
      b[p] = t;
    }
  }
  for (size_t i = 1; i < n; ++i) {
    double sum = b[i];
    for (size_t j = 0; j < i; ++j) sum -= lu[i * n + j] * b[j];
    b[i] = sum;
  }
  for (size_t i = n; i-- > 0;) {
    double sum = b[i];
    for (size_t j = i + 1; j < n; ++j) sum -= lu[i * n + j] * b[j];
    b[i] = sum / lu[i * n + i];
  }
}

gm_status gm_lu_factor(size_t n, double *a, int *ipiv) {
  if (a == NULL || ipiv == NULL || !size_ok(n)) return GM_EINVAL;
  if (!all_finite(n * n, a)) return GM_EDOMAIN;
  if (n <= SMALL_LU) return small_lu_factor(n, a, ipiv);
  lapack_int m = (lapack_int)n;
  /* The _work variant skips LAPACKE's NaN scan: the input is already known to be finite. */
  lapack_int info = LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, m, m, a, m, ipiv);
  if (info > 0) return GM_ESINGULAR; /* U(info, info) is exactly zero */
  return from_lapack_info(info);
}

/* Solve with factors of Aᵀ (see the top of this file); inputs already checked. */
static gm_status solve_factored(size_t n, const double *lu, const int *ipiv, double *b) {
  if (n <= SMALL_LU) {
    small_lu_solve(n, lu, ipiv, b);
    return GM_OK;
  }
  lapack_int m = (lapack_int)n;
  return from_lapack_info(LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'T', m, 1, lu, m, ipiv, b, m));
}

/* The factors are finite when gm_lu_factor succeeded, so only b is checked here: a solve runs
 * at every Newton iteration. */
gm_status gm_lu_solve(size_t n, const double *lu, const int *ipiv, double *b) {
  if (lu == NULL || ipiv == NULL || b == NULL || !size_ok(n)) return GM_EINVAL;
  if (!all_finite(n, b)) return GM_EDOMAIN;
  return solve_factored(n, lu, ipiv, b);
}

gm_status gm_dense_solve(size_t n, double *a, double *b) {
  if (a == NULL || b == NULL || !size_ok(n)) return GM_EINVAL;
  if (!all_finite(n, b)) return GM_EDOMAIN;
  /* Pivots of small systems live on the stack, so that common calls do not allocate. */
  enum { SMALL = 64 };
  int small[SMALL];
  int *ipiv = n <= SMALL ? small : malloc(n * sizeof *ipiv);
  if (ipiv == NULL) return GM_ENOMEM;
  gm_status s = gm_lu_factor(n, a, ipiv);
  if (s == GM_OK) s = solve_factored(n, a, ipiv, b);
  if (ipiv != small) free(ipiv);
  return s;
}

gm_status gm_symmetric_eigen(size_t n, double *a, double *eigenvalues) {
  if (a == NULL || eigenvalues == NULL || !size_ok(n)) return GM_EINVAL;
  if (!upper_finite(n, a)) return GM_EDOMAIN;
  /* dsyev (QR iteration) returns eigenvalues in ascending order and orthonormal eigenvectors;
   * in row-major layout column j of a is the eigenvector of eigenvalues[j]. */
  lapack_int m = (lapack_int)n;
  lapack_int info = LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'V', 'U', m, a, m, eigenvalues);
  return from_lapack_info(info); /* info > 0: the QR iteration did not converge */
}
