/* The discrete Poincaré lemma: cone (homotopy) operators from a sequence of elementary collapses
 * (seed 001 §3.11, "generalized star-shaped" complexes).
 *
 * A greedy collapse removes pairs (σ, τ) where τ is a maximal simplex of the remaining complex
 * and σ a face of τ with no other coface. If the complex collapses to one vertex w, expanding it
 * back in reverse order defines a chain homotopy p: C_k -> C_{k+1} with p∂ + ∂p = I on k-chains
 * (k >= 1) and ∂p(v) = v − w: for the pair (σ, τ) with ∂τ = εσ + R,
 *   p(τ) = 0,  p(σ) = ε (τ − p(R)).
 * Proof (induction on the expansion; every face of τ other than σ, and every face of σ, was
 * already present): ∂p(σ) = ε(εσ + R − ∂p(R)) = σ + ε p(∂R) = σ − p(∂σ), since ∂p(R) = R − p∂R
 * and ∂R = −ε∂σ; and p(∂τ) = ε p(σ) + p(R) = τ. On vertices the same computation gives
 * ∂p(σ) = σ − w because R has coefficient sum −ε. This is the seed's recursion
 * p(σ^k) = σ^{k+1} − p(∂σ^{k+1} − σ^k), p(σ^{k+1}) = 0, with the signs of the incidence made
 * explicit. The cocone operator is H = pᵀ: ⟨Hα, σ⟩ = ⟨α, pσ⟩. */
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"

typedef struct {
  size_t *data;
  size_t len, cap;
} stack;

static int stack_push(stack *s, size_t v) {
  if (s->len == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 1024;
    size_t *d = realloc(s->data, cap * sizeof(size_t));
    if (d == NULL) return 0;
    s->data = d;
    s->cap = cap;
  }
  s->data[s->len++] = v;
  return 1;
}

typedef struct {
  size_t k, sigma, tau;
  double eps;
} collapse_pair;

typedef struct {
  const gm_complex *cx;
  gm_csr *cof[GM_DEC_MAX_DIM]; /* cof[k] = d_kᵀ: cofaces of k-simplices with incidence */
  size_t *count[GM_DEC_MAX_DIM + 1];
  unsigned char *alive[GM_DEC_MAX_DIM + 1];
  stack st;
  int oom;
} collapser;

#define ENC(k, s) ((s) * 4 + (k))

/* Faces of the alive maximal simplex (k, s) that now have exactly one coface become free. */
static void push_free_faces(collapser *c, size_t k, size_t s) {
  if (k == 0) return;
  const gm_csr *d = c->cx->d[k - 1];
  for (size_t q = d->row_start[s]; q < d->row_start[s + 1]; ++q) {
    size_t f = d->col[q];
    if (c->alive[k - 1][f] && c->count[k - 1][f] == 1 && !stack_push(&c->st, ENC(k - 1, f)))
      c->oom = 1;
  }
}

static void decrement(collapser *c, size_t k, size_t f) {
  size_t cnt = --c->count[k][f];
  if (!c->alive[k][f]) return;
  if (cnt == 1 && !stack_push(&c->st, ENC(k, f))) c->oom = 1;
  if (cnt == 0) push_free_faces(c, k, f);
}

gm_status gm_dec_cone_operators(const gm_complex *cx, gm_csr *H[GM_DEC_MAX_DIM + 1],
                                size_t *apex, gm_error *err) {
  if (cx == NULL || H == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) H[k] = NULL;
  const size_t n = cx->n;
  collapser c;
  memset(&c, 0, sizeof c);
  c.cx = cx;
  size_t total = 0;
  for (size_t k = 0; k <= n; ++k) total += cx->count[k];
  collapse_pair *pairs = malloc((total / 2 + 1) * sizeof(collapse_pair));
  size_t n_pairs = 0;
  gm_status st = GM_OK;
  double *acc = NULL;
  unsigned char *mark = NULL;
  size_t *touched = NULL, *row_start[GM_DEC_MAX_DIM] = {0}, *row_len[GM_DEC_MAX_DIM] = {0};
  stack pool_col[GM_DEC_MAX_DIM];
  double *pool_val[GM_DEC_MAX_DIM] = {0};
  size_t pool_val_cap[GM_DEC_MAX_DIM] = {0};
  memset(pool_col, 0, sizeof pool_col);
  if (pairs == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  for (size_t k = 0; k <= n; ++k) {
    c.count[k] = calloc(cx->count[k] ? cx->count[k] : 1, sizeof(size_t));
    c.alive[k] = malloc(cx->count[k] ? cx->count[k] : 1);
    if (!c.count[k] || !c.alive[k] || (k < n && gm_csr_transpose(cx->d[k], &c.cof[k]) != GM_OK)) {
      st = gm_error_set(err, GM_ENOMEM, "out of memory");
      goto done;
    }
    memset(c.alive[k], 1, cx->count[k]);
    if (k < n)
      for (size_t s = 0; s < cx->count[k]; ++s) {
        c.count[k][s] = c.cof[k]->row_start[s + 1] - c.cof[k]->row_start[s];
        if (c.count[k][s] == 1 && !stack_push(&c.st, ENC(k, s))) c.oom = 1;
      }
  }
  /* greedy collapse */
  while (c.st.len > 0 && !c.oom) {
    size_t code = c.st.data[--c.st.len], k = code % 4, s = code / 4;
    if (k >= n || !c.alive[k][s] || c.count[k][s] != 1) continue;
    const gm_csr *cf = c.cof[k];
    size_t tau = SIZE_MAX;
    double eps = 0.0;
    for (size_t q = cf->row_start[s]; q < cf->row_start[s + 1]; ++q)
      if (c.alive[k + 1][cf->col[q]]) {
        tau = cf->col[q];
        eps = cf->val[q];
        break;
      }
    if (tau == SIZE_MAX || c.count[k + 1][tau] != 0) continue;
    pairs[n_pairs].k = k;
    pairs[n_pairs].sigma = s;
    pairs[n_pairs].tau = tau;
    pairs[n_pairs].eps = eps;
    ++n_pairs;
    c.alive[k][s] = 0;
    c.alive[k + 1][tau] = 0;
    const gm_csr *d = cx->d[k];
    for (size_t q = d->row_start[tau]; q < d->row_start[tau + 1]; ++q)
      if (d->col[q] != s) decrement(&c, k, d->col[q]);
    if (k >= 1) {
      const gm_csr *dm = cx->d[k - 1];
      for (size_t q = dm->row_start[s]; q < dm->row_start[s + 1]; ++q)
        decrement(&c, k - 1, dm->col[q]);
    }
  }
  if (c.oom) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory in the collapse");
    goto done;
  }
  size_t left = 0, w = SIZE_MAX;
  for (size_t k = 0; k <= n; ++k)
    for (size_t s = 0; s < cx->count[k]; ++s)
      if (c.alive[k][s]) {
        ++left;
        if (k == 0) w = s;
      }
  if (left != 1 || w == SIZE_MAX) {
    st = gm_error_set(err, GM_EUNSUPPORTED,
                      "the complex does not collapse to a vertex (%zu simplices left after "
                      "%zu elementary collapses): it is not contractible, or not collapsible "
                      "greedily; the Poincaré lemma needs a contractible complex",
                      left, n_pairs);
    goto done;
  }
  if (apex) *apex = w;
  /* chain homotopy p in reverse collapse order */
  size_t maxc = 0;
  for (size_t k = 0; k <= n; ++k)
    if (cx->count[k] > maxc) maxc = cx->count[k];
  acc = calloc(maxc, sizeof(double));
  touched = malloc(maxc * sizeof(size_t));
  mark = calloc(maxc, 1);
  if (!acc || !touched || !mark) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory");
    goto done;
  }
  for (size_t k = 0; k < n; ++k) {
    row_start[k] = calloc(cx->count[k] ? cx->count[k] : 1, sizeof(size_t));
    row_len[k] = calloc(cx->count[k] ? cx->count[k] : 1, sizeof(size_t));
    if (!row_start[k] || !row_len[k]) {
      st = gm_error_set(err, GM_ENOMEM, "out of memory");
      goto done;
    }
  }
  for (size_t i = n_pairs; i-- > 0;) {
    const size_t k = pairs[i].k, sigma = pairs[i].sigma, tau = pairs[i].tau;
    const double eps = pairs[i].eps;
    size_t nt = 0;
    acc[tau] += eps;
    mark[tau] = 1;
    touched[nt++] = tau;
    const gm_csr *d = cx->d[k];
    for (size_t q = d->row_start[tau]; q < d->row_start[tau + 1]; ++q) {
      size_t f = d->col[q];
      if (f == sigma) continue;
      double inc = d->val[q];
      for (size_t r = row_start[k][f]; r < row_start[k][f] + row_len[k][f]; ++r) {
        size_t col = pool_col[k].data[r];
        if (!mark[col]) {
          mark[col] = 1;
          touched[nt++] = col;
        }
        acc[col] -= eps * inc * pool_val[k][r];
      }
    }
    row_start[k][sigma] = pool_col[k].len;
    for (size_t q = 0; q < nt; ++q) {
      size_t col = touched[q];
      double v = acc[col];
      acc[col] = 0.0;
      mark[col] = 0;
      if (v == 0.0) continue;
      if (!stack_push(&pool_col[k], col)) {
        st = gm_error_set(err, GM_ENOMEM, "out of memory for the cone chains");
        goto done;
      }
      if (pool_col[k].cap > pool_val_cap[k]) {
        double *nv = realloc(pool_val[k], pool_col[k].cap * sizeof(double));
        if (nv == NULL) {
          st = gm_error_set(err, GM_ENOMEM, "out of memory for the cone chains");
          goto done;
        }
        pool_val[k] = nv;
        pool_val_cap[k] = pool_col[k].cap;
      }
      pool_val[k][pool_col[k].len - 1] = v;
    }
    row_len[k][sigma] = pool_col[k].len - row_start[k][sigma];
  }
  for (size_t k = 0; k < n && st == GM_OK; ++k) {
    size_t nnz = pool_col[k].len;
    gm_csr *h = NULL;
    st = gm_csr_create(cx->count[k], cx->count[k + 1], nnz, &h);
    if (st != GM_OK) {
      st = gm_error_set(err, st, "out of memory");
      break;
    }
    /* rows in index order, columns sorted within a row */
    size_t pos = 0;
    for (size_t s = 0; s < cx->count[k]; ++s) {
      size_t b = row_start[k][s], e = b + row_len[k][s], p0 = pos;
      for (size_t r = b; r < e; ++r) {
        size_t col = pool_col[k].data[r];
        double v = pool_val[k][r];
        size_t q = pos++;
        while (q > p0 && h->col[q - 1] > col) {
          h->col[q] = h->col[q - 1];
          h->val[q] = h->val[q - 1];
          --q;
        }
        h->col[q] = col;
        h->val[q] = v;
      }
      h->row_start[s + 1] = pos;
    }
    H[k + 1] = h;
  }
done:
  if (st != GM_OK)
    for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) {
      gm_csr_free(H[k]);
      H[k] = NULL;
    }
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) {
    free(c.count[k]);
    free(c.alive[k]);
    if (k < GM_DEC_MAX_DIM) {
      gm_csr_free(c.cof[k]);
      free(row_start[k]);
      free(row_len[k]);
      free(pool_col[k].data);
      free(pool_val[k]);
    }
  }
  free(c.st.data);
  free(pairs);
  free(acc);
  free(touched);
  free(mark);
  return st;
}
