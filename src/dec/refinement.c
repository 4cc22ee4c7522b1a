/* Parent maps of a red refinement (src/mesh/refine.c) and the nested transfers of cochains.
 *
 * Carrier. Every fine vertex lies in a coarse vertex or at the midpoint of a coarse edge; the
 * union S of the coarse vertices of a fine simplex σ's vertices spans the smallest coarse
 * simplex containing σ (σ's barycentre has positive barycentric coordinates on all of S), its
 * carrier. When dim S = dim σ, σ is a piece of the coarse simplex S with an orientation sign: the
 * sign of det[β_j(s_i)], the barycentric coordinates of σ's vertices in S (entries 0, ½, 1).
 *
 * Restriction (fine → coarse, seed 001 ch. 3 "remeshing": coarsening sums the fine values):
 *   ⟨R ω, τ⟩ = Σ_{σ ⊂ τ, dim σ = dim τ} sgn(σ, τ) ⟨ω, σ⟩,
 * i.e. R = Sdᵀ for the subdivision chain map Sd τ = Σ sgn(σ,τ) σ. Sd commutes with ∂ (the
 * boundary of the subdivided simplex is the subdivided boundary: interior pieces cancel in
 * pairs), so d_c R = R d_f exactly: R is a cochain map. For k = 0 it is the injection.
 *
 * Prolongation (coarse → fine): ⟨P ω, σ⟩ = ∫_σ W ω, the de Rham map of the coarse Whitney
 * interpolant. d W = W d (Whitney 1957) and the de Rham map commutes with d (Stokes), so
 * d_f P = P d_c exactly as well, and R P = I (∫ over the pieces sums to ∫ over τ). The Whitney
 * form of a face τ of S pulled back to S is S's own Whitney form (and 0 when τ ⊄ S), so the
 * integral is computed inside the carrier: with β_0..β_k the barycentric coordinates of σ's
 * vertices in S and b their mean, for τ = [s_{i_0}..s_{i_k}] ⊂ S (the integrand is affine, the
 * barycentre rule is exact):
 *   ∫_σ φ_τ = Σ_j (−1)^j b(i_j) det[(β_l − β_0)(i_{j'})]_{j' ≠ j, l = 1..k}. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"
#include "geomint/multigrid.h"

struct gm_refinement {
  const gm_complex *coarse, *fine;
  size_t n;
  unsigned char *parent_dim[GM_DEC_MAX_DIM + 1];
  size_t *parent[GM_DEC_MAX_DIM + 1];
  signed char *parent_sign[GM_DEC_MAX_DIM + 1];
};

void gm_refinement_free(gm_refinement *r) {
  if (r == NULL) return;
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) {
    free(r->parent_dim[k]);
    free(r->parent[k]);
    free(r->parent_sign[k]);
  }
  free(r);
}

/* Coarse vertices carrying fine vertex v (1 or 2, ascending). */
static size_t carrier_of_vertex(const gm_complex *c, size_t v, size_t s[2]) {
  if (v < c->n_vertices) {
    s[0] = v;
    return 1;
  }
  const size_t *e = c->simplices[1] + 2 * (v - c->n_vertices);
  s[0] = e[0], s[1] = e[1];
  return 2;
}

/* Barycentric coordinates of fine vertex v in the carrier S (m+1 ascending coarse vertices). */
static void barycentric_in(const gm_complex *c, size_t v, const size_t *S, size_t m, double *beta) {
  size_t s[2];
  size_t q = carrier_of_vertex(c, v, s);
  for (size_t i = 0; i <= m; ++i) beta[i] = 0.0;
  for (size_t a = 0; a < q; ++a)
    for (size_t i = 0; i <= m; ++i)
      if (S[i] == s[a]) beta[i] += q == 1 ? 1.0 : 0.5;
}

static double det_small(size_t n, double *a) { /* Gaussian elimination with pivoting, n <= 4 */
  double det = 1.0;
  for (size_t c = 0; c < n; ++c) {
    size_t p = c;
    for (size_t r = c + 1; r < n; ++r)
      if (fabs(a[r * n + c]) > fabs(a[p * n + c])) p = r;
    if (a[p * n + c] == 0.0) return 0.0;
    if (p != c) {
      for (size_t j = 0; j < n; ++j) {
        double t = a[c * n + j];
        a[c * n + j] = a[p * n + j], a[p * n + j] = t;
      }
      det = -det;
    }
    det *= a[c * n + c];
    for (size_t r = c + 1; r < n; ++r) {
      double f = a[r * n + c] / a[c * n + c];
      for (size_t j = c; j < n; ++j) a[r * n + j] -= f * a[c * n + j];
    }
  }
  return det;
}

/* The carrier S (ascending, returns its size) of the fine k-simplex with the given vertices. */
static size_t carrier(const gm_complex *c, size_t k, const size_t *verts, size_t *S) {
  size_t m = 0;
  for (size_t i = 0; i <= k; ++i) {
    size_t s[2] = {0, 0};
    size_t q = carrier_of_vertex(c, verts[i], s);
    for (size_t a = 0; a < q; ++a) {
      size_t j = 0;
      while (j < m && S[j] != s[a]) ++j;
      if (j == m && m < 8) S[m++] = s[a];
    }
  }
  for (size_t i = 1; i < m; ++i) /* insertion sort */
    for (size_t j = i; j > 0 && S[j - 1] > S[j]; --j) {
      size_t t = S[j];
      S[j] = S[j - 1], S[j - 1] = t;
    }
  return m;
}

gm_status gm_refinement_create(const gm_complex *coarse, const gm_complex *fine,
                               gm_refinement **out, gm_error *err) {
  if (coarse == NULL || fine == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  const size_t n = coarse->n, N = coarse->N, nv = coarse->n_vertices;
  if (fine->n != n || fine->N != N)
    return gm_error_set(err, GM_EINVAL, "the fine complex has dimension %zu in R^%zu, the coarse "
                        "one %zu in R^%zu", fine->n, fine->N, n, N);
  const size_t per = (size_t)1 << n;
  if (fine->n_vertices != nv + coarse->count[1] || fine->count[n] != per * coarse->count[n])
    return gm_error_set(err, GM_EINVAL,
                        "not a red refinement: the fine complex has %zu vertices and %zu cells, "
                        "red refinement gives %zu and %zu",
                        fine->n_vertices, fine->count[n], nv + coarse->count[1],
                        per * coarse->count[n]);
  for (size_t v = 0; v < fine->n_vertices; ++v) {
    size_t s[2] = {0, 0};
    size_t q = carrier_of_vertex(coarse, v, s);
    for (size_t j = 0; j < N; ++j) {
      double want = q == 1 ? coarse->x[s[0] * N + j]
                           : 0.5 * (coarse->x[s[0] * N + j] + coarse->x[s[1] * N + j]);
      if (fine->x[v * N + j] != want)
        return gm_error_set(err, GM_EINVAL,
                            "not nested: fine vertex %zu is not %s (coordinate %zu is %.17g, "
                            "expected %.17g)",
                            v, q == 1 ? "the coarse vertex of the same index"
                                      : "the midpoint of its coarse edge",
                            j, fine->x[v * N + j], want);
    }
  }
  gm_refinement *r = calloc(1, sizeof *r);
  if (r == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  r->coarse = coarse, r->fine = fine, r->n = n;
  for (size_t k = 0; k <= n; ++k) {
    size_t m = fine->count[k];
    r->parent_dim[k] = malloc(m ? m : 1);
    r->parent[k] = malloc((m ? m : 1) * sizeof(size_t));
    r->parent_sign[k] = malloc(m ? m : 1);
    if (!r->parent_dim[k] || !r->parent[k] || !r->parent_sign[k]) {
      gm_refinement_free(r);
      return gm_error_set(err, GM_ENOMEM, "out of memory for the parent maps (%zu %zu-simplices)",
                          m, k);
    }
    for (size_t i = 0; i < m; ++i) {
      const size_t *verts = fine->simplices[k] + i * (k + 1);
      size_t S[8];
      size_t ms = carrier(coarse, k, verts, S);
      size_t p = ms <= n + 1 ? gm_complex_find(coarse, ms - 1, S) : SIZE_MAX;
      if (p == SIZE_MAX || (k == n && p != i / per)) {
        gm_refinement_free(r);
        return gm_error_set(err, GM_EINVAL,
                            "not nested: fine %zu-simplex %zu lies in no coarse simplex%s", k, i,
                            k == n ? " (or not in the parent cell its index says)" : "");
      }
      r->parent_dim[k][i] = (unsigned char)(ms - 1);
      r->parent[k][i] = p;
      r->parent_sign[k][i] = 0;
      if (ms - 1 == k) {
        double a[16];
        for (size_t l = 0; l <= k; ++l) barycentric_in(coarse, verts[l], S, k, a + l * (k + 1));
        double det = det_small(k + 1, a);
        int sgn = det > 0 ? 1 : -1;
        if (k == n) sgn *= fine->orient[i] * coarse->orient[p];
        r->parent_sign[k][i] = (signed char)sgn;
      }
    }
  }
  *out = r;
  return GM_OK;
}

const gm_complex *gm_refinement_coarse(const gm_refinement *r) { return r->coarse; }
const gm_complex *gm_refinement_fine(const gm_refinement *r) { return r->fine; }
const unsigned char *gm_refinement_parent_dim(const gm_refinement *r, size_t k) {
  return r && k <= r->n ? r->parent_dim[k] : NULL;
}
const size_t *gm_refinement_parent(const gm_refinement *r, size_t k) {
  return r && k <= r->n ? r->parent[k] : NULL;
}
const signed char *gm_refinement_parent_sign(const gm_refinement *r, size_t k) {
  return r && k <= r->n ? r->parent_sign[k] : NULL;
}

gm_status gm_refinement_restriction(const gm_refinement *r, size_t k, gm_csr **out,
                                    gm_error *err) {
  if (r == NULL || out == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (k > r->n) return gm_error_set(err, GM_EINVAL, "k = %zu > dimension %zu", k, r->n);
  const size_t nf = r->fine->count[k], nc = r->coarse->count[k];
  size_t nnz = 0;
  for (size_t i = 0; i < nf; ++i) nnz += r->parent_dim[k][i] == k;
  size_t *rows = malloc((nnz ? nnz : 1) * sizeof(size_t));
  size_t *cols = malloc((nnz ? nnz : 1) * sizeof(size_t));
  double *vals = malloc((nnz ? nnz : 1) * sizeof(double));
  gm_status st = GM_ENOMEM;
  if (rows && cols && vals) {
    size_t w = 0;
    for (size_t i = 0; i < nf; ++i)
      if (r->parent_dim[k][i] == k) {
        rows[w] = r->parent[k][i], cols[w] = i, vals[w++] = r->parent_sign[k][i];
      }
    st = gm_csr_from_triplets(nc, nf, nnz, rows, cols, vals, out, err);
  } else {
    gm_error_set(err, st, "out of memory");
  }
  free(rows), free(cols), free(vals);
  return st;
}

gm_status gm_refinement_prolongation(const gm_refinement *r, size_t k, gm_csr **out,
                                     gm_error *err) {
  if (r == NULL || out == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (k > r->n) return gm_error_set(err, GM_EINVAL, "k = %zu > dimension %zu", k, r->n);
  const gm_complex *c = r->coarse, *f = r->fine;
  const size_t nf = f->count[k], nc = c->count[k];
  const size_t cap = nf * gm_binomial(r->n + 1, k + 1);
  size_t *rows = malloc((cap ? cap : 1) * sizeof(size_t));
  size_t *cols = malloc((cap ? cap : 1) * sizeof(size_t));
  double *vals = malloc((cap ? cap : 1) * sizeof(double));
  if (!rows || !cols || !vals) {
    free(rows), free(cols), free(vals);
    return gm_error_set(err, GM_ENOMEM, "out of memory for the prolongation (%zu entries)", cap);
  }
  size_t w = 0;
  for (size_t i = 0; i < nf; ++i) {
    const size_t *verts = f->simplices[k] + i * (k + 1);
    size_t S[8];
    const size_t m = carrier(c, k, verts, S) - 1;
    double beta[4][4], b[4] = {0, 0, 0, 0};
    for (size_t l = 0; l <= k; ++l) {
      barycentric_in(c, verts[l], S, m, beta[l]);
      for (size_t q = 0; q <= m; ++q) b[q] += beta[l][q] / (double)(k + 1);
    }
    const int sf = k == r->n ? f->orient[i] : 1;
    /* the (k+1)-subsets I of the m+1 carrier positions */
    for (unsigned mask = 1; mask < (1u << (m + 1)); ++mask) {
      size_t I[4], ni = 0;
      for (size_t q = 0; q <= m; ++q)
        if (mask & (1u << q)) I[ni++] = q;
      if (ni != k + 1) continue;
      double val = 0.0;
      for (size_t j = 0; j <= k; ++j) {
        double a[9];
        size_t row = 0;
        for (size_t jj = 0; jj <= k; ++jj) {
          if (jj == j) continue;
          for (size_t l = 1; l <= k; ++l) a[row * k + (l - 1)] = beta[l][I[jj]] - beta[0][I[jj]];
          ++row;
        }
        double det = k == 0 ? 1.0 : det_small(k, a);
        val += ((j & 1) ? -1.0 : 1.0) * b[I[j]] * det;
      }
      if (val == 0.0) continue;
      size_t tv[4];
      for (size_t q = 0; q <= k; ++q) tv[q] = S[I[q]];
      size_t t = gm_complex_find(c, k, tv);
      const int sc = k == r->n ? c->orient[t] : 1;
      rows[w] = i, cols[w] = t, vals[w++] = val * sf * sc;
    }
  }
  gm_status st = gm_csr_from_triplets(nf, nc, w, rows, cols, vals, out, err);
  free(rows), free(cols), free(vals);
  return st;
}

gm_status gm_refinement_well_centredness(const gm_refinement *r, gm_well_centredness *wc) {
  if (r == NULL || wc == NULL) return GM_EINVAL;
  memset(wc, 0, sizeof *wc);
  const size_t n = r->n, N = r->coarse->N, per = (size_t)1 << n;
  wc->coarse_margin = INFINITY, wc->fine_margin = INFINITY, wc->children_margin = INFINITY;
  double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], cc[GM_DEC_MAX_EMBED], bary[GM_LOCAL_MAX];
  unsigned char *wcc = malloc(r->coarse->count[n] ? r->coarse->count[n] : 1);
  if (wcc == NULL) return GM_ENOMEM;
  for (size_t t = 0; t < r->coarse->count[n]; ++t) {
    gm_gather_points(r->coarse, n, r->coarse->simplices[n] + t * (n + 1), p);
    gm_local_circumcenter(N, n, p, cc, bary);
    double mn = INFINITY;
    for (size_t i = 0; i <= n; ++i) mn = fmin(mn, bary[i]);
    wcc[t] = mn > 0.0;
    wc->coarse_well_centred += wcc[t];
    wc->coarse_margin = fmin(wc->coarse_margin, mn);
  }
  for (size_t t = 0; t < r->fine->count[n]; ++t) {
    gm_gather_points(r->fine, n, r->fine->simplices[n] + t * (n + 1), p);
    gm_local_circumcenter(N, n, p, cc, bary);
    double mn = INFINITY;
    for (size_t i = 0; i <= n; ++i) mn = fmin(mn, bary[i]);
    wc->fine_well_centred += mn > 0.0;
    wc->fine_margin = fmin(wc->fine_margin, mn);
    if (wcc[t / per]) {
      wc->children_of_well_centred += 1;
      wc->children_well_centred += mn > 0.0;
      wc->children_margin = fmin(wc->children_margin, mn);
    }
  }
  wc->coarse_cells = r->coarse->count[n];
  wc->fine_cells = r->fine->count[n];
  free(wcc);
  return GM_OK;
}

gm_status gm_refinement_vertex_prolongation(const gm_complex *coarse, size_t n_fine_vertices,
                                            const unsigned char *coarse_drop,
                                            const unsigned char *fine_drop, gm_csr **out,
                                            gm_error *err) {
  if (coarse == NULL || out == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  const size_t nv = coarse->n_vertices, ne = coarse->count[1], nf = n_fine_vertices;
  if (nf != nv + ne)
    return gm_error_set(err, GM_EINVAL,
                        "not a red refinement: %zu fine vertices, the coarse complex has %zu "
                        "vertices and %zu edges",
                        nf, nv, ne);
  size_t *cmap = malloc((nv ? nv : 1) * sizeof(size_t)), nc = 0, nr = 0;
  if (cmap == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  for (size_t v = 0; v < nv; ++v) cmap[v] = coarse_drop && coarse_drop[v] ? SIZE_MAX : nc++;
  for (size_t v = 0; v < nf; ++v) nr += !(fine_drop && fine_drop[v]);
  gm_csr *P = NULL;
  gm_status st = gm_csr_create(nr, nc, nv + 2 * ne, &P);
  if (st != GM_OK) {
    free(cmap);
    return gm_error_set(err, st, "out of memory for the prolongation");
  }
  size_t w = 0, r = 0;
  for (size_t v = 0; v < nf; ++v) {
    if (fine_drop && fine_drop[v]) continue;
    size_t c[2] = {v, SIZE_MAX};
    double val = 1.0;
    if (v >= nv) { /* midpoint: the mean of the edge's ends (ascending, so columns ascend) */
      c[0] = coarse->simplices[1][2 * (v - nv)], c[1] = coarse->simplices[1][2 * (v - nv) + 1];
      val = 0.5;
    }
    for (int q = 0; q < 2; ++q)
      if (c[q] != SIZE_MAX && cmap[c[q]] != SIZE_MAX) P->col[w] = cmap[c[q]], P->val[w++] = val;
    P->row_start[++r] = w;
  }
  free(cmap);
  *out = P;
  return GM_OK;
}
