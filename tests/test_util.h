/* Helpers shared by the tests: build a library problem and run a method on it. */
#ifndef GM_TEST_UTIL_H
#define GM_TEST_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "geomint/geomint.h"

typedef struct {
  gm_model *model;
  const gm_problem *problem;
  double t0;
  double y0[64];
  size_t n;
} test_model;

/* A library problem with one parameter changed (param NULL: all defaults). */
static inline test_model test_model_with(const char *name, const char *param, double value) {
  test_model tm;
  memset(&tm, 0, sizeof tm);
  cr_assert_eq(gm_model_create(name, &tm.model), GM_OK, "model %s", name);
  if (param != NULL) cr_assert_eq(gm_model_set(tm.model, param, value), GM_OK);
  cr_assert_eq(gm_model_build(tm.model), GM_OK, "%s", gm_model_errmsg(tm.model));
  tm.problem = gm_model_problem(tm.model);
  tm.n = gm_model_state_size(tm.model);
  cr_assert_leq(tm.n, 64);
  gm_model_initial_state(tm.model, &tm.t0, tm.y0);
  return tm;
}

static inline test_model test_model_make(const char *name) {
  return test_model_with(name, NULL, 0.0);
}

static inline gm_integrator *test_integrator(const gm_method *m, const gm_problem *pb,
                                             double t0, const double *y0) {
  gm_integrator *it = NULL;
  gm_error err = {{0}};
  cr_assert_eq(gm_integrator_create(m, pb, &it, &err), GM_OK, "%s: %s", m->name, err.message);
  cr_assert_eq(gm_integrator_set_state(it, t0, y0), GM_OK);
  return it;
}

static inline double gm_norm_inf_test(size_t n, const double *x) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) m = fmax(m, fabs(x[i]));
  return m;
}

/* Can the method integrate the problem's kind? */
static inline int test_accepts(const gm_method *m, const gm_problem *pb) {
  gm_integrator *it = NULL;
  if (gm_integrator_create(m, pb, &it, NULL) != GM_OK) return 0;
  gm_integrator_free(it);
  return 1;
}

#endif
