/* Mesh quality report behind `geomint mesh info`: counts, χ, Betti numbers, boundary, and the
 * defects a DEC computation cares about. Everything that can be counted is counted, also when
 * the complex or its geometry cannot be built (then the reason is kept in the report). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dec/internal.h"
#include "geomint/mesh.h"

typedef struct {
  size_t v[3];
} face_key;

static int cmp_face(const void *a, const void *b) {
  const face_key *x = a, *y = b;
  for (int i = 0; i < 3; ++i)
    if (x->v[i] != y->v[i]) return x->v[i] < y->v[i] ? -1 : 1;
  return 0;
}

/* (n−1)-faces shared by more than two cells. */
static gm_status count_non_manifold(const gm_mesh *m, size_t *count) {
  const size_t n = m->dim, kp = n + 1, nf = m->n_cells * kp;
  face_key *f = malloc((nf ? nf : 1) * sizeof(face_key));
  if (f == NULL) return GM_ENOMEM;
  for (size_t t = 0; t < m->n_cells; ++t)
    for (size_t i = 0; i < kp; ++i) {
      face_key *k = &f[t * kp + i];
      size_t q = 0;
      k->v[0] = k->v[1] = k->v[2] = 0;
      for (size_t j = 0; j < kp; ++j)
        if (j != i) k->v[q++] = m->cells[t * kp + j];
      for (size_t a = 1; a < q; ++a) /* sort */
        for (size_t b = a; b > 0 && k->v[b - 1] > k->v[b]; --b) {
          size_t s = k->v[b];
          k->v[b] = k->v[b - 1];
          k->v[b - 1] = s;
        }
    }
  qsort(f, nf, sizeof(face_key), cmp_face);
  size_t c = 0;
  for (size_t i = 0; i < nf;) {
    size_t j = i + 1;
    while (j < nf && cmp_face(&f[i], &f[j]) == 0) ++j;
    if (j - i > 2) ++c;
    i = j;
  }
  free(f);
  *count = c;
  return GM_OK;
}

gm_status gm_mesh_quality(const gm_mesh *mesh, gm_mesh_report *r, gm_error *err) {
  if (mesh == NULL || r == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  memset(r, 0, sizeof *r);
  const size_t n = mesh->dim, N = mesh->N, kp = n + 1;
  r->dim = n;
  r->N = N;
  r->count[0] = mesh->n_vertices;
  r->count[n] = mesh->n_cells;
  r->min_volume = INFINITY;
  r->shortest_edge = INFINITY;
  gm_status st = count_non_manifold(mesh, &r->non_manifold);
  if (st != GM_OK) return gm_error_set(err, st, "out of memory");
  /* per-cell geometry: degenerate, not well-centred, extreme volumes and edges. Each cell is
   * divided by s, the power of two just above its largest coordinate difference, before the
   * local geometry is computed, so edges and shape tests are right for coordinates of 1e160 or
   * 1e-160 (whose squared lengths overflow or underflow); the volume is vol(scaled) s^n, and a
   * cell whose true volume is outside double precision is counted in out_of_range. */
  double p[GM_LOCAL_MAX * GM_DEC_MAX_EMBED], c[GM_DEC_MAX_EMBED], bary[GM_LOCAL_MAX];
  for (size_t t = 0; t < mesh->n_cells; ++t) {
    int bad_index = 0;
    for (size_t i = 0; i < kp; ++i) {
      size_t v = mesh->cells[t * kp + i];
      if (v >= mesh->n_vertices) bad_index = 1;
      else memcpy(p + i * N, mesh->x + v * N, N * sizeof(double));
    }
    if (bad_index) continue;
    double span = 0.0;
    for (size_t i = 1; i < kp; ++i)
      for (size_t q = 0; q < N; ++q) span = fmax(span, fabs(p[i * N + q] - p[q]));
    if (!(span > 0.0) || !isfinite(span)) { /* coincident vertices, or a difference past DBL_MAX */
      if (span == 0.0) r->shortest_edge = 0.0;
      else r->longest_edge = INFINITY, ++r->out_of_range;
      ++r->degenerate;
      continue;
    }
    /* a power of two, so scaling is exact and ordinary meshes get bitwise the old numbers */
    int ex;
    frexp(span, &ex);
    const double scale = ldexp(1.0, ex);
    for (size_t i = 0; i < kp * N; ++i) p[i] /= scale;
    double vol = gm_local_circumcenter(N, n, p, c, bary);
    double L = 0.0;
    for (size_t i = 0; i < kp; ++i)
      for (size_t j = i + 1; j < kp; ++j) {
        double d2 = 0.0;
        for (size_t q = 0; q < N; ++q) d2 += (p[i * N + q] - p[j * N + q]) * (p[i * N + q] - p[j * N + q]);
        double e = sqrt(d2);
        if (e > L) L = e;
        if (e * scale < r->shortest_edge) r->shortest_edge = e * scale;
      }
    if (L * scale > r->longest_edge) r->longest_edge = L * scale;
    double Ln = n == 1 ? L : n == 2 ? L * L : L * L * L;
    if (!(vol > 1e-12 * Ln)) {
      ++r->degenerate;
      continue;
    }
    vol *= n == 1 ? scale : n == 2 ? scale * scale : scale * scale * scale;
    if (!isfinite(vol) || vol < DBL_MIN) {
      ++r->out_of_range;
    } else {
      if (vol < r->min_volume) r->min_volume = vol;
      if (vol > r->max_volume) r->max_volume = vol;
    }
    for (size_t i = 0; i < kp; ++i)
      if (!(bary[i] > 0.0)) {
        ++r->not_well_centred;
        break;
      }
  }
  if (r->min_volume == INFINITY) r->min_volume = 0.0;
  if (r->shortest_edge == INFINITY) r->shortest_edge = 0.0;
  gm_complex *cx = NULL;
  gm_error local = {{0}};
  st = gm_mesh_complex(mesh, &cx, &local);
  if (st == GM_ENOMEM) return gm_error_set(err, st, "%s", local.message);
  if (st != GM_OK) {
    snprintf(r->complex_error, sizeof r->complex_error, "%s", local.message);
    return GM_OK;
  }
  r->complex_ok = 1;
  for (size_t k = 0; k <= n; ++k) {
    r->count[k] = gm_complex_count(cx, k);
    r->boundary_count[k] = gm_complex_boundary_count(cx, k);
  }
  r->euler_characteristic = gm_complex_euler_characteristic(cx);
  r->betti_known = gm_complex_betti_numbers(cx, r->betti) == GM_OK;
  r->reoriented = gm_complex_reoriented_count(cx);
  if (r->out_of_range > 0) { /* the Hodge stars would overflow or underflow as well */
    snprintf(r->geometry_error, sizeof r->geometry_error,
             "%zu cells have volumes outside double precision (edges from %.3g to %.3g): "
             "rescale the mesh",
             r->out_of_range, r->shortest_edge, r->longest_edge);
    gm_complex_free(cx);
    return GM_OK;
  }
  gm_geometry_options o = gm_geometry_defaults();
  o.allow_inverted = 1;
  gm_geometry *g = NULL;
  st = gm_geometry_create(cx, &o, &g, &local);
  if (st == GM_ENOMEM) {
    gm_complex_free(cx);
    return gm_error_set(err, st, "%s", local.message);
  }
  if (st != GM_OK) {
    snprintf(r->geometry_error, sizeof r->geometry_error, "%s", local.message);
  } else {
    r->geometry_ok = 1;
    r->inverted = gm_geometry_inverted_count(g);
    for (size_t k = 0; k <= n; ++k) {
      r->negative_duals[k] = gm_geometry_negative_duals(g, k);
      const double *s = gm_geometry_hodge_star(g, k);
      double lo = INFINITY, hi = -INFINITY;
      for (size_t i = 0; i < cx->count[k]; ++i) {
        if (s[i] < lo) lo = s[i];
        if (s[i] > hi) hi = s[i];
      }
      r->star_min[k] = lo;
      r->star_max[k] = hi;
    }
    gm_geometry_free(g);
  }
  gm_complex_free(cx);
  return GM_OK;
}
