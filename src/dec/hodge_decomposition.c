/* Hodge decomposition of cochains and harmonic bases (see geomint/dec.h for the method). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"

#define TIKHONOV_EPS 1e-10
#define TIKHONOV_MAX_ITER 30

/* A semi-definite system A x = b solved by iterated Tikhonov regularization. */
typedef struct {
  gm_csr *a;
  gm_sparse_cholesky *ch;
  double *r, *dx;
} semidef;

static void semidef_free(semidef *s) {
  gm_csr_free(s->a);
  gm_sparse_cholesky_free(s->ch);
  free(s->r);
  free(s->dx);
}

static gm_status semidef_init(semidef *s, gm_csr *a, gm_error *err) {
  s->a = a;
  size_t n = a->n_rows;
  s->r = malloc((n ? n : 1) * sizeof(double));
  s->dx = malloc((n ? n : 1) * sizeof(double));
  if (!s->r || !s->dx) return gm_error_set(err, GM_ENOMEM, "out of memory");
  double *diag = malloc((n ? n : 1) * sizeof(double));
  if (diag == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  double dmax = 0.0;
  for (size_t i = 0; i < n; ++i) {
    diag[i] = gm_csr_get(a, i, i);
    if (diag[i] > dmax) dmax = diag[i];
  }
  for (size_t i = 0; i < n; ++i) diag[i] = TIKHONOV_EPS * (diag[i] > 0.0 ? diag[i] : dmax);
  gm_csr *D = NULL, *reg = NULL;
  gm_status st = gm_csr_diagonal(n, diag, &D);
  free(diag);
  if (st == GM_OK) st = gm_csr_add(1.0, a, 1.0, D, &reg);
  gm_csr_free(D);
  if (st != GM_OK) return gm_error_set(err, st, "out of memory");
  st = gm_sparse_cholesky_create(reg, &s->ch, err);
  gm_csr_free(reg);
  return st;
}

/* x = A⁺-like solution of A x = b (b in the range of A), iterating until the update stalls. */
static gm_status semidef_solve(semidef *s, const double *b, double *x) {
  const size_t n = s->a->n_rows;
  memset(x, 0, n * sizeof(double));
  double bnorm = gm_norm_inf(n, b);
  if (bnorm == 0.0) return GM_OK;
  for (int it = 0; it < TIKHONOV_MAX_ITER; ++it) {
    gm_csr_matvec(s->a, -1.0, x, 0.0, s->r);
    for (size_t i = 0; i < n; ++i) s->r[i] += b[i];
    gm_status st = gm_sparse_cholesky_solve(s->ch, s->r, s->dx);
    if (st != GM_OK) return st;
    for (size_t i = 0; i < n; ++i) x[i] += s->dx[i];
    if (gm_norm_inf(n, s->r) <= 1e-15 * bnorm) break;
    if (gm_norm_inf(n, s->dx) <= 1e-16 * gm_norm_inf(n, x)) break;
  }
  return GM_OK;
}

struct gm_hodge_decomposition {
  const gm_geometry *g;
  size_t k;
  int has_exact, has_coexact;
  semidef ex, co;
  double *rhs_ex, *beta, *rhs_co, *eta, *tmp;
  char errmsg[GM_ERRMSG_SIZE];
};

gm_status gm_hodge_decomposition_create(const gm_geometry *g, size_t k,
                                        gm_hodge_decomposition **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (g == NULL || k > g->cx->n) return gm_error_set(err, GM_EINVAL, "degree k out of range");
  const gm_complex *cx = g->cx;
  for (size_t i = 0; i < cx->count[k]; ++i)
    if (!(g->star[k][i] > 0.0))
      return gm_error_set(err, GM_EDOMAIN,
                          "Hodge decomposition needs a positive Hodge star: *_%zu = %.3g on "
                          "%zu-simplex %zu (the mesh is not well-centred there)",
                          k, g->star[k][i], k, i);
  gm_hodge_decomposition *hd = calloc(1, sizeof *hd);
  if (hd == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  hd->g = g;
  hd->k = k;
  hd->has_exact = k >= 1;
  hd->has_coexact = k < cx->n;
  gm_status st = GM_OK;
  size_t nk = cx->count[k];
  hd->tmp = malloc(nk * sizeof(double));
  if (hd->tmp == NULL) st = gm_error_set(err, GM_ENOMEM, "out of memory");
  if (st == GM_OK && hd->has_exact) { /* d_{k−1}ᵀ ⋆_k d_{k−1} */
    gm_csr *w = NULL, *wt = NULL, *a = NULL;
    st = gm_csr_copy(cx->d[k - 1], &w);
    if (st == GM_OK) gm_csr_scale_rows(w, g->star[k]), st = gm_csr_transpose(cx->d[k - 1], &wt);
    if (st == GM_OK) st = gm_csr_multiply(wt, w, &a);
    gm_csr_free(w), gm_csr_free(wt);
    if (st != GM_OK) st = gm_error_set(err, st, "out of memory");
    else st = semidef_init(&hd->ex, a, err);
    size_t m = cx->count[k - 1];
    hd->rhs_ex = malloc(m * sizeof(double));
    hd->beta = malloc(m * sizeof(double));
    if (st == GM_OK && (!hd->rhs_ex || !hd->beta)) st = gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  if (st == GM_OK && hd->has_coexact) { /* d_k ⋆_k^{-1} d_kᵀ */
    gm_csr *w = NULL, *wt = NULL, *a = NULL;
    double *inv = malloc(nk * sizeof(double));
    if (inv == NULL) st = GM_ENOMEM;
    for (size_t i = 0; inv && i < nk; ++i) inv[i] = 1.0 / g->star[k][i];
    if (st == GM_OK) st = gm_csr_copy(cx->d[k], &w);
    if (st == GM_OK) gm_csr_scale_cols(w, inv), st = gm_csr_transpose(cx->d[k], &wt);
    if (st == GM_OK) st = gm_csr_multiply(w, wt, &a);
    free(inv);
    gm_csr_free(w), gm_csr_free(wt);
    if (st != GM_OK) st = gm_error_set(err, st, "out of memory");
    else st = semidef_init(&hd->co, a, err);
    size_t m = cx->count[k + 1];
    hd->rhs_co = malloc(m * sizeof(double));
    hd->eta = malloc(m * sizeof(double));
    if (st == GM_OK && (!hd->rhs_co || !hd->eta)) st = gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  if (st != GM_OK) {
    gm_hodge_decomposition_free(hd);
    return st;
  }
  *out = hd;
  return GM_OK;
}

void gm_hodge_decomposition_free(gm_hodge_decomposition *hd) {
  if (hd == NULL) return;
  semidef_free(&hd->ex);
  semidef_free(&hd->co);
  free(hd->rhs_ex), free(hd->beta), free(hd->rhs_co), free(hd->eta), free(hd->tmp);
  free(hd);
}

const char *gm_hodge_decomposition_errmsg(const gm_hodge_decomposition *hd) {
  return hd ? hd->errmsg : "no decomposition";
}

gm_status gm_hodge_decomposition_apply(gm_hodge_decomposition *hd, const double *alpha,
                                       double *exact, double *coexact, double *harmonic) {
  if (hd == NULL || alpha == NULL) return GM_EINVAL;
  const gm_geometry *g = hd->g;
  const gm_complex *cx = g->cx;
  const size_t k = hd->k, nk = cx->count[k];
  if (gm_first_nonfinite(nk, alpha) != nk)
    return gm_fail(hd->errmsg, sizeof hd->errmsg, GM_EDOMAIN, "the cochain has non-finite values");
  if (harmonic) memcpy(harmonic, alpha, nk * sizeof(double));
  gm_status st;
  if (hd->has_exact) {
    for (size_t i = 0; i < nk; ++i) hd->tmp[i] = g->star[k][i] * alpha[i];
    gm_csr_matvec_transpose(cx->d[k - 1], 1.0, hd->tmp, 0.0, hd->rhs_ex);
    st = semidef_solve(&hd->ex, hd->rhs_ex, hd->beta);
    if (st != GM_OK)
      return gm_fail(hd->errmsg, sizeof hd->errmsg, st, "exact part: %s",
                     gm_sparse_cholesky_errmsg(hd->ex.ch));
    gm_csr_matvec(cx->d[k - 1], 1.0, hd->beta, 0.0, hd->tmp);
    if (exact) memcpy(exact, hd->tmp, nk * sizeof(double));
    if (harmonic)
      for (size_t i = 0; i < nk; ++i) harmonic[i] -= hd->tmp[i];
  } else if (exact) {
    memset(exact, 0, nk * sizeof(double));
  }
  if (hd->has_coexact) {
    gm_csr_matvec(cx->d[k], 1.0, alpha, 0.0, hd->rhs_co);
    st = semidef_solve(&hd->co, hd->rhs_co, hd->eta);
    if (st != GM_OK)
      return gm_fail(hd->errmsg, sizeof hd->errmsg, st, "coexact part: %s",
                     gm_sparse_cholesky_errmsg(hd->co.ch));
    gm_csr_matvec_transpose(cx->d[k], 1.0, hd->eta, 0.0, hd->tmp);
    for (size_t i = 0; i < nk; ++i) hd->tmp[i] /= g->star[k][i];
    if (coexact) memcpy(coexact, hd->tmp, nk * sizeof(double));
    if (harmonic)
      for (size_t i = 0; i < nk; ++i) harmonic[i] -= hd->tmp[i];
  } else if (coexact) {
    memset(coexact, 0, nk * sizeof(double));
  }
  return GM_OK;
}

static double pseudo_random(uint64_t *state) { /* splitmix64, local state */
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1p-52 - 1.0;
}

gm_status gm_dec_harmonic_basis(const gm_geometry *g, size_t k, size_t *count, double **basis,
                                gm_error *err) {
  if (g == NULL || count == NULL || basis == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *count = 0;
  *basis = NULL;
  size_t betti[GM_DEC_MAX_DIM + 1];
  gm_status st = gm_complex_betti_numbers(g->cx, betti);
  if (st != GM_OK) return gm_error_set(err, st, "Betti numbers of this complex are not available");
  if (k > g->cx->n) return gm_error_set(err, GM_EINVAL, "degree k out of range");
  const size_t b = betti[k], nk = g->cx->count[k];
  if (b == 0) return GM_OK;
  gm_hodge_decomposition *hd = NULL;
  st = gm_hodge_decomposition_create(g, k, &hd, err);
  if (st != GM_OK) return st;
  double *h = malloc(b * nk * sizeof(double)), *r = malloc(nk * sizeof(double));
  if (!h || !r) {
    free(h), free(r);
    gm_hodge_decomposition_free(hd);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  uint64_t seed = 0x5eed0000u + k;
  const double *w = g->star[k];
  for (size_t j = 0; j < b && st == GM_OK; ++j) {
    for (size_t i = 0; i < nk; ++i) r[i] = pseudo_random(&seed);
    st = gm_hodge_decomposition_apply(hd, r, NULL, NULL, h + j * nk);
    for (int pass = 0; pass < 2 && st == GM_OK; ++pass) { /* Gram–Schmidt, twice */
      double *v = h + j * nk;
      for (size_t q = 0; q < j; ++q) {
        double dot = 0.0;
        for (size_t i = 0; i < nk; ++i) dot += w[i] * v[i] * h[q * nk + i];
        for (size_t i = 0; i < nk; ++i) v[i] -= dot * h[q * nk + i];
      }
      double nrm = 0.0;
      for (size_t i = 0; i < nk; ++i) nrm += w[i] * v[i] * v[i];
      nrm = sqrt(nrm);
      if (!(nrm > 0.0)) {
        st = gm_error_set(err, GM_ESINGULAR, "harmonic space has dimension below b_%zu = %zu", k, b);
        break;
      }
      for (size_t i = 0; i < nk; ++i) v[i] /= nrm;
    }
  }
  if (st != GM_OK && err && err->message[0] == '\0')
    gm_error_set(err, st, "%s", gm_hodge_decomposition_errmsg(hd));
  gm_hodge_decomposition_free(hd);
  free(r);
  if (st != GM_OK) {
    free(h);
    return st;
  }
  *count = b;
  *basis = h;
  return GM_OK;
}
