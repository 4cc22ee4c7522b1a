/* Simplicial complexes: faces of every dimension in canonical (lexicographic) order, consistent
 * orientation, signed incidence matrices, boundary subcomplex, Euler characteristic and Betti
 * numbers.
 *
 * Faces are found by sorting: every k-simplex contributes its k+1 facets (drop vertex i, which
 * keeps the tuple sorted), the facet tuples are sorted by an LSD counting sort on each vertex
 * position (radix = number of vertices; stable, no limit on the index range), and equal
 * neighbours are merged. The boundary of [v0..vk] is Σ_i (−1)^i [v0..v̂i..vk] (seed 001 §3.4,
 * seed 000 §1.3.3), so row σ of d_{k−1} = ∂_kᵀ holds (−1)^i at the column of facet i. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"

static const char *simplex_name(size_t k) {
  static const char *names[] = {"vertex", "edge", "triangle", "tetrahedron"};
  return k <= 3 ? names[k] : "simplex";
}

size_t gm_binomial(size_t n, size_t k) {
  if (k > n) return 0;
  size_t r = 1;
  for (size_t i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

int gm_simplex_sign(const gm_complex *cx, size_t k, size_t i) {
  return k == cx->n ? cx->orient[i] : 1;
}

void gm_gather_points(const gm_complex *cx, size_t k, const size_t *vertices, double *p) {
  for (size_t i = 0; i <= k; ++i)
    memcpy(p + i * cx->N, cx->x + vertices[i] * cx->N, cx->N * sizeof(double));
}

/* Sort t[0..m) ascending (m <= 4) and return the parity of the permutation (0 even, 1 odd). */
static int sort_small(size_t *t, size_t m) {
  int parity = 0;
  for (size_t i = 1; i < m; ++i)
    for (size_t j = i; j > 0 && t[j - 1] > t[j]; --j) {
      size_t s = t[j];
      t[j] = t[j - 1];
      t[j - 1] = s;
      parity ^= 1;
    }
  return parity;
}

/* Facets of the k-simplices (k >= 1): fill simplices[k-1] (k >= 2) and faces[k]. */
static gm_status build_faces(gm_complex *cx, size_t k, gm_error *err) {
  const size_t kp = k + 1, m = cx->count[k], nocc = m * kp;
  const size_t *tup = cx->simplices[k];
  cx->faces[k] = malloc((nocc ? nocc : 1) * sizeof(size_t));
  if (cx->faces[k] == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory for faces");
  if (k == 1) { /* facet i of [a, b] is the vertex opposite i */
    for (size_t e = 0; e < m; ++e) {
      cx->faces[1][2 * e] = tup[2 * e + 1];
      cx->faces[1][2 * e + 1] = tup[2 * e];
    }
    return GM_OK;
  }
  const size_t nv = cx->n_vertices, fk = k; /* facet length: 2 or 3 */
  if (nv > UINT32_MAX) return gm_error_set(err, GM_EINVAL, "more than 2^32 vertices");
  /* Bucket the facet occurrences by their first vertex (one counting-sort pass), then sort each
   * (small) bucket by the remaining one or two vertices packed into 64 bits. */
  uint64_t *key = malloc((nocc ? nocc : 1) * sizeof(uint64_t));
  size_t *a = malloc((nocc ? nocc : 1) * sizeof(size_t));
  size_t *cnt = calloc(nv + 1, sizeof(size_t));
  size_t *b = malloc((nocc ? nocc : 1) * sizeof(size_t)); /* first position of each facet */
  if (!key || !a || !cnt || !b) {
    free(key), free(a), free(cnt), free(b);
    return gm_error_set(err, GM_ENOMEM, "out of memory sorting %zu faces", nocc);
  }
  for (size_t s = 0; s < m; ++s) {
    const size_t *t = tup + s * kp;
    cnt[t[1] + 1]++; /* facet 0 starts with vertex 1, the others with vertex 0 */
    cnt[t[0] + 1] += k;
  }
  for (size_t v = 0; v < nv; ++v) cnt[v + 1] += cnt[v];
  for (size_t s = 0; s < m; ++s) {
    const size_t *t = tup + s * kp;
    for (size_t i = 0; i < kp; ++i) {
      size_t f[GM_LOCAL_MAX], q = 0;
      for (size_t j = 0; j < kp; ++j)
        if (j != i) f[q++] = t[j];
      uint64_t kk = fk == 2 ? (uint64_t)f[1] : ((uint64_t)f[1] << 32) | (uint64_t)f[2];
      size_t pos = cnt[f[0]]++;
      key[pos] = kk;
      a[pos] = s * kp + i;
    }
  }
  /* cnt[v] is now the end of bucket v; sort each bucket by key (insertion sort: buckets hold a
   * few dozen entries on meshes; ties are occurrences of the same facet) */
  size_t n_unique = 0, begin = 0;
  for (size_t v = 0; v < nv; ++v) {
    size_t end = cnt[v];
    for (size_t p = begin + 1; p < end; ++p) {
      uint64_t kk = key[p];
      size_t id = a[p], q = p;
      while (q > begin && key[q - 1] > kk) {
        key[q] = key[q - 1];
        a[q] = a[q - 1];
        --q;
      }
      key[q] = kk;
      a[q] = id;
    }
    for (size_t p = begin; p < end; ++p) {
      if (p == begin || key[p] != key[p - 1]) {
        b[n_unique++] = p;
      }
      cx->faces[k][a[p]] = n_unique - 1;
    }
    begin = end;
  }
  if (k == cx->n) { /* the cofaces of each facet are its occurrences, in simplex order */
    cx->cofaces = malloc(2 * (n_unique ? n_unique : 1) * sizeof(size_t));
    cx->coface_local = malloc(2 * (n_unique ? n_unique : 1));
    if (!cx->cofaces || !cx->coface_local) {
      free(key), free(a), free(cnt), free(b);
      return gm_error_set(err, GM_ENOMEM, "out of memory for %zu faces", n_unique);
    }
    for (size_t u = 0; u < n_unique; ++u) {
      const size_t p0 = b[u], p1 = u + 1 < n_unique ? b[u + 1] : nocc;
      const size_t s0 = a[p0] / kp;
      cx->cofaces[2 * u] = s0;
      cx->coface_local[2 * u] = (unsigned char)(a[p0] - s0 * kp);
      cx->cofaces[2 * u + 1] = SIZE_MAX;
      cx->coface_local[2 * u + 1] = 0;
      if (p1 - p0 == 2) {
        const size_t s1 = a[p0 + 1] / kp, i1 = a[p0 + 1] - s1 * kp;
        cx->cofaces[2 * u + 1] = s1;
        cx->coface_local[2 * u + 1] = (unsigned char)i1;
        /* the same facet with the same opposite vertex: a duplicated simplex */
        if (tup[a[p0]] == tup[s1 * kp + i1]) cx->faces_problem = 1;
      } else if (p1 - p0 > 2) {
        cx->faces_problem = 1; /* non-manifold */
      }
    }
  }
  free(key);
  free(cnt);
  size_t *faces_tup = malloc((n_unique ? n_unique : 1) * fk * sizeof(size_t));
  if (faces_tup == NULL) {
    free(a), free(b);
    return gm_error_set(err, GM_ENOMEM, "out of memory for %zu faces", n_unique);
  }
  for (size_t u = 0; u < n_unique; ++u) {
    size_t occ = a[b[u]], s = occ / kp, i = occ - s * kp;
    for (size_t j = 0; j < fk; ++j) faces_tup[u * fk + j] = tup[s * kp + (j < i ? j : j + 1)];
  }
  free(a);
  free(b);
  cx->simplices[k - 1] = faces_tup;
  cx->count[k - 1] = n_unique;
  return GM_OK;
}

/* Signed n-volume (times n!) of the sorted tuple t when N == n. */
static double signed_volume(const gm_complex *cx, const size_t *t) {
  const size_t n = cx->n, N = cx->N;
  double e[3][3] = {{0}};
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 0; j < N && j < 3; ++j) e[i - 1][j] = cx->x[t[i] * N + j] - cx->x[t[0] * N + j];
  if (n == 1) return e[0][0];
  if (n == 2) return e[0][0] * e[1][1] - e[0][1] * e[1][0];
  return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
         e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
         e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
}

static size_t local_index(const gm_complex *cx, size_t top, size_t face) {
  const size_t kp = cx->n + 1;
  for (size_t i = 0; i < kp; ++i)
    if (cx->faces[cx->n][top * kp + i] == face) return i;
  return SIZE_MAX;
}

/* Cofaces of (n−1)-faces, manifold and duplicate checks, consistent orientation by a breadth
 * first search over the dual graph. */
/* Orientation from the sign of the volume of every top simplex (N == n): the result of the
 * breadth first search below whenever every volume is non-zero and the signs are consistent
 * across every interior face (a consistent orientation of a connected component is unique up to
 * sign, and the search then picks the sign of positive total volume). 0: use the search. */
static int orient_by_volume(gm_complex *cx) {
  const size_t n = cx->n, kp = n + 1, nt = cx->count[n], nf = cx->count[n - 1];
  int ok = 1;
  GM_OMP(omp parallel for schedule(static) if (nt > GM_OMP_MIN) reduction(&& : ok))
  for (size_t t = 0; t < nt; ++t) {
    double v = signed_volume(cx, cx->simplices[n] + t * kp);
    cx->orient[t] = (signed char)(v > 0.0 ? 1 : -1);
    ok = ok && v != 0.0;
  }
  if (!ok) return 0;
  GM_OMP(omp parallel for schedule(static) if (nf > GM_OMP_MIN) reduction(&& : ok))
  for (size_t f = 0; f < nf; ++f) {
    const size_t t = cx->cofaces[2 * f], o = cx->cofaces[2 * f + 1];
    if (o == SIZE_MAX) continue;
    const unsigned i = cx->coface_local[2 * f], j = cx->coface_local[2 * f + 1];
    int want = -cx->orient[t] * (((i + j) & 1) ? -1 : 1);
    ok = ok && cx->orient[o] == want;
  }
  return ok;
}

/* Cofaces of (n−1)-faces, manifold and duplicate checks, consistent orientation by a breadth
 * first search over the dual graph. */
static gm_status orient(gm_complex *cx, const signed char *given, gm_error *err) {
  const size_t n = cx->n, kp = n + 1, nt = cx->count[n], nf = cx->count[n - 1];
  gm_status st = GM_OK;
  if (cx->cofaces == NULL) { /* n == 1: build_faces found the vertices without sorting */
    cx->cofaces = malloc(2 * (nf ? nf : 1) * sizeof(size_t));
    cx->coface_local = malloc(2 * (nf ? nf : 1));
    if (!cx->cofaces || !cx->coface_local) return gm_error_set(err, GM_ENOMEM, "out of memory");
    cx->faces_problem = 1;
  }
  if (cx->faces_problem) { /* redo the cofaces in simplex order to report the first problem */
    for (size_t f = 0; f < 2 * nf; ++f) cx->cofaces[f] = SIZE_MAX;
    for (size_t t = 0; t < nt && st == GM_OK; ++t)
      for (size_t i = 0; i < kp; ++i) {
        size_t f = cx->faces[n][t * kp + i];
        size_t *c = cx->cofaces + 2 * f;
        if (c[0] == SIZE_MAX) {
          c[0] = t;
          cx->coface_local[2 * f] = (unsigned char)i;
        } else if (c[1] == SIZE_MAX) {
          c[1] = t;
          cx->coface_local[2 * f + 1] = (unsigned char)i;
          size_t j = local_index(cx, c[0], f);
          if (cx->simplices[n][c[0] * kp + j] == cx->simplices[n][t * kp + i]) {
            st = gm_error_set(err, GM_EINVAL, "%s %zu and %s %zu have the same vertices",
                              simplex_name(n), c[0], simplex_name(n), t);
            break;
          }
        } else {
          const size_t *fv = cx->simplices[n - 1] + f * n;
          char verts[96];
          int w = 0;
          for (size_t j = 0; j < n && w >= 0 && (size_t)w < sizeof verts; ++j)
            w += snprintf(verts + w, sizeof verts - (size_t)w, j ? ", %zu" : "%zu", fv[j]);
          st = gm_error_set(err, GM_EINVAL,
                            "non-manifold complex: %s (%s) is shared by more than two %s "
                            "(%zu, %zu, %zu)",
                            simplex_name(n - 1), verts, n == 1 ? "edges" : n == 2 ? "triangles" : "tetrahedra",
                            c[0], c[1], t);
          break;
        }
      }
    if (st != GM_OK) return st;
  }
  if (cx->N == n && orient_by_volume(cx)) {
    for (size_t t = 0; t < nt; ++t) cx->n_reoriented += cx->orient[t] != given[t];
    return GM_OK;
  }
  size_t *queue = malloc((nt ? nt : 1) * sizeof(size_t));
  size_t *comp = malloc((nt ? nt : 1) * sizeof(size_t));
  if (!queue || !comp) {
    free(queue), free(comp);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  for (size_t t = 0; t < nt; ++t) {
    comp[t] = SIZE_MAX;
    cx->orient[t] = given[t];
  }
  for (size_t root = 0; root < nt && st == GM_OK; ++root) {
    if (comp[root] != SIZE_MAX) continue;
    size_t head = 0, tail = 0;
    queue[tail++] = root;
    comp[root] = root;
    while (head < tail && st == GM_OK) {
      size_t t = queue[head++];
      for (size_t i = 0; i < kp; ++i) {
        size_t f = cx->faces[n][t * kp + i];
        int second = cx->cofaces[2 * f] == t;
        size_t o = cx->cofaces[2 * f + (size_t)second];
        if (o == SIZE_MAX) continue;
        size_t j = cx->coface_local[2 * f + (size_t)second];
        /* induced orientations on the shared face must be opposite: o_t(−1)^i = −o_o(−1)^j */
        int want = -cx->orient[t] * (((i + j) & 1) ? -1 : 1);
        if (comp[o] == SIZE_MAX) {
          comp[o] = root;
          cx->orient[o] = (signed char)want;
          queue[tail++] = o;
        } else if (cx->orient[o] != want) {
          st = gm_error_set(err, GM_EINVAL,
                            "complex is not orientable: %s %zu and %s %zu cannot be oriented "
                            "consistently across their common face",
                            simplex_name(n), t, simplex_name(n), o);
          break;
        }
      }
    }
    if (st == GM_OK && cx->N == n) { /* volume meshes: positive total volume per component */
      double vol = 0.0;
      for (size_t q = 0; q < tail; ++q)
        vol += cx->orient[queue[q]] * signed_volume(cx, cx->simplices[n] + queue[q] * kp);
      if (vol < 0.0)
        for (size_t q = 0; q < tail; ++q) cx->orient[queue[q]] = (signed char)-cx->orient[queue[q]];
    }
  }
  free(queue);
  free(comp);
  if (st != GM_OK) return st;
  for (size_t t = 0; t < nt; ++t) cx->n_reoriented += cx->orient[t] != given[t];
  return GM_OK;
}

static gm_status build_d(gm_complex *cx, size_t k, gm_error *err) {
  /* d_{k−1}: rows = k-simplices, k+1 entries each at facets k, k−1, .., 0 (ascending columns:
   * dropping a later vertex gives a lexicographically smaller tuple). */
  const size_t kp = k + 1, m = cx->count[k];
  gm_csr *d = NULL;
  if (gm_csr_create(m, cx->count[k - 1], m * kp, &d) != GM_OK)
    return gm_error_set(err, GM_ENOMEM, "out of memory for d_%zu", k - 1);
  for (size_t s = 0; s < m; ++s) {
    double o = gm_simplex_sign(cx, k, s);
    for (size_t r = 0; r < kp; ++r) {
      size_t i = k - r;
      d->col[s * kp + r] = cx->faces[k][s * kp + i];
      d->val[s * kp + r] = (i & 1) ? -o : o;
    }
    d->row_start[s + 1] = (s + 1) * kp;
  }
  cx->d[k - 1] = d;
  return GM_OK;
}

gm_status gm_complex_create(size_t N, size_t n_vertices, const double *x, size_t dim,
                            size_t n_top, const size_t *top, gm_complex **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "output pointer is NULL");
  *out = NULL;
  if (dim < 1 || dim > GM_DEC_MAX_DIM)
    return gm_error_set(err, GM_EINVAL, "dimension %zu is not 1, 2 or 3", dim);
  if (N < dim)
    return gm_error_set(err, GM_EINVAL, "%zu-simplices need at least %zu coordinates, not %zu",
                        dim, dim, N);
  if (N > GM_DEC_MAX_EMBED)
    return gm_error_set(err, GM_EINVAL, "embedding dimension %zu exceeds %d", N, GM_DEC_MAX_EMBED);
  if (n_vertices == 0 || n_top == 0)
    return gm_error_set(err, GM_EINVAL, "empty complex (%zu vertices, %zu simplices)", n_vertices,
                        n_top);
  if (x == NULL || top == NULL) return gm_error_set(err, GM_EINVAL, "NULL array");
  size_t bad = gm_first_nonfinite(N * n_vertices, x);
  if (bad < N * n_vertices)
    return gm_error_set(err, GM_EDOMAIN, "coordinate %zu of vertex %zu is not finite", bad % N,
                        bad / N);
  const size_t kp = dim + 1;
  for (size_t t = 0; t < n_top; ++t)
    for (size_t i = 0; i < kp; ++i) {
      if (top[t * kp + i] >= n_vertices)
        return gm_error_set(err, GM_EINVAL, "%s %zu: vertex index %zu out of range (%zu vertices)",
                            simplex_name(dim), t, top[t * kp + i], n_vertices);
      for (size_t j = 0; j < i; ++j)
        if (top[t * kp + j] == top[t * kp + i])
          return gm_error_set(err, GM_EINVAL, "%s %zu repeats vertex %zu", simplex_name(dim), t,
                              top[t * kp + i]);
    }
  gm_complex *cx = calloc(1, sizeof *cx);
  if (cx == NULL) return gm_error_set(err, GM_ENOMEM, "out of memory");
  cx->n = dim;
  cx->N = N;
  cx->n_vertices = n_vertices;
  cx->count[0] = n_vertices;
  cx->count[dim] = n_top;
  cx->x = malloc(N * n_vertices * sizeof(double));
  cx->simplices[0] = malloc(n_vertices * sizeof(size_t));
  cx->simplices[dim] = malloc(n_top * kp * sizeof(size_t));
  cx->orient = malloc(n_top);
  signed char *given = malloc(n_top);
  unsigned char *used = calloc(n_vertices, 1);
  gm_status st = GM_OK;
  if (!cx->x || !cx->simplices[0] || !cx->simplices[dim] || !cx->orient || !given || !used) {
    st = gm_error_set(err, GM_ENOMEM, "out of memory for %zu simplices", n_top);
    goto done;
  }
  memcpy(cx->x, x, N * n_vertices * sizeof(double));
  for (size_t v = 0; v < n_vertices; ++v) cx->simplices[0][v] = v;
  for (size_t t = 0; t < n_top; ++t) {
    size_t *s = cx->simplices[dim] + t * kp;
    memcpy(s, top + t * kp, kp * sizeof(size_t));
    given[t] = sort_small(s, kp) ? -1 : 1;
    for (size_t i = 0; i < kp; ++i) used[s[i]] = 1;
  }
  for (size_t v = 0; v < n_vertices; ++v)
    if (!used[v]) {
      st = gm_error_set(err, GM_EINVAL, "vertex %zu is not used by any %s", v, simplex_name(dim));
      goto done;
    }
  for (size_t k = dim; k >= 1 && st == GM_OK; --k) st = build_faces(cx, k, err);
  if (st != GM_OK) goto done;
  st = orient(cx, given, err);
  for (size_t k = 1; k <= dim && st == GM_OK; ++k) st = build_d(cx, k, err);
  if (st != GM_OK) goto done;
  /* boundary subcomplex: (n−1)-faces with one coface, and all their faces */
  for (size_t k = 0; k <= dim; ++k) {
    cx->boundary[k] = calloc(cx->count[k] ? cx->count[k] : 1, 1);
    if (cx->boundary[k] == NULL) {
      st = gm_error_set(err, GM_ENOMEM, "out of memory");
      goto done;
    }
  }
  for (size_t f = 0; f < cx->count[dim - 1]; ++f)
    cx->boundary[dim - 1][f] = cx->cofaces[2 * f + 1] == SIZE_MAX;
  for (size_t k = dim - 1; k >= 1; --k)
    for (size_t s = 0; s < cx->count[k]; ++s)
      if (cx->boundary[k][s])
        for (size_t i = 0; i <= k; ++i) cx->boundary[k - 1][cx->faces[k][s * (k + 1) + i]] = 1;
  for (size_t k = 0; k <= dim; ++k)
    for (size_t s = 0; s < cx->count[k]; ++s) cx->n_boundary[k] += cx->boundary[k][s];
done:
  free(given);
  free(used);
  if (st != GM_OK) {
    gm_complex_free(cx);
    return st;
  }
  *out = cx;
  return GM_OK;
}

void gm_complex_free(gm_complex *cx) {
  if (cx == NULL) return;
  free(cx->x);
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) {
    free(cx->simplices[k]);
    free(cx->faces[k]);
    free(cx->boundary[k]);
    if (k < GM_DEC_MAX_DIM) gm_csr_free(cx->d[k]);
  }
  free(cx->orient);
  free(cx->cofaces);
  free(cx->coface_local);
  free(cx);
}

size_t gm_complex_dim(const gm_complex *cx) { return cx->n; }
size_t gm_complex_embedding_dim(const gm_complex *cx) { return cx->N; }
size_t gm_complex_count(const gm_complex *cx, size_t k) { return k <= cx->n ? cx->count[k] : 0; }
const size_t *gm_complex_simplices(const gm_complex *cx, size_t k) {
  return k <= cx->n ? cx->simplices[k] : NULL;
}
const size_t *gm_complex_faces(const gm_complex *cx, size_t k) {
  return (k >= 1 && k <= cx->n) ? cx->faces[k] : NULL;
}
const signed char *gm_complex_orientation(const gm_complex *cx) { return cx->orient; }
size_t gm_complex_reoriented_count(const gm_complex *cx) { return cx->n_reoriented; }
const double *gm_complex_coordinates(const gm_complex *cx) { return cx->x; }
const gm_csr *gm_complex_d(const gm_complex *cx, size_t k) { return k < cx->n ? cx->d[k] : NULL; }
const size_t *gm_complex_face_cofaces(const gm_complex *cx) { return cx->cofaces; }
const unsigned char *gm_complex_boundary_mask(const gm_complex *cx, size_t k) {
  return k <= cx->n ? cx->boundary[k] : NULL;
}
size_t gm_complex_boundary_count(const gm_complex *cx, size_t k) {
  return k <= cx->n ? cx->n_boundary[k] : 0;
}

gm_status gm_complex_boundary_matrix(const gm_complex *cx, size_t k, gm_csr **out) {
  if (cx == NULL || out == NULL || k < 1 || k > cx->n) return GM_EINVAL;
  return gm_csr_transpose(cx->d[k - 1], out);
}

static int tuple_cmp(const size_t *a, const size_t *b, size_t m) {
  for (size_t i = 0; i < m; ++i)
    if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
  return 0;
}

size_t gm_complex_find(const gm_complex *cx, size_t k, const size_t *vertices) {
  if (cx == NULL || vertices == NULL || k > cx->n) return SIZE_MAX;
  size_t t[GM_LOCAL_MAX];
  memcpy(t, vertices, (k + 1) * sizeof(size_t));
  sort_small(t, k + 1);
  for (size_t i = 1; i <= k; ++i)
    if (t[i] == t[i - 1]) return SIZE_MAX;
  if (k == 0) return t[0] < cx->n_vertices ? t[0] : SIZE_MAX;
  if (k == cx->n) { /* tops are in user order: go through the facet opposite vertex 0 */
    size_t f = gm_complex_find(cx, k - 1, t + 1);
    if (f == SIZE_MAX) return SIZE_MAX;
    for (size_t c = 0; c < 2; ++c) {
      size_t s = cx->cofaces[2 * f + c];
      if (s != SIZE_MAX && tuple_cmp(cx->simplices[k] + s * (k + 1), t, k + 1) == 0) return s;
    }
    return SIZE_MAX;
  }
  size_t lo = 0, hi = cx->count[k];
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (tuple_cmp(cx->simplices[k] + mid * (k + 1), t, k + 1) < 0)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo < cx->count[k] && tuple_cmp(cx->simplices[k] + lo * (k + 1), t, k + 1) == 0) return lo;
  return SIZE_MAX;
}

long gm_complex_euler_characteristic(const gm_complex *cx) {
  long chi = 0;
  for (size_t k = 0; k <= cx->n; ++k) chi += (k & 1) ? -(long)cx->count[k] : (long)cx->count[k];
  return chi;
}

static size_t uf_find(size_t *parent, size_t a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

gm_status gm_complex_betti_numbers(const gm_complex *cx, size_t betti[GM_DEC_MAX_DIM + 1]) {
  if (cx == NULL || betti == NULL) return GM_EINVAL;
  const size_t n = cx->n, nv = cx->n_vertices;
  for (size_t k = 0; k <= GM_DEC_MAX_DIM; ++k) betti[k] = 0;
  size_t *all = malloc(nv * sizeof(size_t)), *bnd = malloc(nv * sizeof(size_t));
  unsigned char *comp_closed = malloc(nv), *seen = calloc(nv, 1);
  if (!all || !bnd || !comp_closed || !seen) {
    free(all), free(bnd), free(comp_closed), free(seen);
    return GM_ENOMEM;
  }
  for (size_t v = 0; v < nv; ++v) all[v] = bnd[v] = v, comp_closed[v] = 1;
  const size_t *e = cx->simplices[1];
  for (size_t i = 0; i < cx->count[1]; ++i) {
    size_t a = uf_find(all, e[2 * i]), b = uf_find(all, e[2 * i + 1]);
    if (a != b) all[a] = b;
    if (n >= 2 && cx->boundary[1][i]) {
      a = uf_find(bnd, e[2 * i]), b = uf_find(bnd, e[2 * i + 1]);
      if (a != b) bnd[a] = b;
    }
  }
  size_t b0 = 0, closed = 0, bcomps = 0;
  for (size_t v = 0; v < nv; ++v) b0 += uf_find(all, v) == v;
  for (size_t v = 0; v < nv; ++v)
    if (cx->boundary[0][v]) comp_closed[uf_find(all, v)] = 0;
  for (size_t v = 0; v < nv; ++v)
    if (uf_find(all, v) == v && comp_closed[v]) ++closed;
  for (size_t v = 0; v < nv; ++v)
    if (cx->boundary[0][v] && !seen[uf_find(bnd, v)]) {
      seen[uf_find(bnd, v)] = 1;
      ++bcomps;
    }
  free(all), free(bnd), free(comp_closed), free(seen);
  long chi = gm_complex_euler_characteristic(cx);
  long b[4] = {(long)b0, 0, 0, 0};
  if (n == 1) {
    b[1] = b[0] - chi; /* χ = b0 − b1 */
  } else if (n == 2) {
    if (n == 2 && cx->N == 2 && closed) return GM_EUNSUPPORTED; /* cannot happen for a manifold */
    b[2] = (long)closed; /* an oriented closed surface has b2 = 1, one with boundary 0 */
    b[1] = b[0] + b[2] - chi;
  } else {
    /* Alexander duality for a compact 3-manifold in R^3: every boundary surface but the outer
     * one of each component bounds a cavity, so b2 = #boundary surfaces − b0; b3 = 0. */
    if (closed || cx->N != 3) return GM_EUNSUPPORTED;
    b[2] = (long)bcomps - b[0];
    b[1] = b[0] + b[2] - chi;
  }
  for (size_t k = 0; k <= n; ++k) {
    if (b[k] < 0) return GM_EUNSUPPORTED;
    betti[k] = (size_t)b[k];
  }
  return GM_OK;
}
