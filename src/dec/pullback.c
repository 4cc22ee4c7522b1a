/* Pull-back of cochains under a simplicial map (seed 001 ch. 3, "dynamic DEC"; notes 001:
 * ⟨f*α, σ⟩ = ⟨α, f(σ)⟩). A vertex map f: K_0 → M_0 is simplicial when the image of every
 * simplex of K spans a simplex of M; f(σ) is then that simplex with the sign of the permutation
 * that sorts the images (times the orientations of top simplices), or 0 when two vertices of σ
 * have the same image (σ collapses). f_# on chains commutes with ∂ (the standard chain map of a
 * simplicial map, degenerate simplices being 0), so f* = f_#ᵀ commutes with d exactly. */
#include <stdint.h>
#include <stdlib.h>

#include "dec/internal.h"
#include "geomint/multigrid.h"

gm_status gm_dec_pullback(const gm_complex *K, const gm_complex *M, const size_t *vertex_map,
                          size_t k, gm_csr **out, gm_error *err) {
  if (K == NULL || M == NULL || vertex_map == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  *out = NULL;
  if (k > K->n || k > M->n)
    return gm_error_set(err, GM_EINVAL, "k = %zu exceeds the dimension of K (%zu) or M (%zu)", k,
                        K->n, M->n);
  for (size_t v = 0; v < K->n_vertices; ++v)
    if (vertex_map[v] >= M->n_vertices)
      return gm_error_set(err, GM_EINVAL, "vertex %zu maps to %zu, M has %zu vertices", v,
                          vertex_map[v], M->n_vertices);
  const size_t nk = K->count[k];
  size_t *rows = malloc((nk ? nk : 1) * sizeof(size_t));
  size_t *cols = malloc((nk ? nk : 1) * sizeof(size_t));
  double *vals = malloc((nk ? nk : 1) * sizeof(double));
  if (!rows || !cols || !vals) {
    free(rows), free(cols), free(vals);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  size_t w = 0;
  gm_status st = GM_OK;
  for (size_t i = 0; i < nk && st == GM_OK; ++i) {
    size_t img[GM_LOCAL_MAX];
    for (size_t q = 0; q <= k; ++q) img[q] = vertex_map[K->simplices[k][i * (k + 1) + q]];
    int sign = 1, degenerate = 0;
    for (size_t a = 1; a <= k; ++a) /* insertion sort, counting transpositions */
      for (size_t b = a; b > 0 && img[b - 1] >= img[b]; --b) {
        if (img[b - 1] == img[b]) {
          degenerate = 1;
          break;
        }
        size_t t = img[b];
        img[b] = img[b - 1], img[b - 1] = t;
        sign = -sign;
      }
    if (!degenerate)
      for (size_t a = 1; a <= k; ++a) degenerate |= img[a] == img[a - 1];
    if (degenerate) continue;
    size_t t = gm_complex_find(M, k, img);
    if (t == SIZE_MAX) {
      st = gm_error_set(err, GM_EINVAL,
                        "not a simplicial map: the image of %zu-simplex %zu of K is not a simplex "
                        "of M",
                        k, i);
      break;
    }
    sign *= gm_simplex_sign(K, k, i) * gm_simplex_sign(M, k, t);
    rows[w] = i, cols[w] = t, vals[w++] = sign;
  }
  if (st == GM_OK) st = gm_csr_from_triplets(nk, M->count[k], w, rows, cols, vals, out, err);
  free(rows), free(cols), free(vals);
  return st;
}
