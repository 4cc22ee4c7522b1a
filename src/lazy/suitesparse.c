/* CHOLMOD and UMFPACK, opened on first use (lazy.h): the sparse factorizations of
 * src/core/sparse_solve.c (DEC and mesh solvers). */
#include <cholmod.h>
#include <umfpack.h>

#include "lazy/lazy.h"

static gm_lazy_lib cholmod = GM_LAZY_LIB(GM_CHOLMOD_SONAME);
static gm_lazy_lib umfpack = GM_LAZY_LIB(GM_UMFPACK_SONAME);

static struct {
  int (*start)(cholmod_common *);
  int (*finish)(cholmod_common *);
  cholmod_factor *(*analyze)(cholmod_sparse *, cholmod_common *);
  int (*factorize)(cholmod_sparse *, cholmod_factor *, cholmod_common *);
  int (*free_dense)(cholmod_dense **, cholmod_common *);
  int (*free_factor)(cholmod_factor **, cholmod_common *);
  int (*solve2)(int, cholmod_factor *, cholmod_dense *, cholmod_sparse *, cholmod_dense **,
                cholmod_sparse **, cholmod_dense **, cholmod_dense **, cholmod_common *);
} ch;

static struct {
  void (*defaults)(double *);
  void (*free_numeric)(void **);
  void (*free_symbolic)(void **);
  SuiteSparse_long (*numeric)(const SuiteSparse_long *, const SuiteSparse_long *,
                              const double *, void *, void **, const double *, double *);
  SuiteSparse_long (*symbolic)(SuiteSparse_long, SuiteSparse_long, const SuiteSparse_long *,
                               const SuiteSparse_long *, const double *, void **,
                               const double *, double *);
  SuiteSparse_long (*wsolve)(SuiteSparse_long, const SuiteSparse_long *,
                             const SuiteSparse_long *, const double *, double *, const double *,
                             void *, const double *, double *, SuiteSparse_long *, double *);
} um;

/* the pointers have the headers' types (a mismatch is a compile error with -Werror) */
static void check_types(void) {
  (void)sizeof(ch.start == &cholmod_l_start);
  (void)sizeof(ch.finish == &cholmod_l_finish);
  (void)sizeof(ch.analyze == &cholmod_l_analyze);
  (void)sizeof(ch.factorize == &cholmod_l_factorize);
  (void)sizeof(ch.free_dense == &cholmod_l_free_dense);
  (void)sizeof(ch.free_factor == &cholmod_l_free_factor);
  (void)sizeof(ch.solve2 == &cholmod_l_solve2);
  (void)sizeof(um.defaults == &umfpack_dl_defaults);
  (void)sizeof(um.free_numeric == &umfpack_dl_free_numeric);
  (void)sizeof(um.free_symbolic == &umfpack_dl_free_symbolic);
  (void)sizeof(um.numeric == &umfpack_dl_numeric);
  (void)sizeof(um.symbolic == &umfpack_dl_symbolic);
  (void)sizeof(um.wsolve == &umfpack_dl_wsolve);
}

#define FIND(lib, field, name) gm_lazy_find(&lib, name, &field, sizeof field)

static void load_cholmod(void) {
  (void)check_types;
  cholmod.ok = gm_lazy_open(&cholmod) && FIND(cholmod, ch.start, "cholmod_l_start") &&
               FIND(cholmod, ch.finish, "cholmod_l_finish") &&
               FIND(cholmod, ch.analyze, "cholmod_l_analyze") &&
               FIND(cholmod, ch.factorize, "cholmod_l_factorize") &&
               FIND(cholmod, ch.free_dense, "cholmod_l_free_dense") &&
               FIND(cholmod, ch.free_factor, "cholmod_l_free_factor") &&
               FIND(cholmod, ch.solve2, "cholmod_l_solve2");
}

static void load_umfpack(void) {
  umfpack.ok = gm_lazy_open(&umfpack) && FIND(umfpack, um.defaults, "umfpack_dl_defaults") &&
               FIND(umfpack, um.free_numeric, "umfpack_dl_free_numeric") &&
               FIND(umfpack, um.free_symbolic, "umfpack_dl_free_symbolic") &&
               FIND(umfpack, um.numeric, "umfpack_dl_numeric") &&
               FIND(umfpack, um.symbolic, "umfpack_dl_symbolic") &&
               FIND(umfpack, um.wsolve, "umfpack_dl_wsolve");
}

static int cholmod_ready(void) {
  pthread_once(&cholmod.once, load_cholmod);
  return cholmod.ok;
}

static int umfpack_ready(void) {
  pthread_once(&umfpack.once, load_umfpack);
  return umfpack.ok;
}

/* Without the library: FALSE (or NULL) with Common->status = CHOLMOD_INVALID. */
int cholmod_l_start(cholmod_common *c) {
  if (cholmod_ready()) return ch.start(c);
  c->status = CHOLMOD_INVALID;
  return 0;
}

int cholmod_l_finish(cholmod_common *c) { return cholmod_ready() ? ch.finish(c) : 0; }

cholmod_factor *cholmod_l_analyze(cholmod_sparse *a, cholmod_common *c) {
  if (cholmod_ready()) return ch.analyze(a, c);
  c->status = CHOLMOD_INVALID;
  return NULL;
}

int cholmod_l_factorize(cholmod_sparse *a, cholmod_factor *l, cholmod_common *c) {
  if (cholmod_ready()) return ch.factorize(a, l, c);
  c->status = CHOLMOD_INVALID;
  return 0;
}

int cholmod_l_free_dense(cholmod_dense **x, cholmod_common *c) {
  return cholmod_ready() ? ch.free_dense(x, c) : 0;
}

int cholmod_l_free_factor(cholmod_factor **l, cholmod_common *c) {
  return cholmod_ready() ? ch.free_factor(l, c) : 0;
}

int cholmod_l_solve2(int sys, cholmod_factor *l, cholmod_dense *b, cholmod_sparse *bset,
                     cholmod_dense **x, cholmod_sparse **xset, cholmod_dense **y,
                     cholmod_dense **e, cholmod_common *c) {
  if (cholmod_ready()) return ch.solve2(sys, l, b, bset, x, xset, y, e, c);
  c->status = CHOLMOD_INVALID;
  return 0;
}

/* Without the library: UMFPACK_ERROR_internal_error. */
void umfpack_dl_defaults(double control[UMFPACK_CONTROL]) {
  if (umfpack_ready()) um.defaults(control);
}

void umfpack_dl_free_numeric(void **numeric) {
  if (umfpack_ready()) um.free_numeric(numeric);
}

void umfpack_dl_free_symbolic(void **symbolic) {
  if (umfpack_ready()) um.free_symbolic(symbolic);
}

SuiteSparse_long umfpack_dl_numeric(const SuiteSparse_long ap[], const SuiteSparse_long ai[],
                                    const double ax[], void *symbolic, void **numeric,
                                    const double control[UMFPACK_CONTROL],
                                    double info[UMFPACK_INFO]) {
  return umfpack_ready() ? um.numeric(ap, ai, ax, symbolic, numeric, control, info)
                         : UMFPACK_ERROR_internal_error;
}

SuiteSparse_long umfpack_dl_symbolic(SuiteSparse_long n_row, SuiteSparse_long n_col,
                                     const SuiteSparse_long ap[], const SuiteSparse_long ai[],
                                     const double ax[], void **symbolic,
                                     const double control[UMFPACK_CONTROL],
                                     double info[UMFPACK_INFO]) {
  return umfpack_ready() ? um.symbolic(n_row, n_col, ap, ai, ax, symbolic, control, info)
                         : UMFPACK_ERROR_internal_error;
}

SuiteSparse_long umfpack_dl_wsolve(SuiteSparse_long sys, const SuiteSparse_long ap[],
                                   const SuiteSparse_long ai[], const double ax[], double x[],
                                   const double b[], void *numeric,
                                   const double control[UMFPACK_CONTROL],
                                   double info[UMFPACK_INFO], SuiteSparse_long wi[],
                                   double w[]) {
  return umfpack_ready() ? um.wsolve(sys, ap, ai, ax, x, b, numeric, control, info, wi, w)
                         : UMFPACK_ERROR_internal_error;
}
