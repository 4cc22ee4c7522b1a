/* geomint sparse: a small compressed-sparse-row matrix type and sparse direct solvers.
 *
 * gm_csr is a plain struct whose fields may be read (and, with care, the values written): row i
 * holds the entries col[row_start[i] .. row_start[i+1]) with ascending column indices and no
 * duplicates (every function here returns matrices in that form and accepts only that form).
 * Factorizations go through SuiteSparse: CHOLMOD for symmetric positive definite matrices,
 * UMFPACK for general square ones (DESIGN §7). Each factorization is an object that owns its
 * workspace, so gm_sparse_*_solve allocates nothing. Pointer parameters are borrowed unless a
 * comment says otherwise. */
#ifndef GEOMINT_SPARSE_H
#define GEOMINT_SPARSE_H

#include <stddef.h>

#include "geomint/core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gm_csr {
  size_t n_rows, n_cols;
  size_t *row_start; /* n_rows + 1 offsets; row_start[n_rows] is the number of entries */
  size_t *col;       /* column of each entry, ascending within a row */
  double *val;       /* value of each entry */
} gm_csr;

/* A matrix with room for nnz entries; row_start is zeroed (an all-zero matrix when nnz = 0). */
gm_status gm_csr_create(size_t n_rows, size_t n_cols, size_t nnz, gm_csr **out);
void gm_csr_free(gm_csr *a);
size_t gm_csr_nnz(const gm_csr *a);

/* Assemble from n triplets (rows[i], cols[i], vals[i]); duplicates are summed, entries that sum
 * to exactly zero are kept (use gm_csr_drop_zeros). Errors: GM_EINVAL for an index out of range
 * (the message names the triplet), GM_EDOMAIN for a non-finite value. */
gm_status gm_csr_from_triplets(size_t n_rows, size_t n_cols, size_t n, const size_t *rows,
                               const size_t *cols, const double *vals, gm_csr **out,
                               gm_error *err);
/* The n×n diagonal matrix diag(d) (d copied; d == NULL gives the identity). */
gm_status gm_csr_diagonal(size_t n, const double *d, gm_csr **out);
gm_status gm_csr_copy(const gm_csr *a, gm_csr **out);
gm_status gm_csr_transpose(const gm_csr *a, gm_csr **out);
/* out = a b (GM_EINVAL when a->n_cols != b->n_rows). */
gm_status gm_csr_multiply(const gm_csr *a, const gm_csr *b, gm_csr **out);
/* out = alpha a + beta b (same shape). */
gm_status gm_csr_add(double alpha, const gm_csr *a, double beta, const gm_csr *b, gm_csr **out);
/* In place: a = s a; a = diag(d) a; a = a diag(d). */
void gm_csr_scale(gm_csr *a, double s);
void gm_csr_scale_rows(gm_csr *a, const double *d);
void gm_csr_scale_cols(gm_csr *a, const double *d);
/* Remove entries with |value| <= tol, in place. */
void gm_csr_drop_zeros(gm_csr *a, double tol);
/* y = alpha a x + beta y (beta == 0 ignores the old y, even NaN); y and x must not overlap. */
void gm_csr_matvec(const gm_csr *a, double alpha, const double *x, double beta, double *y);
/* y = alpha aᵀ x + beta y. */
void gm_csr_matvec_transpose(const gm_csr *a, double alpha, const double *x, double beta,
                             double *y);
/* max |a_ij| (0 for an empty matrix). */
double gm_csr_max_abs(const gm_csr *a);
/* Value of entry (i, j) (0 when not stored). */
double gm_csr_get(const gm_csr *a, size_t i, size_t j);
/* max |a_ij - a_ji| relative to max |a_ij| (0 for a symmetric matrix); -1 when not square. */
double gm_csr_asymmetry(const gm_csr *a);

/* ---- sparse Cholesky (CHOLMOD) --------------------------------------------------------- */

typedef struct gm_sparse_cholesky gm_sparse_cholesky;

/* Analyse (fill-reducing ordering) and factor the symmetric positive definite matrix a. Both
 * triangles must be stored; only the lower one is read. Errors: GM_EINVAL (not square, not
 * finite), GM_ESINGULAR (not positive definite: the message gives the failing column). */
gm_status gm_sparse_cholesky_create(const gm_csr *a, gm_sparse_cholesky **out, gm_error *err);
void gm_sparse_cholesky_free(gm_sparse_cholesky *ch);
/* Factor a new matrix with the same sparsity pattern, reusing the analysis. */
gm_status gm_sparse_cholesky_refactor(gm_sparse_cholesky *ch, const gm_csr *a);
/* Solve A x = b (n values each; x and b may alias). No allocation after the first call. */
gm_status gm_sparse_cholesky_solve(gm_sparse_cholesky *ch, const double *b, double *x);
size_t gm_sparse_cholesky_size(const gm_sparse_cholesky *ch);
/* Entries of the factor L (including fill-in). */
double gm_sparse_cholesky_factor_nnz(const gm_sparse_cholesky *ch);
const char *gm_sparse_cholesky_errmsg(const gm_sparse_cholesky *ch);

/* ---- sparse LU (UMFPACK) --------------------------------------------------------------- */

typedef struct gm_sparse_lu gm_sparse_lu;

/* Analyse and factor the square matrix a. GM_ESINGULAR when UMFPACK finds it singular. */
gm_status gm_sparse_lu_create(const gm_csr *a, gm_sparse_lu **out, gm_error *err);
void gm_sparse_lu_free(gm_sparse_lu *lu);
/* Solve A x = b (x and b must not alias). No allocation. */
gm_status gm_sparse_lu_solve(gm_sparse_lu *lu, const double *b, double *x);
const char *gm_sparse_lu_errmsg(const gm_sparse_lu *lu);

#ifdef __cplusplus
}
#endif
#endif
