/* Geometric multigrid: V-cycle with Gauss–Seidel smoothing and Galerkin coarse operators, and
 * conjugate gradients preconditioned by it.
 *
 * V-cycle (Briggs, Henson, McCormick, "A Multigrid Tutorial", 2nd ed., SIAM 2000, §3 and §10;
 * Galerkin coarse operator A_c = Pᵀ A P, ibid. eq. (10.3) / the variational property): on
 * level l, ν₁ forward Gauss–Seidel sweeps, restriction of the residual by Pᵀ, the cycle on level
 * l+1 from zero, correction x += P x_c, ν₂ backward sweeps; the coarsest level is solved by
 * CHOLMOD. With ν₁ = ν₂ the backward sweep is the adjoint of the forward one in the A inner
 * product, so the cycle is a symmetric positive definite preconditioner for CG (Hackbusch,
 * "Multi-Grid Methods and Applications", 1985, §10.7), and PCG is the textbook algorithm
 * (Saad, "Iterative Methods for Sparse Linear Systems", 2nd ed., Alg. 9.1). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/multigrid.h"

typedef struct level {
  gm_csr *A, *P, *PT; /* P, PT: to and from the next coarser level (NULL on the coarsest) */
  size_t *diag;       /* position of the diagonal entry of each row */
  double *x, *b, *r;
} level;

struct gm_multigrid {
  size_t n_levels;
  level *lv;
  gm_sparse_cholesky *coarse;
  gm_multigrid_options opt;
  double *work[4]; /* PCG: r, z, p, q on the finest level */
  char msg[GM_ERRMSG_SIZE];
};

gm_multigrid_options gm_multigrid_defaults(void) {
  gm_multigrid_options o = {2, 2, 200, 1e-10};
  return o;
}

void gm_multigrid_free(gm_multigrid *mg) {
  if (mg == NULL) return;
  for (size_t l = 0; mg->lv && l < mg->n_levels; ++l) {
    gm_csr_free(mg->lv[l].A);
    gm_csr_free(mg->lv[l].P);
    gm_csr_free(mg->lv[l].PT);
    free(mg->lv[l].diag);
    free(mg->lv[l].x), free(mg->lv[l].b), free(mg->lv[l].r);
  }
  free(mg->lv);
  gm_sparse_cholesky_free(mg->coarse);
  for (int i = 0; i < 4; ++i) free(mg->work[i]);
  free(mg);
}

gm_status gm_multigrid_create(const gm_csr *A, size_t n_prolongations, const gm_csr *const *P,
                              const gm_multigrid_options *options, gm_multigrid **out,
                              gm_error *err) {
  if (A == NULL || out == NULL || (n_prolongations > 0 && P == NULL))
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  if (A->n_rows != A->n_cols || A->n_rows == 0)
    return gm_error_set(err, GM_EINVAL, "the matrix is %zu × %zu: needs a non-empty square one",
                        A->n_rows, A->n_cols);
  for (size_t l = 0; l < n_prolongations; ++l) {
    size_t rows_want = l == 0 ? A->n_rows : P[l - 1]->n_cols;
    if (P[l] == NULL || P[l]->n_rows != rows_want || P[l]->n_cols == 0)
      return gm_error_set(err, GM_EINVAL,
                          "prolongation %zu is %zu × %zu: it must have %zu rows (the unknowns of "
                          "level %zu) and at least one column",
                          l, P[l] ? P[l]->n_rows : 0, P[l] ? P[l]->n_cols : 0, rows_want, l);
  }
  gm_multigrid *mg = calloc(1, sizeof *mg);
  if (mg == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  mg->opt = options ? *options : gm_multigrid_defaults();
  if (!(mg->opt.rtol > 0.0) || mg->opt.max_iterations == 0) {
    gm_multigrid_free(mg);
    return gm_error_set(err, GM_EINVAL, "rtol must be > 0 and max_iterations >= 1");
  }
  mg->n_levels = n_prolongations + 1;
  mg->lv = calloc(mg->n_levels, sizeof(level));
  gm_status st = mg->lv ? gm_csr_copy(A, &mg->lv[0].A) : GM_ENOMEM;
  for (size_t l = 0; st == GM_OK && l < mg->n_levels; ++l) {
    level *L = &mg->lv[l];
    if (l + 1 < mg->n_levels) {
      gm_csr *AP = NULL;
      st = gm_csr_copy(P[l], &L->P);
      if (st == GM_OK) st = gm_csr_transpose(P[l], &L->PT);
      if (st == GM_OK) st = gm_csr_multiply(L->A, L->P, &AP);
      if (st == GM_OK) st = gm_csr_multiply(L->PT, AP, &mg->lv[l + 1].A);
      gm_csr_free(AP);
      if (st != GM_OK) break;
    }
    const size_t n = L->A->n_rows;
    L->diag = malloc(n * sizeof(size_t));
    L->x = malloc(n * sizeof(double));
    L->b = malloc(n * sizeof(double));
    L->r = malloc(n * sizeof(double));
    if (!L->diag || !L->x || !L->b || !L->r) {
      st = GM_ENOMEM;
      break;
    }
    for (size_t i = 0; i < n; ++i) {
      L->diag[i] = SIZE_MAX;
      for (size_t p = L->A->row_start[i]; p < L->A->row_start[i + 1]; ++p)
        if (L->A->col[p] == i) L->diag[i] = p;
      if (L->diag[i] == SIZE_MAX || !(L->A->val[L->diag[i]] > 0.0)) {
        gm_multigrid_free(mg);
        return gm_error_set(err, GM_ESINGULAR,
                            "level %zu: diagonal entry %zu is %g, not positive (Gauss–Seidel needs "
                            "a positive diagonal)",
                            l, i, L->diag[i] == SIZE_MAX ? 0.0 : L->A->val[L->diag[i]]);
      }
    }
  }
  for (int i = 0; st == GM_OK && i < 4; ++i)
    if ((mg->work[i] = malloc(A->n_rows * sizeof(double))) == NULL) st = GM_ENOMEM;
  if (st != GM_OK) {
    gm_multigrid_free(mg);
    return gm_error_set(err, st, "out of memory building the multigrid hierarchy");
  }
  st = gm_sparse_cholesky_create(mg->lv[mg->n_levels - 1].A, &mg->coarse, err);
  if (st != GM_OK) {
    gm_multigrid_free(mg);
    return st;
  }
  *out = mg;
  return GM_OK;
}

size_t gm_multigrid_levels(const gm_multigrid *mg) { return mg ? mg->n_levels : 0; }

size_t gm_multigrid_level_size(const gm_multigrid *mg, size_t level_index, size_t *nnz) {
  if (mg == NULL || level_index >= mg->n_levels) return 0;
  if (nnz) *nnz = gm_csr_nnz(mg->lv[level_index].A);
  return mg->lv[level_index].A->n_rows;
}

const char *gm_multigrid_errmsg(const gm_multigrid *mg) { return mg ? mg->msg : ""; }

static void gauss_seidel(const level *L, const double *b, double *x, int backward) {
  const gm_csr *A = L->A;
  const size_t n = A->n_rows;
  for (size_t q = 0; q < n; ++q) {
    const size_t i = backward ? n - 1 - q : q;
    double s = b[i];
    for (size_t p = A->row_start[i]; p < A->row_start[i + 1]; ++p) s -= A->val[p] * x[A->col[p]];
    x[i] += s / A->val[L->diag[i]];
  }
}

static void cycle(gm_multigrid *mg, size_t l) {
  level *L = &mg->lv[l];
  if (l + 1 == mg->n_levels) {
    gm_sparse_cholesky_solve(mg->coarse, L->b, L->x);
    return;
  }
  for (size_t s = 0; s < mg->opt.pre_smooth; ++s) gauss_seidel(L, L->b, L->x, 0);
  memcpy(L->r, L->b, L->A->n_rows * sizeof(double));
  gm_csr_matvec(L->A, -1.0, L->x, 1.0, L->r);
  level *C = &mg->lv[l + 1];
  gm_csr_matvec(L->PT, 1.0, L->r, 0.0, C->b);
  memset(C->x, 0, C->A->n_rows * sizeof(double));
  cycle(mg, l + 1);
  gm_csr_matvec(L->P, 1.0, C->x, 1.0, L->x);
  for (size_t s = 0; s < mg->opt.post_smooth; ++s) gauss_seidel(L, L->b, L->x, 1);
}

void gm_multigrid_vcycle(gm_multigrid *mg, const double *b, double *x) {
  level *L = &mg->lv[0];
  const size_t n = L->A->n_rows;
  memcpy(L->b, b, n * sizeof(double));
  memcpy(L->x, x, n * sizeof(double));
  cycle(mg, 0);
  memcpy(x, L->x, n * sizeof(double));
}

static double dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

gm_status gm_multigrid_pcg(gm_multigrid *mg, const double *b, double *x, size_t *iterations,
                           double *relres) {
  if (mg == NULL || b == NULL || x == NULL) return GM_EINVAL;
  const gm_csr *A = mg->lv[0].A;
  const size_t n = A->n_rows;
  double *r = mg->work[0], *z = mg->work[1], *p = mg->work[2], *q = mg->work[3];
  const double bnorm = sqrt(dot(n, b, b));
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(b[i]) || !isfinite(x[i])) {
      snprintf(mg->msg, sizeof mg->msg, "non-finite %s at entry %zu", isfinite(b[i]) ? "x" : "b", i);
      return GM_EDOMAIN;
    }
  memcpy(r, b, n * sizeof(double));
  gm_csr_matvec(A, -1.0, x, 1.0, r);
  double res = sqrt(dot(n, r, r));
  size_t it = 0;
  if (bnorm == 0.0) {
    memset(x, 0, n * sizeof(double));
    res = 0.0;
  }
  double rz = 0.0;
  while (res > mg->opt.rtol * bnorm && it < mg->opt.max_iterations) {
    memset(z, 0, n * sizeof(double));
    gm_multigrid_vcycle(mg, r, z);
    double rz_new = dot(n, r, z);
    if (it == 0)
      memcpy(p, z, n * sizeof(double));
    else
      for (size_t i = 0; i < n; ++i) p[i] = z[i] + (rz_new / rz) * p[i];
    rz = rz_new;
    gm_csr_matvec(A, 1.0, p, 0.0, q);
    double alpha = rz / dot(n, p, q);
    for (size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    res = sqrt(dot(n, r, r));
    ++it;
  }
  if (iterations) *iterations = it;
  double rel = bnorm > 0.0 ? res / bnorm : 0.0;
  if (relres) *relres = rel;
  if (!(rel <= mg->opt.rtol)) {
    snprintf(mg->msg, sizeof mg->msg,
             "multigrid-preconditioned CG: relative residual %.3g after %zu iterations, above "
             "rtol = %.3g",
             rel, it, mg->opt.rtol);
    return GM_ENOCONV;
  }
  return GM_OK;
}

double gm_multigrid_contraction(gm_multigrid *mg, size_t cycles) {
  if (mg == NULL || cycles < 4) return NAN;
  const gm_csr *A = mg->lv[0].A;
  const size_t n = A->n_rows;
  double *e = malloc(n * sizeof(double)), *zero = calloc(n, sizeof(double)),
         *Ae = malloc(n * sizeof(double));
  if (!e || !zero || !Ae) {
    free(e), free(zero), free(Ae);
    return NAN;
  }
  uint64_t s = 0x9E3779B97F4A7C15ull;
  for (size_t i = 0; i < n; ++i) {
    s ^= s << 13, s ^= s >> 7, s ^= s << 17;
    e[i] = (double)(s >> 11) / 9007199254740992.0 - 0.5;
  }
  double prev = 0.0, log_sum = 0.0;
  size_t counted = 0;
  for (size_t c = 0; c <= cycles; ++c) {
    if (c > 0) gm_multigrid_vcycle(mg, zero, e);
    gm_csr_matvec(A, 1.0, e, 0.0, Ae);
    double norm = sqrt(dot(n, e, Ae));
    if (!(norm > 0.0)) break; /* converged to zero exactly */
    if (c >= 3) log_sum += log(norm / prev), ++counted;
    prev = norm;
  }
  free(e), free(zero), free(Ae);
  return counted ? exp(log_sum / (double)counted) : 0.0;
}
