/* geomint._core, second part: Maxwell on simplicial meshes (the DEC leapfrog and the AVI of
 * gm_mesh_maxwell), the multisymplectic PDE schemes (gm_pde), harminv and generated meshes.
 * As in _core.c: no numerics here, only argument checks, views and copies; every status becomes
 * geomint.Error with the library's message. */
#include "_core.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- harminv ---------------------------------------------------------------------------- */

/* harminv(re, im or None, dt, f_min, f_max, n_basis, max_modes) -> dict of arrays */
static PyObject *core_harminv(PyObject *mod, PyObject *args) {
  (void)mod;
  PyObject *re_obj, *im_obj;
  double dt, f_min, f_max;
  Py_ssize_t n_basis, max_modes;
  if (!PyArg_ParseTuple(args, "OOdddnn", &re_obj, &im_obj, &dt, &f_min, &f_max, &n_basis,
                        &max_modes))
    return NULL;
  if (n_basis < 0 || max_modes < 1) {
    PyErr_SetString(PyExc_ValueError, "n_basis must be >= 0 and max_modes >= 1");
    return NULL;
  }
  PyArrayObject *re = (PyArrayObject *)PyArray_FROMANY(re_obj, NPY_DOUBLE, 1, 1,
                                                        NPY_ARRAY_CARRAY_RO);
  if (re == NULL) return NULL;
  size_t n = (size_t)PyArray_SIZE(re);
  PyArrayObject *im = NULL;
  if (im_obj != Py_None && !(im = as_doubles(im_obj, n, "the imaginary part"))) {
    Py_DECREF(re);
    return NULL;
  }
  gm_harminv_mode *modes = malloc((size_t)max_modes * sizeof *modes);
  size_t n_modes = 0;
  gm_error err = {{0}};
  gm_status st = modes ? GM_OK : GM_ENOMEM;
  if (st == GM_OK) {
    Py_BEGIN_ALLOW_THREADS st = gm_harminv(n, PyArray_DATA(re), im ? PyArray_DATA(im) : NULL, dt,
                                           f_min, f_max, (size_t)n_basis, (size_t)max_modes,
                                           modes, &n_modes, &err);
    Py_END_ALLOW_THREADS
  }
  Py_DECREF(re);
  Py_XDECREF(im);
  if (st != GM_OK) {
    free(modes);
    return st == GM_ENOMEM && !err.message[0] ? PyErr_NoMemory()
                                               : raise_status(st, "harminv: %s", err.message);
  }
  static const char *keys[] = {"frequency", "decay", "q", "amplitude", "phase", "error"};
  PyObject *out = PyDict_New();
  for (size_t k = 0; out && k < 6; ++k) {
    npy_intp dims[1] = {(npy_intp)n_modes};
    PyObject *a = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    if (a == NULL) {
      Py_CLEAR(out);
      break;
    }
    double *v = PyArray_DATA((PyArrayObject *)a);
    for (size_t i = 0; i < n_modes; ++i) {
      const gm_harminv_mode *m = &modes[i];
      const double fields[6] = {m->frequency, m->decay, m->q, m->amplitude, m->phase, m->error};
      v[i] = fields[k];
    }
    if (PyDict_SetItemString(out, keys[k], a) < 0) Py_CLEAR(out);
    Py_DECREF(a);
  }
  free(modes);
  return out;
}

/* ---- generated meshes as complexes --------------------------------------------------------- */

static PyObject *complex_of_mesh(gm_mesh *mesh, gm_error *err) {
  ComplexObject *c = (ComplexObject *)ComplexType.tp_alloc(&ComplexType, 0);
  if (c == NULL) {
    gm_mesh_free(mesh);
    return NULL;
  }
  c->mesh = mesh;
  gm_status st = gm_mesh_complex(mesh, &c->cx, err);
  if (st != GM_OK) {
    Py_DECREF(c);
    return raise_status(st, "complex: %s", err->message);
  }
  return (PyObject *)c;
}

/* mesh_rectangle(x0, x1, y0, y1, nx, ny, pattern) */
static PyObject *core_mesh_rectangle(PyObject *mod, PyObject *args) {
  (void)mod;
  double x0, x1, y0, y1;
  Py_ssize_t nx, ny;
  int pattern;
  if (!PyArg_ParseTuple(args, "ddddnni", &x0, &x1, &y0, &y1, &nx, &ny, &pattern)) return NULL;
  if (nx < 1 || ny < 1) {
    PyErr_Format(PyExc_ValueError, "nx and ny must be >= 1, got %zd and %zd", nx, ny);
    return NULL;
  }
  gm_mesh *mesh = NULL;
  gm_error err = {{0}};
  gm_status st = gm_mesh_rectangle(x0, x1, y0, y1, (size_t)nx, (size_t)ny, (gm_diagonal)pattern,
                                   &mesh, &err);
  if (st != GM_OK) return raise_status(st, "rectangle: %s", err.message);
  return complex_of_mesh(mesh, &err);
}

/* mesh_box(lo, hi, nx, ny, nz, pattern) with lo, hi 3-tuples */
static PyObject *core_mesh_box(PyObject *mod, PyObject *args) {
  (void)mod;
  double lo[3], hi[3];
  Py_ssize_t nx, ny, nz;
  int pattern;
  if (!PyArg_ParseTuple(args, "(ddd)(ddd)nnni", &lo[0], &lo[1], &lo[2], &hi[0], &hi[1], &hi[2],
                        &nx, &ny, &nz, &pattern))
    return NULL;
  if (nx < 1 || ny < 1 || nz < 1) {
    PyErr_SetString(PyExc_ValueError, "nx, ny and nz must be >= 1");
    return NULL;
  }
  gm_mesh *mesh = NULL;
  gm_error err = {{0}};
  gm_status st = gm_mesh_box(lo, hi, (size_t)nx, (size_t)ny, (size_t)nz,
                             (gm_box_pattern)pattern, &mesh, &err);
  if (st != GM_OK) return raise_status(st, "box: %s", err.message);
  return complex_of_mesh(mesh, &err);
}

/* ---- Maxwell on a mesh ----------------------------------------------------------------------- */

typedef struct {
  PyObject_HEAD
  gm_mesh_maxwell *s;
  PyObject *complex; /* strong ref: the geometry is borrowed from it */
  size_t n_edges, n_faces;
} MeshMaxwellObject;

static void MeshMaxwell_dealloc(MeshMaxwellObject *self) {
  gm_mesh_maxwell_free(self->s);
  Py_XDECREF(self->complex);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* MeshMaxwell(complex, epsilon=None, mu=None, avi=False, whitney=False, dt=0, courant=0.9,
 *             avi_fraction=0.1, allow_negative_stars=False) */
static int MeshMaxwell_init(MeshMaxwellObject *self, PyObject *args, PyObject *kw) {
  static char *names[] = {"complex", "epsilon", "mu", "avi", "whitney", "dt", "courant",
                          "avi_fraction", "allow_negative_stars", NULL};
  PyObject *cx_obj, *eps_obj = Py_None, *mu_obj = Py_None;
  int avi = 0, whitney = 0, negative = 0;
  gm_mesh_maxwell_options o = gm_mesh_maxwell_defaults();
  if (!PyArg_ParseTupleAndKeywords(args, kw, "O!|OOppdddp", names, &ComplexType, &cx_obj,
                                   &eps_obj, &mu_obj, &avi, &whitney, &o.dt, &o.courant,
                                   &o.avi_fraction, &negative))
    return -1;
  ComplexObject *cx = (ComplexObject *)cx_obj;
  gm_geometry *g = geometry(cx);
  if (g == NULL) return -1;
  size_t top = gm_complex_count(cx->cx, gm_complex_dim(cx->cx));
  PyArrayObject *eps = NULL, *mu = NULL;
  if (eps_obj != Py_None && !(eps = as_doubles(eps_obj, top, "epsilon (one per top simplex)")))
    return -1;
  if (mu_obj != Py_None && !(mu = as_doubles(mu_obj, top, "mu (one per top simplex)"))) {
    Py_XDECREF(eps);
    return -1;
  }
  o.scheme = avi ? GM_MESH_AVI : GM_MESH_LEAPFROG;
  o.star = whitney ? GM_MESH_STAR_WHITNEY : GM_MESH_STAR_DIAGONAL;
  o.allow_negative_stars = negative;
  gm_error err = {{0}};
  gm_status st = gm_mesh_maxwell_create(g, eps ? PyArray_DATA(eps) : NULL,
                                        mu ? PyArray_DATA(mu) : NULL, &o, &self->s, &err);
  Py_XDECREF(eps);
  Py_XDECREF(mu);
  if (st != GM_OK) {
    raise_status(st, "%s", err.message);
    return -1;
  }
  Py_INCREF(cx_obj);
  self->complex = cx_obj;
  self->n_edges = gm_complex_count(cx->cx, 1);
  self->n_faces = gm_complex_count(cx->cx, 2);
  return 0;
}

static PyObject *MeshMaxwell_set_fields(MeshMaxwellObject *self, PyObject *args) {
  PyObject *e_obj, *b_obj = Py_None;
  if (!PyArg_ParseTuple(args, "O|O", &e_obj, &b_obj)) return NULL;
  PyArrayObject *e = as_doubles(e_obj, self->n_edges, "E (one value per edge)");
  if (e == NULL) return NULL;
  PyArrayObject *b = NULL;
  if (b_obj != Py_None && !(b = as_doubles(b_obj, self->n_faces, "B (one value per face)"))) {
    Py_DECREF(e);
    return NULL;
  }
  gm_status st = gm_mesh_maxwell_set_fields(self->s, PyArray_DATA(e), b ? PyArray_DATA(b) : NULL);
  Py_DECREF(e);
  Py_XDECREF(b);
  if (st != GM_OK) return raise_status(st, "set_fields: %s", gm_mesh_maxwell_errmsg(self->s));
  Py_RETURN_NONE;
}

static PyObject *MeshMaxwell_advance(MeshMaxwellObject *self, PyObject *args) {
  Py_ssize_t n;
  if (!PyArg_ParseTuple(args, "n", &n)) return NULL;
  if (n < 0) {
    PyErr_SetString(PyExc_ValueError, "steps must be >= 0");
    return NULL;
  }
  gm_status st;
  Py_BEGIN_ALLOW_THREADS st = gm_mesh_maxwell_advance(self->s, (size_t)n);
  Py_END_ALLOW_THREADS
  if (st != GM_OK) return raise_status(st, "advance: %s", gm_mesh_maxwell_errmsg(self->s));
  Py_RETURN_NONE;
}

static PyObject *MeshMaxwell_advance_to(MeshMaxwellObject *self, PyObject *args) {
  double t;
  if (!PyArg_ParseTuple(args, "d", &t)) return NULL;
  gm_status st;
  Py_BEGIN_ALLOW_THREADS st = gm_mesh_maxwell_advance_to(self->s, t);
  Py_END_ALLOW_THREADS
  if (st != GM_OK) return raise_status(st, "advance_to: %s", gm_mesh_maxwell_errmsg(self->s));
  Py_RETURN_NONE;
}

/* E on the edges: a read-only view of the solver's array (valid until the next advance). */
static PyObject *MeshMaxwell_get_e(MeshMaxwellObject *self, void *c) {
  (void)c;
  npy_intp dims[1] = {(npy_intp)self->n_edges};
  return array_view(gm_mesh_maxwell_e(self->s), 1, dims, (PyObject *)self);
}

/* B on the faces at the current time (a copy: the AVI synchronises it). */
static PyObject *MeshMaxwell_get_b(MeshMaxwellObject *self, void *c) {
  (void)c;
  npy_intp dims[1] = {(npy_intp)self->n_faces};
  PyObject *a = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
  if (a) gm_mesh_maxwell_sync_b(self->s, PyArray_DATA((PyArrayObject *)a));
  return a;
}

static PyObject *MeshMaxwell_energy(MeshMaxwellObject *self, PyObject *a) {
  (void)a;
  gm_mesh_maxwell_energy e;
  gm_mesh_maxwell_energy_get(self->s, &e);
  return Py_BuildValue("{s:d,s:d,s:d,s:d}", "electric", e.electric, "magnetic", e.magnetic,
                       "plain", e.plain, "leapfrog", e.leapfrog);
}

static PyObject *MeshMaxwell_div_b(MeshMaxwellObject *self, PyObject *a) {
  (void)a;
  return PyFloat_FromDouble(gm_mesh_maxwell_div_b(self->s));
}

static PyObject *MeshMaxwell_gauss(MeshMaxwellObject *self, PyObject *a) {
  (void)a;
  ComplexObject *cx = (ComplexObject *)self->complex;
  npy_intp dims[1] = {(npy_intp)gm_complex_count(cx->cx, 0)};
  PyObject *out = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
  if (out) gm_mesh_maxwell_gauss(self->s, PyArray_DATA((PyArrayObject *)out));
  return out;
}

/* add_probe(component, x (3 values), capacity) -> id */
static PyObject *MeshMaxwell_add_probe(MeshMaxwellObject *self, PyObject *args) {
  const char *name;
  double x[3] = {0.0, 0.0, 0.0};
  Py_ssize_t capacity;
  if (!PyArg_ParseTuple(args, "s(ddd)n", &name, &x[0], &x[1], &x[2], &capacity)) return NULL;
  gm_yee_component c;
  if (gm_yee_component_find(name, &c) != GM_OK)
    return raise_status(GM_ENOTFOUND, "unknown field component '%s' (Ex, Ey, Ez, Hx, Hy, Hz)",
                        name);
  if (capacity < 1) {
    PyErr_SetString(PyExc_ValueError, "capacity must be >= 1");
    return NULL;
  }
  size_t id;
  gm_status st = gm_mesh_maxwell_add_probe(self->s, c, x, (size_t)capacity, &id);
  if (st != GM_OK) return raise_status(st, "probe %s: %s", name, gm_mesh_maxwell_errmsg(self->s));
  return PyLong_FromSize_t(id);
}

static PyObject *MeshMaxwell_probe(MeshMaxwellObject *self, PyObject *args) {
  Py_ssize_t id;
  if (!PyArg_ParseTuple(args, "n", &id)) return NULL;
  size_t n;
  const double *t, *v;
  gm_status st = id >= 0 ? gm_mesh_maxwell_probe_samples(self->s, (size_t)id, &n, &t, &v)
                         : GM_EINVAL;
  if (st != GM_OK) return raise_status(st, "probe %zd: %s", id, gm_mesh_maxwell_errmsg(self->s));
  return Py_BuildValue("(NN)", array_copy(t, n), array_copy(v, n));
}

static PyObject *MeshMaxwell_get_dt(MeshMaxwellObject *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(gm_mesh_maxwell_dt(self->s));
}
static PyObject *MeshMaxwell_get_time(MeshMaxwellObject *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(gm_mesh_maxwell_time(self->s));
}
static PyObject *MeshMaxwell_get_step(MeshMaxwellObject *self, void *c) {
  (void)c;
  return PyLong_FromSize_t(gm_mesh_maxwell_step(self->s));
}
static PyObject *MeshMaxwell_get_cfl(MeshMaxwellObject *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(gm_mesh_maxwell_cfl_limit(self->s));
}

static PyMethodDef MeshMaxwell_methods[] = {
    {"set_fields", (PyCFunction)MeshMaxwell_set_fields, METH_VARARGS, "set_fields(E, B=None)"},
    {"advance", (PyCFunction)MeshMaxwell_advance, METH_VARARGS, "advance(n) steps (leapfrog)"},
    {"advance_to", (PyCFunction)MeshMaxwell_advance_to, METH_VARARGS, "advance_to(t)"},
    {"energy", (PyCFunction)MeshMaxwell_energy, METH_NOARGS, "electric, magnetic, leapfrog"},
    {"div_b", (PyCFunction)MeshMaxwell_div_b, METH_NOARGS, "max |d B| over top simplices"},
    {"gauss", (PyCFunction)MeshMaxwell_gauss, METH_NOARGS, "div D - rho per vertex"},
    {"add_probe", (PyCFunction)MeshMaxwell_add_probe, METH_VARARGS,
     "add_probe(component, (x, y, z), capacity) -> id"},
    {"probe", (PyCFunction)MeshMaxwell_probe, METH_VARARGS, "probe(id) -> (t, values)"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef MeshMaxwell_getset[] = {
    {"E", (getter)MeshMaxwell_get_e, NULL, "E on the edges (read-only view)", NULL},
    {"B", (getter)MeshMaxwell_get_b, NULL, "B on the faces at the current time (copy)", NULL},
    {"dt", (getter)MeshMaxwell_get_dt, NULL, "time step", NULL},
    {"time", (getter)MeshMaxwell_get_time, NULL, "time reached", NULL},
    {"step", (getter)MeshMaxwell_get_step, NULL, "steps (AVI: events) done", NULL},
    {"cfl_limit", (getter)MeshMaxwell_get_cfl, NULL, "the leapfrog's CFL limit", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyTypeObject MeshMaxwellType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "geomint._core.MeshMaxwell",
    .tp_basicsize = sizeof(MeshMaxwellObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "MeshMaxwell(complex, epsilon=None, mu=None, avi=False, whitney=False, dt=0, "
              "courant=0.9, avi_fraction=0.1, allow_negative_stars=False)",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)MeshMaxwell_init,
    .tp_dealloc = (destructor)MeshMaxwell_dealloc,
    .tp_methods = MeshMaxwell_methods,
    .tp_getset = MeshMaxwell_getset,
};

/* ---- multisymplectic PDE schemes ---------------------------------------------------------- */

typedef struct {
  PyObject_HEAD
  gm_pde *pde;
  gm_pde_equation eq;         /* the built-in equation (its params are static) */
  const gm_pde_scheme *scheme;
  gm_pde_grid grid;
} PdeObject;

static void Pde_dealloc(PdeObject *self) {
  gm_pde_free(self->pde);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

static int equation_by_name(const char *name, gm_pde_equation *eq) {
  if (strcmp(name, "sine-gordon") == 0) *eq = gm_pde_sine_gordon();
  else if (strcmp(name, "nls") == 0) *eq = gm_pde_nls();
  else if (strcmp(name, "kdv") == 0) *eq = gm_pde_kdv();
  else return -1;
  return 0;
}

static const char *pde_scheme_name_at(const void *ctx, size_t i) {
  (void)ctx;
  const gm_pde_scheme *s = gm_pde_scheme_at(i);
  return s ? s->name : NULL;
}

/* An unknown scheme name, with the library's suggestions. */
static PyObject *raise_unknown_scheme(const char *name) {
  char list[256];
  if (gm_suggest(name, pde_scheme_name_at, NULL, list, sizeof list) > 0)
    return raise_status(GM_ENOTFOUND, "unknown PDE scheme '%s'; did you mean: %s?", name, list);
  return raise_status(GM_ENOTFOUND, "unknown PDE scheme '%s' (geomint.pde.schemes() lists them)",
                      name);
}

static PyObject *pde_scheme_row(const gm_pde_scheme *s) {
  return Py_BuildValue("{s:s,s:i,s:i,s:O,s:O,s:O,s:O,s:s,s:s}", "name", s->name, "order_t",
                       s->order_t, "order_x", s->order_x, "multisymplectic",
                       s->multisymplectic ? Py_True : Py_False, "energy_conserving",
                       s->energy_conserving ? Py_True : Py_False, "explicit",
                       s->is_explicit ? Py_True : Py_False, "scalar",
                       s->scalar ? Py_True : Py_False, "law", s->law ? s->law : "", "reference",
                       s->reference ? s->reference : "");
}

static PyObject *core_pde_schemes(PyObject *mod, PyObject *a) {
  (void)mod, (void)a;
  PyObject *out = PyList_New(0);
  for (size_t i = 0; out && i < gm_pde_scheme_count(); ++i) {
    PyObject *row = pde_scheme_row(gm_pde_scheme_at(i));
    if (row == NULL || PyList_Append(out, row) < 0) Py_CLEAR(out);
    Py_XDECREF(row);
  }
  return out;
}

/* pde_point_x(scheme, n, h, x0) -> x of every state point (gauss-prk: the Gauss points) */
static PyObject *core_pde_point_x(PyObject *mod, PyObject *args) {
  (void)mod;
  const char *name;
  Py_ssize_t n;
  double h, x0;
  if (!PyArg_ParseTuple(args, "sndd", &name, &n, &h, &x0)) return NULL;
  const gm_pde_scheme *s;
  if (gm_pde_scheme_find(name, &s) != GM_OK) return raise_unknown_scheme(name);
  if (n < 1) {
    PyErr_SetString(PyExc_ValueError, "n must be >= 1");
    return NULL;
  }
  gm_pde_grid g = {(size_t)n, h, x0, {0}};
  npy_intp dims[1] = {(npy_intp)n};
  PyObject *out = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
  if (out == NULL) return NULL;
  double *x = PyArray_DATA((PyArrayObject *)out);
  for (Py_ssize_t i = 0; i < n; ++i) x[i] = gm_pde_point_x(s, &g, (size_t)i);
  return out;
}

/* Pde(equation, scheme, n, h, x0, twist, dt, s0, newton_tol, newton_max_iter,
 *     dirichlet_left, dirichlet_right, track_variations) */
static int Pde_init(PdeObject *self, PyObject *args, PyObject *kw) {
  static char *names[] = {"equation", "scheme", "n", "h", "x0", "twist", "dt", "s0",
                          "newton_tol", "newton_max_iter", "dirichlet_left", "dirichlet_right",
                          "track_variations", NULL};
  const char *eq_name, *scheme_name;
  Py_ssize_t n, max_iter = 0;
  double h, x0, dt, tol = 0.0;
  PyObject *twist_obj, *s0_obj;
  unsigned int left = 0, right = 0;
  int track = 0;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "ssnddOdO|dnIIp", names, &eq_name, &scheme_name, &n,
                                   &h, &x0, &twist_obj, &dt, &s0_obj, &tol, &max_iter, &left,
                                   &right, &track))
    return -1;
  if (equation_by_name(eq_name, &self->eq) < 0) {
    raise_status(GM_ENOTFOUND, "unknown PDE equation '%s' (sine-gordon, nls, kdv)", eq_name);
    return -1;
  }
  if (gm_pde_scheme_find(scheme_name, &self->scheme) != GM_OK) {
    raise_unknown_scheme(scheme_name);
    return -1;
  }
  if (n < 1) {
    PyErr_SetString(PyExc_ValueError, "n must be >= 1");
    return -1;
  }
  size_t d = self->eq.dim;
  PyArrayObject *tw = as_doubles(twist_obj, d, "twist (one value per component)");
  if (tw == NULL) return -1;
  self->grid = (gm_pde_grid){(size_t)n, h, x0, {0}};
  memcpy(self->grid.twist, PyArray_DATA(tw), d * sizeof(double));
  Py_DECREF(tw);
  PyArrayObject *s0 = as_doubles(s0_obj, (size_t)n * d, "s0 (n points x the equation's dim)");
  if (s0 == NULL) return -1;
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  if (tol > 0.0) o.newton_tol = tol;
  if (max_iter > 0) o.newton_max_iter = (size_t)max_iter;
  o.dirichlet_left = left;
  o.dirichlet_right = right;
  o.track_variations = track;
  gm_error err = {{0}};
  gm_status st = gm_pde_create(&self->grid, &self->eq, self->scheme, &o, PyArray_DATA(s0),
                               &self->pde, &err);
  Py_DECREF(s0);
  if (st != GM_OK) {
    raise_status(st, "pde %s/%s: %s", eq_name, scheme_name, err.message);
    return -1;
  }
  return 0;
}

static PyObject *Pde_advance(PdeObject *self, PyObject *args) {
  Py_ssize_t n;
  if (!PyArg_ParseTuple(args, "n", &n)) return NULL;
  if (n < 0) {
    PyErr_SetString(PyExc_ValueError, "steps must be >= 0");
    return NULL;
  }
  gm_error err = {{0}};
  gm_status st;
  Py_BEGIN_ALLOW_THREADS st = gm_pde_advance(self->pde, (size_t)n, &err);
  Py_END_ALLOW_THREADS
  if (st != GM_OK) return raise_status(st, "advance: %s", err.message);
  Py_RETURN_NONE;
}

/* The state (n, d): a read-only view, valid until the next advance. */
static PyObject *Pde_get_state(PdeObject *self, void *c) {
  (void)c;
  npy_intp dims[2] = {(npy_intp)gm_pde_n(self->pde), (npy_intp)gm_pde_dim(self->pde)};
  return array_view(gm_pde_state(self->pde), 2, dims, (PyObject *)self);
}

static PyObject *Pde_invariants(PdeObject *self, PyObject *a) {
  (void)a;
  double rel = gm_pde_ms_residual(self->pde, NULL);
  return Py_BuildValue("{s:d,s:d,s:d,s:d,s:d,s:d,s:d}", "energy", gm_pde_energy(self->pde),
                       "momentum", gm_pde_momentum(self->pde), "norm", gm_pde_norm(self->pde),
                       "mass", gm_pde_mass(self->pde), "cell_energy",
                       gm_pde_cell_energy(self->pde), "cell_momentum",
                       gm_pde_cell_momentum(self->pde), "ms_residual", rel >= 0 ? rel : NAN);
}

static PyObject *Pde_get_stats(PdeObject *self, void *c) {
  (void)c;
  gm_pde_stats s = gm_pde_get_stats(self->pde);
  return Py_BuildValue("{s:n,s:n,s:n,s:n,s:n,s:d}", "steps", (Py_ssize_t)s.steps,
                       "newton_iterations", (Py_ssize_t)s.newton_iterations, "factorizations",
                       (Py_ssize_t)s.factorizations, "hessian_fd_evaluations",
                       (Py_ssize_t)s.hessian_fd_evaluations, "gradient_evaluations",
                       (Py_ssize_t)s.gradient_evaluations, "max_newton_residual",
                       s.max_newton_residual);
}
static PyObject *Pde_get_time(PdeObject *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(gm_pde_time(self->pde));
}
static PyObject *Pde_get_steps(PdeObject *self, void *c) {
  (void)c;
  return PyLong_FromSize_t(gm_pde_steps(self->pde));
}
static PyObject *Pde_get_dim(PdeObject *self, void *c) {
  (void)c;
  return PyLong_FromSize_t(self->eq.dim);
}

static PyMethodDef Pde_methods[] = {
    {"advance", (PyCFunction)Pde_advance, METH_VARARGS, "advance(n) steps"},
    {"invariants", (PyCFunction)Pde_invariants, METH_NOARGS,
     "energy, momentum, norm, mass, cell energy/momentum, multisymplectic residual"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef Pde_getset[] = {
    {"state", (getter)Pde_get_state, NULL, "state (n, d): read-only view", NULL},
    {"stats", (getter)Pde_get_stats, NULL, "Newton statistics", NULL},
    {"time", (getter)Pde_get_time, NULL, "time", NULL},
    {"steps", (getter)Pde_get_steps, NULL, "steps done", NULL},
    {"dim", (getter)Pde_get_dim, NULL, "components per point", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyTypeObject PdeType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "geomint._core.Pde",
    .tp_basicsize = sizeof(PdeObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Pde(equation, scheme, n, h, x0, twist, dt, s0, ...): a multisymplectic scheme",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)Pde_init,
    .tp_dealloc = (destructor)Pde_dealloc,
    .tp_methods = Pde_methods,
    .tp_getset = Pde_getset,
};

/* ---- registration ---------------------------------------------------------------------------- */

static PyMethodDef fields_functions[] = {
    {"harminv", core_harminv, METH_VARARGS,
     "harminv(re, im, dt, f_min, f_max, n_basis, max_modes) -> dict of arrays"},
    {"mesh_rectangle", core_mesh_rectangle, METH_VARARGS,
     "mesh_rectangle(x0, x1, y0, y1, nx, ny, pattern) -> Complex"},
    {"mesh_box", core_mesh_box, METH_VARARGS, "mesh_box(lo, hi, nx, ny, nz, pattern) -> Complex"},
    {"pde_schemes", core_pde_schemes, METH_NOARGS, "the PDE scheme table"},
    {"pde_point_x", core_pde_point_x, METH_VARARGS, "pde_point_x(scheme, n, h, x0)"},
    {NULL, NULL, 0, NULL}};

int fields_add_to_module(PyObject *m) {
  if (PyType_Ready(&MeshMaxwellType) < 0 || PyType_Ready(&PdeType) < 0) return -1;
  if (PyModule_AddObjectRef(m, "MeshMaxwell", (PyObject *)&MeshMaxwellType) < 0 ||
      PyModule_AddObjectRef(m, "Pde", (PyObject *)&PdeType) < 0)
    return -1;
  return PyModule_AddFunctions(m, fields_functions);
}
