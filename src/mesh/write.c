/* Mesh writers: OFF (triangle meshes) and VTU (ParaView XML UnstructuredGrid, ASCII) with
 * cochains and vector fields attached to vertices, edges, faces and cells.
 *
 * VTU layout (VTK file formats, "XML file formats", UnstructuredGrid): the points are the
 * vertices (padded to 3 coordinates); the cells are the top simplices, followed by the
 * k-simplices of every degree 0 < k < n that carries a field (VTK_LINE = 3, VTK_TRIANGLE = 5,
 * VTK_TETRA = 10). Degree-0 fields are PointData; other fields are CellData over all cells,
 * NaN on cells of another degree; the Int32 CellData "degree" tells the cells apart (threshold
 * on it in ParaView). Top simplices are written with their orientation (two vertices swapped
 * where the orientation is negative). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/mesh.h"

gm_status gm_mesh_write_off(const gm_mesh *mesh, const char *path, gm_error *err) {
  if (mesh == NULL || path == NULL) return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (mesh->dim != 2 || mesh->N > 3)
    return gm_error_set(err, GM_EINVAL, "OFF holds triangle meshes in R^2 or R^3, not %zu-cells in R^%zu",
                        mesh->dim, mesh->N);
  FILE *f = fopen(path, "w");
  if (f == NULL) return gm_error_set(err, GM_EIO, "cannot write %s: %s", path, strerror(errno));
  fprintf(f, "OFF\n%zu %zu 0\n", mesh->n_vertices, mesh->n_cells);
  for (size_t v = 0; v < mesh->n_vertices; ++v) {
    double p[3] = {0, 0, 0};
    for (size_t j = 0; j < mesh->N; ++j) p[j] = mesh->x[v * mesh->N + j];
    fprintf(f, "%.17g %.17g %.17g\n", p[0], p[1], p[2]);
  }
  for (size_t t = 0; t < mesh->n_cells; ++t)
    fprintf(f, "3 %zu %zu %zu\n", mesh->cells[3 * t], mesh->cells[3 * t + 1], mesh->cells[3 * t + 2]);
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return gm_error_set(err, GM_EIO, "error writing %s", path);
  return GM_OK;
}

static void write_value(FILE *f, double v) {
  if (v != v)
    fputs(" NaN", f);
  else
    fprintf(f, " %.17g", v);
}

gm_status gm_vtu_write(const char *path, const gm_complex *cx, size_t n_fields,
                       const gm_vtu_field *fields, gm_error *err) {
  if (path == NULL || cx == NULL || (n_fields > 0 && fields == NULL))
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  const size_t n = gm_complex_dim(cx), N = gm_complex_embedding_dim(cx);
  if (N > 3) return gm_error_set(err, GM_EINVAL, "VTU points have 3 coordinates, the complex has %zu", N);
  int with[GM_DEC_MAX_DIM + 1] = {0};
  with[n] = 1;
  for (size_t i = 0; i < n_fields; ++i) {
    const gm_vtu_field *fl = &fields[i];
    if (fl->name == NULL || fl->values == NULL || fl->degree > n ||
        !(fl->n_components == 1 || fl->n_components == 3))
      return gm_error_set(err, GM_EINVAL,
                          "field %zu: needs a name, values, degree <= %zu and 1 or 3 components", i, n);
    for (const char *c = fl->name; *c; ++c)
      if (*c == '"' || *c == '<' || *c == '>' || *c == '&')
        return gm_error_set(err, GM_EINVAL, "field %zu: name '%s' has a character XML would need escaped", i, fl->name);
    if (fl->degree > 0) with[fl->degree] = 1;
  }
  /* cell blocks: top first, then the other degrees in increasing order */
  size_t order[GM_DEC_MAX_DIM + 1], n_blocks = 0, n_cells = 0, n_conn = 0;
  order[n_blocks++] = n;
  for (size_t k = 1; k < n; ++k)
    if (with[k]) order[n_blocks++] = k;
  for (size_t b = 0; b < n_blocks; ++b) {
    n_cells += gm_complex_count(cx, order[b]);
    n_conn += gm_complex_count(cx, order[b]) * (order[b] + 1);
  }
  FILE *f = fopen(path, "w");
  if (f == NULL) return gm_error_set(err, GM_EIO, "cannot write %s: %s", path, strerror(errno));
  const size_t nv = gm_complex_count(cx, 0);
  const double *x = gm_complex_coordinates(cx);
  fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
             "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"%zu\" "
             "NumberOfCells=\"%zu\">\n<Points>\n<DataArray type=\"Float64\" "
             "NumberOfComponents=\"3\" format=\"ascii\">\n",
          nv, n_cells);
  for (size_t v = 0; v < nv; ++v) {
    for (size_t j = 0; j < 3; ++j) write_value(f, j < N ? x[v * N + j] : 0.0);
    fputc('\n', f);
  }
  fputs("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
        "format=\"ascii\">\n", f);
  const signed char *orient = gm_complex_orientation(cx);
  for (size_t b = 0; b < n_blocks; ++b) {
    const size_t k = order[b], *s = gm_complex_simplices(cx, k);
    for (size_t i = 0; i < gm_complex_count(cx, k); ++i) {
      size_t t[4];
      memcpy(t, s + i * (k + 1), (k + 1) * sizeof(size_t));
      if (k == n && orient[i] < 0) {
        size_t tmp = t[0];
        t[0] = t[1];
        t[1] = tmp;
      }
      for (size_t j = 0; j <= k; ++j) fprintf(f, " %zu", t[j]);
      fputc('\n', f);
    }
  }
  fputs("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n", f);
  size_t off = 0;
  for (size_t b = 0; b < n_blocks; ++b)
    for (size_t i = 0; i < gm_complex_count(cx, order[b]); ++i) {
      off += order[b] + 1;
      fprintf(f, " %zu", off);
    }
  fputs("\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n", f);
  static const int vtk_type[] = {1, 3, 5, 10};
  for (size_t b = 0; b < n_blocks; ++b)
    for (size_t i = 0; i < gm_complex_count(cx, order[b]); ++i) fprintf(f, " %d", vtk_type[order[b]]);
  fputs("\n</DataArray>\n</Cells>\n<PointData>\n", f);
  for (size_t i = 0; i < n_fields; ++i) {
    const gm_vtu_field *fl = &fields[i];
    if (fl->degree != 0) continue;
    fprintf(f, "<DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"%zu\" format=\"ascii\">\n",
            fl->name, fl->n_components);
    for (size_t v = 0; v < nv; ++v) {
      for (size_t c = 0; c < fl->n_components; ++c) write_value(f, fl->values[v * fl->n_components + c]);
      fputc('\n', f);
    }
    fputs("</DataArray>\n", f);
  }
  fputs("</PointData>\n<CellData>\n<DataArray type=\"Int32\" Name=\"degree\" format=\"ascii\">\n", f);
  for (size_t b = 0; b < n_blocks; ++b)
    for (size_t i = 0; i < gm_complex_count(cx, order[b]); ++i) fprintf(f, " %zu", order[b]);
  fputs("\n</DataArray>\n", f);
  for (size_t i = 0; i < n_fields; ++i) {
    const gm_vtu_field *fl = &fields[i];
    if (fl->degree == 0) continue;
    fprintf(f, "<DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"%zu\" format=\"ascii\">\n",
            fl->name, fl->n_components);
    for (size_t b = 0; b < n_blocks; ++b)
      for (size_t s = 0; s < gm_complex_count(cx, order[b]); ++s) {
        for (size_t c = 0; c < fl->n_components; ++c)
          write_value(f, order[b] == fl->degree ? fl->values[s * fl->n_components + c] : NAN);
        fputc('\n', f);
      }
    fputs("</DataArray>\n", f);
  }
  (void)n_conn;
  fputs("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n", f);
  int bad = ferror(f);
  if (fclose(f) != 0 || bad) return gm_error_set(err, GM_EIO, "error writing %s", path);
  return GM_OK;
}
