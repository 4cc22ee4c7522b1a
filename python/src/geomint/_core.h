/* Shared parts of the two translation units of geomint._core: _core.c (tables, ODE problems,
 * the integrator, DEC complexes, Yee scenes) and _fields.c (mesh Maxwell, the multisymplectic
 * PDE schemes, harminv, generated meshes). */
#ifndef GEOMINT_PY_CORE_H
#define GEOMINT_PY_CORE_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION
#define PY_ARRAY_UNIQUE_SYMBOL geomint_core_ARRAY_API
#ifndef GEOMINT_CORE_IMPORTS_ARRAY
#define NO_IMPORT_ARRAY
#endif
#include <numpy/arrayobject.h>

#include "geomint/geomint.h"

extern PyObject *Error; /* geomint.Error */

/* Raise geomint.Error(message) with .code (the gm_status) and .reason (gm_strerror). */
PyObject *raise_status(gm_status st, const char *fmt, ...);
/* A 1-D float64 array of n values copied from x. */
PyObject *array_copy(const double *x, size_t n);
/* A read-only view of library memory whose lifetime is owner's. */
PyObject *array_view(const double *x, int nd, npy_intp *dims, PyObject *owner);
/* A C-contiguous float64 array of exactly n values from obj (new reference), or NULL with
 * ValueError naming `what`. */
PyArrayObject *as_doubles(PyObject *obj, size_t n, const char *what);
/* An array owning the malloc'ed data (freed with it; freed here on failure). */
PyObject *owned_array(double *data, int nd, npy_intp *dims);

typedef struct {
  PyObject_HEAD
  gm_mesh *mesh;          /* owned, NULL when built from arrays only */
  gm_complex *cx;         /* owned */
  gm_geometry *g;         /* owned, NULL until first needed */
  char geometry_error[GM_ERRMSG_SIZE];
} ComplexObject;

extern PyTypeObject ComplexType;
/* The circumcentric geometry of a complex (made on first use), or NULL with the error set. */
gm_geometry *geometry(ComplexObject *self);

/* _fields.c: its types and functions, added to the module by PyInit__core. */
int fields_add_to_module(PyObject *module);

#endif
