/* HDF5 snapshots of fields on a box of cells (libhdf5, Debian libhdf5-dev). Without HDF5 at
 * configure time the writer is an explicit GM_EUNSUPPORTED error, never a silent no-op.
 *
 * Layout: root attributes time, origin[3], spacing[3], n_cells[3]; groups /cell and /point with
 * one dataset per array, shape [nz][ny][nx] or [nz][ny][nx][components], IEEE little-endian
 * doubles. HDF5 prints its error stack by default: the writer turns that off for the duration
 * of the call (the library never prints) and restores the previous handler. */
#include <errno.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/io.h"
#include "io/image_internal.h"

#if GM_HAVE_HDF5
#include <hdf5.h>

int gm_hdf5_available(void) { return 1; }

/* Extent along axis a as stored: cells or points, 1 on a flat axis. */
static hsize_t stored_extent(const gm_image *im, size_t a, gm_image_centering c) {
  if (a >= im->dim) return 1;
  return (hsize_t)(im->n_cells[a] + (c == GM_IMAGE_POINT ? 1 : 0));
}

static int write_attribute(hid_t file, const char *name, hid_t type, size_t n, const void *v) {
  hsize_t dims[1] = {(hsize_t)n};
  hid_t space = H5Screate_simple(1, dims, NULL);
  if (space < 0) return -1;
  hid_t attr = H5Acreate2(file, name, type == H5T_NATIVE_DOUBLE ? H5T_IEEE_F64LE : H5T_STD_U64LE,
                          space, H5P_DEFAULT, H5P_DEFAULT);
  int rc = attr < 0 ? -1 : (H5Awrite(attr, type, v) < 0 ? -1 : 0);
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  return rc;
}

/* One dataset; components are written one at a time into a hyperslab of the last axis, so
 * nothing is copied. */
static int write_dataset(hid_t group, const gm_image *im, const gm_image_array *a) {
  hsize_t dims[4] = {stored_extent(im, 2, a->centering), stored_extent(im, 1, a->centering),
                     stored_extent(im, 0, a->centering), (hsize_t)a->n_components};
  int rank = a->n_components == 1 ? 3 : 4;
  hid_t space = H5Screate_simple(rank, dims, NULL);
  if (space < 0) return -1;
  hid_t set = H5Dcreate2(group, a->name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT,
                         H5P_DEFAULT);
  int rc = set < 0 ? -1 : 0;
  hsize_t n = dims[0] * dims[1] * dims[2];
  hid_t mem = H5Screate_simple(1, &n, NULL);
  if (mem < 0) rc = -1;
  for (size_t c = 0; rc == 0 && c < a->n_components; ++c) {
    if (rank == 3) {
      rc = H5Dwrite(set, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, a->component[c]) < 0 ? -1 : 0;
      continue;
    }
    hsize_t start[4] = {0, 0, 0, (hsize_t)c}, count[4] = {dims[0], dims[1], dims[2], 1};
    if (H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
        H5Dwrite(set, H5T_NATIVE_DOUBLE, mem, space, H5P_DEFAULT, a->component[c]) < 0)
      rc = -1;
  }
  if (mem >= 0) H5Sclose(mem);
  if (set >= 0) H5Dclose(set);
  H5Sclose(space);
  return rc;
}

static int write_file(hid_t file, const gm_image *im, const gm_image_array *arrays,
                      size_t n_arrays, double time, const char **what) {
  double origin[3], spacing[3];
  unsigned long long n_cells[3];
  for (size_t a = 0; a < 3; ++a) {
    origin[a] = im->origin[a];
    spacing[a] = a < im->dim ? im->spacing[a] : 1.0;
    n_cells[a] = a < im->dim ? im->n_cells[a] : 1;
  }
  *what = "attributes";
  if (write_attribute(file, "time", H5T_NATIVE_DOUBLE, 1, &time) != 0 ||
      write_attribute(file, "origin", H5T_NATIVE_DOUBLE, 3, origin) != 0 ||
      write_attribute(file, "spacing", H5T_NATIVE_DOUBLE, 3, spacing) != 0 ||
      write_attribute(file, "n_cells", H5T_NATIVE_ULLONG, 3, n_cells) != 0)
    return -1;
  for (int pass = 0; pass < 2; ++pass) {
    gm_image_centering c = pass == 0 ? GM_IMAGE_CELL : GM_IMAGE_POINT;
    hid_t group = -1;
    for (size_t k = 0; k < n_arrays; ++k) {
      if (arrays[k].centering != c) continue;
      *what = arrays[k].name;
      if (group < 0) {
        group = H5Gcreate2(file, c == GM_IMAGE_CELL ? "cell" : "point", H5P_DEFAULT,
                           H5P_DEFAULT, H5P_DEFAULT);
        if (group < 0) return -1;
      }
      if (write_dataset(group, im, &arrays[k]) != 0) {
        H5Gclose(group);
        return -1;
      }
    }
    if (group >= 0 && H5Gclose(group) < 0) return -1;
  }
  return 0;
}

gm_status gm_hdf5_write(const char *path, const gm_image *image, const gm_image_array *arrays,
                        size_t n_arrays, double time, gm_error *err) {
  if (path == NULL || path[0] == '\0') return gm_error_set(err, GM_EINVAL, "hdf5: no file name");
  gm_status st = gm_image_validate(image, arrays, n_arrays, err);
  if (st != GM_OK) return st;
  H5E_auto2_t old_func = NULL;
  void *old_data = NULL;
  H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  errno = 0;
  hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) {
    st = gm_error_set(err, GM_EIO, "cannot create HDF5 file '%s' (%s)", path,
                      errno != 0 ? strerror(errno) : "HDF5 error");
  } else {
    const char *what = "";
    int rc = write_file(file, image, arrays, n_arrays, time, &what);
    if (H5Fclose(file) < 0 && rc == 0) {
      what = "(closing)";
      rc = -1;
    }
    if (rc != 0) st = gm_error_set(err, GM_EIO, "cannot write '%s' to HDF5 file '%s'", what, path);
  }
  H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
  return st;
}

#else

int gm_hdf5_available(void) { return 0; }

gm_status gm_hdf5_write(const char *path, const gm_image *image, const gm_image_array *arrays,
                        size_t n_arrays, double time, gm_error *err) {
  (void)path, (void)image, (void)arrays, (void)n_arrays, (void)time;
  return gm_error_set(err, GM_EUNSUPPORTED,
                      "geomint was built without HDF5 (install libhdf5-dev and reconfigure)");
}

#endif
