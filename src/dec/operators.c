/* Codifferential, Laplacians and divergence as sparse matrices. */
#include <stdlib.h>

#include "dec/internal.h"

static gm_status need_nonzero(const gm_geometry *g, size_t k, gm_error *err) {
  for (size_t i = 0; i < g->cx->count[k]; ++i)
    if (g->star[k][i] == 0.0)
      return gm_error_set(err, GM_EDOMAIN,
                          "Hodge star *_%zu is zero on %zu-simplex %zu: its inverse is needed "
                          "(the mesh is not well-centred there)",
                          k, k, i);
  return GM_OK;
}

gm_status gm_dec_codifferential(const gm_geometry *g, size_t k, gm_csr **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (g == NULL || k < 1 || k > g->cx->n)
    return gm_error_set(err, GM_EINVAL, "codifferential needs 1 <= k <= n");
  gm_status st = need_nonzero(g, k - 1, err);
  if (st != GM_OK) return st;
  gm_csr *dt = NULL;
  st = gm_csr_transpose(g->cx->d[k - 1], &dt);
  if (st != GM_OK) return gm_error_set(err, st, "out of memory");
  gm_csr_scale_cols(dt, g->star[k]);
  for (size_t i = 0; i < dt->n_rows; ++i)
    for (size_t p = dt->row_start[i]; p < dt->row_start[i + 1]; ++p) dt->val[p] /= g->star[k - 1][i];
  *out = dt;
  return GM_OK;
}

/* d_kᵀ ⋆_{k+1} d_k */
static gm_status curl_curl(const gm_geometry *g, size_t k, gm_csr **out) {
  gm_csr *dt = NULL, *r = NULL;
  gm_status st = gm_csr_transpose(g->cx->d[k], &dt);
  if (st != GM_OK) return st;
  gm_csr_scale_cols(dt, g->star[k + 1]);
  st = gm_csr_multiply(dt, g->cx->d[k], &r);
  gm_csr_free(dt);
  *out = r;
  return st;
}

/* ⋆_k d_{k−1} ⋆_{k−1}^{-1} d_{k−1}ᵀ ⋆_k */
static gm_status grad_div(const gm_geometry *g, size_t k, gm_csr **out) {
  gm_csr *a = NULL, *at = NULL, *r = NULL;
  gm_status st = gm_csr_copy(g->cx->d[k - 1], &a);
  if (st != GM_OK) return st;
  gm_csr_scale_rows(a, g->star[k]); /* ⋆_k d */
  st = gm_csr_transpose(a, &at);
  if (st == GM_OK) {
    for (size_t i = 0; i < at->n_rows; ++i)
      for (size_t p = at->row_start[i]; p < at->row_start[i + 1]; ++p) at->val[p] /= g->star[k - 1][i];
    st = gm_csr_multiply(a, at, &r);
  }
  gm_csr_free(a);
  gm_csr_free(at);
  *out = r;
  return st;
}

gm_status gm_dec_stiffness(const gm_geometry *g, size_t k, gm_csr **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (g == NULL || k > g->cx->n) return gm_error_set(err, GM_EINVAL, "k out of range");
  const size_t n = g->cx->n;
  gm_csr *a = NULL, *b = NULL;
  gm_status st = GM_OK;
  if (k >= 1) {
    st = need_nonzero(g, k - 1, err);
    if (st != GM_OK) return st;
  }
  if (k < n) st = curl_curl(g, k, &a);
  if (st == GM_OK && k >= 1) st = grad_div(g, k, &b);
  if (st != GM_OK) {
    gm_csr_free(a), gm_csr_free(b);
    return gm_error_set(err, st, "out of memory");
  }
  if (a && b) {
    st = gm_csr_add(1.0, a, 1.0, b, out);
    gm_csr_free(a), gm_csr_free(b);
  } else {
    *out = a ? a : b;
  }
  if (st != GM_OK) return gm_error_set(err, st, "out of memory");
  return GM_OK;
}

gm_status gm_dec_laplacian(const gm_geometry *g, size_t k, gm_csr **out, gm_error *err) {
  gm_status st = gm_dec_stiffness(g, k, out, err);
  if (st != GM_OK) return st;
  st = need_nonzero(g, k, err);
  if (st != GM_OK) {
    gm_csr_free(*out);
    *out = NULL;
    return st;
  }
  gm_csr *a = *out;
  for (size_t i = 0; i < a->n_rows; ++i)
    for (size_t p = a->row_start[i]; p < a->row_start[i + 1]; ++p) a->val[p] /= g->star[k][i];
  return GM_OK;
}

gm_status gm_dec_divergence(const gm_geometry *g, gm_csr **out, gm_error *err) {
  gm_status st = gm_dec_codifferential(g, 1, out, err);
  if (st == GM_OK) gm_csr_scale(*out, -1.0);
  return st;
}

/* Seed 000 §3.3.3: the dual boundary of the cell of a boundary k-simplex includes its boundary
 * dual cell, where ⋆β takes the boundary value flux[σ]; summation by parts then gives eq. 3.8. */
gm_status gm_dec_codifferential_boundary(const gm_geometry *g, size_t k, const double *beta,
                                         const double *flux, double *out, gm_error *err) {
  if (g == NULL || beta == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  const gm_complex *cx = g->cx;
  if (k >= cx->n) return gm_error_set(err, GM_EINVAL, "codifferential needs 0 <= k < n");
  gm_status st = need_nonzero(g, k, err);
  if (st != GM_OK) return st;
  const gm_csr *d = cx->d[k];
  const size_t m = cx->count[k];
  for (size_t s = 0; s < m; ++s) out[s] = 0.0;
  for (size_t r = 0; r < d->n_rows; ++r) {
    double sb = g->star[k + 1][r] * beta[r];
    for (size_t q = d->row_start[r]; q < d->row_start[r + 1]; ++q) out[d->col[q]] += d->val[q] * sb;
  }
  for (size_t s = 0; s < m; ++s) {
    if (flux != NULL && cx->boundary[k][s]) out[s] -= flux[s];
    out[s] /= g->star[k][s];
  }
  return GM_OK;
}

double gm_dec_boundary_pairing(const gm_complex *cx, size_t k, const double *alpha,
                               const double *flux) {
  if (cx == NULL || alpha == NULL || flux == NULL || k >= cx->n) return 0.0;
  double sum = 0.0;
  for (size_t s = 0; s < cx->count[k]; ++s)
    if (cx->boundary[k][s]) sum += alpha[s] * flux[s];
  return sum;
}
