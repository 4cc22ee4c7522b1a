/* Helpers the ODE experiments share: a model built at its defaults, an integrator of a named
 * row at the model's initial state. */
#include <stdio.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/methods.h"
#include "geomint/oscillatory.h"

gm_status gm_experiment_model(const char *name, gm_model **out, gm_error *err) {
  *out = NULL;
  gm_model *model = NULL;
  gm_status st = gm_model_create(name, &model);
  if (st == GM_OK) st = gm_model_build(model);
  if (st != GM_OK) {
    gm_error_set(err, st, "the model %s: %s", name,
                 model ? gm_model_errmsg(model) : gm_strerror(st));
    gm_model_free(model);
    return st;
  }
  *out = model;
  return GM_OK;
}

gm_status gm_experiment_start(const gm_model *model, const char *method, size_t substeps,
                              gm_integrator **out, gm_error *err) {
  *out = NULL;
  const gm_method *m = gm_method_find(method);
  if (m == NULL) return gm_error_set(err, GM_EINVAL, "no method named %s", method);
  gm_integrator *it = NULL;
  gm_status st = gm_integrator_create(m, gm_model_problem(model), &it, err);
  if (st != GM_OK) return st;
  double t0, y0[64];
  gm_model_initial_state(model, &t0, y0);
  st = gm_integrator_set_state(it, t0, y0);
  if (st == GM_OK && substeps > 0) st = gm_oscillatory_set_substeps(it, substeps);
  if (st != GM_OK) {
    gm_error_set(err, st, "%s: %s", method, gm_integrator_errmsg(it));
    gm_integrator_free(it);
    return st;
  }
  *out = it;
  return GM_OK;
}
