/* Empirical order of convergence: errors at a fixed final time for halved steps, and the
 * least-squares slope of log(error) against log(dt). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ode/internal.h"

/* Errors below this multiple of the solution's size are round-off, not truncation. */
#define ROUNDOFF_FLOOR 1e-13

static gm_status integrate_to(const gm_scheme *scheme, const gm_problem *pb, double t0,
                              const double *y0, double t_end, double dt, double *y_end,
                              double *t_reached, gm_error *err) {
  gm_integrator *it = NULL;
  gm_status st = gm_integrator_create_scheme(scheme, pb, &it, err);
  if (st != GM_OK) return st;
  st = gm_integrator_set_state(it, t0, y0);
  if (st == GM_OK) st = gm_integrator_integrate(it, t_end, dt);
  if (st == GM_OK) {
    memcpy(y_end, gm_integrator_state(it), gm_problem_state_size(pb) * sizeof *y_end);
    /* t_end exactly, except for methods that choose their own steps (vi-sem-*) */
    if (t_reached != NULL) *t_reached = gm_integrator_time(it);
  } else
    gm_error_set(err, st, "%s at dt = %g: %s", scheme->method->name, dt,
                 gm_integrator_errmsg(it));
  gm_integrator_free(it);
  return st;
}

/* The most accurate explicit method that accepts the problem; for Lagrangian problems, which
 * no explicit row integrates, the most accurate fixed-step variational row. */
static const gm_method *default_reference(const gm_problem *pb) {
  const gm_method *best = NULL;
  const int lagrangian = pb->kind == GM_PROBLEM_LAGRANGIAN;
  for (size_t i = 0, n = gm_method_count(); i < n; ++i) {
    const gm_method *m = gm_method_at(i);
    gm_integrator *it = NULL;
    if (lagrangian ? (m->flags & GM_ENERGY_PRESERVING) != 0 : !(m->flags & GM_EXPLICIT)) continue;
    if (gm_integrator_create(m, pb, &it, NULL) != GM_OK) continue;
    gm_integrator_free(it);
    if (best == NULL || m->order > best->order) best = m;
  }
  return best;
}

gm_status gm_order_measure(const gm_scheme *scheme, const gm_problem *problem, double t0,
                           const double *y0, double t_end, double dt0, size_t n_levels,
                           double refinement, const gm_method *reference, gm_order_result *out,
                           gm_error *err) {
  if (scheme == NULL || scheme->method == NULL || problem == NULL || y0 == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  if (n_levels < 2 || n_levels > GM_ORDER_MAX_LEVELS)
    return gm_error_set(err, GM_EINVAL, "number of levels must be in [2, %d], got %zu",
                        GM_ORDER_MAX_LEVELS, n_levels);
  if (!(dt0 > 0.0) || !isfinite(dt0) || !isfinite(t_end) || !(t_end > t0))
    return gm_error_set(err, GM_EINVAL, "need dt0 > 0 and t_end > t0 (got dt0 = %g, t_end = %g)",
                        dt0, t_end);
  if (!(refinement > 1.0) || !isfinite(refinement))
    return gm_error_set(err, GM_EINVAL, "refinement must be a finite number > 1, got %g",
                        refinement);
  memset(out, 0, sizeof *out);
  const size_t n = gm_problem_state_size(problem);
  double *exact = malloc(n * sizeof *exact), *y = malloc(n * sizeof *y);
  if (exact == NULL || y == NULL) {
    free(exact);
    free(y);
    return gm_error_set(err, GM_ENOMEM, "out of memory");
  }
  gm_status st = GM_OK;
  double dt_min = dt0 / pow(refinement, (double)(n_levels - 1));
  if (problem->exact != NULL) {
    out->reference_is_exact = 1;
    if (problem->exact(problem->ctx, t_end, exact) != 0)
      st = gm_error_set(err, GM_ECALLBACK, "the exact solution failed at t = %g", t_end);
  } else {
    if (reference == NULL) reference = default_reference(problem);
    out->reference = reference;
    if (reference == NULL)
      st = gm_error_set(err, GM_EUNSUPPORTED, "no exact solution and no reference method");
    else
      st = integrate_to(&(gm_scheme){reference, NULL, GM_SOLVER_DEFAULT, 0}, problem, t0, y0,
                        t_end, dt_min / 64.0, exact, NULL, err);
  }
  double scale = fmax(1.0, gm_norm_inf(n, exact));
  for (size_t l = 0; l < n_levels && st == GM_OK; ++l) {
    double dt = dt0 / pow(refinement, (double)l);
    double t_reached = t_end;
    st = integrate_to(scheme, problem, t0, y0, t_end, dt, y, &t_reached, err);
    if (st != GM_OK) break;
    if (t_reached != t_end) { /* a method that chose its own steps: compare where it ended */
      if (problem->exact == NULL) {
        st = gm_error_set(err, GM_EUNSUPPORTED, "'%s' chooses its own steps: its order needs "
                          "the problem's exact solution", scheme->method->name);
        break;
      }
      if (problem->exact(problem->ctx, t_reached, exact) != 0) {
        st = gm_error_set(err, GM_ECALLBACK, "the exact solution failed at t = %g", t_reached);
        break;
      }
    }
    double e = 0.0;
    if (gm_problem_space(problem) != NULL) { /* a manifold: the distance in its chart */
      double z[64];
      if (gm_problem_chart_dim(problem) > 64 ||
          gm_problem_to_chart(problem, exact, y, z) != GM_OK) {
        st = gm_error_set(err, GM_EDOMAIN, "the state at dt = %g is outside the chart", dt);
        break;
      }
      for (size_t i = 0; i < gm_problem_chart_dim(problem); ++i) e = fmax(e, fabs(z[i]));
    } else {
      for (size_t i = 0; i < n; ++i) e = fmax(e, fabs(y[i] - exact[i]));
    }
    out->dts[l] = dt;
    out->errors[l] = e;
    out->n_levels = l + 1;
  }
  free(exact);
  free(y);
  if (st != GM_OK) return st;
  /* Least squares over the levels above round-off. */
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  size_t m = 0;
  for (size_t l = 0; l < out->n_levels; ++l) {
    if (!(out->errors[l] > ROUNDOFF_FLOOR * scale)) continue;
    double x = log(out->dts[l]), v = log(out->errors[l]);
    sx += x;
    sy += v;
    sxx += x * x;
    sxy += x * v;
    ++m;
  }
  out->n_fitted = m;
  if (m < 2) {
    out->order = NAN;
    return gm_error_set(err, GM_EINVAL,
                        "only %zu level(s) have errors above round-off: use a larger dt0", m);
  }
  out->order = ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx);
  return GM_OK;
}
