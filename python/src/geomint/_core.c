/* geomint._core: the CPython extension over libgeomint (DESIGN §5c: no numerics of its own).
 *
 * A hand-written extension rather than cffi: the force of a user problem is called from the
 * library's inner loop, and here the trampoline (copy the state into a persistent read-only
 * NumPy array, call, copy the result out) runs in C; with cffi the same trampoline is Python
 * code (docs/python.md gives the measured costs of both).
 *
 * Ownership: every object holds references to what its C counterpart borrows (an integrator
 * keeps its problem alive, a geometry its complex). Status codes become geomint.Error carrying
 * the library's message; Python exceptions raised in callbacks are kept and re-raised after the
 * library returns GM_ECALLBACK. */
#define GEOMINT_CORE_IMPORTS_ARRAY
#include "_core.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

PyObject *Error; /* geomint.Error */

/* Raise geomint.Error(message) with .code (the gm_status) and .reason (gm_strerror). */
PyObject *raise_status(gm_status st, const char *fmt, ...) {
  char msg[2 * GM_ERRMSG_SIZE];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  PyObject *exc = PyObject_CallFunction(Error, "s", msg);
  if (exc == NULL) return NULL;
  PyObject *code = PyLong_FromLong((long)st), *reason = PyUnicode_FromString(gm_strerror(st));
  if (code && reason) {
    PyObject_SetAttrString(exc, "code", code);
    PyObject_SetAttrString(exc, "reason", reason);
  }
  Py_XDECREF(code);
  Py_XDECREF(reason);
  PyErr_SetObject(Error, exc);
  Py_DECREF(exc);
  return NULL;
}

/* A 1-D float64 array of n values copied from x. */
PyObject *array_copy(const double *x, size_t n) {
  npy_intp dims[1] = {(npy_intp)n};
  PyObject *a = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
  if (a && n) memcpy(PyArray_DATA((PyArrayObject *)a), x, n * sizeof *x);
  return a;
}

/* A read-only view of library memory whose lifetime is owner's. */
PyObject *array_view(const double *x, int nd, npy_intp *dims, PyObject *owner) {
  PyObject *a = PyArray_New(&PyArray_Type, nd, dims, NPY_DOUBLE, NULL, (void *)x, 0,
                            NPY_ARRAY_CARRAY_RO, NULL);
  if (a == NULL) return NULL;
  Py_INCREF(owner);
  if (PyArray_SetBaseObject((PyArrayObject *)a, owner) < 0) {
    Py_DECREF(a);
    return NULL;
  }
  return a;
}

/* A C-contiguous float64 array of exactly n values from obj (checked by the Python layer
 * too; here it guards the C memory). New reference or NULL with ValueError naming `what`. */
PyArrayObject *as_doubles(PyObject *obj, size_t n, const char *what) {
  PyArrayObject *a =
      (PyArrayObject *)PyArray_FROMANY(obj, NPY_DOUBLE, 0, 0, NPY_ARRAY_CARRAY_RO);
  if (a == NULL) return NULL;
  if ((size_t)PyArray_SIZE(a) != n) {
    PyErr_Format(PyExc_ValueError, "%s: expected %zu values, got %zd", what, n,
                 (Py_ssize_t)PyArray_SIZE(a));
    Py_DECREF(a);
    return NULL;
  }
  return a;
}

/* ---- did you mean ------------------------------------------------------------------------ */

static const char *method_name_at(const void *ctx, size_t i) {
  (void)ctx;
  const gm_method *m = gm_method_at(i);
  return m ? m->name : NULL;
}
static const char *model_name_at(const void *ctx, size_t i) {
  (void)ctx;
  const gm_model_info *m = gm_model_info_at(i);
  return m ? m->name : NULL;
}

static PyObject *raise_unknown(const char *kind, const char *name, gm_name_at at) {
  char list[512];
  if (gm_suggest(name, at, NULL, list, sizeof list) > 0)
    return raise_status(GM_ENOTFOUND, "unknown %s '%s'; did you mean: %s?", kind, name, list);
  return raise_status(GM_ENOTFOUND, "unknown %s '%s' (geomint.%s() lists them)", kind, name,
                      kind[0] == 'm' ? "methods" : "problems");
}

/* A method by name: a table row (borrowed) or a constructed gauss-S row (*owned, to free). */
static const gm_method *find_method(const char *name, gm_method **owned) {
  *owned = NULL;
  const gm_method *m = gm_method_find(name);
  if (m) return m;
  gm_error err = {{0}};
  gm_status st = gm_method_create(name, owned, &err);
  if (st == GM_OK) return *owned;
  if (st == GM_ENOTFOUND) raise_unknown("method", name, method_name_at);
  else raise_status(st, "method '%s': %s", name, err.message);
  return NULL;
}

/* ---- tables: methods and problems -------------------------------------------------------- */

static PyObject *kinds_list(unsigned mask) {
  PyObject *l = PyList_New(0);
  for (size_t b = 0; l && b < GM_N_PROBLEM_KINDS; ++b)
    if (mask & (1u << b)) {
      PyObject *s = PyUnicode_FromString(gm_problem_kind_name((gm_problem_kind)(1u << b)));
      if (s == NULL || PyList_Append(l, s) < 0) Py_CLEAR(l);
      Py_XDECREF(s);
    }
  return l;
}

static PyObject *method_row(const gm_method *m) {
  PyObject *flags = PyList_New(0);
  for (size_t b = 0; flags && b < GM_N_METHOD_FLAGS; ++b)
    if (m->flags & (1u << b)) {
      PyObject *s = PyUnicode_FromString(gm_method_flag_name(b));
      if (s == NULL || PyList_Append(flags, s) < 0) Py_CLEAR(flags);
      Py_XDECREF(s);
    }
  if (flags == NULL) return NULL;
  return Py_BuildValue("{s:s,s:s,s:i,s:n,s:N,s:N,s:s,s:s,s:z}", "name", m->name, "family",
                       gm_method_family_name(m->family), "order", m->order, "stages",
                       (Py_ssize_t)m->n_stages, "flags", flags, "accepts",
                       kinds_list(m->accepts), "description",
                       m->description ? m->description : "", "reference",
                       m->reference ? m->reference : "", "basic", m->basic);
}

static PyObject *core_methods(PyObject *self, PyObject *args) {
  (void)self, (void)args;
  PyObject *out = PyList_New(0);
  for (size_t i = 0; out && i < gm_method_count(); ++i) {
    PyObject *row = method_row(gm_method_at(i));
    if (row == NULL || PyList_Append(out, row) < 0) Py_CLEAR(out);
    Py_XDECREF(row);
  }
  return out;
}


/* The row of one method by name (table rows and gauss-S / lobatto-iiia-iiib-S). */
static PyObject *core_method(PyObject *self, PyObject *arg) {
  (void)self;
  const char *name = PyUnicode_AsUTF8(arg);
  if (name == NULL) return NULL;
  gm_method *owned;
  const gm_method *m = find_method(name, &owned);
  if (m == NULL) return NULL;
  PyObject *row = method_row(m);
  gm_method_free(owned);
  return row;
}

static PyObject *core_problems(PyObject *self, PyObject *args) {
  (void)self, (void)args;
  PyObject *out = PyList_New(0);
  for (size_t i = 0; out && i < gm_model_count(); ++i) {
    const gm_model_info *m = gm_model_info_at(i);
    PyObject *params = PyList_New(0);
    for (size_t k = 0; params && k < m->n_params; ++k) {
      const gm_param_info *p = &m->params[k];
      PyObject *t = p->type == GM_PARAM_TEXT
                        ? Py_BuildValue("(sOs)", p->name, Py_None, p->description)
                        : Py_BuildValue("(sds)", p->name, p->default_value, p->description);
      if (t == NULL || PyList_Append(params, t) < 0) Py_CLEAR(params);
      Py_XDECREF(t);
    }
    PyObject *inv = PyList_New(0);
    for (size_t k = 0; inv && k < m->n_invariants; ++k) {
      PyObject *s = PyUnicode_FromString(m->invariant_names[k]);
      if (s == NULL || PyList_Append(inv, s) < 0) Py_CLEAR(inv);
      Py_XDECREF(s);
    }
    PyObject *row = (params && inv) ? Py_BuildValue(
        "{s:s,s:s,s:s,s:n,s:N,s:N,s:O}", "name", m->name, "description", m->description, "kind",
        gm_problem_kind_name(m->kind), "dim", (Py_ssize_t)m->default_dim, "params", params,
        "invariants", inv, "has_exact", m->has_exact ? Py_True : Py_False) : NULL;
    if (row == NULL) { Py_XDECREF(params); Py_XDECREF(inv); }
    if (row == NULL || PyList_Append(out, row) < 0) Py_CLEAR(out);
    Py_XDECREF(row);
  }
  return out;
}

/* ---- problems: built-in models and Python callables --------------------------------------- */

/* Both problem types start with this header, so the integrator handles them alike. */
typedef struct {
  PyObject_HEAD
  gm_problem *problem;      /* the C problem (inside the model or in `own`) */
  double t0;
  double *y0;               /* initial state (state size), owned */
  size_t n_state;
  int python;               /* callbacks are Python functions */
  PyObject *pending;        /* exception raised by a callback (strong ref), or NULL */
  const char *pending_in;   /* which callback raised it */
  double pending_t;         /* the time of that call, NaN when the callback has no t */
} ProblemBase;

static void keep_exception(ProblemBase *pb, const char *where, double t) {
  if (pb->pending != NULL) {
    PyErr_Clear();
    return;
  }
  PyObject *type, *value, *tb;
  PyErr_Fetch(&type, &value, &tb);
  PyErr_NormalizeException(&type, &value, &tb);
  if (tb) PyException_SetTraceback(value, tb);
  Py_XDECREF(type);
  Py_XDECREF(tb);
  pb->pending = value;
  pb->pending_in = where;
  pb->pending_t = t;
}

typedef struct {
  ProblemBase base;
  gm_model *model;
} ModelObject;

static void Model_dealloc(ModelObject *self) {
  gm_model_free(self->model);
  free(self->base.y0);
  Py_XDECREF(self->base.pending);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* Model(name, set): a built-in problem with parameters (dict of number or text). */
static int Model_init(ModelObject *self, PyObject *args, PyObject *kw) {
  static char *names[] = {"name", "set", NULL};
  const char *name;
  PyObject *set = NULL;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "s|O", names, &name, &set)) return -1;
  if (gm_model_create(name, &self->model) != GM_OK) {
    raise_unknown("problem", name, model_name_at);
    return -1;
  }
  if (set && set != Py_None) {
    if (!PyDict_Check(set)) {
      PyErr_SetString(PyExc_TypeError, "set: expected a dict of parameter names to values");
      return -1;
    }
    PyObject *key, *value;
    Py_ssize_t pos = 0;
    while (PyDict_Next(set, &pos, &key, &value)) {
      const char *k = PyUnicode_AsUTF8(key);
      if (k == NULL) return -1;
      gm_status st;
      if (PyUnicode_Check(value)) {
        st = gm_model_set_text(self->model, k, PyUnicode_AsUTF8(value));
      } else {
        double v = PyFloat_AsDouble(value);
        if (v == -1.0 && PyErr_Occurred()) return -1;
        st = gm_model_set(self->model, k, v);
      }
      if (st != GM_OK) {
        raise_status(st, "%s: set %s: %s", name, k, gm_model_errmsg(self->model));
        return -1;
      }
    }
  }
  gm_status st = gm_model_build(self->model);
  if (st != GM_OK) {
    raise_status(st, "%s: %s", name, gm_model_errmsg(self->model));
    return -1;
  }
  self->base.problem = (gm_problem *)gm_model_problem(self->model);
  self->base.n_state = gm_model_state_size(self->model);
  self->base.y0 = malloc(self->base.n_state * sizeof(double));
  if (self->base.y0 == NULL) {
    PyErr_NoMemory();
    return -1;
  }
  gm_model_initial_state(self->model, &self->base.t0, self->base.y0);
  return 0;
}

/* ---- user problems ---- */

typedef struct {
  ProblemBase base;
  gm_problem own;
  PyObject *fn[6];          /* kind-specific callables (see Problem_init) */
  PyObject *invariant_fns;  /* unused slot for symmetry with the docs */
  PyArrayObject *arg_q, *arg_p, *arg_y; /* persistent read-only argument arrays */
  PyArrayObject *arg_R, *arg_x;         /* rigid bodies: R (3×3) and x (3) */
  double *buffer;           /* backing store of the argument arrays */
} ProblemObject;

enum { FN_A, FN_B, FN_C, FN_D, FN_E, FN_F };

static void Problem_dealloc(ProblemObject *self) {
  for (int i = 0; i < 6; ++i) Py_XDECREF(self->fn[i]);
  Py_XDECREF(self->arg_q);
  Py_XDECREF(self->arg_p);
  Py_XDECREF(self->arg_y);
  Py_XDECREF(self->arg_R);
  Py_XDECREF(self->arg_x);
  free(self->buffer);
  free(self->base.y0);
  Py_XDECREF(self->base.pending);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* Copy n values into the persistent argument array a (read-only to the callee). */
static inline void fill(PyArrayObject *a, const double *x, size_t n) {
  memcpy(PyArray_DATA(a), x, n * sizeof *x);
}

/* Copy the callable's result (n values) into out; 0 or 1 with the exception kept. */
static int take_result(ProblemObject *self, PyObject *res, double *out, size_t n,
                       const char *where, double t) {
  if (res == NULL) {
    keep_exception(&self->base, where, t);
    return 1;
  }
  PyArrayObject *a;
  if (PyArray_CheckExact(res) && PyArray_TYPE((PyArrayObject *)res) == NPY_DOUBLE &&
      PyArray_IS_C_CONTIGUOUS((PyArrayObject *)res)) {
    a = (PyArrayObject *)res;
    Py_INCREF(a);
  } else {
    a = (PyArrayObject *)PyArray_FROMANY(res, NPY_DOUBLE, 0, 0, NPY_ARRAY_CARRAY_RO);
  }
  Py_DECREF(res);
  if (a == NULL) {
    keep_exception(&self->base, where, t);
    return 1;
  }
  if ((size_t)PyArray_SIZE(a) != n) {
    PyErr_Format(PyExc_ValueError, "%s returned %zd values, expected %zu", where,
                 (Py_ssize_t)PyArray_SIZE(a), n);
    Py_DECREF(a);
    keep_exception(&self->base, where, t);
    return 1;
  }
  memcpy(out, PyArray_DATA(a), n * sizeof *out);
  Py_DECREF(a);
  return 0;
}

static double take_scalar(ProblemObject *self, PyObject *res, const char *where) {
  if (res == NULL) {
    keep_exception(&self->base, where, NAN);
    return NAN;
  }
  double v = PyFloat_AsDouble(res);
  Py_DECREF(res);
  if (v == -1.0 && PyErr_Occurred()) {
    keep_exception(&self->base, where, NAN);
    return NAN;
  }
  return v;
}

/* separable: fn = {dV(q), V(q), dT(p), T(p)}; dT/T NULL: T = ½|p|² */
static int sep_potential_gradient(void *ctx, const double *q, double *out) {
  ProblemObject *self = ctx;
  size_t d = self->own.dim;
  fill(self->arg_q, q, d);
  return take_result(self, PyObject_CallOneArg(self->fn[FN_A], (PyObject *)self->arg_q), out,
                     d, "the potential gradient", NAN);
}
static double sep_potential(void *ctx, const double *q) {
  ProblemObject *self = ctx;
  fill(self->arg_q, q, self->own.dim);
  return take_scalar(self, PyObject_CallOneArg(self->fn[FN_B], (PyObject *)self->arg_q),
                     "the potential");
}
static int sep_kinetic_gradient(void *ctx, const double *p, double *out) {
  ProblemObject *self = ctx;
  size_t d = self->own.dim;
  fill(self->arg_p, p, d);
  return take_result(self, PyObject_CallOneArg(self->fn[FN_C], (PyObject *)self->arg_p), out,
                     d, "the kinetic gradient", NAN);
}
static double sep_kinetic(void *ctx, const double *p) {
  ProblemObject *self = ctx;
  fill(self->arg_p, p, self->own.dim);
  return take_scalar(self, PyObject_CallOneArg(self->fn[FN_D], (PyObject *)self->arg_p),
                     "the kinetic energy");
}
/* T = ½|p|², written as the library's own problems write it */
static int free_kinetic_gradient(void *ctx, const double *p, double *out) {
  ProblemObject *self = ctx;
  memcpy(out, p, self->own.dim * sizeof *p);
  return 0;
}
static double free_kinetic(void *ctx, const double *p) {
  ProblemObject *self = ctx;
  double s = 0.0;
  for (size_t i = 0; i < self->own.dim; ++i) s += p[i] * p[i];
  return 0.5 * s;
}
static int free_kinetic_hessian(void *ctx, const double *p, double *h) {
  ProblemObject *self = ctx;
  (void)p;
  size_t d = self->own.dim;
  for (size_t i = 0; i < d * d; ++i) h[i] = 0.0;
  for (size_t i = 0; i < d; ++i) h[i * d + i] = 1.0;
  return 0;
}

/* Hamiltonian: fn = {H(q, p), dH_dq(q, p), dH_dp(q, p)} */
static PyObject *call_qp(ProblemObject *self, PyObject *fn, const double *q, const double *p) {
  size_t d = self->own.dim;
  fill(self->arg_q, q, d);
  fill(self->arg_p, p, d);
  return PyObject_CallFunctionObjArgs(fn, (PyObject *)self->arg_q, (PyObject *)self->arg_p,
                                      NULL);
}
static double ham_h(void *ctx, const double *q, const double *p) {
  ProblemObject *self = ctx;
  return take_scalar(self, call_qp(self, self->fn[FN_A], q, p), "the Hamiltonian");
}
static int ham_dq(void *ctx, const double *q, const double *p, double *out) {
  ProblemObject *self = ctx;
  return take_result(self, call_qp(self, self->fn[FN_B], q, p), out, self->own.dim,
                     "dH/dq", NAN);
}
static int ham_dp(void *ctx, const double *q, const double *p, double *out) {
  ProblemObject *self = ctx;
  return take_result(self, call_qp(self, self->fn[FN_C], q, p), out, self->own.dim,
                     "dH/dp", NAN);
}

/* Lagrangian: fn = {L(q, v), dL_dq(q, v), dL_dv(q, v)} */
static double lag_l(void *ctx, const double *q, const double *v) {
  ProblemObject *self = ctx;
  return take_scalar(self, call_qp(self, self->fn[FN_A], q, v), "the Lagrangian");
}
static int lag_dq(void *ctx, const double *q, const double *v, double *out) {
  ProblemObject *self = ctx;
  return take_result(self, call_qp(self, self->fn[FN_B], q, v), out, self->own.dim,
                     "dL/dq", NAN);
}
static int lag_dv(void *ctx, const double *q, const double *v, double *out) {
  ProblemObject *self = ctx;
  return take_result(self, call_qp(self, self->fn[FN_C], q, v), out, self->own.dim,
                     "dL/dv", NAN);
}

/* first order: fn = {f(t, y), jacobian(t, y) or NULL} */
static int fo_rhs(void *ctx, double t, const double *y, double *out) {
  ProblemObject *self = ctx;
  size_t n = self->own.dim;
  fill(self->arg_y, y, n);
  PyObject *pt = PyFloat_FromDouble(t);
  PyObject *res = pt ? PyObject_CallFunctionObjArgs(self->fn[FN_A], pt, self->arg_y, NULL) : NULL;
  Py_XDECREF(pt);
  return take_result(self, res, out, n, "the right-hand side f(t, y)", t);
}
static int fo_jacobian(void *ctx, double t, const double *y, double *out) {
  ProblemObject *self = ctx;
  size_t n = self->own.dim;
  fill(self->arg_y, y, n);
  PyObject *pt = PyFloat_FromDouble(t);
  PyObject *res = pt ? PyObject_CallFunctionObjArgs(self->fn[FN_B], pt, self->arg_y, NULL) : NULL;
  Py_XDECREF(pt);
  return take_result(self, res, out, n * n, "the Jacobian of f", t);
}

/* Poisson system y' = S(y)∇H(y): fn = {H(y), ∇H(y), S(y) (n×n), ∇²H(y) or NULL} */
static PyObject *call_y(ProblemObject *self, PyObject *fn, const double *y) {
  fill(self->arg_y, y, self->base.n_state);
  return PyObject_CallOneArg(fn, (PyObject *)self->arg_y);
}
static double poisson_h(void *ctx, const double *y) {
  ProblemObject *self = ctx;
  return take_scalar(self, call_y(self, self->fn[FN_A], y), "the Hamiltonian H(y)");
}
static int poisson_grad(void *ctx, const double *y, double *out) {
  ProblemObject *self = ctx;
  return take_result(self, call_y(self, self->fn[FN_B], y), out, self->own.dim,
                     "the gradient of H", NAN);
}
static int poisson_structure(void *ctx, const double *y, double *out) {
  ProblemObject *self = ctx;
  size_t n = self->own.dim;
  return take_result(self, call_y(self, self->fn[FN_C], y), out, n * n,
                     "the structure matrix S(y)", NAN);
}
static int poisson_hess(void *ctx, const double *y, double *out) {
  ProblemObject *self = ctx;
  size_t n = self->own.dim;
  return take_result(self, call_y(self, self->fn[FN_D], y), out, n * n, "the Hessian of H",
                     NAN);
}

/* Rigid body: fn = {V(R) or V(R, x), gradient (g in the body frame; dim 6: g then ∂V/∂x)}.
 * R is passed as a read-only 3×3 array (row-major, body to space), x as a 3-vector. */
static PyObject *call_rigid(ProblemObject *self, PyObject *fn, const double *r,
                            const double *x) {
  fill(self->arg_R, r, 9);
  if (self->own.dim == 3) return PyObject_CallOneArg(fn, (PyObject *)self->arg_R);
  fill(self->arg_x, x, 3);
  return PyObject_CallFunctionObjArgs(fn, (PyObject *)self->arg_R, (PyObject *)self->arg_x,
                                      NULL);
}
static double rigid_v(void *ctx, const double *r, const double *x) {
  ProblemObject *self = ctx;
  return take_scalar(self, call_rigid(self, self->fn[FN_A], r, x), "the potential V(R)");
}
static int rigid_grad(void *ctx, const double *r, const double *x, double *g, double *fx) {
  ProblemObject *self = ctx;
  double out[6];
  size_t n = self->own.dim == 3 ? 3 : 6;
  if (take_result(self, call_rigid(self, self->fn[FN_B], r, x), out, n,
                  "the potential gradient (body frame)", NAN))
    return 1;
  memcpy(g, out, 3 * sizeof *g);
  if (n == 6) memcpy(fx, out + 3, 3 * sizeof *fx);
  return 0;
}

static PyArrayObject *argument_array(double *data, size_t n) {
  npy_intp dims[1] = {(npy_intp)n};
  return (PyArrayObject *)PyArray_New(&PyArray_Type, 1, dims, NPY_DOUBLE, NULL, data, 0,
                                      NPY_ARRAY_CARRAY_RO, NULL);
}

static PyObject *callable_or_null(PyObject *o, const char *what, int required) {
  if (o == NULL || o == Py_None) {
    if (required) PyErr_Format(PyExc_TypeError, "%s is required for this kind", what);
    return NULL;
  }
  if (!PyCallable_Check(o)) {
    PyErr_Format(PyExc_TypeError, "%s must be callable", what);
    return NULL;
  }
  Py_INCREF(o);
  return o;
}

/* Problem(kind, dim, t0, y0, a, b, c, d): the callables by kind (Python layer names them):
 *   "separable":   a = ∇V(q), b = V(q), c = ∇T(p), d = T(p)   (c, d None: T = ½|p|²)
 *   "hamiltonian": a = H(q, p), b = ∂H/∂q, c = ∂H/∂p
 *   "lagrangian":  a = L(q, v), b = ∂L/∂q, c = ∂L/∂v   (state (q, p), p = ∂L/∂v)
 *   "first-order": a = f(t, y), b = ∂f/∂y (optional) */
static int Problem_init(ProblemObject *self, PyObject *args, PyObject *kw) {
  static char *names[] = {"kind", "dim", "t0", "y0", "a", "b", "c", "d", "inertia", "mass",
                          NULL};
  const char *kind;
  Py_ssize_t dim;
  double t0, mass = 0.0;
  PyObject *y0, *a = NULL, *b = NULL, *c = NULL, *d = NULL, *inertia = NULL;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "sndO|OOOOOd", names, &kind, &dim, &t0, &y0, &a,
                                   &b, &c, &d, &inertia, &mass))
    return -1;
  if (dim <= 0) {
    PyErr_SetString(PyExc_ValueError, "dim must be positive");
    return -1;
  }
  gm_problem *pb = &self->own;
  memset(pb, 0, sizeof *pb);
  pb->dim = (size_t)dim;
  pb->ctx = self;
  size_t n = (size_t)dim;
  if (strcmp(kind, "separable") == 0) {
    pb->kind = GM_PROBLEM_SEPARABLE;
    if (!(self->fn[FN_A] = callable_or_null(a, "the potential gradient", 1))) return -1;
    self->fn[FN_B] = callable_or_null(b, "the potential", 0);
    if (PyErr_Occurred()) return -1;
    self->fn[FN_C] = callable_or_null(c, "the kinetic gradient", 0);
    if (PyErr_Occurred()) return -1;
    self->fn[FN_D] = callable_or_null(d, "the kinetic energy", 0);
    if (PyErr_Occurred()) return -1;
    pb->potential_gradient = sep_potential_gradient;
    pb->potential = self->fn[FN_B] ? sep_potential : NULL;
    if (self->fn[FN_C]) {
      pb->kinetic_gradient = sep_kinetic_gradient;
      pb->kinetic = self->fn[FN_D] ? sep_kinetic : NULL;
    } else {
      pb->kinetic_gradient = free_kinetic_gradient;
      pb->kinetic = free_kinetic;
      pb->kinetic_hessian = free_kinetic_hessian;
      pb->kinetic_is_quadratic = 1;
    }
  } else if (strcmp(kind, "hamiltonian") == 0) {
    pb->kind = GM_PROBLEM_HAMILTONIAN;
    if (!(self->fn[FN_A] = callable_or_null(a, "H(q, p)", 1))) return -1;
    if (!(self->fn[FN_B] = callable_or_null(b, "dH/dq", 1))) return -1;
    if (!(self->fn[FN_C] = callable_or_null(c, "dH/dp", 1))) return -1;
    pb->hamiltonian = ham_h;
    pb->dh_dq = ham_dq;
    pb->dh_dp = ham_dp;
  } else if (strcmp(kind, "lagrangian") == 0) {
    pb->kind = GM_PROBLEM_LAGRANGIAN;
    if (!(self->fn[FN_A] = callable_or_null(a, "L(q, v)", 1))) return -1;
    if (!(self->fn[FN_B] = callable_or_null(b, "dL/dq", 1))) return -1;
    if (!(self->fn[FN_C] = callable_or_null(c, "dL/dv", 1))) return -1;
    pb->lagrangian = lag_l;
    pb->dl_dq = lag_dq;
    pb->dl_dv = lag_dv;
  } else if (strcmp(kind, "first-order") == 0) {
    pb->kind = GM_PROBLEM_FIRST_ORDER;
    if (!(self->fn[FN_A] = callable_or_null(a, "f(t, y)", 1))) return -1;
    self->fn[FN_B] = callable_or_null(b, "the Jacobian", 0);
    if (PyErr_Occurred()) return -1;
    pb->rhs = fo_rhs;
    pb->rhs_jacobian = self->fn[FN_B] ? fo_jacobian : NULL;
  } else if (strcmp(kind, "poisson") == 0) {
    pb->kind = GM_PROBLEM_POISSON;
    if (!(self->fn[FN_A] = callable_or_null(a, "H(y)", 1))) return -1;
    if (!(self->fn[FN_B] = callable_or_null(b, "grad_H(y)", 1))) return -1;
    if (!(self->fn[FN_C] = callable_or_null(c, "S(y)", 1))) return -1;
    self->fn[FN_D] = callable_or_null(d, "the Hessian of H", 0);
    if (PyErr_Occurred()) return -1;
    pb->poisson_energy = poisson_h;
    pb->poisson_gradient = poisson_grad;
    pb->structure_matrix = poisson_structure;
    pb->poisson_hessian = self->fn[FN_D] ? poisson_hess : NULL;
  } else if (strcmp(kind, "rigid-body") == 0) {
    /* a = V, b = its gradient (both or neither: a free body); inertia: 9 values (J) */
    pb->kind = GM_PROBLEM_RIGID_BODY;
    if (dim != 3 && dim != 6) {
      PyErr_Format(PyExc_ValueError, "rigid body: dim must be 3 (attitude) or 6 (attitude and "
                   "position), got %zd", dim);
      return -1;
    }
    self->fn[FN_A] = callable_or_null(a, "V", 0);
    if (PyErr_Occurred()) return -1;
    self->fn[FN_B] = callable_or_null(b, "grad_V", 0);
    if (PyErr_Occurred()) return -1;
    if ((self->fn[FN_A] == NULL) != (self->fn[FN_B] == NULL)) {
      PyErr_SetString(PyExc_ValueError, "rigid body: give both V and grad_V, or neither");
      return -1;
    }
    PyArrayObject *j = as_doubles(inertia ? inertia : Py_None, 9, "inertia");
    if (j == NULL) return -1;
    memcpy(pb->inertia, PyArray_DATA(j), sizeof pb->inertia);
    Py_DECREF(j);
    pb->mass = mass;
    pb->space = gm_rigid_body_space((size_t)dim);
    if (self->fn[FN_A]) {
      pb->rigid_potential = rigid_v;
      pb->rigid_potential_gradient = rigid_grad;
    }
  } else {
    PyErr_Format(PyExc_ValueError,
                 "kind must be 'separable', 'hamiltonian', 'lagrangian', 'first-order', "
                 "'poisson' or 'rigid-body', got '%s'", kind);
    return -1;
  }
  gm_error err = {{0}};
  gm_status st = gm_problem_validate(pb, &err);
  if (st != GM_OK) {
    raise_status(st, "problem: %s", err.message);
    return -1;
  }
  self->base.problem = pb;
  self->base.python = 1;
  self->base.t0 = t0;
  self->base.n_state = gm_problem_state_size(pb);
  self->buffer = calloc(2 * n + self->base.n_state + 12, sizeof(double));
  self->base.y0 = malloc(self->base.n_state * sizeof(double));
  if (!self->buffer || !self->base.y0) {
    PyErr_NoMemory();
    return -1;
  }
  PyArrayObject *y = as_doubles(y0, self->base.n_state, "y0");
  if (y == NULL) return -1;
  memcpy(self->base.y0, PyArray_DATA(y), self->base.n_state * sizeof(double));
  Py_DECREF(y);
  self->arg_q = argument_array(self->buffer, n);
  self->arg_p = argument_array(self->buffer + n, n);
  self->arg_y = argument_array(self->buffer + 2 * n, self->base.n_state);
  npy_intp d33[2] = {3, 3};
  double *rx = self->buffer + 2 * n + self->base.n_state;
  self->arg_R = (PyArrayObject *)PyArray_New(&PyArray_Type, 2, d33, NPY_DOUBLE, NULL, rx, 0,
                                             NPY_ARRAY_CARRAY_RO, NULL);
  self->arg_x = argument_array(rx + 9, 3);
  return (self->arg_q && self->arg_p && self->arg_y && self->arg_R && self->arg_x) ? 0 : -1;
}

/* Shared getters of both problem types. */
static PyObject *Base_get_kind(ProblemBase *self, void *c) {
  (void)c;
  return PyUnicode_FromString(gm_problem_kind_name(self->problem->kind));
}
static PyObject *Base_get_dim(ProblemBase *self, void *c) {
  (void)c;
  return PyLong_FromSize_t(self->problem->dim);
}
static PyObject *Base_get_state_size(ProblemBase *self, void *c) {
  (void)c;
  return PyLong_FromSize_t(self->n_state);
}
static PyObject *Base_get_t0(ProblemBase *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(self->t0);
}
static PyObject *Base_get_y0(ProblemBase *self, void *c) {
  (void)c;
  return array_copy(self->y0, self->n_state);
}
static PyObject *Base_get_has_momenta(ProblemBase *self, void *c) {
  (void)c;
  return PyBool_FromLong(gm_problem_has_momenta(self->problem));
}

/* Re-raise a callback's exception (if any), noting which callback and when. */
static PyObject *reraise_pending(ProblemBase *pb, double t) {
  PyObject *exc = pb->pending;
  pb->pending = NULL;
  double when = isnan(pb->pending_t) ? t : pb->pending_t;
  char when_text[64];
  snprintf(when_text, sizeof when_text, "%.17g", when);
  PyObject *note = PyUnicode_FromFormat(isnan(pb->pending_t)
                                            ? "geomint: raised by %s in the step from t = %s"
                                            : "geomint: raised by %s at t = %s",
                                        pb->pending_in, when_text);
  if (note) {
    PyObject *r = PyObject_CallMethod(exc, "add_note", "O", note);
    Py_XDECREF(r);
    Py_DECREF(note);
    PyErr_Clear();
  }
  PyObject *pt = PyFloat_FromDouble(when);
  if (pt) {
    PyObject_SetAttrString(exc, "geomint_time", pt);
    Py_DECREF(pt);
    PyErr_Clear();
  }
  PyObject *tb = PyException_GetTraceback(exc);
  PyObject *type = (PyObject *)Py_TYPE(exc);
  Py_INCREF(type);
  PyErr_Restore(type, exc, tb);
  return NULL;
}

static PyObject *Base_energy(ProblemBase *self, PyObject *y) {
  if (!gm_problem_has_energy(self->problem)) Py_RETURN_NONE;
  PyArrayObject *a = as_doubles(y, self->n_state, "y");
  if (a == NULL) return NULL;
  double e = gm_problem_energy(self->problem, PyArray_DATA(a));
  Py_DECREF(a);
  if (self->pending) return reraise_pending(self, NAN);
  return PyFloat_FromDouble(e);
}

static PyObject *Base_invariants(ProblemBase *self, PyObject *y) {
  PyArrayObject *a = as_doubles(y, self->n_state, "y");
  if (a == NULL) return NULL;
  PyObject *d = PyDict_New();
  for (size_t k = 0; d && k < self->problem->n_invariants; ++k) {
    const gm_invariant *inv = &self->problem->invariants[k];
    PyObject *v = PyFloat_FromDouble(inv->value(self->problem->ctx, PyArray_DATA(a)));
    if (v == NULL || PyDict_SetItemString(d, inv->name, v) < 0) Py_CLEAR(d);
    Py_XDECREF(v);
  }
  Py_DECREF(a);
  return d;
}

static PyObject *Base_exact(ProblemBase *self, PyObject *t) {
  if (self->problem->exact == NULL) Py_RETURN_NONE;
  double tt = PyFloat_AsDouble(t);
  if (tt == -1.0 && PyErr_Occurred()) return NULL;
  npy_intp dims[1] = {(npy_intp)self->n_state};
  PyObject *out = PyArray_SimpleNew(1, dims, NPY_DOUBLE);
  if (out == NULL) return NULL;
  double *y = PyArray_DATA((PyArrayObject *)out);
  memcpy(y, self->y0, self->n_state * sizeof *y);
  if (self->problem->exact(self->problem->ctx, tt, y) != 0) {
    Py_DECREF(out);
    return raise_status(GM_ECALLBACK, "exact solution failed at t = %g", tt);
  }
  return out;
}

static PyGetSetDef Base_getset[] = {
    {"kind", (getter)Base_get_kind, NULL, "problem kind ('separable', ...)", NULL},
    {"dim", (getter)Base_get_dim, NULL, "degrees of freedom (first order: state length)", NULL},
    {"state_size", (getter)Base_get_state_size, NULL, "numbers per state", NULL},
    {"t0", (getter)Base_get_t0, NULL, "initial time", NULL},
    {"y0", (getter)Base_get_y0, NULL, "initial state (a copy)", NULL},
    {"has_momenta", (getter)Base_get_has_momenta, NULL, "state is (q, p)", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyMethodDef Base_methods[] = {
    {"energy", (PyCFunction)Base_energy, METH_O, "energy at the state y (None without one)"},
    {"invariants", (PyCFunction)Base_invariants, METH_O, "declared invariants at y, by name"},
    {"exact", (PyCFunction)Base_exact, METH_O, "exact state at time t (None without one)"},
    {NULL, NULL, 0, NULL}};

static PyTypeObject ModelType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "geomint._core.Model",
    .tp_basicsize = sizeof(ModelObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Model(name, set=None): a built-in problem with its parameters",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)Model_init,
    .tp_dealloc = (destructor)Model_dealloc,
    .tp_getset = Base_getset,
    .tp_methods = Base_methods,
};

static PyTypeObject ProblemType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "geomint._core.Problem",
    .tp_basicsize = sizeof(ProblemObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Problem(kind, dim, t0, y0, a, b, c, d): a problem of Python callables",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)Problem_init,
    .tp_dealloc = (destructor)Problem_dealloc,
    .tp_getset = Base_getset,
    .tp_methods = Base_methods,
};

static ProblemBase *as_problem(PyObject *o) {
  if (PyObject_TypeCheck(o, &ModelType) || PyObject_TypeCheck(o, &ProblemType)) {
    ProblemBase *pb = (ProblemBase *)o;
    if (pb->problem) return pb;
  }
  PyErr_SetString(PyExc_TypeError, "problem: expected a geomint Model or Problem");
  return NULL;
}

/* A scheme from names: method, basic (None: the row's), solver (None: default). */
static int make_scheme(const char *method, const char *basic, const char *solver, int comp,
                       gm_scheme *s, gm_method **own_m, gm_method **own_b) {
  memset(s, 0, sizeof *s);
  *own_b = NULL;
  if (!(s->method = find_method(method, own_m))) return -1;
  if (basic && !(s->basic = find_method(basic, own_b))) return -1;
  if (solver && gm_solver_find(solver, &s->solver) != GM_OK) {
    raise_status(GM_ENOTFOUND,
                 "unknown solver '%s' (default, newton, simplified-newton, fixed-point, "
                 "fixed-point-positions)", solver);
    return -1;
  }
  s->compensated = comp;
  return 0;
}

/* ---- the integrator ------------------------------------------------------------------------ */

typedef struct {
  PyObject_HEAD
  gm_integrator *it;
  PyObject *problem;   /* strong ref: the gm_problem is borrowed from it */
  ProblemBase *pb;
  gm_method *own_method, *own_basic;
  PyObject *observer;  /* Python observer(t, y) or NULL */
  PyArrayObject *obs_y; /* persistent argument of the observer */
  size_t every;
  PyObject *progress;   /* Python progress(fraction, t) or NULL */
  double t_start, t_target; /* of the run in progress (fraction of the way) */
  /* the recording of the run in progress */
  int recording;
  size_t n_rec, cap_rec;
  double *rec_t, *rec_y;
} IntegratorObject;

static void Integrator_dealloc(IntegratorObject *self) {
  gm_integrator_free(self->it);
  gm_method_free(self->own_method);
  gm_method_free(self->own_basic);
  Py_XDECREF(self->problem);
  Py_XDECREF(self->observer);
  Py_XDECREF(self->progress);
  Py_XDECREF(self->obs_y);
  free(self->rec_t);
  free(self->rec_y);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* The observer the integrator calls every `every` steps: record (t, y), then the Python one. */
static int record_observe(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  IntegratorObject *self = ctx;
  size_t n = self->pb->n_state;
  if (self->recording) {
    if (self->n_rec == self->cap_rec) {
      size_t cap = self->cap_rec ? 2 * self->cap_rec : 64;
      double *nt = realloc(self->rec_t, cap * sizeof *nt);
      if (nt) self->rec_t = nt;
      double *ny = nt ? realloc(self->rec_y, cap * n * sizeof *ny) : NULL;
      if (ny) self->rec_y = ny;
      if (!nt || !ny) {
        PyErr_NoMemory();
        keep_exception(self->pb, "the recording of the trajectory", t);
        return 1;
      }
      self->cap_rec = cap;
    }
    self->rec_t[self->n_rec] = t;
    memcpy(self->rec_y + self->n_rec * n, y, n * sizeof *y);
    self->n_rec++;
  }
  if (self->observer) {
    memcpy(PyArray_DATA(self->obs_y), y, n * sizeof *y);
    PyObject *pt = PyFloat_FromDouble(t);
    PyObject *r = pt ? PyObject_CallFunctionObjArgs(self->observer, pt, self->obs_y, NULL) : NULL;
    Py_XDECREF(pt);
    if (r == NULL) {
      keep_exception(self->pb, "the observer", t);
      return 1;
    }
    Py_DECREF(r);
  }
  if (PyErr_CheckSignals() < 0) {
    keep_exception(self->pb, "a signal", t);
    return 1;
  }
  return 0;
}

/* The progress observer: progress(fraction of the run's time span done, t). */
static int progress_observe(void *ctx, size_t step, double t, const double *y) {
  (void)step, (void)y;
  IntegratorObject *self = ctx;
  double span = self->t_target - self->t_start;
  double f = NAN; /* unknown for a resumed checkpoint */
  if (isfinite(span)) f = span != 0.0 ? fmin(1.0, fmax(0.0, (t - self->t_start) / span)) : 1.0;
  PyObject *r = PyObject_CallFunction(self->progress, "dd", f, t);
  if (r == NULL) {
    keep_exception(self->pb, "the progress callback", t);
    return 1;
  }
  Py_DECREF(r);
  if (PyErr_CheckSignals() < 0) {
    keep_exception(self->pb, "a signal", t);
    return 1;
  }
  return 0;
}

/* Integrator(method, problem, basic=None, solver=None, compensated=False, every=1,
 *            observer=None, record=True, progress=None, progress_every=1000) */
static int Integrator_init(IntegratorObject *self, PyObject *args, PyObject *kw) {
  static char *names[] = {"method", "problem", "basic", "solver", "compensated", "every",
                          "observer", "record", "progress", "progress_every", NULL};
  const char *method, *basic = NULL, *solver = NULL;
  PyObject *problem, *observer = NULL, *progress = NULL;
  int comp = 0, record = 1;
  Py_ssize_t every = 1, progress_every = 1000;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "sO|zzpnOpOn", names, &method, &problem, &basic,
                                   &solver, &comp, &every, &observer, &record, &progress,
                                   &progress_every))
    return -1;
  if (progress_every < 1) {
    PyErr_SetString(PyExc_ValueError, "progress_every must be >= 1");
    return -1;
  }
  ProblemBase *pb = as_problem(problem);
  if (pb == NULL) return -1;
  if (every < 1) {
    PyErr_SetString(PyExc_ValueError, "every must be >= 1");
    return -1;
  }
  gm_scheme scheme;
  if (make_scheme(method, basic, solver, comp, &scheme, &self->own_method, &self->own_basic))
    return -1;
  gm_error err = {{0}};
  gm_status st = gm_integrator_create_scheme(&scheme, pb->problem, &self->it, &err);
  if (pb->pending) {
    reraise_pending(pb, pb->t0);
    return -1;
  }
  if (st != GM_OK) {
    raise_status(st, "%s: %s", method, err.message);
    return -1;
  }
  Py_INCREF(problem);
  self->problem = problem;
  self->pb = pb;
  self->every = (size_t)every;
  self->recording = 0;
  if (observer && observer != Py_None) {
    if (!PyCallable_Check(observer)) {
      PyErr_SetString(PyExc_TypeError, "observer must be callable as observer(t, y)");
      return -1;
    }
    Py_INCREF(observer);
    self->observer = observer;
    npy_intp dims[1] = {(npy_intp)pb->n_state};
    self->obs_y = (PyArrayObject *)PyArray_SimpleNew(1, dims, NPY_DOUBLE);
    if (self->obs_y == NULL) return -1;
    PyArray_CLEARFLAGS(self->obs_y, NPY_ARRAY_WRITEABLE);
  }
  if (record || self->observer) {
    st = gm_integrator_add_observer(self->it, record_observe, self, self->every);
    if (st != GM_OK) {
      raise_status(st, "%s", gm_integrator_errmsg(self->it));
      return -1;
    }
  }
  self->recording = record;
  if (progress && progress != Py_None) {
    if (!PyCallable_Check(progress)) {
      PyErr_SetString(PyExc_TypeError, "progress must be callable as progress(fraction, t)");
      return -1;
    }
    Py_INCREF(progress);
    self->progress = progress;
    st = gm_integrator_add_observer(self->it, progress_observe, self, (size_t)progress_every);
    if (st != GM_OK) {
      raise_status(st, "%s", gm_integrator_errmsg(self->it));
      return -1;
    }
  }
  st = gm_integrator_set_state(self->it, pb->t0, pb->y0);
  if (st != GM_OK) {
    raise_status(st, "initial state: %s", gm_integrator_errmsg(self->it));
    return -1;
  }
  return 0;
}

static PyObject *Integrator_set_state(IntegratorObject *self, PyObject *args) {
  double t;
  PyObject *y;
  if (!PyArg_ParseTuple(args, "dO", &t, &y)) return NULL;
  PyArrayObject *a = as_doubles(y, self->pb->n_state, "y");
  if (a == NULL) return NULL;
  gm_status st = gm_integrator_set_state(self->it, t, PyArray_DATA(a));
  Py_DECREF(a);
  if (st != GM_OK) return raise_status(st, "state: %s", gm_integrator_errmsg(self->it));
  Py_RETURN_NONE;
}

/* Free function for capsules owning malloc'ed buffers handed to NumPy. */
static void capsule_free(PyObject *cap) { free(PyCapsule_GetPointer(cap, NULL)); }

PyObject *owned_array(double *data, int nd, npy_intp *dims) {
  PyObject *a = PyArray_SimpleNewFromData(nd, dims, NPY_DOUBLE, data);
  if (a == NULL) {
    free(data);
    return NULL;
  }
  PyObject *cap = PyCapsule_New(data, NULL, capsule_free);
  if (cap == NULL || PyArray_SetBaseObject((PyArrayObject *)a, cap) < 0) {
    Py_XDECREF(cap);
    Py_DECREF(a);
    return NULL;
  }
  return a;
}

/* Run and return (t, y) of the recorded states, the recording buffers handed to NumPy. */
static PyObject *finish_run(IntegratorObject *self, gm_status st) {
  ProblemBase *pb = self->pb;
  if (pb->pending) return reraise_pending(pb, gm_integrator_time(self->it));
  if (st != GM_OK)
    return raise_status(st, "%s", gm_integrator_errmsg(self->it));
  npy_intp dt[1] = {(npy_intp)self->n_rec}, dy[2] = {(npy_intp)self->n_rec,
                                                      (npy_intp)pb->n_state};
  double *rt = self->rec_t, *ry = self->rec_y;
  if (rt == NULL) rt = malloc(sizeof *rt);
  if (ry == NULL) ry = malloc(sizeof *ry);
  self->rec_t = NULL;
  self->rec_y = NULL;
  self->n_rec = self->cap_rec = 0;
  if (!rt || !ry) {
    free(rt);
    free(ry);
    return PyErr_NoMemory();
  }
  PyObject *at = owned_array(rt, 1, dt);
  if (at == NULL) {
    free(ry);
    return NULL;
  }
  PyObject *ay = owned_array(ry, 2, dy);
  if (ay == NULL) {
    Py_DECREF(at);
    return NULL;
  }
  return Py_BuildValue("(NN)", at, ay);
}

static PyObject *Integrator_run(IntegratorObject *self, PyObject *args) {
  Py_ssize_t steps;
  double dt;
  if (!PyArg_ParseTuple(args, "nd", &steps, &dt)) return NULL;
  if (steps < 0) {
    PyErr_SetString(PyExc_ValueError, "steps must be >= 0");
    return NULL;
  }
  self->n_rec = 0;
  self->t_start = gm_integrator_time(self->it);
  self->t_target = self->t_start + (double)steps * dt;
  gm_status st = gm_integrator_run(self->it, (size_t)steps, dt);
  return finish_run(self, st);
}

static PyObject *Integrator_integrate(IntegratorObject *self, PyObject *args) {
  double t_end, dt;
  if (!PyArg_ParseTuple(args, "dd", &t_end, &dt)) return NULL;
  self->n_rec = 0;
  self->t_start = gm_integrator_time(self->it);
  self->t_target = t_end;
  gm_status st = gm_integrator_integrate(self->it, t_end, dt);
  return finish_run(self, st);
}

static PyObject *Integrator_resume(IntegratorObject *self, PyObject *args) {
  (void)args;
  self->n_rec = 0;
  self->t_start = self->t_target = NAN; /* the checkpoint's target is not exposed */
  gm_status st = gm_integrator_resume(self->it);
  return finish_run(self, st);
}

static PyObject *Integrator_save(IntegratorObject *self, PyObject *args) {
  const char *path;
  if (!PyArg_ParseTuple(args, "s", &path)) return NULL;
  gm_status st = gm_integrator_save_file(self->it, path, NULL, 0);
  if (st != GM_OK) return raise_status(st, "%s", gm_integrator_errmsg(self->it));
  Py_RETURN_NONE;
}

static PyObject *Integrator_load(IntegratorObject *self, PyObject *args) {
  const char *path;
  if (!PyArg_ParseTuple(args, "s", &path)) return NULL;
  gm_status st = gm_integrator_load_file(self->it, path, NULL, 0, NULL);
  if (st != GM_OK) return raise_status(st, "%s", gm_integrator_errmsg(self->it));
  Py_RETURN_NONE;
}

static PyObject *Integrator_get_time(IntegratorObject *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(gm_integrator_time(self->it));
}

/* The state as a read-only view of the integrator's memory, valid until the next step. */
static PyObject *Integrator_get_state(IntegratorObject *self, void *c) {
  (void)c;
  npy_intp dims[1] = {(npy_intp)self->pb->n_state};
  return array_view(gm_integrator_state(self->it), 1, dims, (PyObject *)self);
}

static PyObject *Integrator_state_address(IntegratorObject *self, PyObject *a) {
  (void)a;
  return PyLong_FromVoidPtr((void *)gm_integrator_state(self->it));
}

static PyObject *Integrator_get_stats(IntegratorObject *self, void *c) {
  (void)c;
  gm_stats s = gm_integrator_stats(self->it);
  return Py_BuildValue("{s:n,s:n,s:n,s:n,s:n,s:n,s:n}", "steps", (Py_ssize_t)s.steps,
                       "force_evals", (Py_ssize_t)s.force_evals, "jacobian_evals",
                       (Py_ssize_t)s.jacobian_evals, "fd_jacobians", (Py_ssize_t)s.fd_jacobians,
                       "newton_iterations", (Py_ssize_t)s.newton_iterations,
                       "fixed_point_iterations", (Py_ssize_t)s.fixed_point_iterations,
                       "newton_failures", (Py_ssize_t)s.newton_failures);
}

static PyObject *Integrator_get_solver(IntegratorObject *self, void *c) {
  (void)c;
  return PyUnicode_FromString(gm_solver_name(gm_integrator_solver(self->it)));
}

static PyMethodDef Integrator_methods[] = {
    {"set_state", (PyCFunction)Integrator_set_state, METH_VARARGS, "set_state(t, y): copied"},
    {"run", (PyCFunction)Integrator_run, METH_VARARGS,
     "run(steps, dt) -> (t, y) of the observed states"},
    {"integrate", (PyCFunction)Integrator_integrate, METH_VARARGS,
     "integrate(t_end, dt) -> (t, y): equal steps of at most dt ending at t_end"},
    {"resume", (PyCFunction)Integrator_resume, METH_NOARGS,
     "continue the run of a loaded checkpoint -> (t, y)"},
    {"save", (PyCFunction)Integrator_save, METH_VARARGS, "save(path): a checkpoint"},
    {"load", (PyCFunction)Integrator_load, METH_VARARGS, "load(path): a checkpoint"},
    {"_state_address", (PyCFunction)Integrator_state_address, METH_NOARGS,
     "address of the library's state array (for no-copy checks)"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef Integrator_getset[] = {
    {"time", (getter)Integrator_get_time, NULL, "current time", NULL},
    {"state", (getter)Integrator_get_state, NULL,
     "current state: a read-only view of the library's array, valid until the next step", NULL},
    {"stats", (getter)Integrator_get_stats, NULL, "statistics as a dict", NULL},
    {"solver", (getter)Integrator_get_solver, NULL, "solver of implicit stages", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyTypeObject IntegratorType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "geomint._core.Integrator",
    .tp_basicsize = sizeof(IntegratorObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Integrator(method, problem, basic=None, solver=None, compensated=False, every=1, "
              "observer=None, record=True)",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)Integrator_init,
    .tp_dealloc = (destructor)Integrator_dealloc,
    .tp_methods = Integrator_methods,
    .tp_getset = Integrator_getset,
};

/* ---- empirical order ----------------------------------------------------------------------- */

static PyObject *core_order(PyObject *mod, PyObject *args, PyObject *kw) {
  (void)mod;
  static char *names[] = {"method", "problem", "t_end", "basic", "solver", NULL};
  const char *method, *basic = NULL, *solver = NULL;
  PyObject *problem;
  double t_end;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "sOd|zz", names, &method, &problem, &t_end, &basic,
                                   &solver))
    return NULL;
  ProblemBase *pb = as_problem(problem);
  if (pb == NULL) return NULL;
  gm_scheme scheme;
  gm_method *om = NULL, *ob = NULL;
  PyObject *out = NULL;
  if (make_scheme(method, basic, solver, 0, &scheme, &om, &ob) == 0) {
    gm_order_result r;
    gm_error err = {{0}};
    gm_status st = gm_order_measure_window(&scheme, pb->problem, pb->t0, pb->y0, t_end, NULL, &r,
                                           &err);
    if (pb->pending) {
      reraise_pending(pb, NAN);
    } else if (st != GM_OK) {
      raise_status(st, "order of %s: %s", method, err.message);
    } else {
      static const char *outcomes[] = {"measured", "pre-asymptotic", "round-off",
                                       "too-few-levels", "irregular", "not-settled"};
      out = Py_BuildValue("{s:d,s:i,s:N,s:N,s:n,s:s,s:O}", "order", r.order, "declared",
                          scheme.method->order, "dts", array_copy(r.dts, r.n_levels), "errors",
                          array_copy(r.errors, r.n_levels), "n_fitted", (Py_ssize_t)r.n_fitted,
                          "outcome", outcomes[r.outcome], "reference_is_exact",
                          r.reference_is_exact ? Py_True : Py_False);
    }
  }
  gm_method_free(om);
  gm_method_free(ob);
  return out;
}

/* ---- DEC: complexes, geometry, operators ---------------------------------------------------- */

static PyObject *csr_tuple(const gm_csr *a) {
  size_t nnz = gm_csr_nnz(a);
  npy_intp dr[1] = {(npy_intp)a->n_rows + 1}, dn[1] = {(npy_intp)nnz};
  PyObject *indptr = PyArray_SimpleNew(1, dr, NPY_INT64);
  PyObject *indices = PyArray_SimpleNew(1, dn, NPY_INT64);
  PyObject *data = array_copy(a->val, nnz);
  if (!indptr || !indices || !data) {
    Py_XDECREF(indptr);
    Py_XDECREF(indices);
    Py_XDECREF(data);
    return NULL;
  }
  int64_t *ip = PyArray_DATA((PyArrayObject *)indptr), *ix = PyArray_DATA((PyArrayObject *)indices);
  for (size_t i = 0; i <= a->n_rows; ++i) ip[i] = (int64_t)a->row_start[i];
  for (size_t i = 0; i < nnz; ++i) ix[i] = (int64_t)a->col[i];
  return Py_BuildValue("(NNN(nn))", data, indices, indptr, (Py_ssize_t)a->n_rows,
                       (Py_ssize_t)a->n_cols);
}

static void Complex_dealloc(ComplexObject *self) {
  gm_geometry_free(self->g);
  gm_complex_free(self->cx);
  gm_mesh_free(self->mesh);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* Complex(path=None, vertices=None, simplices=None) */
static int Complex_init(ComplexObject *self, PyObject *args, PyObject *kw) {
  static char *names[] = {"path", "vertices", "simplices", NULL};
  const char *path = NULL;
  PyObject *v = NULL, *s = NULL;
  if (!PyArg_ParseTupleAndKeywords(args, kw, "|zOO", names, &path, &v, &s)) return -1;
  gm_error err = {{0}};
  gm_status st;
  if (path) {
    st = gm_mesh_read(path, &self->mesh, &err);
    if (st != GM_OK) {
      raise_status(st, "%s", err.message);
      return -1;
    }
    st = gm_mesh_complex(self->mesh, &self->cx, &err);
  } else {
    PyArrayObject *va = (PyArrayObject *)PyArray_FROMANY(v, NPY_DOUBLE, 2, 2, NPY_ARRAY_CARRAY_RO);
    if (va == NULL) return -1;
    PyArrayObject *sa = (PyArrayObject *)PyArray_FROMANY(s, NPY_UINT64, 2, 2,
                                                         NPY_ARRAY_CARRAY_RO | NPY_ARRAY_FORCECAST);
    if (sa == NULL) {
      Py_DECREF(va);
      return -1;
    }
    size_t nv = (size_t)PyArray_DIM(va, 0), N = (size_t)PyArray_DIM(va, 1);
    size_t nt = (size_t)PyArray_DIM(sa, 0), k = (size_t)PyArray_DIM(sa, 1);
    st = gm_mesh_create(N, nv, k - 1, nt, &self->mesh);
    if (st == GM_OK) {
      memcpy(self->mesh->x, PyArray_DATA(va), nv * N * sizeof(double));
      memcpy(self->mesh->cells, PyArray_DATA(sa), nt * k * sizeof(size_t));
      st = gm_mesh_complex(self->mesh, &self->cx, &err);
    } else {
      snprintf(err.message, sizeof err.message, "cannot create a mesh of %zu vertices in R^%zu "
               "and %zu simplices of %zu vertices", nv, N, nt, k);
    }
    Py_DECREF(va);
    Py_DECREF(sa);
  }
  if (st != GM_OK) {
    raise_status(st, "complex: %s", err.message);
    return -1;
  }
  return 0;
}

gm_geometry *geometry(ComplexObject *self) {
  if (self->g) return self->g;
  gm_error err = {{0}};
  gm_status st = gm_geometry_create(self->cx, NULL, &self->g, &err);
  if (st != GM_OK) {
    raise_status(st, "geometry: %s", err.message);
    return NULL;
  }
  return self->g;
}

static int check_k(ComplexObject *self, Py_ssize_t k, Py_ssize_t max) {
  if (k < 0 || k > max) {
    PyErr_Format(PyExc_ValueError, "k must be in 0..%zd for this complex of dimension %zu, got %zd",
                 max, gm_complex_dim(self->cx), k);
    return -1;
  }
  return 0;
}

static PyObject *Complex_d(ComplexObject *self, PyObject *args) {
  Py_ssize_t k;
  if (!PyArg_ParseTuple(args, "n", &k)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx) - 1)) return NULL;
  return csr_tuple(gm_complex_d(self->cx, (size_t)k));
}

typedef gm_status (*operator_fn)(const gm_geometry *, size_t, gm_csr **, gm_error *);

static PyObject *operator_tuple(ComplexObject *self, PyObject *args, operator_fn fn,
                                const char *what, Py_ssize_t lo) {
  Py_ssize_t k;
  if (!PyArg_ParseTuple(args, "n", &k)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx))) return NULL;
  if (k < lo) {
    PyErr_Format(PyExc_ValueError, "%s needs k >= %zd, got %zd", what, lo, k);
    return NULL;
  }
  gm_geometry *g = geometry(self);
  if (g == NULL) return NULL;
  gm_csr *a = NULL;
  gm_error err = {{0}};
  gm_status st = fn(g, (size_t)k, &a, &err);
  if (st != GM_OK) return raise_status(st, "%s %zd: %s", what, k, err.message);
  PyObject *t = csr_tuple(a);
  gm_csr_free(a);
  return t;
}

static PyObject *Complex_codifferential(ComplexObject *self, PyObject *args) {
  return operator_tuple(self, args, gm_dec_codifferential, "codifferential", 1);
}
static PyObject *Complex_laplacian(ComplexObject *self, PyObject *args) {
  return operator_tuple(self, args, gm_dec_laplacian, "laplacian", 0);
}

/* The diagonal of ⋆_k as an array (a copy: the geometry may be shared). */
static PyObject *Complex_star(ComplexObject *self, PyObject *args) {
  Py_ssize_t k;
  if (!PyArg_ParseTuple(args, "n", &k)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx))) return NULL;
  gm_geometry *g = geometry(self);
  if (g == NULL) return NULL;
  return array_copy(gm_geometry_hodge_star(g, (size_t)k), gm_complex_count(self->cx, (size_t)k));
}

static PyObject *Complex_volumes(ComplexObject *self, PyObject *args) {
  Py_ssize_t k;
  int dual = 0;
  if (!PyArg_ParseTuple(args, "n|p", &k, &dual)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx))) return NULL;
  gm_geometry *g = geometry(self);
  if (g == NULL) return NULL;
  const double *v = dual ? gm_geometry_dual_volumes(g, (size_t)k)
                         : gm_geometry_primal_volumes(g, (size_t)k);
  return array_copy(v, gm_complex_count(self->cx, (size_t)k));
}

static PyObject *Complex_count(ComplexObject *self, PyObject *args) {
  Py_ssize_t k;
  if (!PyArg_ParseTuple(args, "n", &k)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx))) return NULL;
  return PyLong_FromSize_t(gm_complex_count(self->cx, (size_t)k));
}

static PyObject *Complex_simplices(ComplexObject *self, PyObject *args) {
  Py_ssize_t k;
  if (!PyArg_ParseTuple(args, "n", &k)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx))) return NULL;
  npy_intp dims[2] = {(npy_intp)gm_complex_count(self->cx, (size_t)k), (npy_intp)k + 1};
  PyObject *a = PyArray_SimpleNew(2, dims, NPY_INT64);
  if (a == NULL) return NULL;
  const size_t *s = gm_complex_simplices(self->cx, (size_t)k);
  int64_t *o = PyArray_DATA((PyArrayObject *)a);
  for (npy_intp i = 0; i < dims[0] * dims[1]; ++i) o[i] = (int64_t)s[i];
  return a;
}

static PyObject *Complex_boundary_mask(ComplexObject *self, PyObject *args) {
  Py_ssize_t k;
  if (!PyArg_ParseTuple(args, "n", &k)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx))) return NULL;
  npy_intp dims[1] = {(npy_intp)gm_complex_count(self->cx, (size_t)k)};
  PyObject *a = PyArray_SimpleNew(1, dims, NPY_BOOL);
  if (a == NULL) return NULL;
  const unsigned char *m = gm_complex_boundary_mask(self->cx, (size_t)k);
  npy_bool *o = PyArray_DATA((PyArrayObject *)a);
  for (npy_intp i = 0; i < dims[0]; ++i) o[i] = m[i] != 0;
  return a;
}

static PyObject *Complex_get_vertices(ComplexObject *self, void *c) {
  (void)c;
  npy_intp dims[2] = {(npy_intp)gm_complex_count(self->cx, 0),
                      (npy_intp)gm_complex_embedding_dim(self->cx)};
  return array_view(gm_complex_coordinates(self->cx), 2, dims, (PyObject *)self);
}
static PyObject *Complex_get_dim(ComplexObject *self, void *c) {
  (void)c;
  return PyLong_FromSize_t(gm_complex_dim(self->cx));
}

static PyObject *Complex_quality(ComplexObject *self, PyObject *a) {
  (void)a;
  gm_mesh_report r;
  gm_error err = {{0}};
  gm_status st = gm_mesh_quality(self->mesh, &r, &err);
  if (st != GM_OK) return raise_status(st, "mesh quality: %s", err.message);
  PyObject *count = PyList_New(0), *stmin = PyList_New(0), *stmax = PyList_New(0);
  for (size_t k = 0; count && stmin && stmax && k <= r.dim; ++k) {
    PyObject *c = PyLong_FromSize_t(r.count[k]), *lo = PyFloat_FromDouble(r.star_min[k]),
             *hi = PyFloat_FromDouble(r.star_max[k]);
    if (c) PyList_Append(count, c);
    if (lo) PyList_Append(stmin, lo);
    if (hi) PyList_Append(stmax, hi);
    Py_XDECREF(c);
    Py_XDECREF(lo);
    Py_XDECREF(hi);
  }
  return Py_BuildValue(
      "{s:n,s:n,s:N,s:l,s:n,s:n,s:n,s:n,s:N,s:N,s:d,s:d,s:d,s:d,s:O,s:O,s:s,s:s}", "dim",
      (Py_ssize_t)r.dim, "N", (Py_ssize_t)r.N, "count", count, "euler_characteristic",
      r.euler_characteristic, "degenerate", (Py_ssize_t)r.degenerate, "inverted",
      (Py_ssize_t)r.inverted, "not_well_centred", (Py_ssize_t)r.not_well_centred, "reoriented",
      (Py_ssize_t)r.reoriented, "star_min", stmin, "star_max", stmax, "min_volume", r.min_volume,
      "max_volume", r.max_volume, "shortest_edge", r.shortest_edge, "longest_edge",
      r.longest_edge, "complex_ok", r.complex_ok ? Py_True : Py_False, "geometry_ok",
      r.geometry_ok ? Py_True : Py_False, "complex_error", r.complex_error, "geometry_error",
      r.geometry_error);
}

/* The library's Poisson check (manufactured solution): report and u. */
static PyObject *Complex_poisson_check(ComplexObject *self, PyObject *a) {
  (void)a;
  gm_poisson_report r;
  gm_error err = {{0}};
  double *u = malloc(self->mesh->n_vertices * sizeof *u);
  if (u == NULL) return PyErr_NoMemory();
  gm_status st = gm_mesh_poisson(self->mesh, &r, u, &err);
  if (st != GM_OK) {
    free(u);
    return raise_status(st, "poisson: %s", err.message);
  }
  npy_intp dims[1] = {(npy_intp)self->mesh->n_vertices};
  PyObject *ua = owned_array(u, 1, dims);
  if (ua == NULL) return NULL;
  return Py_BuildValue("({s:n,s:n,s:d,s:d,s:d,s:d}N)", "n_vertices", (Py_ssize_t)r.n_vertices,
                       "n_unknowns", (Py_ssize_t)r.n_unknowns, "h", r.h, "error_max",
                       r.error_max, "error_l2", r.error_l2, "solution_max", r.solution_max, ua);
}

/* A new float64 array of shape (n, m) (m = 0: 1-D of n). */
static PyObject *new_doubles(size_t n, size_t m) {
  npy_intp dims[2] = {(npy_intp)n, (npy_intp)m};
  return PyArray_SimpleNew(m ? 2 : 1, dims, NPY_DOUBLE);
}

/* wedge(k, alpha, l, beta): the primal–primal (barycentric) wedge, count(k+l) values. */
static PyObject *Complex_wedge(ComplexObject *self, PyObject *args) {
  Py_ssize_t k, l;
  PyObject *a, *b;
  if (!PyArg_ParseTuple(args, "nOnO", &k, &a, &l, &b)) return NULL;
  if (check_k(self, k, (Py_ssize_t)gm_complex_dim(self->cx)) ||
      check_k(self, l, (Py_ssize_t)gm_complex_dim(self->cx) - k))
    return NULL;
  PyArrayObject *aa = as_doubles(a, gm_complex_count(self->cx, (size_t)k), "alpha");
  if (aa == NULL) return NULL;
  PyArrayObject *ba = as_doubles(b, gm_complex_count(self->cx, (size_t)l), "beta");
  PyObject *out = ba ? new_doubles(gm_complex_count(self->cx, (size_t)(k + l)), 0) : NULL;
  gm_status st = GM_OK;
  if (out)
    st = gm_dec_wedge(self->cx, (size_t)k, PyArray_DATA(aa), (size_t)l, PyArray_DATA(ba),
                      PyArray_DATA((PyArrayObject *)out));
  Py_DECREF(aa);
  Py_XDECREF(ba);
  if (out && st != GM_OK) {
    Py_DECREF(out);
    return raise_status(st, "wedge of a %zd-cochain and a %zd-cochain failed", k, l);
  }
  return out;
}

/* flat(X): a vector per top simplex (n_top × N) to a primal 1-cochain. */
static PyObject *Complex_flat(ComplexObject *self, PyObject *x) {
  gm_geometry *g = geometry(self);
  if (g == NULL) return NULL;
  size_t n = gm_complex_dim(self->cx), N = gm_complex_embedding_dim(self->cx);
  PyArrayObject *xa = as_doubles(x, gm_complex_count(self->cx, n) * N, "X (one vector per top simplex)");
  if (xa == NULL) return NULL;
  PyObject *out = new_doubles(gm_complex_count(self->cx, 1), 0);
  gm_status st = out ? gm_dec_flat(g, PyArray_DATA(xa), PyArray_DATA((PyArrayObject *)out))
                     : GM_OK;
  Py_DECREF(xa);
  if (out && st != GM_OK) {
    Py_DECREF(out);
    return raise_status(st, "flat failed");
  }
  return out;
}

/* sharp(alpha): a primal 1-cochain to a vector per vertex (n_vertices × N). */
static PyObject *Complex_sharp(ComplexObject *self, PyObject *a) {
  gm_geometry *g = geometry(self);
  if (g == NULL) return NULL;
  PyArrayObject *aa = as_doubles(a, gm_complex_count(self->cx, 1), "alpha (a 1-cochain)");
  if (aa == NULL) return NULL;
  PyObject *out = new_doubles(gm_complex_count(self->cx, 0), gm_complex_embedding_dim(self->cx));
  gm_status st = out ? gm_dec_sharp(g, PyArray_DATA(aa), PyArray_DATA((PyArrayObject *)out))
                     : GM_OK;
  Py_DECREF(aa);
  if (out && st != GM_OK) {
    Py_DECREF(out);
    return raise_status(st, "sharp failed");
  }
  return out;
}

static PyMethodDef Complex_methods[] = {
    {"wedge", (PyCFunction)Complex_wedge, METH_VARARGS, "wedge(k, alpha, l, beta)"},
    {"flat", (PyCFunction)Complex_flat, METH_O, "flat(X): vectors per top simplex -> 1-cochain"},
    {"sharp", (PyCFunction)Complex_sharp, METH_O, "sharp(alpha): 1-cochain -> vectors per vertex"},
    {"d", (PyCFunction)Complex_d, METH_VARARGS, "d(k) -> (data, indices, indptr, shape)"},
    {"codifferential", (PyCFunction)Complex_codifferential, METH_VARARGS, "δ_k as CSR parts"},
    {"laplacian", (PyCFunction)Complex_laplacian, METH_VARARGS, "Δ_k as CSR parts"},
    {"star", (PyCFunction)Complex_star, METH_VARARGS, "diagonal of ⋆_k"},
    {"volumes", (PyCFunction)Complex_volumes, METH_VARARGS, "volumes(k, dual=False)"},
    {"count", (PyCFunction)Complex_count, METH_VARARGS, "number of k-simplices"},
    {"simplices", (PyCFunction)Complex_simplices, METH_VARARGS, "k-simplices as vertex indices"},
    {"boundary_mask", (PyCFunction)Complex_boundary_mask, METH_VARARGS, "k-simplices on ∂K"},
    {"quality", (PyCFunction)Complex_quality, METH_NOARGS, "mesh quality report"},
    {"poisson_check", (PyCFunction)Complex_poisson_check, METH_NOARGS,
     "the library's manufactured Poisson solve -> (report, u)"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef Complex_getset[] = {
    {"vertices", (getter)Complex_get_vertices, NULL, "vertex coordinates (read-only view)", NULL},
    {"dim", (getter)Complex_get_dim, NULL, "dimension of the top simplices", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

PyTypeObject ComplexType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "geomint._core.Complex",
    .tp_basicsize = sizeof(ComplexObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Complex(path=None, vertices=None, simplices=None): a simplicial complex",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)Complex_init,
    .tp_dealloc = (destructor)Complex_dealloc,
    .tp_methods = Complex_methods,
    .tp_getset = Complex_getset,
};

/* ---- Yee scenes ------------------------------------------------------------------------------- */

typedef struct {
  PyObject_HEAD
  gm_yee_scene scene;
  gm_yee *solver;
  int have_scene;
} YeeObject;

static void Yee_dealloc(YeeObject *self) {
  gm_yee_free(self->solver);
  if (self->have_scene) gm_yee_scene_clear(&self->scene);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* Yee(json_text, name) */
static int Yee_init(YeeObject *self, PyObject *args) {
  const char *text, *name;
  if (!PyArg_ParseTuple(args, "ss", &text, &name)) return -1;
  gm_error err = {{0}};
  gm_status st = gm_yee_scene_parse(text, name, &self->scene, &err);
  if (st != GM_OK) {
    raise_status(st, "%s", err.message);
    return -1;
  }
  self->have_scene = 1;
  st = gm_yee_scene_build(&self->scene, name, &self->solver, &err);
  if (st != GM_OK) {
    raise_status(st, "%s", err.message);
    return -1;
  }
  return 0;
}

static PyObject *Yee_advance(YeeObject *self, PyObject *args) {
  Py_ssize_t n;
  if (!PyArg_ParseTuple(args, "n", &n)) return NULL;
  if (n < 0) {
    PyErr_SetString(PyExc_ValueError, "steps must be >= 0");
    return NULL;
  }
  gm_status st;
  Py_BEGIN_ALLOW_THREADS st = gm_yee_advance(self->solver, (size_t)n);
  Py_END_ALLOW_THREADS
  if (st != GM_OK) return raise_status(st, "advance: %s", gm_yee_errmsg(self->solver));
  Py_RETURN_NONE;
}

static PyObject *Yee_advance_to(YeeObject *self, PyObject *args) {
  double t;
  if (!PyArg_ParseTuple(args, "d", &t)) return NULL;
  gm_status st;
  Py_BEGIN_ALLOW_THREADS st = gm_yee_advance_to(self->solver, t);
  Py_END_ALLOW_THREADS
  if (st != GM_OK) return raise_status(st, "advance_to: %s", gm_yee_errmsg(self->solver));
  Py_RETURN_NONE;
}

static PyObject *Yee_run_steps(YeeObject *self, PyObject *a) {
  (void)a;
  return PyLong_FromSize_t(gm_yee_scene_total_steps(&self->scene, gm_yee_dt(self->solver)));
}

/* The whole array of a component (ghost layers included) as a read-only view (z, y, x), and
 * the index slices of the component's own locations. */
static PyObject *Yee_field(YeeObject *self, PyObject *args) {
  const char *name;
  int part = 0;
  if (!PyArg_ParseTuple(args, "s|i", &name, &part)) return NULL;
  gm_yee_component c;
  if (gm_yee_component_find(name, &c) != GM_OK)
    return raise_status(GM_ENOTFOUND, "unknown field component '%s' (Ex, Ey, Ez, Hx, Hy, Hz)",
                        name);
  const double *f = gm_yee_field(self->solver, c, part);
  if (f == NULL)
    return raise_status(GM_EINVAL, "this grid has no component %s%s", name,
                        part ? " (imaginary part)" : "");
  gm_yee_layout l;
  gm_yee_get_layout(self->solver, &l);
  size_t count[3];
  gm_yee_component_count(&l, c, count);
  npy_intp dims[3] = {(npy_intp)l.extent[2], (npy_intp)l.extent[1], (npy_intp)l.extent[0]};
  PyObject *a = array_view(f, 3, dims, (PyObject *)self);
  if (a == NULL) return NULL;
  return Py_BuildValue("(N(nnn)(nnn))", a, (Py_ssize_t)l.offset[2], (Py_ssize_t)l.offset[1],
                       (Py_ssize_t)l.offset[0], (Py_ssize_t)count[2], (Py_ssize_t)count[1],
                       (Py_ssize_t)count[0]);
}

static PyObject *Yee_field_address(YeeObject *self, PyObject *args) {
  const char *name;
  if (!PyArg_ParseTuple(args, "s", &name)) return NULL;
  gm_yee_component c;
  if (gm_yee_component_find(name, &c) != GM_OK) Py_RETURN_NONE;
  return PyLong_FromVoidPtr((void *)gm_yee_field(self->solver, c, 0));
}

static PyObject *Yee_probes(YeeObject *self, PyObject *a) {
  (void)a;
  PyObject *d = PyDict_New();
  for (size_t i = 0; d && i < self->scene.n_probes && i < gm_yee_probe_count(self->solver); ++i) {
    size_t n;
    const double *t, *re, *im;
    if (gm_yee_probe_samples(self->solver, i, &n, &t, &re, &im) != GM_OK) continue;
    PyObject *v = Py_BuildValue("(NN)", array_copy(t, n), array_copy(re, n));
    if (v == NULL || PyDict_SetItemString(d, self->scene.probes[i].name, v) < 0) Py_CLEAR(d);
    Py_XDECREF(v);
  }
  return d;
}

static PyObject *Yee_energy(YeeObject *self, PyObject *a) {
  (void)a;
  gm_yee_energy e;
  gm_status st = gm_yee_get_energy(self->solver, &e);
  if (st != GM_OK) return raise_status(st, "energy: %s", gm_yee_errmsg(self->solver));
  return Py_BuildValue("{s:d,s:d,s:d,s:d}", "electric", e.electric, "magnetic", e.magnetic,
                       "plain", e.plain, "leapfrog", e.leapfrog);
}

static PyObject *Yee_fluxes(YeeObject *self, PyObject *a) {
  (void)a;
  PyObject *d = PyDict_New();
  for (size_t i = 0; d && i < self->scene.n_fluxes; ++i) {
    const gm_yee_scene_flux *f = &self->scene.fluxes[i];
    double v;
    gm_status st = gm_yee_poynting_flux(self->solver, f->axis, f->index, &v);
    if (st != GM_OK) {
      Py_DECREF(d);
      return raise_status(st, "flux %s: %s", f->name, gm_yee_errmsg(self->solver));
    }
    PyObject *pv = PyFloat_FromDouble(v);
    if (pv == NULL || PyDict_SetItemString(d, f->name, pv) < 0) Py_CLEAR(d);
    Py_XDECREF(pv);
  }
  return d;
}

static PyObject *Yee_get_time(YeeObject *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(gm_yee_time_h(self->solver));
}
static PyObject *Yee_get_dt(YeeObject *self, void *c) {
  (void)c;
  return PyFloat_FromDouble(gm_yee_dt(self->solver));
}
static PyObject *Yee_get_step(YeeObject *self, void *c) {
  (void)c;
  return PyLong_FromSize_t(gm_yee_step(self->solver));
}
static PyObject *Yee_get_grid(YeeObject *self, void *c) {
  (void)c;
  gm_yee_layout l;
  gm_yee_get_layout(self->solver, &l);
  return Py_BuildValue("{s:(nnn),s:(ddd),s:(ddd)}", "n", (Py_ssize_t)l.n[0], (Py_ssize_t)l.n[1],
                       (Py_ssize_t)l.n[2], "h", l.h[0], l.h[1], l.h[2], "origin", l.origin[0],
                       l.origin[1], l.origin[2]);
}

static PyMethodDef Yee_methods[] = {
    {"advance", (PyCFunction)Yee_advance, METH_VARARGS, "advance(n) steps"},
    {"advance_to", (PyCFunction)Yee_advance_to, METH_VARARGS, "advance_to(t)"},
    {"run_steps", (PyCFunction)Yee_run_steps, METH_NOARGS, "steps the scene's run makes"},
    {"field", (PyCFunction)Yee_field, METH_VARARGS, "field(name, part=0) -> (view, offset, count)"},
    {"_field_address", (PyCFunction)Yee_field_address, METH_VARARGS, "address of a field array"},
    {"probes", (PyCFunction)Yee_probes, METH_NOARGS, "{name: (t, values)}"},
    {"energy", (PyCFunction)Yee_energy, METH_NOARGS, "energies"},
    {"fluxes", (PyCFunction)Yee_fluxes, METH_NOARGS, "{name: Poynting flux}"},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef Yee_getset[] = {
    {"time", (getter)Yee_get_time, NULL, "time of H (n dt)", NULL},
    {"dt", (getter)Yee_get_dt, NULL, "time step", NULL},
    {"step", (getter)Yee_get_step, NULL, "steps taken", NULL},
    {"grid", (getter)Yee_get_grid, NULL, "cells, sizes, origin", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyTypeObject YeeType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "geomint._core.Yee",
    .tp_basicsize = sizeof(YeeObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "Yee(json_text, name): the Yee solver of a scene",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)Yee_init,
    .tp_dealloc = (destructor)Yee_dealloc,
    .tp_methods = Yee_methods,
    .tp_getset = Yee_getset,
};

/* ---- module ------------------------------------------------------------------------------------ */

/* The bare cost of the library calling a Python function n times with a persistent argument
 * array, as the force trampoline does (for bench/python_overhead.py). */
static PyObject *core_call_loop(PyObject *mod, PyObject *args) {
  (void)mod;
  PyObject *fn, *arg;
  Py_ssize_t n;
  if (!PyArg_ParseTuple(args, "OOn", &fn, &arg, &n)) return NULL;
  for (Py_ssize_t i = 0; i < n; ++i) {
    PyObject *r = PyObject_CallOneArg(fn, arg);
    if (r == NULL) return NULL;
    Py_DECREF(r);
  }
  Py_RETURN_NONE;
}

static PyMethodDef core_functions[] = {
    {"methods", core_methods, METH_NOARGS, "the method table as a list of dicts"},
    {"problems", core_problems, METH_NOARGS, "the built-in problems as a list of dicts"},
    {"method", core_method, METH_O, "the row of one method by name"},
    {"order", (PyCFunction)(void (*)(void))core_order, METH_VARARGS | METH_KEYWORDS,
     "order(method, problem, t_end, basic=None, solver=None) -> dict"},
    {"_call_loop", core_call_loop, METH_VARARGS, "call fn(arg) n times from C"},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef core_module = {PyModuleDef_HEAD_INIT, "geomint._core",
                                         "CPython binding of libgeomint", -1, core_functions,
                                         NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__core(void) {
  import_array();
  PyTypeObject *types[] = {&ModelType, &ProblemType, &IntegratorType, &ComplexType, &YeeType};
  for (size_t i = 0; i < sizeof types / sizeof *types; ++i)
    if (PyType_Ready(types[i]) < 0) return NULL;
  PyObject *m = PyModule_Create(&core_module);
  if (m == NULL) return NULL;
  Error = PyErr_NewExceptionWithDoc(
      "geomint.Error",
      "A geomint library call failed; str(e) is the library's message, e.code the gm_status, "
      "e.reason its sentence.",
      NULL, NULL);
  if (Error == NULL || PyModule_AddObjectRef(m, "Error", Error) < 0) return NULL;
  if (fields_add_to_module(m) < 0) return NULL;
  const char *names[] = {"Model", "Problem", "Integrator", "Complex", "Yee"};
  for (size_t i = 0; i < sizeof types / sizeof *types; ++i)
    if (PyModule_AddObjectRef(m, names[i], (PyObject *)types[i]) < 0) return NULL;
  return m;
}
