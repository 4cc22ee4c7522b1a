/* Sparse direct solvers through SuiteSparse: CHOLMOD (Chen, Davis, Hager, Rajamanickam 2008) for
 * symmetric positive definite matrices and UMFPACK (Davis 2004) for general square ones.
 *
 * A CSR matrix read as compressed-sparse-column is its transpose. For CHOLMOD the matrix is
 * symmetric, so the CSR arrays are passed as they are (stype = 1 reads the "upper" CSC part, which
 * is the lower CSR triangle). For UMFPACK the CSC matrix is Aᵀ and we solve with UMFPACK_At. Index
 * arrays are copied once into SuiteSparse's 64-bit integer type. Each object owns its own
 * cholmod_common (no global state) with printing switched off (the library never prints). */
#include <cholmod.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <umfpack.h>

#include "core/internal.h"
#include "geomint/sparse.h"

typedef SuiteSparse_long ss_long;

/* Copy the CSR index arrays into SuiteSparse's integer type. */
static int copy_indices(const gm_csr *a, ss_long **p, ss_long **i) {
  size_t nnz = gm_csr_nnz(a);
  *p = malloc((a->n_rows + 1) * sizeof(ss_long));
  *i = malloc((nnz ? nnz : 1) * sizeof(ss_long));
  if (*p == NULL || *i == NULL) return 0;
  for (size_t r = 0; r <= a->n_rows; ++r) (*p)[r] = (ss_long)a->row_start[r];
  for (size_t k = 0; k < nnz; ++k) (*i)[k] = (ss_long)a->col[k];
  return 1;
}

static int csr_finite(const gm_csr *a) {
  size_t nnz = gm_csr_nnz(a);
  return gm_first_nonfinite(nnz, a->val) == nnz;
}

/* ---- CHOLMOD --------------------------------------------------------------------------- */

struct gm_sparse_cholesky {
  size_t n, nnz;
  ss_long *p, *i;
  cholmod_common common;
  int started;
  cholmod_factor *factor;
  cholmod_dense *x, *y, *e; /* workspace of cholmod_l_solve2, kept between solves */
  char errmsg[GM_ERRMSG_SIZE];
};

static cholmod_sparse sparse_view(gm_sparse_cholesky *ch, const gm_csr *a) {
  cholmod_sparse s;
  memset(&s, 0, sizeof s);
  s.nrow = ch->n;
  s.ncol = ch->n;
  s.nzmax = ch->nnz ? ch->nnz : 1;
  s.p = ch->p;
  s.i = ch->i;
  s.x = a->val;
  s.stype = 1;
  s.itype = CHOLMOD_LONG;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

static gm_status factor_now(gm_sparse_cholesky *ch, const gm_csr *a) {
  cholmod_sparse s = sparse_view(ch, a);
  if (!cholmod_l_factorize(&s, ch->factor, &ch->common) || ch->common.status < 0)
    return gm_fail(ch->errmsg, sizeof ch->errmsg,
                   ch->common.status == CHOLMOD_OUT_OF_MEMORY ? GM_ENOMEM : GM_EINVAL,
                   "CHOLMOD factorization failed (status %d)", ch->common.status);
  /* Simplicial factors are LDLᵀ, which succeeds on indefinite matrices: a positive definite
   * matrix has D > 0 (D is stored on the diagonal of the packed factor, column j at p[j]). */
  cholmod_factor *f = ch->factor;
  if (!f->is_super && !f->is_ll && ch->common.status == CHOLMOD_OK) {
    const ss_long *fp = f->p;
    const double *fx = f->x;
    for (size_t j = 0; j < ch->n; ++j)
      if (!(fx[fp[j]] > 0.0))
        return gm_fail(ch->errmsg, sizeof ch->errmsg, GM_ESINGULAR,
                       "matrix is not positive definite: pivot %zu of %zu is %.3g", j, ch->n,
                       fx[fp[j]]);
  }
  if (ch->common.status == CHOLMOD_NOT_POSDEF || (size_t)ch->factor->minor < ch->n)
    return gm_fail(ch->errmsg, sizeof ch->errmsg, GM_ESINGULAR,
                   "matrix is not positive definite: CHOLMOD stopped at column %zu of %zu",
                   (size_t)ch->factor->minor, ch->n);
  return GM_OK;
}

static int same_pattern(const gm_sparse_cholesky *ch, const gm_csr *a) {
  if (a->n_rows != ch->n || a->n_cols != ch->n || gm_csr_nnz(a) != ch->nnz) return 0;
  for (size_t r = 0; r <= ch->n; ++r)
    if ((size_t)ch->p[r] != a->row_start[r]) return 0;
  for (size_t k = 0; k < ch->nnz; ++k)
    if ((size_t)ch->i[k] != a->col[k]) return 0;
  return 1;
}

gm_status gm_sparse_cholesky_create(const gm_csr *a, gm_sparse_cholesky **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (a == NULL) return gm_error_set(err, GM_EINVAL, "matrix is NULL");
  if (a->n_rows != a->n_cols || a->n_rows == 0)
    return gm_error_set(err, GM_EINVAL, "Cholesky needs a non-empty square matrix, not %zu x %zu",
                        a->n_rows, a->n_cols);
  if (!csr_finite(a)) return gm_error_set(err, GM_EDOMAIN, "matrix has non-finite entries");
  gm_sparse_cholesky *ch = calloc(1, sizeof *ch);
  if (ch == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  ch->n = a->n_rows;
  ch->nnz = gm_csr_nnz(a);
  if (!copy_indices(a, &ch->p, &ch->i)) {
    gm_sparse_cholesky_free(ch);
    return gm_error_set(err, GM_ENOMEM, "out of memory for a %zu x %zu matrix", a->n_rows,
                        a->n_cols);
  }
  cholmod_l_start(&ch->common);
  ch->started = 1;
  ch->common.print = 0;
  cholmod_sparse s = sparse_view(ch, a);
  ch->factor = cholmod_l_analyze(&s, &ch->common);
  if (ch->factor == NULL) {
    gm_status st = ch->common.status == CHOLMOD_OUT_OF_MEMORY ? GM_ENOMEM : GM_EINVAL;
    gm_error_set(err, st, "CHOLMOD analysis failed (status %d)", ch->common.status);
    gm_sparse_cholesky_free(ch);
    return st;
  }
  gm_status st = factor_now(ch, a);
  if (st == GM_OK) {
    /* One solve with a zero right-hand side allocates the solve workspace now. */
    double *zero = calloc(ch->n, sizeof(double));
    if (zero == NULL)
      st = gm_fail(ch->errmsg, sizeof ch->errmsg, GM_ENOMEM, "out of memory");
    else
      st = gm_sparse_cholesky_solve(ch, zero, zero);
    free(zero);
  }
  if (st != GM_OK) {
    gm_error_set(err, st, "%s", ch->errmsg);
    gm_sparse_cholesky_free(ch);
    return st;
  }
  *out = ch;
  return GM_OK;
}

void gm_sparse_cholesky_free(gm_sparse_cholesky *ch) {
  if (ch == NULL) return;
  if (ch->started) {
    cholmod_l_free_factor(&ch->factor, &ch->common);
    cholmod_l_free_dense(&ch->x, &ch->common);
    cholmod_l_free_dense(&ch->y, &ch->common);
    cholmod_l_free_dense(&ch->e, &ch->common);
    cholmod_l_finish(&ch->common);
  }
  free(ch->p);
  free(ch->i);
  free(ch);
}

gm_status gm_sparse_cholesky_refactor(gm_sparse_cholesky *ch, const gm_csr *a) {
  if (ch == NULL || a == NULL) return GM_EINVAL;
  if (!same_pattern(ch, a))
    return gm_fail(ch->errmsg, sizeof ch->errmsg, GM_EINVAL,
                   "refactor needs the sparsity pattern of the analysed matrix");
  if (!csr_finite(a))
    return gm_fail(ch->errmsg, sizeof ch->errmsg, GM_EDOMAIN, "matrix has non-finite entries");
  return factor_now(ch, a);
}

gm_status gm_sparse_cholesky_solve(gm_sparse_cholesky *ch, const double *b, double *x) {
  if (ch == NULL || b == NULL || x == NULL) return GM_EINVAL;
  cholmod_dense rhs;
  memset(&rhs, 0, sizeof rhs);
  rhs.nrow = ch->n;
  rhs.ncol = 1;
  rhs.nzmax = ch->n;
  rhs.d = ch->n;
  rhs.x = (void *)(uintptr_t)b; /* read only: CHOLMOD does not write B */
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  if (!cholmod_l_solve2(CHOLMOD_A, ch->factor, &rhs, NULL, &ch->x, NULL, &ch->y, &ch->e,
                        &ch->common))
    return gm_fail(ch->errmsg, sizeof ch->errmsg, GM_ENOMEM, "CHOLMOD solve failed (status %d)",
                   ch->common.status);
  memmove(x, ch->x->x, ch->n * sizeof(double));
  if (gm_first_nonfinite(ch->n, x) != ch->n)
    return gm_fail(ch->errmsg, sizeof ch->errmsg, GM_EDOMAIN, "solution is not finite");
  return GM_OK;
}

size_t gm_sparse_cholesky_size(const gm_sparse_cholesky *ch) { return ch ? ch->n : 0; }

double gm_sparse_cholesky_factor_nnz(const gm_sparse_cholesky *ch) {
  return ch ? ch->common.lnz : 0.0;
}

const char *gm_sparse_cholesky_errmsg(const gm_sparse_cholesky *ch) {
  return ch ? ch->errmsg : "no Cholesky object";
}

/* ---- UMFPACK --------------------------------------------------------------------------- */

struct gm_sparse_lu {
  size_t n;
  ss_long *p, *i;
  double *x;
  void *symbolic, *numeric;
  double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
  ss_long *wi;
  double *w;
  char errmsg[GM_ERRMSG_SIZE];
};

gm_status gm_sparse_lu_create(const gm_csr *a, gm_sparse_lu **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (a == NULL) return gm_error_set(err, GM_EINVAL, "matrix is NULL");
  if (a->n_rows != a->n_cols || a->n_rows == 0)
    return gm_error_set(err, GM_EINVAL, "LU needs a non-empty square matrix, not %zu x %zu",
                        a->n_rows, a->n_cols);
  if (!csr_finite(a)) return gm_error_set(err, GM_EDOMAIN, "matrix has non-finite entries");
  gm_sparse_lu *lu = calloc(1, sizeof *lu);
  if (lu == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  size_t n = a->n_rows, nnz = gm_csr_nnz(a);
  lu->n = n;
  lu->x = malloc((nnz ? nnz : 1) * sizeof(double));
  lu->wi = malloc(n * sizeof(ss_long));
  lu->w = malloc(5 * n * sizeof(double)); /* 5n: with iterative refinement (UMFPACK guide) */
  if (!copy_indices(a, &lu->p, &lu->i) || !lu->x || !lu->wi || !lu->w) {
    gm_sparse_lu_free(lu);
    return gm_error_set(err, GM_ENOMEM, "out of memory for a %zu x %zu matrix", n, n);
  }
  if (nnz) memcpy(lu->x, a->val, nnz * sizeof(double));
  umfpack_dl_defaults(lu->control);
  lu->control[UMFPACK_PRL] = 0;
  ss_long nl = (ss_long)n;
  ss_long rc = umfpack_dl_symbolic(nl, nl, lu->p, lu->i, lu->x, &lu->symbolic, lu->control,
                                   lu->info);
  if (rc != UMFPACK_OK) {
    gm_status st = rc == UMFPACK_ERROR_out_of_memory ? GM_ENOMEM : GM_EINVAL;
    gm_error_set(err, st, "UMFPACK symbolic analysis failed (status %ld)", (long)rc);
    gm_sparse_lu_free(lu);
    return st;
  }
  rc = umfpack_dl_numeric(lu->p, lu->i, lu->x, lu->symbolic, &lu->numeric, lu->control, lu->info);
  if (rc != UMFPACK_OK) {
    gm_status st = rc == UMFPACK_WARNING_singular_matrix ? GM_ESINGULAR
                   : rc == UMFPACK_ERROR_out_of_memory   ? GM_ENOMEM
                                                         : GM_EINVAL;
    gm_error_set(err, st, "UMFPACK factorization failed: %s (status %ld)",
                 st == GM_ESINGULAR ? "matrix is singular" : "error", (long)rc);
    gm_sparse_lu_free(lu);
    return st;
  }
  *out = lu;
  return GM_OK;
}

void gm_sparse_lu_free(gm_sparse_lu *lu) {
  if (lu == NULL) return;
  if (lu->numeric) umfpack_dl_free_numeric(&lu->numeric);
  if (lu->symbolic) umfpack_dl_free_symbolic(&lu->symbolic);
  free(lu->p);
  free(lu->i);
  free(lu->x);
  free(lu->wi);
  free(lu->w);
  free(lu);
}

gm_status gm_sparse_lu_solve(gm_sparse_lu *lu, const double *b, double *x) {
  if (lu == NULL || b == NULL || x == NULL || b == x) return GM_EINVAL;
  ss_long rc = umfpack_dl_wsolve(UMFPACK_At, lu->p, lu->i, lu->x, x, b, lu->numeric, lu->control,
                                 lu->info, lu->wi, lu->w);
  if (rc != UMFPACK_OK)
    return gm_fail(lu->errmsg, sizeof lu->errmsg, GM_ESINGULAR, "UMFPACK solve failed (status %ld)",
                   (long)rc);
  if (gm_first_nonfinite(lu->n, x) != lu->n)
    return gm_fail(lu->errmsg, sizeof lu->errmsg, GM_EDOMAIN, "solution is not finite");
  return GM_OK;
}

const char *gm_sparse_lu_errmsg(const gm_sparse_lu *lu) { return lu ? lu->errmsg : "no LU object"; }
