/* Snapshots on a box of cells: sizes and the checks shared by the .vti and HDF5 writers. */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/io.h"
#include "io/image_internal.h"

#define NAME_MAX_LEN 63

static int image_ok(const gm_image *im) {
  if (im == NULL || im->dim < 1 || im->dim > 3) return 0;
  size_t cells = 1;
  for (size_t a = 0; a < im->dim; ++a) {
    if (im->n_cells[a] < 1 || !(im->spacing[a] > 0.0) || !isfinite(im->spacing[a])) return 0;
    if (im->n_cells[a] >= SIZE_MAX / 8 / (cells + 1)) return 0; /* byte counts must not wrap */
    cells *= im->n_cells[a] + 1;
  }
  for (size_t a = 0; a < 3; ++a)
    if (!isfinite(im->origin[a])) return 0;
  return 1;
}

size_t gm_image_extent(const gm_image *im, size_t axis) {
  return axis < im->dim ? im->n_cells[axis] : 0;
}

size_t gm_image_cell_count(const gm_image *im) {
  if (!image_ok(im)) return 0;
  size_t n = 1;
  for (size_t a = 0; a < im->dim; ++a) n *= im->n_cells[a];
  return n;
}

size_t gm_image_point_count(const gm_image *im) {
  if (!image_ok(im)) return 0;
  size_t n = 1;
  for (size_t a = 0; a < im->dim; ++a) n *= im->n_cells[a] + 1;
  return n;
}

size_t gm_image_array_count(const gm_image *im, const gm_image_array *a) {
  return a->centering == GM_IMAGE_POINT ? gm_image_point_count(im) : gm_image_cell_count(im);
}

/* Names go into XML attributes and HDF5 paths unescaped: keep them to a safe alphabet. */
static int name_ok(const char *s) {
  if (s == NULL || s[0] == '\0' || strlen(s) > NAME_MAX_LEN) return 0;
  for (; *s; ++s)
    if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-' && *s != '.') return 0;
  return 1;
}

gm_status gm_image_validate(const gm_image *im, const gm_image_array *arrays, size_t n_arrays,
                            gm_error *err) {
  if (im == NULL) return gm_error_set(err, GM_EINVAL, "image: NULL");
  if (im->dim < 1 || im->dim > 3)
    return gm_error_set(err, GM_EINVAL, "image: dimension %zu (expected 1, 2 or 3)", im->dim);
  for (size_t a = 0; a < im->dim; ++a) {
    if (im->n_cells[a] < 1)
      return gm_error_set(err, GM_EINVAL, "image: no cells along axis %zu", a);
    if (!(im->spacing[a] > 0.0) || !isfinite(im->spacing[a]))
      return gm_error_set(err, GM_EINVAL, "image: spacing %g along axis %zu (must be > 0)",
                          im->spacing[a], a);
  }
  if (!image_ok(im)) return gm_error_set(err, GM_EINVAL, "image: non-finite origin or too many cells");
  if (n_arrays > 0 && arrays == NULL)
    return gm_error_set(err, GM_EINVAL, "image: %zu arrays but NULL", n_arrays);
  for (size_t k = 0; k < n_arrays; ++k) {
    const gm_image_array *a = &arrays[k];
    if (!name_ok(a->name))
      return gm_error_set(err, GM_EINVAL,
                          "image: array %zu: name '%s' (use 1-%d letters, digits, '_', '-', '.')",
                          k, a->name != NULL ? a->name : "(null)", NAME_MAX_LEN);
    if (a->centering != GM_IMAGE_CELL && a->centering != GM_IMAGE_POINT)
      return gm_error_set(err, GM_EINVAL, "image: array '%s': unknown centering", a->name);
    if (a->n_components < 1 || a->n_components > GM_IMAGE_MAX_COMPONENTS)
      return gm_error_set(err, GM_EINVAL, "image: array '%s': %zu components (1 to %d)", a->name,
                          a->n_components, GM_IMAGE_MAX_COMPONENTS);
    for (size_t c = 0; c < a->n_components; ++c)
      if (a->component[c] == NULL)
        return gm_error_set(err, GM_EINVAL, "image: array '%s': component %zu is NULL", a->name,
                            c);
    for (size_t j = 0; j < k; ++j)
      if (strcmp(arrays[j].name, a->name) == 0 && arrays[j].centering == a->centering)
        return gm_error_set(err, GM_EINVAL, "image: two arrays named '%s'", a->name);
  }
  return GM_OK;
}
