/* Snapshots of the Yee solver: E (edges) and H (faces) averaged to cell centres, written as
 * VTK image data and/or HDF5 with a ParaView collection (.pvd) that lists the .vti files with
 * their times. All scratch is allocated at create; a write allocates nothing. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/io.h"

#define MAX_ARRAYS 7 /* E, H, E_im, H_im, epsilon, mu, sigma */

struct gm_yee_writer {
  char *prefix;              /* owned */
  unsigned formats;
  gm_vti_encoding encoding;
  gm_image image;
  size_t n_cells;
  int complex_fields;
  double *scratch;           /* owned: 6 (or 12) cell arrays of the averaged components */
  double *media;             /* owned: 3 cell arrays ε, μ, σ, or NULL */
  gm_image_array arrays[MAX_ARRAYS];
  size_t n_arrays;
  double *times;             /* owned: time of each .vti written, for the .pvd */
  size_t *steps;             /* owned */
  size_t count, cap;
  size_t last_step;          /* step of the last snapshot (valid when count > 0) */
  char errmsg[GM_ERRMSG_SIZE];
};

gm_status gm_yee_cell_average(const gm_yee *solver, gm_yee_component c, int part, double *out) {
  if (solver == NULL || out == NULL) return GM_EINVAL;
  const double *f = gm_yee_field(solver, c, part);
  if (f == NULL) return GM_EINVAL;
  gm_yee_layout L;
  gm_yee_get_layout(solver, &L);
  double shift[3];
  gm_yee_component_shift(L.dim, c, shift);
  size_t axes = gm_yee_dim_axes(L.dim);
  /* Along a present axis a component sits either at the cell's mid-plane (shift ½: one
   * location) or on its two bounding planes (shift 0: their mean). */
  long span[3];
  double weight = 1.0;
  for (size_t a = 0; a < 3; ++a) {
    span[a] = a < axes && shift[a] == 0.0 ? 2 : 1;
    weight /= (double)span[a];
  }
  size_t n0 = L.n[0], n1 = L.n[1], n2 = L.n[2];
  for (size_t k = 0; k < n2; ++k)
    for (size_t j = 0; j < n1; ++j)
      for (size_t i = 0; i < n0; ++i) {
        double sum = 0.0;
        for (long dk = 0; dk < span[2]; ++dk)
          for (long dj = 0; dj < span[1]; ++dj)
            for (long di = 0; di < span[0]; ++di)
              sum += f[gm_yee_index(&L, (long)i + di, (long)j + dj, (long)k + dk)];
        out[i + n0 * (j + n1 * k)] = weight * sum;
      }
  return GM_OK;
}

gm_status gm_yee_writer_create(const gm_yee *solver, const gm_yee_materials *materials,
                               const char *prefix, unsigned formats, gm_vti_encoding encoding,
                               gm_yee_writer **out, gm_error *err) {
  if (out == NULL) return gm_error_set(err, GM_EINVAL, "snapshot writer: out is NULL");
  *out = NULL;
  if (solver == NULL) return gm_error_set(err, GM_EINVAL, "snapshot writer: solver is NULL");
  if (prefix == NULL || prefix[0] == '\0')
    return gm_error_set(err, GM_EINVAL, "snapshot writer: no file prefix");
  if (formats == 0 || (formats & ~(unsigned)(GM_SNAPSHOT_VTI | GM_SNAPSHOT_HDF5)) != 0)
    return gm_error_set(err, GM_EINVAL, "snapshot writer: formats %u (use GM_SNAPSHOT_VTI "
                        "and/or GM_SNAPSHOT_HDF5)", formats);
  if (encoding != GM_VTI_ASCII && encoding != GM_VTI_BASE64 && encoding != GM_VTI_APPENDED)
    return gm_error_set(err, GM_EINVAL, "snapshot writer: unknown encoding %d", (int)encoding);
  if ((formats & GM_SNAPSHOT_HDF5) && !gm_hdf5_available())
    return gm_error_set(err, GM_EUNSUPPORTED, "snapshot writer: HDF5 output asked for, but "
                        "geomint was built without HDF5 (install libhdf5-dev and reconfigure)");
  gm_yee_layout L;
  gm_yee_get_layout(solver, &L);
  gm_yee_writer *w = calloc(1, sizeof *w);
  if (w == NULL) return gm_error_set(err, GM_ENOMEM, "snapshot writer: out of memory");
  w->formats = formats;
  w->encoding = encoding;
  w->image.dim = gm_yee_dim_axes(L.dim);
  for (size_t a = 0; a < 3; ++a) {
    w->image.n_cells[a] = L.n[a];
    w->image.spacing[a] = L.h[a];
    w->image.origin[a] = L.origin[a];
  }
  w->n_cells = L.n[0] * L.n[1] * L.n[2];
  w->complex_fields = L.complex_fields;
  size_t n_parts = L.complex_fields ? 2 : 1;
  w->scratch = calloc(6 * n_parts * w->n_cells, sizeof *w->scratch);
  w->prefix = malloc(strlen(prefix) + 1);
  if (w->scratch == NULL || w->prefix == NULL) goto nomem;
  strcpy(w->prefix, prefix);
  static const char *const names[2][2] = {{"E", "H"}, {"E_im", "H_im"}};
  for (size_t part = 0; part < n_parts; ++part)
    for (size_t eh = 0; eh < 2; ++eh) {
      gm_image_array *a = &w->arrays[w->n_arrays++];
      a->name = names[part][eh];
      a->centering = GM_IMAGE_CELL;
      a->n_components = 3;
      for (size_t c = 0; c < 3; ++c)
        a->component[c] = w->scratch + ((part * 2 + eh) * 3 + c) * w->n_cells;
    }
  if (materials != NULL) {
    if (gm_yee_materials_n_cells(materials) != w->n_cells) {
      gm_status st = gm_error_set(err, GM_EINVAL, "snapshot writer: materials have %zu cells, "
                                  "the grid %zu", gm_yee_materials_n_cells(materials), w->n_cells);
      gm_yee_writer_free(w);
      return st;
    }
    w->media = malloc(3 * w->n_cells * sizeof *w->media);
    if (w->media == NULL) goto nomem;
    const double *src[3] = {gm_yee_materials_epsilon(materials), gm_yee_materials_mu(materials),
                            gm_yee_materials_sigma(materials)};
    static const char *const media_names[3] = {"epsilon", "mu", "sigma"};
    for (size_t m = 0; m < 3; ++m) {
      memcpy(w->media + m * w->n_cells, src[m], w->n_cells * sizeof *w->media);
      gm_image_array *a = &w->arrays[w->n_arrays++];
      a->name = media_names[m];
      a->centering = GM_IMAGE_CELL;
      a->n_components = 1;
      a->component[0] = w->media + m * w->n_cells;
    }
  }
  *out = w;
  return GM_OK;
nomem:
  gm_yee_writer_free(w);
  return gm_error_set(err, GM_ENOMEM, "snapshot writer: out of memory");
}

void gm_yee_writer_free(gm_yee_writer *w) {
  if (w == NULL) return;
  free(w->prefix);
  free(w->scratch);
  free(w->media);
  free(w->times);
  free(w->steps);
  free(w);
}

/* The collection file, rewritten whole after each .vti so that it is valid at any time. */
static gm_status write_pvd(gm_yee_writer *w) {
  char path[4096];
  snprintf(path, sizeof path, "%s.pvd", w->prefix);
  const char *slash = strrchr(w->prefix, '/');
  const char *base = slash != NULL ? slash + 1 : w->prefix;
  FILE *f = fopen(path, "w");
  if (f == NULL)
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_EIO, "cannot open '%s' for writing: %s",
                   path, strerror(errno));
  fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
        "  <Collection>\n", f);
  for (size_t k = 0; k < w->count; ++k)
    fprintf(f, "    <DataSet timestep=\"%.17g\" file=\"%s_%06zu.vti\"/>\n", w->times[k], base,
            w->steps[k]);
  fputs("  </Collection>\n</VTKFile>\n", f);
  int bad = ferror(f);
  if (fclose(f) != 0) bad = 1;
  if (bad)
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_EIO, "cannot write '%s': %s", path,
                   strerror(errno));
  return GM_OK;
}

gm_status gm_yee_writer_write(gm_yee_writer *w, const gm_yee *solver) {
  if (w == NULL || solver == NULL) return GM_EINVAL;
  gm_yee_layout L;
  gm_yee_get_layout(solver, &L);
  if (L.n[0] * L.n[1] * L.n[2] != w->n_cells || L.complex_fields != w->complex_fields)
    return gm_fail(w->errmsg, sizeof w->errmsg, GM_EINVAL,
                   "snapshot writer: the solver is not the one the writer was made for");
  size_t n_parts = w->complex_fields ? 2 : 1;
  for (size_t part = 0; part < n_parts; ++part)
    for (size_t c = 0; c < GM_YEE_N_COMPONENTS; ++c) {
      double *out = w->scratch + (part * 6 + c) * w->n_cells;
      if (!gm_yee_dim_has(L.dim, (gm_yee_component)c))
        memset(out, 0, w->n_cells * sizeof *out);
      else if (gm_yee_cell_average(solver, (gm_yee_component)c, (int)part, out) != GM_OK)
        return gm_fail(w->errmsg, sizeof w->errmsg, GM_EINVAL,
                       "snapshot writer: cannot read component %s",
                       gm_yee_component_name((gm_yee_component)c));
    }
  size_t step = gm_yee_step(solver);
  double t = gm_yee_time_h(solver);
  /* the same step again (an explicit write and an observer): overwrite, list it once */
  size_t slot = w->count > 0 && w->last_step == step ? w->count - 1 : w->count;
  char path[4096];
  gm_error err = {{0}};
  if (w->formats & GM_SNAPSHOT_VTI) {
    if (slot == w->cap) {
      size_t cap = w->cap > 0 ? 2 * w->cap : 16;
      double *times = realloc(w->times, cap * sizeof *times);
      if (times != NULL) w->times = times;
      size_t *steps = realloc(w->steps, cap * sizeof *steps);
      if (steps != NULL) w->steps = steps;
      if (times == NULL || steps == NULL)
        return gm_fail(w->errmsg, sizeof w->errmsg, GM_ENOMEM, "snapshot writer: out of memory");
      w->cap = cap;
    }
    snprintf(path, sizeof path, "%s_%06zu.vti", w->prefix, step);
    gm_status st = gm_vti_write(path, &w->image, w->arrays, w->n_arrays, t, w->encoding, &err);
    if (st != GM_OK) return gm_fail(w->errmsg, sizeof w->errmsg, st, "%s", err.message);
    w->times[slot] = t;
    w->steps[slot] = step;
  }
  if (w->formats & GM_SNAPSHOT_HDF5) {
    snprintf(path, sizeof path, "%s_%06zu.h5", w->prefix, step);
    gm_status st = gm_hdf5_write(path, &w->image, w->arrays, w->n_arrays, t, &err);
    if (st != GM_OK) return gm_fail(w->errmsg, sizeof w->errmsg, st, "%s", err.message);
  }
  w->count = slot + 1;
  w->last_step = step;
  if (w->formats & GM_SNAPSHOT_VTI) return write_pvd(w);
  return GM_OK;
}

int gm_yee_writer_observe(void *writer, const gm_yee *solver) {
  return gm_yee_writer_write(writer, solver) == GM_OK ? 0 : 1;
}

size_t gm_yee_writer_count(const gm_yee_writer *w) { return w != NULL ? w->count : 0; }
const char *gm_yee_writer_errmsg(const gm_yee_writer *w) { return w != NULL ? w->errmsg : ""; }
