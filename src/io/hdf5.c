/* HDF5 snapshots of fields on a box of cells (libhdf5, Debian libhdf5-dev). Without HDF5 at
 * configure time the writer is an explicit GM_EUNSUPPORTED error, never a silent no-op.
 *
 * libhdf5 is opened when a snapshot is written (dlopen), not linked: it brings about 35 shared
 * libraries (curl, TLS, Kerberos, LDAP) whose symbol relocation cost every geomint process —
 * and every Python import — about 30 million instructions at start, for a feature few runs use
 * (issue 25, "process start"). The functions come from one dlopen per write, with RTLD_NODELETE
 * so that the library stays loaded and later writes only look the symbols up again; no state is
 * kept between calls. The header gives the types and constants; the type ids are read from
 * libhdf5's own variables (H5T_NATIVE_DOUBLE is the variable H5T_NATIVE_DOUBLE_g after H5open).
 *
 * Layout: root attributes time, origin[3], spacing[3], n_cells[3]; groups /cell and /point with
 * one dataset per array, shape [nz][ny][nx] or [nz][ny][nx][components], IEEE little-endian
 * doubles. HDF5 prints its error stack by default: the writer turns that off for the duration
 * of the call (the library never prints) and restores the previous handler. */
#if GM_HAVE_HDF5
#define _GNU_SOURCE /* RTLD_DEFAULT */
#include <dlfcn.h>
#endif
#include <errno.h>
#include <string.h>

#include "core/internal.h"
#include "geomint/io.h"
#include "io/image_internal.h"

#if GM_HAVE_HDF5
#include <hdf5.h>

/* The part of libhdf5's API the writer uses, looked up by name (the versioned names behind the
 * header's macros: H5Acreate is H5Acreate2, ...). */
typedef struct hdf5_api {
  herr_t (*open)(void);
  hid_t (*screate_simple)(int, const hsize_t *, const hsize_t *);
  herr_t (*sclose)(hid_t);
  herr_t (*sselect_hyperslab)(hid_t, H5S_seloper_t, const hsize_t *, const hsize_t *,
                              const hsize_t *, const hsize_t *);
  hid_t (*acreate)(hid_t, const char *, hid_t, hid_t, hid_t, hid_t);
  herr_t (*awrite)(hid_t, hid_t, const void *);
  herr_t (*aclose)(hid_t);
  hid_t (*dcreate)(hid_t, const char *, hid_t, hid_t, hid_t, hid_t, hid_t);
  herr_t (*dwrite)(hid_t, hid_t, hid_t, hid_t, hid_t, const void *);
  herr_t (*dclose)(hid_t);
  hid_t (*gcreate)(hid_t, const char *, hid_t, hid_t, hid_t);
  herr_t (*gclose)(hid_t);
  hid_t (*fcreate)(const char *, unsigned, hid_t, hid_t);
  herr_t (*fclose)(hid_t);
  herr_t (*eget_auto)(hid_t, H5E_auto2_t *, void **);
  herr_t (*eset_auto)(hid_t, H5E_auto2_t, void *);
  hid_t native_double, native_ullong, ieee_f64le, std_u64le; /* type ids */
} hdf5_api;

/* Function pointers from dlsym's void *: the POSIX way (the object pointer is copied bitwise). */
static int find(void *lib, const char *name, void *fn, size_t size) {
  void *sym = dlsym(lib, name);
  if (sym == NULL) return -1;
  memcpy(fn, &sym, size);
  return 0;
}

/* A program that links libhdf5 itself and uses H5T_NATIVE_DOUBLE has its own copy of the
 * variable (a copy relocation) and libhdf5 initialises that copy: look in the global scope
 * first, then in the library we opened. */
static int find_type(void *lib, const char *name, hid_t *out) {
  const hid_t *v = (const hid_t *)dlsym(RTLD_DEFAULT, name);
  if (v == NULL) v = (const hid_t *)dlsym(lib, name);
  if (v == NULL) return -1;
  *out = *v;
  return 0;
}

static gm_status load_hdf5(hdf5_api *api, void **lib, gm_error *err) {
  *lib = dlopen(GM_HDF5_SONAME, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
  if (*lib == NULL)
    return gm_error_set(err, GM_EUNSUPPORTED, "cannot load the HDF5 library %s: %s",
                        GM_HDF5_SONAME, dlerror());
#define GM_FIND(field, name) (find(*lib, name, &api->field, sizeof api->field) != 0)
  int missing = GM_FIND(open, "H5open") || GM_FIND(screate_simple, "H5Screate_simple") ||
                GM_FIND(sclose, "H5Sclose") || GM_FIND(sselect_hyperslab, "H5Sselect_hyperslab") ||
                GM_FIND(acreate, "H5Acreate2") || GM_FIND(awrite, "H5Awrite") ||
                GM_FIND(aclose, "H5Aclose") || GM_FIND(dcreate, "H5Dcreate2") ||
                GM_FIND(dwrite, "H5Dwrite") || GM_FIND(dclose, "H5Dclose") ||
                GM_FIND(gcreate, "H5Gcreate2") || GM_FIND(gclose, "H5Gclose") ||
                GM_FIND(fcreate, "H5Fcreate") || GM_FIND(fclose, "H5Fclose") ||
                GM_FIND(eget_auto, "H5Eget_auto2") || GM_FIND(eset_auto, "H5Eset_auto2");
#undef GM_FIND
  if (!missing && api->open() < 0) missing = 1;
  if (!missing)
    missing = find_type(*lib, "H5T_NATIVE_DOUBLE_g", &api->native_double) ||
              find_type(*lib, "H5T_NATIVE_ULLONG_g", &api->native_ullong) ||
              find_type(*lib, "H5T_IEEE_F64LE_g", &api->ieee_f64le) ||
              find_type(*lib, "H5T_STD_U64LE_g", &api->std_u64le);
  if (missing) {
    dlclose(*lib);
    return gm_error_set(err, GM_EUNSUPPORTED, "the HDF5 library %s lacks a function geomint uses",
                        GM_HDF5_SONAME);
  }
  return GM_OK;
}

int gm_hdf5_available(void) {
  void *lib = dlopen(GM_HDF5_SONAME, RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE);
  if (lib == NULL) return 0;
  dlclose(lib);
  return 1;
}

/* Extent along axis a as stored: cells or points, 1 on a flat axis. */
static hsize_t stored_extent(const gm_image *im, size_t a, gm_image_centering c) {
  if (a >= im->dim) return 1;
  return (hsize_t)(im->n_cells[a] + (c == GM_IMAGE_POINT ? 1 : 0));
}

static int write_attribute(const hdf5_api *api, hid_t file, const char *name, hid_t type, size_t n, const void *v) {
  hsize_t dims[1] = {(hsize_t)n};
  hid_t space = api->screate_simple(1, dims, NULL);
  if (space < 0) return -1;
  hid_t attr = api->acreate(file, name, type == api->native_double ? api->ieee_f64le : api->std_u64le,
                          space, H5P_DEFAULT, H5P_DEFAULT);
  int rc = attr < 0 ? -1 : (api->awrite(attr, type, v) < 0 ? -1 : 0);
  if (attr >= 0) api->aclose(attr);
  api->sclose(space);
  return rc;
}

/* One dataset; components are written one at a time into a hyperslab of the last axis, so
 * nothing is copied. */
static int write_dataset(const hdf5_api *api, hid_t group, const gm_image *im, const gm_image_array *a) {
  hsize_t dims[4] = {stored_extent(im, 2, a->centering), stored_extent(im, 1, a->centering),
                     stored_extent(im, 0, a->centering), (hsize_t)a->n_components};
  int rank = a->n_components == 1 ? 3 : 4;
  hid_t space = api->screate_simple(rank, dims, NULL);
  if (space < 0) return -1;
  hid_t set = api->dcreate(group, a->name, api->ieee_f64le, space, H5P_DEFAULT, H5P_DEFAULT,
                         H5P_DEFAULT);
  int rc = set < 0 ? -1 : 0;
  hsize_t n = dims[0] * dims[1] * dims[2];
  hid_t mem = api->screate_simple(1, &n, NULL);
  if (mem < 0) rc = -1;
  for (size_t c = 0; rc == 0 && c < a->n_components; ++c) {
    if (rank == 3) {
      rc = api->dwrite(set, api->native_double, mem, space, H5P_DEFAULT, a->component[c]) < 0 ? -1 : 0;
      continue;
    }
    hsize_t start[4] = {0, 0, 0, (hsize_t)c}, count[4] = {dims[0], dims[1], dims[2], 1};
    if (api->sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL) < 0 ||
        api->dwrite(set, api->native_double, mem, space, H5P_DEFAULT, a->component[c]) < 0)
      rc = -1;
  }
  if (mem >= 0) api->sclose(mem);
  if (set >= 0) api->dclose(set);
  api->sclose(space);
  return rc;
}

static int write_file(const hdf5_api *api, hid_t file, const gm_image *im, const gm_image_array *arrays,
                      size_t n_arrays, double time, const char **what) {
  double origin[3], spacing[3];
  unsigned long long n_cells[3];
  for (size_t a = 0; a < 3; ++a) {
    origin[a] = im->origin[a];
    spacing[a] = a < im->dim ? im->spacing[a] : 1.0;
    n_cells[a] = a < im->dim ? im->n_cells[a] : 1;
  }
  *what = "attributes";
  if (write_attribute(api, file, "time", api->native_double, 1, &time) != 0 ||
      write_attribute(api, file, "origin", api->native_double, 3, origin) != 0 ||
      write_attribute(api, file, "spacing", api->native_double, 3, spacing) != 0 ||
      write_attribute(api, file, "n_cells", api->native_ullong, 3, n_cells) != 0)
    return -1;
  for (int pass = 0; pass < 2; ++pass) {
    gm_image_centering c = pass == 0 ? GM_IMAGE_CELL : GM_IMAGE_POINT;
    hid_t group = -1;
    for (size_t k = 0; k < n_arrays; ++k) {
      if (arrays[k].centering != c) continue;
      *what = arrays[k].name;
      if (group < 0) {
        group = api->gcreate(file, c == GM_IMAGE_CELL ? "cell" : "point", H5P_DEFAULT,
                           H5P_DEFAULT, H5P_DEFAULT);
        if (group < 0) return -1;
      }
      if (write_dataset(api, group, im, &arrays[k]) != 0) {
        api->gclose(group);
        return -1;
      }
    }
    if (group >= 0 && api->gclose(group) < 0) return -1;
  }
  return 0;
}

gm_status gm_hdf5_write(const char *path, const gm_image *image, const gm_image_array *arrays,
                        size_t n_arrays, double time, gm_error *err) {
  if (path == NULL || path[0] == '\0') return gm_error_set(err, GM_EINVAL, "hdf5: no file name");
  gm_status st = gm_image_validate(image, arrays, n_arrays, err);
  if (st != GM_OK) return st;
  hdf5_api functions;
  const hdf5_api *api = &functions;
  void *lib = NULL;
  if ((st = load_hdf5(&functions, &lib, err)) != GM_OK) return st;
  H5E_auto2_t old_func = NULL;
  void *old_data = NULL;
  api->eget_auto(H5E_DEFAULT, &old_func, &old_data);
  api->eset_auto(H5E_DEFAULT, NULL, NULL);
  errno = 0;
  /* H5F_ACC_TRUNC's value: the header's macro also calls H5check() and H5open() by name */
  hid_t file = api->fcreate(path, 0x0002u, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) {
    st = gm_error_set(err, GM_EIO, "cannot create HDF5 file '%s' (%s)", path,
                      errno != 0 ? strerror(errno) : "HDF5 error");
  } else {
    const char *what = "";
    int rc = write_file(api, file, image, arrays, n_arrays, time, &what);
    if (api->fclose(file) < 0 && rc == 0) {
      what = "(closing)";
      rc = -1;
    }
    if (rc != 0) st = gm_error_set(err, GM_EIO, "cannot write '%s' to HDF5 file '%s'", what, path);
  }
  api->eset_auto(H5E_DEFAULT, old_func, old_data);
  dlclose(lib);
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
