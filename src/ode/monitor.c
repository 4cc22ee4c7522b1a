/* Energy and invariant monitor, used as an observer: records the largest drift from the
 * initial values. */
#include <math.h>
#include <stdlib.h>

#include "ode/internal.h"

struct gm_monitor {
  const gm_problem *problem;
  double energy0, max_rel_energy, last_rel_energy;
  double *invariant0, *max_drift;
  double *value;      /* the invariants at the step being observed (evaluated once) */
  int has_energy;
  size_t n_observed;
  char errmsg[GM_ERRMSG_SIZE];
};

gm_status gm_monitor_create(const gm_problem *problem, const double *y0, gm_monitor **out) {
  if (out == NULL) return GM_EINVAL;
  *out = NULL;
  if (problem == NULL || y0 == NULL) return GM_EINVAL;
  gm_monitor *mon = calloc(1, sizeof *mon);
  if (mon == NULL) return GM_ENOMEM;
  const size_t k = problem->n_invariants;
  mon->invariant0 = calloc(k ? k : 1, sizeof(double));
  mon->max_drift = calloc(k ? k : 1, sizeof(double));
  mon->value = calloc(k ? k : 1, sizeof(double));
  if (!mon->invariant0 || !mon->max_drift || !mon->value) {
    gm_monitor_free(mon);
    return GM_ENOMEM;
  }
  mon->problem = problem;
  mon->has_energy = gm_problem_has_energy(problem);
  mon->energy0 = gm_problem_energy(problem, y0);
  mon->max_rel_energy = gm_problem_has_energy(problem) ? 0.0 : NAN;
  mon->last_rel_energy = mon->max_rel_energy;
  for (size_t i = 0; i < k; ++i)
    mon->invariant0[i] = problem->invariants[i].value(problem->ctx, y0);
  *out = mon;
  return GM_OK;
}

void gm_monitor_free(gm_monitor *mon) {
  if (mon == NULL) return;
  free(mon->invariant0);
  free(mon->max_drift);
  free(mon->value);
  free(mon);
}

int gm_monitor_observe(void *ctx, size_t step, double t, const double *y) {
  gm_monitor *mon = ctx;
  const gm_problem *pb = mon->problem;
  /* A non-finite energy or invariant stops the run here, before later observers (a CSV
   * writer added after the monitor) record the state; the drifts keep their last finite
   * values. Each invariant is evaluated once (issue 25: the check and the drift had each
   * evaluated it). */
  double rel = NAN;
  if (mon->has_energy) {
    double h = gm_problem_energy(pb, y);
    if (!isfinite(h)) {
      gm_fail(mon->errmsg, sizeof mon->errmsg, GM_EDOMAIN,
              "the energy became %g at step %zu (t = %.17g)", h, step, t);
      return 1;
    }
    double dh = fabs(h - mon->energy0);
    rel = mon->energy0 != 0.0 ? dh / fabs(mon->energy0) : dh;
  }
  for (size_t i = 0; i < pb->n_invariants; ++i) {
    double v = pb->invariants[i].value(pb->ctx, y);
    if (!isfinite(v)) {
      gm_fail(mon->errmsg, sizeof mon->errmsg, GM_EDOMAIN,
              "the invariant '%s' became %g at step %zu (t = %.17g)", pb->invariants[i].name,
              v, step, t);
      return 1;
    }
    mon->value[i] = v;
  }
  if (mon->has_energy) {
    mon->last_rel_energy = rel;
    if (!(rel <= mon->max_rel_energy)) mon->max_rel_energy = rel;
  }
  for (size_t i = 0; i < pb->n_invariants; ++i) {
    double drift = fabs(mon->value[i] - mon->invariant0[i]);
    if (!(drift <= mon->max_drift[i])) mon->max_drift[i] = drift;
  }
  mon->n_observed++;
  return 0;
}

const char *gm_monitor_errmsg(const gm_monitor *mon) { return mon ? mon->errmsg : ""; }

double gm_monitor_initial_energy(const gm_monitor *mon) { return mon ? mon->energy0 : NAN; }
double gm_monitor_max_rel_energy_error(const gm_monitor *mon) {
  return mon ? mon->max_rel_energy : NAN;
}
double gm_monitor_last_rel_energy_error(const gm_monitor *mon) {
  return mon ? mon->last_rel_energy : NAN;
}
double gm_monitor_max_invariant_drift(const gm_monitor *mon, size_t k) {
  if (mon == NULL || k >= mon->problem->n_invariants) return NAN;
  return mon->max_drift[k];
}
size_t gm_monitor_n_observed(const gm_monitor *mon) { return mon ? mon->n_observed : 0; }

/* Checkpoints: what the monitor has recorded (its initial values come from y0 again). */
size_t gm_monitor_state_size(const gm_monitor *mon) {
  return mon != NULL ? 3 + mon->problem->n_invariants : 0;
}

void gm_monitor_state_save(const gm_monitor *mon, double *out) {
  if (mon == NULL || out == NULL) return;
  out[0] = mon->max_rel_energy;
  out[1] = mon->last_rel_energy;
  out[2] = (double)mon->n_observed;
  for (size_t i = 0; i < mon->problem->n_invariants; ++i) out[3 + i] = mon->max_drift[i];
}

void gm_monitor_state_load(gm_monitor *mon, const double *in) {
  if (mon == NULL || in == NULL) return;
  mon->max_rel_energy = in[0];
  mon->last_rel_energy = in[1];
  mon->n_observed = (size_t)in[2];
  for (size_t i = 0; i < mon->problem->n_invariants; ++i) mon->max_drift[i] = in[3 + i];
}
