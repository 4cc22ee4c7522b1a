/* Geometric multigrid: V-cycle with symmetric Gauss–Seidel smoothing and Galerkin coarse
 * operators, and conjugate gradients preconditioned by it.
 *
 * V-cycle (Briggs, Henson, McCormick, "A Multigrid Tutorial", 2nd ed., SIAM 2000, §3 and §10;
 * Galerkin coarse operator A_c = Pᵀ A P, ibid. eq. (10.3) / the variational property): on
 * level l, ν₁ forward Gauss–Seidel sweeps, restriction of the residual by Pᵀ, the cycle on level
 * l+1 from zero, correction x += P x_c, ν₂ backward sweeps; the coarsest level is solved by
 * CHOLMOD. With ν₁ = ν₂ the backward sweep is the adjoint of the forward one in the A inner
 * product, so the cycle is a symmetric positive definite preconditioner for CG (Hackbusch,
 * "Multi-Grid Methods and Applications", 1985, §10.7), and PCG is the textbook algorithm
 * (Saad, "Iterative Methods for Sparse Linear Systems", 2nd ed., Alg. 9.1).
 *
 * Cost (what makes it ~30 sparse products to 1e-10 instead of ~145, bench/dec_multigrid.c):
 * - The cycle is memory-bound, so the smoothing levels keep their operators and prolongations
 *   with 32-bit column indices and single-precision values (8 B per entry instead of the 16 B
 *   of gm_csr); all arithmetic is in double. A preconditioner only has to be a fixed SPD
 *   operator: the cycle is the exact V-cycle of matrices within 6e-8 (relative, entrywise) of
 *   the Galerkin ones, and CG's own product uses the caller's double matrix, so the solution
 *   reaches rtol like any PCG.
 * - The first forward sweep from a zero guess reads only the strictly lower triangle.
 * - The residual after pre-smoothing is restricted as it is computed (r is never stored).
 * - The Galerkin product Pᵀ A P is formed in one pass per coarse row (Gustavson's row-wise
 *   accumulation, F. G. Gustavson, ACM TOMS 4 (1978) 250–269, applied to the triple product)
 *   without the intermediate A P. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/multigrid.h"

/* The cycle's matrices: 32-bit columns and single-precision values, interleaved so that a row
 * is one stream (A: CSR; P: fixed width, the red-refinement prolongation has ≤ 2 entries a row,
 * padded with zero weights, so a row is one 16-byte load). */
typedef struct entry {
  uint32_t col;
  float val;
} entry;

typedef struct cmat {
  size_t n_rows, n_cols;
  size_t *row_start;
  entry *e;
} cmat;

typedef struct ell {
  size_t n_rows, n_cols, width;
  entry *e; /* row i: e[i*width .. (i+1)*width) */
} ell;

typedef struct level {
  cmat A;          /* smoothing levels only (all but the coarsest) */
  ell P;           /* prolongation from the next coarser level */
  size_t *diag;    /* position of the diagonal entry of each row of A */
  double *inv_diag;
  double *x, *b;
  size_t n;
} level;

struct gm_multigrid {
  size_t n_levels;
  level *lv;
  const gm_csr *A;    /* the finest operator (borrowed): CG's product */
  gm_csr *coarsest;   /* the coarsest Galerkin operator, double, factored by CHOLMOD */
  gm_sparse_cholesky *coarse;
  size_t level_nnz_coarsest;
  gm_multigrid_options opt;
  double *work[4]; /* PCG: r, z, p, q on the finest level */
  char msg[GM_ERRMSG_SIZE];
};

gm_multigrid_options gm_multigrid_defaults(void) {
  gm_multigrid_options o = {2, 2, 200, 1e-10};
  return o;
}

static void cmat_free(cmat *m) {
  free(m->row_start), free(m->e);
  memset(m, 0, sizeof *m);
}

/* The compact copy of a, with the position of each row's diagonal entry and its inverse (one
 * pass). GM_ESINGULAR (row in *bad) when a diagonal entry is missing or not positive. */
static gm_status cmat_from_csr(const gm_csr *a, cmat *m, size_t *diag, double *inv_diag,
                               size_t *bad) {
  memset(m, 0, sizeof *m);
  const size_t nnz = gm_csr_nnz(a);
  m->n_rows = a->n_rows, m->n_cols = a->n_cols;
  m->row_start = malloc((a->n_rows + 1) * sizeof(size_t));
  m->e = malloc((nnz ? nnz : 1) * sizeof(entry));
  if (!m->row_start || !m->e) {
    cmat_free(m);
    return GM_ENOMEM;
  }
  m->row_start[0] = 0;
  for (size_t i = 0; i < a->n_rows; ++i) {
    diag[i] = SIZE_MAX;
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) {
      m->e[p].col = (uint32_t)a->col[p], m->e[p].val = (float)a->val[p];
      if (a->col[p] == i) diag[i] = p;
    }
    m->row_start[i + 1] = a->row_start[i + 1];
    if (diag[i] == SIZE_MAX || !(a->val[diag[i]] > 0.0)) {
      *bad = i;
      return GM_ESINGULAR;
    }
    inv_diag[i] = 1.0 / a->val[diag[i]];
  }
  return GM_OK;
}

static gm_status ell_from_csr(const gm_csr *a, ell *m) {
  memset(m, 0, sizeof *m);
  size_t width = 1;
  for (size_t i = 0; i < a->n_rows; ++i)
    if (a->row_start[i + 1] - a->row_start[i] > width) width = a->row_start[i + 1] - a->row_start[i];
  m->n_rows = a->n_rows, m->n_cols = a->n_cols, m->width = width;
  m->e = calloc(a->n_rows * width, sizeof(entry));
  if (m->e == NULL) return GM_ENOMEM;
  for (size_t i = 0; i < a->n_rows; ++i)
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p)
      m->e[i * width + (p - a->row_start[i])] = (entry){(uint32_t)a->col[p], (float)a->val[p]};
  return GM_OK;
}

void gm_multigrid_free(gm_multigrid *mg) {
  if (mg == NULL) return;
  for (size_t l = 0; mg->lv && l < mg->n_levels; ++l) {
    cmat_free(&mg->lv[l].A);
    free(mg->lv[l].P.e);
    free(mg->lv[l].diag), free(mg->lv[l].inv_diag);
    free(mg->lv[l].x), free(mg->lv[l].b);
  }
  free(mg->lv);
  gm_csr_free(mg->coarsest);
  gm_sparse_cholesky_free(mg->coarse);
  for (int i = 0; i < 4; ++i) free(mg->work[i]);
  free(mg);
}

/* C = Pᵀ A P (double) from the compact A and P of a level, one coarse row at a time: for every
 * fine row i with P(i, I) ≠ 0 (the rows of Pᵀ), every A(i, j) and every P(j, J), accumulate
 * P(i,I) A(i,j) P(j,J) into C(I, J). The compact copies halve the memory the gathers touch
 * (the product is bound by the latency of fetching the rows i and j); the coarse operators
 * differ from the double product by float rounding of A's entries, which only changes the
 * (still SPD) preconditioner. */
static gm_status galerkin(const cmat *A, const ell *P, gm_csr **out) {
  const size_t m = P->n_cols, n = P->n_rows, wp = P->width;
  gm_status st = GM_OK;
  size_t nnzp = 0;
  for (size_t q = 0; q < n * wp; ++q) nnzp += P->e[q].val != 0.0f;
  /* Pᵀ: for each coarse column, the fine rows and weights */
  size_t *pt_start = calloc(m + 1, sizeof(size_t)), *mark = malloc(m * sizeof(size_t));
  entry *pt = malloc((nnzp ? nnzp : 1) * sizeof(entry));
  size_t *row_start = calloc(m + 1, sizeof(size_t));
  double *acc = malloc(m * sizeof(double));
  size_t cap = 0, *col = NULL;
  double *val = NULL;
  if (!pt_start || !mark || !pt || !row_start || !acc) st = GM_ENOMEM;
  if (st == GM_OK) {
    for (size_t q = 0; q < n * wp; ++q)
      if (P->e[q].val != 0.0f) ++pt_start[P->e[q].col + 1];
    for (size_t J = 0; J < m; ++J) pt_start[J + 1] += pt_start[J], mark[J] = pt_start[J];
    for (size_t q = 0; q < n * wp; ++q)
      if (P->e[q].val != 0.0f) pt[mark[P->e[q].col]++] = (entry){(uint32_t)(q / wp), P->e[q].val};
    /* first guess of the size: the coarse operator has about as many entries per row as A */
    cap = (A->row_start[A->n_rows] / (A->n_rows ? A->n_rows : 1) + 8) * m;
    col = malloc(cap * sizeof(size_t));
    val = malloc(cap * sizeof(double));
    if (!col || !val) st = GM_ENOMEM;
  }
  for (size_t j = 0; st == GM_OK && j < m; ++j) mark[j] = SIZE_MAX;
  size_t w = 0;
  for (size_t I = 0; st == GM_OK && I < m; ++I) {
    const size_t begin = w;
    for (size_t a = pt_start[I]; a < pt_start[I + 1]; ++a) {
      const size_t i = pt[a].col;
      const double pi = pt[a].val;
      for (size_t p = A->row_start[i]; p < A->row_start[i + 1]; ++p) {
        const entry *pj = P->e + (size_t)A->e[p].col * wp;
        const double pa = pi * (double)A->e[p].val;
        for (size_t q = 0; q < wp; ++q) {
          if (pj[q].val == 0.0f) continue; /* padding */
          const size_t J = pj[q].col;
          if (mark[J] != I) {
            mark[J] = I;
            if (w == cap) {
              size_t ncap = cap * 2 + 16;
              size_t *nc = realloc(col, ncap * sizeof(size_t));
              if (nc) col = nc;
              double *nv = nc ? realloc(val, ncap * sizeof(double)) : NULL;
              if (nv) val = nv;
              if (!nc || !nv) {
                st = GM_ENOMEM;
                goto done;
              }
              cap = ncap;
            }
            col[w++] = J;
            acc[J] = 0.0;
          }
          acc[J] += pa * (double)pj[q].val;
        }
      }
    }
    for (size_t p = begin + 1; p < w; ++p) { /* insertion sort: rows are short */
      size_t cj = col[p], q = p;
      while (q > begin && col[q - 1] > cj) col[q] = col[q - 1], --q;
      col[q] = cj;
    }
    for (size_t p = begin; p < w; ++p) val[p] = acc[col[p]];
    row_start[I + 1] = w;
  }
done:
  if (st == GM_OK) {
    gm_csr *c = NULL;
    st = gm_csr_create(m, m, 0, &c);
    if (st == GM_OK) {
      free(c->row_start), free(c->col), free(c->val);
      c->row_start = row_start, c->col = col, c->val = val;
      row_start = NULL, col = NULL, val = NULL;
      *out = c;
    }
  }
  free(pt_start), free(mark), free(pt);
  free(acc), free(row_start), free(col), free(val);
  return st;
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
  if (A->n_rows > UINT32_MAX)
    return gm_error_set(err, GM_EUNSUPPORTED,
                        "%zu unknowns: the cycle's 32-bit column indices allow at most %u",
                        A->n_rows, UINT32_MAX);
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
  mg->A = A;
  mg->n_levels = n_prolongations + 1;
  mg->lv = calloc(mg->n_levels, sizeof(level));
  gm_status st = mg->lv ? GM_OK : GM_ENOMEM;
  const gm_csr *Al = A; /* the double operator of level l */
  gm_csr *owned = NULL; /* Al when it is a Galerkin product (freed after the next one) */
  for (size_t l = 0; st == GM_OK && l < mg->n_levels; ++l) {
    level *L = &mg->lv[l];
    const size_t n = Al->n_rows;
    L->n = n;
    L->x = malloc(n * sizeof(double));
    L->b = malloc(n * sizeof(double));
    if (!L->x || !L->b) {
      st = GM_ENOMEM;
      break;
    }
    if (l + 1 == mg->n_levels) { /* coarsest: keep the double operator for CHOLMOD */
      if (owned == NULL) st = gm_csr_copy(Al, &owned);
      mg->coarsest = owned;
      owned = NULL;
      break;
    }
    L->diag = malloc(n * sizeof(size_t));
    L->inv_diag = malloc(n * sizeof(double));
    if (!L->diag || !L->inv_diag) {
      st = GM_ENOMEM;
      break;
    }
    size_t bad = 0;
    st = cmat_from_csr(Al, &L->A, L->diag, L->inv_diag, &bad);
    if (st == GM_ESINGULAR) {
      double d = L->diag[bad] == SIZE_MAX ? 0.0 : Al->val[L->diag[bad]];
      gm_csr_free(owned);
      gm_multigrid_free(mg);
      return gm_error_set(err, GM_ESINGULAR,
                          "level %zu: diagonal entry %zu is %g, not positive (Gauss–Seidel needs "
                          "a positive diagonal)",
                          l, bad, d);
    }
    if (st == GM_OK) st = ell_from_csr(P[l], &L->P);
    gm_csr *next = NULL;
    if (st == GM_OK) st = galerkin(&L->A, &L->P, &next);
    gm_csr_free(owned);
    owned = next;
    Al = next;
  }
  gm_csr_free(owned);
  for (int i = 0; st == GM_OK && i < 4; ++i)
    if ((mg->work[i] = malloc(A->n_rows * sizeof(double))) == NULL) st = GM_ENOMEM;
  if (st != GM_OK) {
    gm_multigrid_free(mg);
    return gm_error_set(err, st, st == GM_ENOMEM ? "out of memory building the multigrid hierarchy"
                                                 : "building the multigrid hierarchy failed");
  }
  mg->level_nnz_coarsest = gm_csr_nnz(mg->coarsest);
  st = gm_sparse_cholesky_create(mg->coarsest, &mg->coarse, err);
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
  if (nnz)
    *nnz = level_index + 1 == mg->n_levels ? mg->level_nnz_coarsest
                                           : mg->lv[level_index].A.row_start[mg->lv[level_index].n];
  return mg->lv[level_index].n;
}

const char *gm_multigrid_errmsg(const gm_multigrid *mg) { return mg ? mg->msg : ""; }

/* Forward Gauss–Seidel from x = 0: only the strictly lower part of each row is nonzero in x. */
static void gs_forward_from_zero(const level *L) {
  const entry *e = L->A.e;
  double *x = L->x;
  for (size_t i = 0; i < L->n; ++i) {
    double s = L->b[i];
    for (size_t p = L->A.row_start[i]; p < L->diag[i]; ++p) s -= (double)e[p].val * x[e[p].col];
    x[i] = s * L->inv_diag[i];
  }
}

static void gs_forward(const level *L) {
  const entry *e = L->A.e;
  double *x = L->x;
  for (size_t i = 0; i < L->n; ++i) {
    double s = L->b[i];
    for (size_t p = L->A.row_start[i]; p < L->A.row_start[i + 1]; ++p)
      s -= (double)e[p].val * x[e[p].col];
    x[i] += s * L->inv_diag[i];
  }
}

static void gs_backward(const level *L) {
  const entry *e = L->A.e;
  double *x = L->x;
  for (size_t q = L->n; q-- > 0;) {
    double s = L->b[q];
    for (size_t p = L->A.row_start[q]; p < L->A.row_start[q + 1]; ++p)
      s -= (double)e[p].val * x[e[p].col];
    x[q] += s * L->inv_diag[q];
  }
}

/* bc = Pᵀ (b − A x), the residual formed row by row and scattered at once. */
static void restrict_residual(const level *L, double *bc, size_t nc) {
  const entry *e = L->A.e, *pe = L->P.e;
  const size_t wp = L->P.width;
  memset(bc, 0, nc * sizeof(double));
  for (size_t i = 0; i < L->n; ++i) {
    double r = L->b[i];
    for (size_t p = L->A.row_start[i]; p < L->A.row_start[i + 1]; ++p)
      r -= (double)e[p].val * L->x[e[p].col];
    for (size_t q = i * wp; q < (i + 1) * wp; ++q) bc[pe[q].col] += (double)pe[q].val * r;
  }
}

static void prolong_add(const level *L, const double *xc) {
  const entry *pe = L->P.e;
  const size_t wp = L->P.width;
  for (size_t i = 0; i < L->n; ++i) {
    double s = 0.0;
    for (size_t q = i * wp; q < (i + 1) * wp; ++q) s += (double)pe[q].val * xc[pe[q].col];
    L->x[i] += s;
  }
}

/* One cycle on level l for L->b from x = 0, result in L->x. */
static void cycle(gm_multigrid *mg, size_t l) {
  level *L = &mg->lv[l];
  if (l + 1 == mg->n_levels) {
    gm_sparse_cholesky_solve(mg->coarse, L->b, L->x);
    return;
  }
  if (mg->opt.pre_smooth > 0) {
    gs_forward_from_zero(L);
    for (size_t s = 1; s < mg->opt.pre_smooth; ++s) gs_forward(L);
  } else {
    memset(L->x, 0, L->n * sizeof(double));
  }
  level *C = &mg->lv[l + 1];
  restrict_residual(L, C->b, C->n);
  cycle(mg, l + 1);
  prolong_add(L, C->x);
  for (size_t s = 0; s < mg->opt.post_smooth; ++s) gs_backward(L);
}

/* z = B r for the cycle's operator B (from zero). */
static void precondition(gm_multigrid *mg, const double *r, double *z) {
  level *L = &mg->lv[0];
  memcpy(L->b, r, L->n * sizeof(double));
  cycle(mg, 0);
  memcpy(z, L->x, L->n * sizeof(double));
}

void gm_multigrid_vcycle(gm_multigrid *mg, const double *b, double *x) {
  /* x ← x + B (b − A x) */
  const size_t n = mg->lv[0].n;
  double *r = mg->work[0], *z = mg->work[1];
  memcpy(r, b, n * sizeof(double));
  gm_csr_matvec(mg->A, -1.0, x, 1.0, r);
  precondition(mg, r, z);
  for (size_t i = 0; i < n; ++i) x[i] += z[i];
}

static double dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

gm_status gm_multigrid_pcg(gm_multigrid *mg, const double *b, double *x, size_t *iterations,
                           double *relres) {
  if (mg == NULL || b == NULL || x == NULL) return GM_EINVAL;
  const gm_csr *A = mg->A;
  const size_t n = A->n_rows;
  double *r = mg->work[0], *z = mg->work[1], *p = mg->work[2], *q = mg->work[3];
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(b[i]) || !isfinite(x[i])) {
      snprintf(mg->msg, sizeof mg->msg, "non-finite %s at entry %zu", isfinite(b[i]) ? "x" : "b", i);
      return GM_EDOMAIN;
    }
  const double bnorm = sqrt(dot(n, b, b));
  memcpy(r, b, n * sizeof(double));
  double xx = dot(n, x, x);
  if (xx > 0.0) gm_csr_matvec(A, -1.0, x, 1.0, r); /* a zero guess needs no product */
  double res = sqrt(dot(n, r, r));
  size_t it = 0;
  if (bnorm == 0.0) {
    memset(x, 0, n * sizeof(double));
    res = 0.0;
  }
  double rz = 0.0;
  while (res > mg->opt.rtol * bnorm && it < mg->opt.max_iterations) {
    precondition(mg, r, z);
    double rz_new = dot(n, r, z);
    if (it == 0) {
      memcpy(p, z, n * sizeof(double));
    } else {
      const double beta = rz_new / rz;
      for (size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    }
    rz = rz_new;
    double pq = 0.0; /* q = A p and pᵀq in one pass */
    for (size_t i = 0; i < n; ++i) {
      double s = 0.0;
      for (size_t k = A->row_start[i]; k < A->row_start[i + 1]; ++k) s += A->val[k] * p[A->col[k]];
      q[i] = s;
      pq += p[i] * s;
    }
    const double alpha = rz / pq;
    double rr = 0.0;
    for (size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      rr += r[i] * r[i];
    }
    res = sqrt(rr);
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
  const gm_csr *A = mg->A;
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
