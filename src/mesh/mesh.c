/* gm_mesh: creation, conversion to a complex, filtering. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/mesh.h"

gm_status gm_mesh_create(size_t N, size_t n_vertices, size_t dim, size_t n_cells, gm_mesh **out) {
  if (out == NULL) return GM_EINVAL;
  *out = NULL;
  if (N < 1 || dim < 1 || dim > 3 || N > GM_DEC_MAX_EMBED) return GM_EINVAL;
  if (n_vertices > SIZE_MAX / (8 * N) || n_cells > SIZE_MAX / (8 * (dim + 1))) return GM_ENOMEM;
  gm_mesh *m = calloc(1, sizeof *m);
  if (m == NULL) return GM_ENOMEM;
  m->N = N;
  m->dim = dim;
  m->n_vertices = n_vertices;
  m->n_cells = n_cells;
  m->x = malloc((n_vertices ? n_vertices : 1) * N * sizeof(double));
  m->cells = malloc((n_cells ? n_cells : 1) * (dim + 1) * sizeof(size_t));
  m->cell_tags = calloc(n_cells ? n_cells : 1, sizeof(int));
  if (!m->x || !m->cells || !m->cell_tags) {
    gm_mesh_free(m);
    return GM_ENOMEM;
  }
  *out = m;
  return GM_OK;
}

void gm_mesh_free(gm_mesh *mesh) {
  if (mesh == NULL) return;
  free(mesh->x);
  free(mesh->cells);
  free(mesh->cell_tags);
  free(mesh);
}

gm_status gm_mesh_complex(const gm_mesh *mesh, gm_complex **out, gm_error *err) {
  if (mesh == NULL) return gm_error_set(err, GM_EINVAL, "mesh is NULL");
  return gm_complex_create(mesh->N, mesh->n_vertices, mesh->x, mesh->dim, mesh->n_cells,
                           mesh->cells, out, err);
}

gm_status gm_mesh_filter(gm_mesh *mesh, int (*keep)(void *ctx, const double *centroid), void *ctx) {
  if (mesh == NULL || keep == NULL) return GM_EINVAL;
  const size_t N = mesh->N, kp = mesh->dim + 1;
  size_t *map = malloc((mesh->n_vertices ? mesh->n_vertices : 1) * sizeof(size_t));
  if (map == NULL) return GM_ENOMEM;
  for (size_t v = 0; v < mesh->n_vertices; ++v) map[v] = SIZE_MAX;
  size_t w = 0;
  double c[GM_DEC_MAX_EMBED];
  for (size_t t = 0; t < mesh->n_cells; ++t) {
    const size_t *cell = mesh->cells + t * kp;
    for (size_t j = 0; j < N; ++j) {
      double s = 0.0;
      for (size_t i = 0; i < kp; ++i) s += mesh->x[cell[i] * N + j];
      c[j] = s / (double)kp;
    }
    if (!keep(ctx, c)) continue;
    memmove(mesh->cells + w * kp, cell, kp * sizeof(size_t));
    mesh->cell_tags[w] = mesh->cell_tags[t];
    for (size_t i = 0; i < kp; ++i) map[cell[i]] = 0;
    ++w;
  }
  mesh->n_cells = w;
  size_t nv = 0;
  for (size_t v = 0; v < mesh->n_vertices; ++v)
    if (map[v] == 0) {
      map[v] = nv;
      memmove(mesh->x + nv * N, mesh->x + v * N, N * sizeof(double));
      ++nv;
    }
  mesh->n_vertices = nv;
  for (size_t p = 0; p < w * kp; ++p) mesh->cells[p] = map[mesh->cells[p]];
  free(map);
  return GM_OK;
}
