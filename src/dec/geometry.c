/* Primal and dual geometry of a complex: circumcenters, volumes, signed circumcentric (or
 * barycentric) dual volumes restricted to the complex, dual volumes inside the boundary complex,
 * diagonal Hodge stars, Whitney mass matrices.
 *
 * Dual volumes are accumulated top simplex by top simplex: |⋆σ| = Σ_{T ≻ σ} |⋆σ ∩ T| (seed 001
 * §3.3: "dual volumes are summed per n-simplex"), which is the dual restricted to |K| (seed 000
 * §3.3.2). The dual of a boundary k-simplex inside the boundary (n−1)-complex is computed the
 * same way with the boundary faces as top simplices. Hodge star: ⋆_k = |⋆σ|/|σ| (seed 001 §3.5,
 * Hirani 2003 Def. 4.1.1). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"

gm_geometry_options gm_geometry_defaults(void) {
  gm_geometry_options o;
  o.dual = GM_DUAL_CIRCUMCENTRIC;
  o.degenerate_tol = 1e-12;
  o.allow_inverted = 0;
  return o;
}

/* Global index of the face of simplex s (dimension d) spanned by the vertex positions in mask
 * (bitmask over the d+1 sorted vertices of s). */
static size_t subface(const gm_complex *cx, size_t d, size_t s, unsigned mask) {
  unsigned full = (1u << (d + 1)) - 1;
  while (mask != full) {
    /* drop the highest missing position */
    size_t drop = d;
    while (mask & (1u << drop)) --drop;
    s = cx->faces[d][s * (d + 1) + drop];
    /* remove bit `drop` from both masks (shift the higher bits down) */
    unsigned low = (1u << drop) - 1;
    mask = (mask & low) | ((mask >> 1) & ~low);
    --d;
    full = (1u << (d + 1)) - 1;
  }
  return s;
}

/* Face of simplex s of dimension d given by mask, with vertices handled directly. */
size_t gm_local_face(const gm_complex *cx, size_t d, size_t s, unsigned mask) {
  if ((mask & (mask - 1)) == 0) {
    size_t pos = (size_t)__builtin_ctz(mask);
    return cx->simplices[d][s * (d + 1) + pos];
  }
  return subface(cx, d, s, mask);
}

gm_status gm_complex_local_faces(const gm_complex *cx, size_t top, size_t k, size_t *indices) {
  if (cx == NULL || indices == NULL || k > cx->n || top >= cx->count[cx->n]) return GM_EINVAL;
  const size_t n = cx->n;
  size_t q = 0;
  /* lexicographic order of position subsets of size k+1 */
  size_t pos[GM_LOCAL_MAX];
  for (size_t i = 0; i <= k; ++i) pos[i] = i;
  for (;;) {
    unsigned mask = 0;
    for (size_t i = 0; i <= k; ++i) mask |= 1u << pos[i];
    indices[q++] = gm_local_face(cx, n, top, mask);
    size_t i = k + 1;
    while (i-- > 0 && pos[i] == n - k + i) {
    }
    if (i == SIZE_MAX) break;
    ++pos[i];
    for (size_t j = i + 1; j <= k; ++j) pos[j] = pos[j - 1] + 1;
  }
  return GM_OK;
}

static void local_masks(size_t n, size_t k, unsigned *masks) {
  size_t q = 0;
  size_t pos[GM_LOCAL_MAX];
  for (size_t i = 0; i <= k; ++i) pos[i] = i;
  for (;;) {
    unsigned mask = 0;
    for (size_t i = 0; i <= k; ++i) mask |= 1u << pos[i];
    masks[q++] = mask;
    size_t i = k + 1;
    while (i-- > 0 && pos[i] == n - k + i) {
    }
    if (i == SIZE_MAX) break;
    ++pos[i];
    for (size_t j = i + 1; j <= k; ++j) pos[j] = pos[j - 1] + 1;
  }
}

gm_status gm_geometry_dual_pieces(const gm_geometry *g, size_t top, size_t k, double *pieces) {
  if (g == NULL || pieces == NULL) return GM_EINVAL;
  const gm_complex *cx = g->cx;
  const size_t n = cx->n, N = cx->N;
  if (k > n || top >= cx->count[n]) return GM_EINVAL;
  double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], all[16];
  unsigned masks[6];
  gm_gather_points(cx, n, cx->simplices[n] + top * (n + 1), p);
  gm_local_dual_pieces(N, n, p, g->opt.dual, all);
  local_masks(n, k, masks);
  size_t m = gm_binomial(n + 1, k + 1);
  for (size_t i = 0; i < m; ++i) pieces[i] = all[masks[i]];
  return GM_OK;
}

static double longest_edge(size_t N, size_t m, const double *p) {
  double L = 0.0;
  for (size_t i = 0; i <= m; ++i)
    for (size_t j = i + 1; j <= m; ++j) {
      double d2 = 0.0;
      for (size_t q = 0; q < N; ++q) d2 += (p[i * N + q] - p[j * N + q]) * (p[i * N + q] - p[j * N + q]);
      if (d2 > L) L = d2;
    }
  return sqrt(L);
}

/* Signed n-volume of the oriented top simplex (N == n only). */
static double oriented_volume(size_t n, const double *p, int orient) {
  double e[3][3] = {{0}};
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 0; j < n; ++j) e[i - 1][j] = p[i * n + j] - p[j];
  double det;
  if (n == 1)
    det = e[0][0];
  else if (n == 2)
    det = (e[0][0] * e[1][1] - e[0][1] * e[1][0]) / 2.0;
  else
    det = (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
           e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) / 6.0;
  return orient * det;
}

static const char *name_of(size_t k) {
  static const char *names[] = {"vertex", "edge", "triangle", "tetrahedron"};
  return names[k];
}

/* Circumcentric dual pieces of every subset of the d-simplex s from the stored circumcenters:
 * the recursion of gm_local_dual_pieces (same operations in the same order, hence the same bits)
 * with the sign of each barycentric coordinate taken from g->bsign instead of recomputing the 15
 * circumcenters of a tetrahedron per tetrahedron. idx receives the global index of each subset
 * (bitmask over the d+1 ascending vertices of s). */
static const unsigned char popcount4[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

typedef struct {
  unsigned n_masks;           /* the 2^(d+1) − 2 proper non-empty subsets, by decreasing size and
                                 then increasing mask (the order of gm_local_dual_pieces) */
  unsigned mask[14], sup[14]; /* sup: mask plus its lowest missing position */
  unsigned char pos[14];      /* position of that added vertex within sup */
  unsigned char size[14];
  unsigned char n_up[14];     /* the supersets with one more vertex, by increasing added vertex */
  unsigned up[14][3];
  unsigned char up_pos[14][3];
} face_table;

static void face_table_init(size_t d, face_table *ft) {
  const unsigned full = (1u << (d + 1)) - 1;
  ft->n_masks = 0;
  for (size_t size = d; size >= 1; --size)
    for (unsigned m = 1; m < full; ++m) {
      if (popcount4[m] != size) continue;
      const unsigned q = ft->n_masks++;
      unsigned v = (unsigned)__builtin_ctz(~m);
      unsigned t = m | (1u << v);
      ft->mask[q] = m;
      ft->sup[q] = t;
      ft->pos[q] = popcount4[t & ((1u << v) - 1)];
      ft->size[q] = (unsigned char)size;
      ft->n_up[q] = 0;
      for (unsigned w = 0; w <= d; ++w) {
        if (m & (1u << w)) continue;
        unsigned u = m | (1u << w);
        ft->up[q][ft->n_up[q]] = u;
        ft->up_pos[q][ft->n_up[q]++] = popcount4[u & ((1u << w) - 1)];
      }
    }
}

static void face_indices(const gm_complex *cx, size_t d, size_t s, const face_table *ft,
                         size_t *idx) {
  idx[(1u << (d + 1)) - 1] = s;
  for (unsigned q = 0; q < ft->n_masks; ++q) {
    unsigned m = ft->mask[q];
    if (ft->size[q] == 1)
      idx[m] = cx->simplices[d][s * (d + 1) + (size_t)__builtin_ctz(m)];
    else /* facet of the (size)-face sup opposite the added vertex */
      idx[m] = cx->faces[ft->size[q]][idx[ft->sup[q]] * (ft->size[q] + 1) + ft->pos[q]];
  }
}

static const double factorial_table[] = {1.0, 1.0, 2.0, 6.0};

/* Circumcentric dual pieces of every subset of the d-simplex whose subsets have the global
 * indices idx (face_indices), from the stored circumcenters: the recursion of
 * gm_local_dual_pieces (same operations in the same order, hence the same bits), with the sign
 * of each barycentric coordinate read from g->bsign instead of recomputing the 15 circumcenters
 * of a tetrahedron in every tetrahedron. */
static void stored_dual_pieces(const gm_geometry *g, size_t d, const face_table *ft,
                               const size_t *idx, double *pieces) {
  const size_t N = g->cx->N;
  const unsigned full = (1u << (d + 1)) - 1;
  double P[16];
  P[full] = 1.0;
  pieces[full] = 1.0;
  for (unsigned q = 0; q < ft->n_masks; ++q) {
    const unsigned s = ft->mask[q], size = ft->size[q];
    const double *cs = g->centers[size - 1] + idx[s] * N;
    double sum = 0.0;
    for (unsigned r = 0; r < ft->n_up[q]; ++r) {
      const unsigned t = ft->up[q][r], pos = ft->up_pos[q][r];
      const double *ct = g->centers[size] + idx[t] * N;
      double d2 = 0.0;
      for (size_t j = 0; j < N; ++j) {
        double dd = ct[j] - cs[j];
        d2 += dd * dd;
      }
      unsigned sg = (g->bsign[size][idx[t]] >> (2 * pos)) & 3u;
      double h = sg == 1 ? sqrt(d2) : sg == 2 ? -sqrt(d2) : 0.0;
      sum += h * P[t];
    }
    P[s] = sum;
    pieces[s] = sum / factorial_table[d + 1 - size];
  }
}

/* Circumcenter (or barycenter), volume and barycentric signs of k-simplex s. */
static double center_of(gm_geometry *g, size_t k, size_t s, double *p) {
  const gm_complex *cx = g->cx;
  const size_t N = cx->N;
  gm_gather_points(cx, k, cx->simplices[k] + s * (k + 1), p);
  double *c = g->centers[k] + s * N;
  if (g->opt.dual == GM_DUAL_BARYCENTRIC) {
    for (size_t j = 0; j < N; ++j) {
      double sum = 0.0;
      for (size_t i = 0; i <= k; ++i) sum += p[i * N + j];
      c[j] = sum / (double)(k + 1);
    }
    return gm_local_volume(N, k, p);
  }
  double bary[GM_LOCAL_MAX] = {0, 0, 0, 0};
  double vol = gm_local_circumcenter(N, k, p, c, bary);
  unsigned code = 0;
  for (size_t i = 0; i <= k; ++i) code |= (bary[i] > 0.0 ? 1u : bary[i] < 0.0 ? 2u : 0u) << (2 * i);
  g->bsign[k][s] = (unsigned char)code;
  return vol;
}

/* 0: fine; 1: degenerate; 2: inverted (N == n). */
static int top_check(const gm_geometry *g, size_t s, const double *p, double vol) {
  const gm_complex *cx = g->cx;
  const size_t n = cx->n, N = cx->N;
  double L = longest_edge(N, n, p);
  double Ln = n == 1 ? L : n == 2 ? L * L : L * L * L;
  if (!(vol > g->opt.degenerate_tol * Ln)) return 1;
  if (N == n && oriented_volume(n, p, cx->orient[s]) < 0.0) return 2;
  return 0;
}

gm_status gm_geometry_create(const gm_complex *cx, const gm_geometry_options *options,
                             gm_geometry **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (cx == NULL) return gm_error_set(err, GM_EINVAL, "complex is NULL");
  gm_geometry *g = calloc(1, sizeof *g);
  if (g == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  g->cx = cx;
  g->opt = options ? *options : gm_geometry_defaults();
  if (!(g->opt.degenerate_tol >= 0.0)) g->opt.degenerate_tol = 1e-12;
  const size_t n = cx->n, N = cx->N;
  const int circ = g->opt.dual != GM_DUAL_BARYCENTRIC;
  gm_status st = GM_OK;
  double *block = NULL;
  for (size_t k = 0; k <= n; ++k) {
    size_t m = cx->count[k] ? cx->count[k] : 1;
    g->centers[k] = malloc(m * N * sizeof(double));
    g->primal[k] = malloc(m * sizeof(double));
    g->dual[k] = calloc(m, sizeof(double));
    g->bdual[k] = calloc(m, sizeof(double));
    g->star[k] = malloc(m * sizeof(double));
    g->bsign[k] = calloc(m, 1);
    if (!g->centers[k] || !g->primal[k] || !g->dual[k] || !g->bdual[k] || !g->star[k] ||
        !g->bsign[k]) {
      st = gm_error_set(err, GM_ENOMEM, "out of memory for the geometry of %zu simplices",
                        cx->count[n]);
      goto done;
    }
  }
  /* centers and primal volumes, each simplex once; degenerate and inverted top simplices (the
   * first offending one in index order is reported, whatever the number of threads) */
  for (size_t k = 0; k <= n; ++k) {
    const size_t m = cx->count[k];
    size_t first_bad = SIZE_MAX, inverted = 0;
    const int check = k == n;
    GM_OMP(omp parallel for schedule(static) if (m > GM_OMP_MIN) reduction(min : first_bad) reduction(+ : inverted))
    for (size_t s = 0; s < m; ++s) {
      double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED];
      double vol = center_of(g, k, s, p);
      g->primal[k][s] = vol;
      if (check) {
        int bad = top_check(g, s, p, vol);
        if (bad == 2) ++inverted;
        if ((bad == 1 || (bad == 2 && !g->opt.allow_inverted)) && s < first_bad) first_bad = s;
      }
    }
    if (first_bad != SIZE_MAX) {
      double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED];
      const size_t s = first_bad;
      const double vol = g->primal[n][s];
      gm_gather_points(cx, n, cx->simplices[n] + s * (n + 1), p);
      if (top_check(g, s, p, vol) == 1) {
        double L = longest_edge(N, n, p);
        st = gm_error_set(err, GM_EINVAL, "degenerate %s %zu: volume %.3g for longest edge %.3g",
                          name_of(n), s, vol, L);
      } else {
        st = gm_error_set(err, GM_EINVAL,
                          "inverted %s %zu: its orientation is opposite to its neighbours' "
                          "(signed volume %.3g)",
                          name_of(n), s, -vol);
      }
      goto done;
    }
    if (check) g->inverted = inverted;
  }
  /* dual volumes, accumulated per top simplex in index order: the pieces of a block of top
   * simplices are computed in parallel, then added serially (a fixed summation order) */
  {
    const unsigned full = (1u << (n + 1)) - 1;
    const size_t nt = cx->count[n], B = 8192;
    face_table ft;
    face_table_init(n, &ft);
    block = malloc(B * 16 * sizeof(double));
    size_t *bidx = malloc(B * 16 * sizeof(size_t));
    if (block == NULL || bidx == NULL) {
      free(bidx);
      st = gm_error_set(err, GM_ENOMEM, "out of memory");
      goto done;
    }
    for (size_t T0 = 0; T0 < nt; T0 += B) {
      const size_t nb = nt - T0 < B ? nt - T0 : B;
      GM_OMP(omp parallel for schedule(static) if (nb > 2048))
      for (size_t b = 0; b < nb; ++b) {
        const size_t T = T0 + b;
        size_t *idx = bidx + 16 * b;
        face_indices(cx, n, T, &ft, idx);
        if (circ) {
          stored_dual_pieces(g, n, &ft, idx, block + 16 * b);
        } else {
          double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED];
          gm_gather_points(cx, n, cx->simplices[n] + T * (n + 1), p);
          gm_local_dual_pieces(N, n, p, g->opt.dual, block + 16 * b);
        }
      }
      for (size_t b = 0; b < nb; ++b) {
        const size_t *idx = bidx + 16 * b;
        const double *pieces = block + 16 * b;
        for (unsigned s = 1; s < full; ++s) g->dual[popcount4[s] - 1][idx[s]] += pieces[s];
        g->dual[n][T0 + b] = 1.0;
      }
    }
    free(bidx);
  }
  /* dual volumes inside the boundary complex (seed 000 §3.3.2) */
  if (n == 1) {
    for (size_t v = 0; v < cx->count[0]; ++v) g->bdual[0][v] = cx->boundary[0][v] ? 1.0 : 0.0;
  } else {
    unsigned full = (1u << n) - 1;
    double pieces[16], p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED];
    size_t idx[16];
    face_table ft;
    face_table_init(n - 1, &ft);
    for (size_t F = 0; F < cx->count[n - 1]; ++F) {
      if (!cx->boundary[n - 1][F]) continue;
      face_indices(cx, n - 1, F, &ft, idx);
      if (circ) {
        stored_dual_pieces(g, n - 1, &ft, idx, pieces);
      } else {
        gm_gather_points(cx, n - 1, cx->simplices[n - 1] + F * n, p);
        gm_local_dual_pieces(N, n - 1, p, g->opt.dual, pieces);
      }
      for (unsigned s = 1; s < full; ++s) g->bdual[popcount4[s] - 1][idx[s]] += pieces[s];
      g->bdual[n - 1][F] = 1.0;
    }
  }
  for (size_t k = 0; k <= n; ++k) {
    const size_t m = cx->count[k];
    size_t neg = 0;
    GM_OMP(omp parallel for schedule(static) if (m > GM_OMP_MIN) reduction(+ : neg))
    for (size_t s = 0; s < m; ++s) {
      g->star[k][s] = g->dual[k][s] / g->primal[k][s];
      if (!(g->dual[k][s] > 0.0)) ++neg;
    }
    g->negative[k] = neg;
  }
done:
  free(block);
  if (st != GM_OK) {
    gm_geometry_free(g);
    return st;
  }
  *out = g;
  return GM_OK;
}

void gm_geometry_free(gm_geometry *g) {
  if (g == NULL) return;
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) {
    free(g->centers[k]);
    free(g->primal[k]);
    free(g->dual[k]);
    free(g->bdual[k]);
    free(g->star[k]);
    free(g->bsign[k]);
  }
  free(g);
}

const gm_complex *gm_geometry_complex(const gm_geometry *g) { return g->cx; }
const double *gm_geometry_centers(const gm_geometry *g, size_t k) {
  return k <= g->cx->n ? g->centers[k] : NULL;
}
const double *gm_geometry_primal_volumes(const gm_geometry *g, size_t k) {
  return k <= g->cx->n ? g->primal[k] : NULL;
}
const double *gm_geometry_dual_volumes(const gm_geometry *g, size_t k) {
  return k <= g->cx->n ? g->dual[k] : NULL;
}
const double *gm_geometry_boundary_dual_volumes(const gm_geometry *g, size_t k) {
  return k < g->cx->n ? g->bdual[k] : NULL;
}
const double *gm_geometry_hodge_star(const gm_geometry *g, size_t k) {
  return k <= g->cx->n ? g->star[k] : NULL;
}
size_t gm_geometry_negative_duals(const gm_geometry *g, size_t k) {
  return k <= g->cx->n ? g->negative[k] : 0;
}
size_t gm_geometry_inverted_count(const gm_geometry *g) { return g->inverted; }

gm_status gm_geometry_hodge_star_matrix(const gm_geometry *g, size_t k, int inverse,
                                        gm_csr **out) {
  if (g == NULL || out == NULL || k > g->cx->n) return GM_EINVAL;
  *out = NULL;
  gm_csr *a = NULL;
  gm_status st = gm_csr_diagonal(g->cx->count[k], g->star[k], &a);
  if (st != GM_OK) return st;
  if (inverse)
    for (size_t i = 0; i < g->cx->count[k]; ++i) {
      if (a->val[i] == 0.0) {
        gm_csr_free(a);
        return GM_EDOMAIN;
      }
      a->val[i] = 1.0 / a->val[i];
    }
  *out = a;
  return GM_OK;
}

double gm_geometry_dual_hodge_star(const gm_geometry *g, size_t k, size_t i) {
  const size_t n = g->cx->n;
  double sign = ((k * (n - k)) & 1) ? -1.0 : 1.0;
  return sign / g->star[k][i];
}

/* Whitney mass matrix. In a top simplex T with barycentric coordinates λ_i, the Whitney form of
 * the k-face [i_0..i_k] is φ = k! Σ_j (−1)^j λ_{i_j} dλ_{i_0} ∧ .. (omit j) .. ∧ dλ_{i_k}
 * (Whitney 1957; Bossavit 1988; seed 003/004 §2.5). Then
 * ∫_T φ_σ·φ_τ = (k!)² Σ_{a,b} (−1)^{a+b} ∫_T λ_{σ_a} λ_{τ_b} det[∇λ_{σ\σ_a} · ∇λ_{τ\τ_b}],
 * with ∫_T λ_i λ_j = |T| (1 + δ_ij) / ((n+1)(n+2)) and the inner product of k-vectors given by
 * the Gram determinant of the gradients. */
static double det_small(size_t m, double a[3][3]) {
  if (m == 0) return 1.0;
  if (m == 1) return a[0][0];
  if (m == 2) return a[0][0] * a[1][1] - a[0][1] * a[1][0];
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

gm_status gm_geometry_whitney_mass(const gm_geometry *g, size_t k, gm_csr **out) {
  return gm_geometry_whitney_mass_weighted(g, k, NULL, out);
}

gm_status gm_geometry_whitney_mass_weighted(const gm_geometry *g, size_t k,
                                            const double *cell_weight, gm_csr **out) {
  if (g == NULL || out == NULL || k > g->cx->n) return GM_EINVAL;
  *out = NULL;
  const gm_complex *cx = g->cx;
  const size_t n = cx->n, N = cx->N, nt = cx->count[n];
  const size_t nl = gm_binomial(n + 1, k + 1), per = nl * nl;
  size_t *rows = malloc(nt * per * sizeof(size_t)), *cols = malloc(nt * per * sizeof(size_t));
  double *vals = malloc(nt * per * sizeof(double));
  if (!rows || !cols || !vals) {
    free(rows), free(cols), free(vals);
    return GM_ENOMEM;
  }
  unsigned masks[6];
  local_masks(n, k, masks);
  double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], grad[GM_LOCAL_MAX * GM_DEC_MAX_EMBED];
  double G[GM_LOCAL_MAX][GM_LOCAL_MAX];
  size_t idx[6];
  const double kf = k == 0 ? 1.0 : k == 1 ? 1.0 : k == 2 ? 2.0 : 6.0;
  size_t w = 0;
  gm_status st = GM_OK;
  for (size_t T = 0; T < nt; ++T) {
    gm_gather_points(cx, n, cx->simplices[n] + T * (n + 1), p);
    if (!gm_local_barycentric_gradients(N, n, p, grad)) {
      st = GM_EINVAL;
      break;
    }
    for (size_t a = 0; a <= n; ++a)
      for (size_t b = 0; b <= n; ++b) {
        double s = 0.0;
        for (size_t q = 0; q < N; ++q) s += grad[a * N + q] * grad[b * N + q];
        G[a][b] = s;
      }
    gm_complex_local_faces(cx, T, k, idx);
    const double vol = g->primal[n][T], c = vol / (double)((n + 1) * (n + 2));
    const double o = k == n ? cx->orient[T] : 1.0;
    const double wT = cell_weight ? cell_weight[T] : 1.0; /* material of the cell */
    for (size_t si = 0; si < nl; ++si)
      for (size_t ti = 0; ti < nl; ++ti) {
        size_t sv[GM_LOCAL_MAX], tv[GM_LOCAL_MAX], q = 0, r = 0;
        for (size_t v = 0; v <= n; ++v) {
          if (masks[si] & (1u << v)) sv[q++] = v;
          if (masks[ti] & (1u << v)) tv[r++] = v;
        }
        double sum = 0.0;
        for (size_t a = 0; a <= k; ++a)
          for (size_t b = 0; b <= k; ++b) {
            double m[3][3];
            for (size_t i = 0, ii = 0; i <= k; ++i) {
              if (i == a) continue;
              for (size_t j = 0, jj = 0; j <= k; ++j) {
                if (j == b) continue;
                m[ii][jj++] = G[sv[i]][tv[j]];
              }
              ++ii;
            }
            double lam = c * (sv[a] == tv[b] ? 2.0 : 1.0);
            sum += (((a + b) & 1) ? -1.0 : 1.0) * lam * det_small(k, m);
          }
        rows[w] = idx[si];
        cols[w] = idx[ti];
        vals[w++] = kf * kf * sum * o * o * wT;
      }
  }
  if (st == GM_OK) st = gm_csr_from_triplets(cx->count[k], cx->count[k], w, rows, cols, vals, out, NULL);
  free(rows), free(cols), free(vals);
  return st;
}
