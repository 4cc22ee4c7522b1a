/* Named groups of boundary edges for the fluid solver: the sides of a generated rectangle, and
 * the physical line groups of a Gmsh ASCII 2.2 file. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/fluids.h"

void gm_fluid_groups_free(gm_fluid_groups *g) {
  if (!g) return;
  free(g->names);
  free(g->vertices);
  free(g->group);
  free(g);
}

static gm_status groups_alloc(size_t n_groups, size_t n_edges, gm_fluid_groups **out) {
  gm_fluid_groups *g = calloc(1, sizeof *g);
  if (!g) return GM_ENOMEM;
  g->names = calloc(n_groups ? n_groups : 1, sizeof *g->names);
  g->vertices = calloc(2 * (n_edges ? n_edges : 1), sizeof *g->vertices);
  g->group = calloc(n_edges ? n_edges : 1, sizeof *g->group);
  if (!g->names || !g->vertices || !g->group) { gm_fluid_groups_free(g); return GM_ENOMEM; }
  g->n_groups = n_groups;
  g->n_edges = n_edges;
  *out = g;
  return GM_OK;
}

gm_status gm_fluid_groups_rectangle(const gm_mesh *mesh, gm_fluid_groups **out, gm_error *err) {
  if (!mesh || !out) return gm_error_set(err, GM_EINVAL, "fluid groups: NULL argument");
  *out = NULL;
  if (mesh->dim != 2 || mesh->N != 2)
    return gm_error_set(err, GM_EINVAL, "fluid groups: needs a flat triangle mesh");
  gm_complex *cx = NULL;
  gm_status st = gm_mesh_complex(mesh, &cx, err);
  if (st) return st;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (size_t v = 0; v < mesh->n_vertices; ++v)
    for (int k = 0; k < 2; ++k) {
      lo[k] = fmin(lo[k], mesh->x[2 * v + k]);
      hi[k] = fmax(hi[k], mesh->x[2 * v + k]);
    }
  size_t nb = gm_complex_boundary_count(cx, 1), ne = gm_complex_count(cx, 1);
  const unsigned char *mask = gm_complex_boundary_mask(cx, 1);
  const size_t *edge = gm_complex_simplices(cx, 1);
  const double *x = gm_complex_coordinates(cx);
  gm_fluid_groups *g = NULL;
  st = groups_alloc(4, nb, &g);
  if (st) { gm_complex_free(cx); return gm_error_set(err, st, "fluid groups: out of memory"); }
  static const char *names[4] = {"bottom", "right", "top", "left"};
  for (int k = 0; k < 4; ++k) snprintf(g->names[k], GM_FLUID_NAME_SIZE, "%s", names[k]);
  double tol = 1e-9 * fmax(hi[0] - lo[0], hi[1] - lo[1]);
  size_t k = 0;
  for (size_t e = 0; e < ne; ++e) {
    if (!mask[e]) continue;
    size_t i = edge[2 * e], j = edge[2 * e + 1];
    double m[2] = {0.5 * (x[2 * i] + x[2 * j]), 0.5 * (x[2 * i + 1] + x[2 * j + 1])};
    size_t side = fabs(m[1] - lo[1]) <= tol   ? 0
                  : fabs(m[0] - hi[0]) <= tol ? 1
                  : fabs(m[1] - hi[1]) <= tol ? 2
                  : fabs(m[0] - lo[0]) <= tol ? 3
                                              : 4;
    if (side == 4) {
      gm_fluid_groups_free(g);
      gm_complex_free(cx);
      return gm_error_set(err, GM_EINVAL,
                          "fluid groups: boundary edge at (%g, %g) lies on no side of the "
                          "rectangle [%g, %g]x[%g, %g]", m[0], m[1], lo[0], hi[0], lo[1], hi[1]);
    }
    g->vertices[2 * k] = i;
    g->vertices[2 * k + 1] = j;
    g->group[k++] = side;
  }
  gm_complex_free(cx);
  *out = g;
  return GM_OK;
}
