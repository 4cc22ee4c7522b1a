/* Gmsh ASCII 2.2 writer (Gmsh reference manual, "MSH file format version 2 (legacy)"): nodes,
 * then the cells as elements of type 1 (line), 2 (triangle) or 4 (tetrahedron) with two tags,
 * the physical tag (the cell's tag) and the elementary tag (the same). gm_mesh_read reads it. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/mesh.h"

gm_status gm_mesh_write_msh(const gm_mesh *mesh, const char *path, gm_error *err) {
  if (mesh == NULL || path == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (mesh->N > 3 || mesh->dim < 1 || mesh->dim > 3)
    return gm_error_set(err, GM_EINVAL, "Gmsh holds 1..3-cells in R^1..R^3, not %zu-cells in R^%zu",
                        mesh->dim, mesh->N);
  FILE *f = fopen(path, "w");
  if (f == NULL) return gm_error_set(err, GM_EIO, "cannot write %s: %s", path, strerror(errno));
  static const int type[4] = {0, 1, 2, 4};
  fprintf(f, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%zu\n", mesh->n_vertices);
  for (size_t v = 0; v < mesh->n_vertices; ++v) {
    double p[3] = {0, 0, 0};
    for (size_t j = 0; j < mesh->N; ++j) p[j] = mesh->x[v * mesh->N + j];
    fprintf(f, "%zu %.17g %.17g %.17g\n", v + 1, p[0], p[1], p[2]);
  }
  fprintf(f, "$EndNodes\n$Elements\n%zu\n", mesh->n_cells);
  const size_t kp = mesh->dim + 1;
  for (size_t c = 0; c < mesh->n_cells; ++c) {
    int tag = mesh->cell_tags ? mesh->cell_tags[c] : 0;
    fprintf(f, "%zu %d 2 %d %d", c + 1, type[mesh->dim], tag, tag);
    for (size_t q = 0; q < kp; ++q) fprintf(f, " %zu", mesh->cells[c * kp + q] + 1);
    fputc('\n', f);
  }
  fputs("$EndElements\n", f);
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return gm_error_set(err, GM_EIO, "error writing %s", path);
  return GM_OK;
}
