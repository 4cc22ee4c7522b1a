/* Compressed-sparse-row matrices: assembly, transpose, products, sums, scaling, products with
 * vectors. Rows always have ascending, unique column indices (see geomint/sparse.h). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/sparse.h"

gm_status gm_csr_create(size_t n_rows, size_t n_cols, size_t nnz, gm_csr **out) {
  if (out == NULL) return GM_EINVAL;
  *out = NULL;
  if (n_rows > SIZE_MAX / sizeof(size_t) - 1 || nnz > SIZE_MAX / sizeof(double))
    return GM_ENOMEM;
  gm_csr *a = calloc(1, sizeof *a);
  if (a == NULL) return GM_ENOMEM;
  a->n_rows = n_rows;
  a->n_cols = n_cols;
  a->row_start = calloc(n_rows + 1, sizeof(size_t));
  a->col = malloc((nnz ? nnz : 1) * sizeof(size_t));
  a->val = malloc((nnz ? nnz : 1) * sizeof(double));
  if (!a->row_start || !a->col || !a->val) {
    gm_csr_free(a);
    return GM_ENOMEM;
  }
  *out = a;
  return GM_OK;
}

void gm_csr_free(gm_csr *a) {
  if (a == NULL) return;
  free(a->row_start);
  free(a->col);
  free(a->val);
  free(a);
}

size_t gm_csr_nnz(const gm_csr *a) { return a ? a->row_start[a->n_rows] : 0; }

/* Sort the entries of each row by column and sum duplicates, in place (rows are short: insertion
 * sort). Used after scattering triplets into rows. */
static void sort_and_merge_rows(gm_csr *a) {
  size_t w = 0;
  size_t begin = 0;
  for (size_t i = 0; i < a->n_rows; ++i) {
    size_t end = a->row_start[i + 1];
    for (size_t p = begin + 1; p < end; ++p) {
      size_t c = a->col[p];
      double v = a->val[p];
      size_t q = p;
      while (q > begin && a->col[q - 1] > c) {
        a->col[q] = a->col[q - 1];
        a->val[q] = a->val[q - 1];
        --q;
      }
      a->col[q] = c;
      a->val[q] = v;
    }
    size_t row_w = w;
    for (size_t p = begin; p < end; ++p) {
      if (w > row_w && a->col[w - 1] == a->col[p]) {
        a->val[w - 1] += a->val[p];
      } else {
        a->col[w] = a->col[p];
        a->val[w] = a->val[p];
        ++w;
      }
    }
    a->row_start[i] = row_w;
    begin = end;
  }
  a->row_start[a->n_rows] = w;
}

gm_status gm_csr_from_triplets(size_t n_rows, size_t n_cols, size_t n, const size_t *rows,
                               const size_t *cols, const double *vals, gm_csr **out,
                               gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (n > 0 && (rows == NULL || cols == NULL || vals == NULL))
    return gm_error_set(err, GM_EINVAL, "triplet arrays are NULL");
  for (size_t t = 0; t < n; ++t) {
    if (rows[t] >= n_rows || cols[t] >= n_cols)
      return gm_error_set(err, GM_EINVAL,
                          "triplet %zu: index (%zu, %zu) outside a %zu x %zu matrix", t, rows[t],
                          cols[t], n_rows, n_cols);
    if (!isfinite(vals[t]))
      return gm_error_set(err, GM_EDOMAIN, "triplet %zu: value is not finite", t);
  }
  gm_csr *a = NULL;
  if (gm_csr_create(n_rows, n_cols, n, &a) != GM_OK)
    return gm_error_set(err, GM_ENOMEM, "out of memory for %zu triplets", n);
  for (size_t t = 0; t < n; ++t) a->row_start[rows[t] + 1]++;
  for (size_t i = 0; i < n_rows; ++i) a->row_start[i + 1] += a->row_start[i];
  size_t *next = malloc((n_rows ? n_rows : 1) * sizeof(size_t));
  if (next == NULL) {
    gm_csr_free(a);
    return gm_error_set(err, GM_ENOMEM, "out of memory for %zu triplets", n);
  }
  memcpy(next, a->row_start, n_rows * sizeof(size_t));
  for (size_t t = 0; t < n; ++t) {
    size_t p = next[rows[t]]++;
    a->col[p] = cols[t];
    a->val[p] = vals[t];
  }
  free(next);
  sort_and_merge_rows(a);
  *out = a;
  return GM_OK;
}

gm_status gm_csr_diagonal(size_t n, const double *d, gm_csr **out) {
  gm_csr *a = NULL;
  gm_status st = gm_csr_create(n, n, n, &a);
  if (st != GM_OK) return st;
  for (size_t i = 0; i < n; ++i) {
    a->row_start[i + 1] = i + 1;
    a->col[i] = i;
    a->val[i] = d ? d[i] : 1.0;
  }
  *out = a;
  return GM_OK;
}

gm_status gm_csr_copy(const gm_csr *a, gm_csr **out) {
  if (a == NULL || out == NULL) return GM_EINVAL;
  size_t nnz = gm_csr_nnz(a);
  gm_csr *b = NULL;
  gm_status st = gm_csr_create(a->n_rows, a->n_cols, nnz, &b);
  if (st != GM_OK) return st;
  memcpy(b->row_start, a->row_start, (a->n_rows + 1) * sizeof(size_t));
  if (nnz) {
    memcpy(b->col, a->col, nnz * sizeof(size_t));
    memcpy(b->val, a->val, nnz * sizeof(double));
  }
  *out = b;
  return GM_OK;
}

gm_status gm_csr_transpose(const gm_csr *a, gm_csr **out) {
  if (a == NULL || out == NULL) return GM_EINVAL;
  *out = NULL;
  size_t nnz = gm_csr_nnz(a);
  gm_csr *t = NULL;
  gm_status st = gm_csr_create(a->n_cols, a->n_rows, nnz, &t);
  if (st != GM_OK) return st;
  for (size_t p = 0; p < nnz; ++p) t->row_start[a->col[p] + 1]++;
  for (size_t j = 0; j < a->n_cols; ++j) t->row_start[j + 1] += t->row_start[j];
  /* Scatter rows in ascending order: each transposed row comes out sorted. */
  size_t *next = malloc((a->n_cols ? a->n_cols : 1) * sizeof(size_t));
  if (next == NULL) {
    gm_csr_free(t);
    return GM_ENOMEM;
  }
  memcpy(next, t->row_start, a->n_cols * sizeof(size_t));
  for (size_t i = 0; i < a->n_rows; ++i)
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) {
      size_t q = next[a->col[p]]++;
      t->col[q] = i;
      t->val[q] = a->val[p];
    }
  free(next);
  *out = t;
  return GM_OK;
}

/* Gustavson's row-by-row product with a dense accumulator; the columns of each output row are
 * sorted at the end of the row. Two passes: count, then fill. */
gm_status gm_csr_multiply(const gm_csr *a, const gm_csr *b, gm_csr **out) {
  if (a == NULL || b == NULL || out == NULL || a->n_cols != b->n_rows) return GM_EINVAL;
  *out = NULL;
  size_t m = a->n_rows, n = b->n_cols;
  size_t *mark = malloc((n ? n : 1) * sizeof(size_t));
  double *acc = calloc(n ? n : 1, sizeof(double));
  size_t *row_start = calloc(m + 1, sizeof(size_t));
  if (!mark || !acc || !row_start) {
    free(mark), free(acc), free(row_start);
    return GM_ENOMEM;
  }
  for (size_t j = 0; j < n; ++j) mark[j] = SIZE_MAX;
  for (size_t i = 0; i < m; ++i) {
    size_t count = 0;
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) {
      size_t k = a->col[p];
      for (size_t q = b->row_start[k]; q < b->row_start[k + 1]; ++q)
        if (mark[b->col[q]] != i) {
          mark[b->col[q]] = i;
          ++count;
        }
    }
    row_start[i + 1] = row_start[i] + count;
  }
  gm_csr *c = NULL;
  gm_status st = gm_csr_create(m, n, row_start[m], &c);
  if (st != GM_OK) {
    free(mark), free(acc), free(row_start);
    return st;
  }
  free(c->row_start);
  c->row_start = row_start;
  for (size_t j = 0; j < n; ++j) mark[j] = SIZE_MAX;
  for (size_t i = 0; i < m; ++i) {
    size_t w = row_start[i];
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) {
      size_t k = a->col[p];
      double av = a->val[p];
      for (size_t q = b->row_start[k]; q < b->row_start[k + 1]; ++q) {
        size_t j = b->col[q];
        if (mark[j] != i) {
          mark[j] = i;
          c->col[w++] = j;
          acc[j] = 0.0;
        }
        acc[j] += av * b->val[q];
      }
    }
    /* sort the row's columns (insertion sort: rows are short) and gather the values */
    size_t begin = row_start[i];
    for (size_t p = begin + 1; p < w; ++p) {
      size_t cj = c->col[p], q = p;
      while (q > begin && c->col[q - 1] > cj) {
        c->col[q] = c->col[q - 1];
        --q;
      }
      c->col[q] = cj;
    }
    for (size_t p = begin; p < w; ++p) c->val[p] = acc[c->col[p]];
  }
  free(mark);
  free(acc);
  *out = c;
  return GM_OK;
}

gm_status gm_csr_add(double alpha, const gm_csr *a, double beta, const gm_csr *b, gm_csr **out) {
  if (a == NULL || b == NULL || out == NULL) return GM_EINVAL;
  *out = NULL;
  if (a->n_rows != b->n_rows || a->n_cols != b->n_cols) return GM_EINVAL;
  gm_csr *c = NULL;
  gm_status st = gm_csr_create(a->n_rows, a->n_cols, gm_csr_nnz(a) + gm_csr_nnz(b), &c);
  if (st != GM_OK) return st;
  size_t w = 0;
  for (size_t i = 0; i < a->n_rows; ++i) {
    size_t p = a->row_start[i], pe = a->row_start[i + 1];
    size_t q = b->row_start[i], qe = b->row_start[i + 1];
    while (p < pe || q < qe) {
      if (q >= qe || (p < pe && a->col[p] < b->col[q])) {
        c->col[w] = a->col[p];
        c->val[w++] = alpha * a->val[p++];
      } else if (p >= pe || b->col[q] < a->col[p]) {
        c->col[w] = b->col[q];
        c->val[w++] = beta * b->val[q++];
      } else {
        c->col[w] = a->col[p];
        c->val[w++] = alpha * a->val[p++] + beta * b->val[q++];
      }
    }
    c->row_start[i + 1] = w;
  }
  *out = c;
  return GM_OK;
}

void gm_csr_scale(gm_csr *a, double s) {
  size_t nnz = gm_csr_nnz(a);
  for (size_t p = 0; p < nnz; ++p) a->val[p] *= s;
}

void gm_csr_scale_rows(gm_csr *a, const double *d) {
  for (size_t i = 0; i < a->n_rows; ++i)
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) a->val[p] *= d[i];
}

void gm_csr_scale_cols(gm_csr *a, const double *d) {
  size_t nnz = gm_csr_nnz(a);
  for (size_t p = 0; p < nnz; ++p) a->val[p] *= d[a->col[p]];
}

void gm_csr_drop_zeros(gm_csr *a, double tol) {
  size_t w = 0, begin = 0;
  for (size_t i = 0; i < a->n_rows; ++i) {
    size_t end = a->row_start[i + 1];
    for (size_t p = begin; p < end; ++p)
      if (fabs(a->val[p]) > tol) {
        a->col[w] = a->col[p];
        a->val[w++] = a->val[p];
      }
    begin = end;
    a->row_start[i + 1] = w;
  }
}

void gm_csr_matvec(const gm_csr *a, double alpha, const double *x, double beta, double *y) {
  for (size_t i = 0; i < a->n_rows; ++i) {
    double s = 0.0;
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) s += a->val[p] * x[a->col[p]];
    y[i] = beta == 0.0 ? alpha * s : alpha * s + beta * y[i];
  }
}

void gm_csr_matvec_transpose(const gm_csr *a, double alpha, const double *x, double beta,
                             double *y) {
  for (size_t j = 0; j < a->n_cols; ++j) y[j] = beta == 0.0 ? 0.0 : beta * y[j];
  for (size_t i = 0; i < a->n_rows; ++i) {
    double xi = alpha * x[i];
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) y[a->col[p]] += a->val[p] * xi;
  }
}

double gm_csr_max_abs(const gm_csr *a) { return gm_norm_inf(gm_csr_nnz(a), a->val); }

double gm_csr_get(const gm_csr *a, size_t i, size_t j) {
  if (a == NULL || i >= a->n_rows) return 0.0;
  size_t lo = a->row_start[i], hi = a->row_start[i + 1];
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (a->col[mid] < j)
      lo = mid + 1;
    else
      hi = mid;
  }
  return (lo < a->row_start[i + 1] && a->col[lo] == j) ? a->val[lo] : 0.0;
}

double gm_csr_asymmetry(const gm_csr *a) {
  if (a == NULL || a->n_rows != a->n_cols) return -1.0;
  double m = gm_csr_max_abs(a), d = 0.0;
  for (size_t i = 0; i < a->n_rows; ++i)
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) {
      double e = fabs(a->val[p] - gm_csr_get(a, a->col[p], i));
      if (e > d) d = e;
    }
  return m > 0.0 ? d / m : 0.0;
}
