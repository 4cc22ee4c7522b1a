/* Empirical order of convergence: errors at a fixed final time for halved steps, and the
 * least-squares slope of log(error) against log(dt). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ode/internal.h"

/* Errors below this multiple of the solution's size are round-off, not truncation. */
#define ROUNDOFF_FLOOR 1e-13

/* Progress of a measurement: steps done and planned, reported through the plan's callback by
 * an observer every PROGRESS_EVERY steps (observers never change what a run computes). */
#define PROGRESS_EVERY 64
typedef struct order_progress {
  const gm_order_plan *plan;
  double done, total;
  int stopped; /* the callback asked to stop */
} order_progress;

static int observe_progress(void *ctx, size_t step, double t, const double *y) {
  (void)t;
  (void)y;
  order_progress *p = ctx;
  if (step == 0) return 0;
  p->done += PROGRESS_EVERY;
  p->stopped = p->plan->progress(p->plan->progress_ctx, p->done, fmax(p->total, p->done)) != 0;
  return p->stopped;
}

/* The run's steps are shortened to end exactly at t_end: *dt_taken (if not NULL) gets the step
 * actually used, (t_end − t0)/steps, or dt for methods that choose their own steps. */
static gm_status integrate_to_observed(const gm_scheme *scheme, const gm_problem *pb, double t0,
                                       const double *y0, double t_end, double dt, double *y_end,
                                       double *t_reached, double *dt_taken,
                                       order_progress *progress, gm_error *err) {
  gm_integrator *it = NULL;
  gm_status st = gm_integrator_create_scheme(scheme, pb, &it, err);
  if (st != GM_OK) return st;
  st = gm_integrator_set_state(it, t0, y0);
  if (st == GM_OK && progress != NULL && progress->plan->progress != NULL)
    st = gm_integrator_add_observer(it, observe_progress, progress, PROGRESS_EVERY);
  const double done0 = progress != NULL ? progress->done : 0.0;
  if (st == GM_OK) st = gm_integrator_integrate(it, t_end, dt);
  const size_t steps = gm_integrator_stats(it).steps;
  if (progress != NULL) progress->done = done0 + (double)steps;
  if (st == GM_OK) {
    memcpy(y_end, gm_integrator_state(it), gm_problem_state_size(pb) * sizeof *y_end);
    /* t_end exactly, except for methods that choose their own steps (vi-sem-*) */
    const double t = gm_integrator_time(it);
    if (t_reached != NULL) *t_reached = t;
    if (dt_taken != NULL) *dt_taken = t == t_end && steps > 0 ? (t_end - t0) / (double)steps : dt;
  } else
    gm_error_set(err, st, "%s at dt = %g: %s", scheme->method->name, dt,
                 gm_integrator_errmsg(it));
  gm_integrator_free(it);
  return st;
}

static gm_status integrate_to(const gm_scheme *scheme, const gm_problem *pb, double t0,
                              const double *y0, double t_end, double dt, double *y_end,
                              double *t_reached, gm_error *err) {
  return integrate_to_observed(scheme, pb, t0, y0, t_end, dt, y_end, t_reached, NULL, NULL,
                               err);
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
    st = integrate_to_observed(scheme, problem, t0, y0, t_end, dt, y, &t_reached, &dt, NULL, err);
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

/* ---- the asymptotic window (shared by `geomint order` and tests/convergence) ------------- */

void gm_order_window(int order, double *top, double *bottom) {
  const double p = order > 0 ? (double)order : 1.0;
  double t = fmax(1e-7, fmin(1e-3, pow(10.0, -(p + 2.0))));
  double b = t * pow(10.0, -fmin(6.0, 2.0 * p));
  if (b < 1e-12) b = 1e-12;
  if (top != NULL) *top = t;
  if (bottom != NULL) *bottom = b;
}

/* The state error of one level at step dt against the exact solution (at the time the run
 * reached) or against `reference` (at t_end). */
static gm_status level_error(const gm_scheme *scheme, const gm_problem *pb, double t0,
                             const double *y0, double t_end, double *dt, const double *reference,
                             double *y, double *exact, order_progress *progress, double *error,
                             gm_error *err) {
  const size_t n = gm_problem_state_size(pb);
  double t_reached = t_end;
  gm_status st =
      integrate_to_observed(scheme, pb, t0, y0, t_end, *dt, y, &t_reached, dt, progress, err);
  if (st != GM_OK) return st;
  const double *ref = reference;
  if (pb->exact != NULL) {
    if (pb->exact(pb->ctx, t_reached, exact) != 0)
      return gm_error_set(err, GM_ECALLBACK, "the exact solution failed at t = %g", t_reached);
    ref = exact;
  } else if (t_reached != t_end) {
    return gm_error_set(err, GM_EUNSUPPORTED, "'%s' chooses its own steps: its order needs the "
                        "problem's exact solution", scheme->method->name);
  }
  double e = 0.0;
  for (size_t i = 0; i < n; ++i) e = fmax(e, fabs(y[i] - ref[i]));
  *error = e;
  return GM_OK;
}

/* Without an exact solution: the reference method's run, its step halved until two runs agree
 * to `target` or stop improving (round-off). */
static gm_status reference_run(const gm_method *reference, const gm_problem *pb, double t0,
                               const double *y0, double t_end, double target, double *out,
                               double *work, order_progress *progress, gm_error *err) {
  const size_t n = gm_problem_state_size(pb);
  const gm_scheme sc = {reference, NULL, GM_SOLVER_DEFAULT, 0};
  double h = (t_end - t0) / 16.0, diff_prev = INFINITY;
  gm_status st = integrate_to_observed(&sc, pb, t0, y0, t_end, h, out, NULL, NULL, progress, err);
  for (int k = 0; k < 24 && st == GM_OK; ++k) {
    h /= 2.0;
    st = integrate_to_observed(&sc, pb, t0, y0, t_end, h, work, NULL, NULL, progress, err);
    if (st != GM_OK) break;
    double diff = 0.0;
    for (size_t i = 0; i < n; ++i) diff = fmax(diff, fabs(work[i] - out[i]));
    memcpy(out, work, n * sizeof *out);
    if (diff <= target || diff >= 0.5 * diff_prev) return GM_OK;
    diff_prev = diff;
  }
  if (st == GM_OK)
    st = gm_error_set(err, GM_ENOCONV, "the reference run with %s did not settle",
                      reference->name);
  return st;
}

/* Least-squares slope over the levels from..n_levels−1 whose error is in [lo, hi]; *dev gets
 * the largest distance of those errors from the line, in decades. */
static double fit_levels(const gm_order_result *r, size_t from, double lo, double hi, size_t *n_fit,
                         size_t *first, double *dev) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  size_t m = 0;
  *first = r->n_levels;
  for (size_t l = from; l < r->n_levels; ++l) {
    if (!(r->errors[l] >= lo && r->errors[l] <= hi)) continue;
    double x = log(r->dts[l]), v = log(r->errors[l]);
    sx += x;
    sy += v;
    sxx += x * x;
    sxy += x * v;
    if (*first == r->n_levels) *first = l;
    ++m;
  }
  *n_fit = m;
  *dev = INFINITY;
  if (m < 2) return NAN;
  const double slope = ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx);
  const double b = (sy - slope * sx) / (double)m;
  double d = 0.0;
  for (size_t l = from; l < r->n_levels; ++l)
    if (r->errors[l] >= lo && r->errors[l] <= hi)
      d = fmax(d, fabs(log(r->errors[l]) - (slope * log(r->dts[l]) + b)) / log(10.0));
  *dev = d;
  return slope;
}

/* The fit over the window; where the errors there stray from a power law (the top levels are
 * still pre-asymptotic, e.g. a non-symmetric method's next term), the largest levels are
 * dropped one by one while at least three remain. A curved fit over many levels (deviation
 * above 0.02 decades with more than five levels: kahan-li-8 of position Verlet,
 * whose tiny error constant puts the window's top at dt ≈ T/8, fitted 7.70 over 11 levels with
 * deviation 0.039) also drops its largest levels, down to five. */
#define GM_ORDER_CURVATURE 0.02
static void fit_window(gm_order_result *r, double lo, double hi) {
  size_t m, first;
  double dev;
  double slope = fit_levels(r, 0, lo, hi, &m, &first, &dev);
  r->n_fitted = m;
  r->first_fitted = first;
  r->order = NAN;
  r->fit_deviation = m >= 2 ? dev : 0.0;
  if (m >= 3) {
    for (size_t from = first;
         dev > GM_ORDER_MAX_DEVIATION || (dev > GM_ORDER_CURVATURE && m > 5); ++from) {
      size_t m2, first2;
      double dev2, slope2 = fit_levels(r, from + 1, lo, hi, &m2, &first2, &dev2);
      if (m2 < 3 || (dev <= GM_ORDER_MAX_DEVIATION && m2 < 5)) break;
      slope = slope2, m = m2, first = first2, dev = dev2;
    }
    r->n_fitted = m;
    r->first_fitted = first;
    r->fit_deviation = dev;
    if (dev <= GM_ORDER_MAX_DEVIATION) {
      r->order = slope;
      r->outcome = GM_ORDER_MEASURED;
    } else {
      r->outcome = GM_ORDER_IRREGULAR;
    }
    return;
  }
  size_t above = 0, below = 0;
  for (size_t l = 0; l < r->n_levels; ++l) {
    above += r->errors[l] > hi;
    below += !(r->errors[l] >= lo); /* NaN counts as below: nothing to fit */
  }
  r->outcome = above == r->n_levels ? GM_ORDER_PRE_ASYMPTOTIC
               : below > 0          ? GM_ORDER_ROUNDOFF
                                    : GM_ORDER_TOO_FEW_LEVELS;
}

gm_status gm_order_measure_window(const gm_scheme *scheme, const gm_problem *problem, double t0,
                                  const double *y0, double t_end, const gm_order_plan *plan,
                                  gm_order_result *out, gm_error *err) {
  if (scheme == NULL || scheme->method == NULL || problem == NULL || y0 == NULL || out == NULL)
    return gm_error_set(err, GM_EINVAL, "NULL argument");
  const gm_order_plan none = {0};
  if (plan == NULL) plan = &none;
  if (!isfinite(t_end) || !isfinite(t0) || !(t_end > t0))
    return gm_error_set(err, GM_EINVAL, "need a finite t_end > t0 (got t0 = %g, t_end = %g)", t0,
                        t_end);
  if (plan->dt0 != 0.0 && (!(plan->dt0 > 0.0) || !isfinite(plan->dt0)))
    return gm_error_set(err, GM_EINVAL, "dt0 must be positive and finite, got %g", plan->dt0);
  if (plan->refinement != 0.0 && (!(plan->refinement > 1.0) || !isfinite(plan->refinement)))
    return gm_error_set(err, GM_EINVAL, "refinement must be a finite number > 1, got %g",
                        plan->refinement);
  if (plan->n_levels == 1 || plan->n_levels > GM_ORDER_MAX_LEVELS)
    return gm_error_set(err, GM_EINVAL, "number of levels must be in [2, %d], got %zu",
                        GM_ORDER_MAX_LEVELS, plan->n_levels);
  /* A scheme that cannot integrate the problem at all (another kind, a missing split or
   * callback) is that error, not an error "above the window" at every step. */
  gm_integrator *probe = NULL;
  gm_status created = gm_integrator_create_scheme(scheme, problem, &probe, err);
  gm_integrator_free(probe);
  if (created != GM_OK) return created;
  memset(out, 0, sizeof *out);
  out->order = NAN;
  const int p = scheme->method->order;
  double top, bottom;
  gm_order_window(p, &top, &bottom);
  const size_t n = gm_problem_state_size(problem);
  double scale = 1.0;
  for (size_t i = 0; i < n; ++i) scale = fmax(scale, fabs(y0[i]));
  out->window_top = top * scale;
  out->window_bottom = bottom * scale;
  const double ratio =
      plan->refinement != 0.0 ? plan->refinement : fmin(2.0, pow(10.0, 0.5 / (double)p));
  out->refinement = ratio;
  double *ref = malloc(n * sizeof *ref), *y = malloc(n * sizeof *y),
         *exact = malloc(n * sizeof *exact);
  order_progress progress = {plan, 0.0, 0.0, 0};
  gm_status st = GM_OK;
  if (ref == NULL || y == NULL || exact == NULL) st = gm_error_set(err, GM_ENOMEM, "out of memory");
  if (st == GM_OK) {
    if (problem->exact != NULL) {
      out->reference_is_exact = 1;
    } else {
      const gm_method *reference =
          plan->reference != NULL ? plan->reference : default_reference(problem);
      out->reference = reference;
      if (reference == NULL)
        st = gm_error_set(err, GM_EUNSUPPORTED, "no exact solution and no reference method");
      else
        st = reference_run(reference, problem, t0, y0, t_end, 0.01 * out->window_bottom, ref, y,
                           &progress, err);
    }
  }
  /* the largest step: given, or the largest power of two inside the top of the window */
  double dt0 = plan->dt0, dt0_taken = NAN, e0 = NAN;
  if (st == GM_OK && dt0 == 0.0) {
    double h = 1.0;
    while (h > t_end - t0) h /= 2.0;
    for (; st == GM_OK; h /= 2.0) {
      if (h < 1e-6 * fmin(1.0, t_end - t0)) {
        st = gm_error_set(err, GM_ENOCONV, "%s: the error stays above the asymptotic window "
                          "(%.1e) down to dt = %g", scheme->method->name, out->window_top, h);
        break;
      }
      progress.total = progress.done + (t_end - t0) / h;
      gm_error level_err = {{0}};
      double h_taken = h;
      gm_status lst = level_error(scheme, problem, t0, y0, t_end, &h_taken, ref, y, exact,
                                  &progress, &e0, &level_err);
      if (progress.stopped) {
        st = gm_error_set(err, GM_ECALLBACK, "stopped by the progress callback");
        break;
      }
      if (lst == GM_OK && e0 <= out->window_top) {
        dt0 = h;
        dt0_taken = h_taken;
        break;
      }
      e0 = NAN;
      if (lst == GM_ECALLBACK || lst == GM_ENOMEM) { /* not a step too large: an error */
        st = gm_error_set(err, lst, "%s", level_err.message);
        break;
      }
    }
  }
  size_t levels = plan->n_levels;
  if (levels == 0) {
    const double decades = log10(top / bottom);
    levels = (size_t)ceil(decades / ((double)p * log10(ratio))) + 1;
    if (levels > GM_ORDER_MAX_LEVELS) levels = GM_ORDER_MAX_LEVELS;
    if (levels < 3) levels = 3;
  }
  if (st == GM_OK) {
    double planned = 0.0;
    for (size_t l = 0; l < levels; ++l) planned += (t_end - t0) / (dt0 / pow(ratio, (double)l));
    progress.total = progress.done + planned;
  }
  /* levels whose shortened step equals the previous level's (few steps, small ratio) are
   * skipped: each level has its own step */
  for (size_t k = 0, l = 0; l < levels && k < 4 * levels && st == GM_OK; ++k) {
    double dt = k == 0 && !isnan(e0) ? dt0_taken : dt0 / pow(ratio, (double)k);
    double e = e0;
    if (k > 0 || isnan(e0)) {
      gm_status lst = level_error(scheme, problem, t0, y0, t_end, &dt, ref, y, exact, &progress,
                                  &e, err);
      if (progress.stopped)
        lst = gm_error_set(err, GM_ECALLBACK, "stopped by the progress callback");
      if (lst != GM_OK) {
        /* a finer level that fails ends the levels; a failure before two levels is an error,
         * and so is a stop asked for by the progress callback */
        if (l < 2 || progress.stopped) st = lst;
        break;
      }
    }
    if (l > 0 && dt == out->dts[l - 1]) continue;
    out->dts[l] = dt;
    out->errors[l] = e;
    out->n_levels = ++l;
  }
  free(ref);
  free(y);
  free(exact);
  if (st != GM_OK) return st;
  fit_window(out, out->window_bottom, out->window_top);
  /* A clean power law whose slope is not the declared order, with a finer level already below
   * the window: whether the slope would settle cannot be seen above round-off, so it is not
   * reported as the order. Measured on Kepler with e = 0.6 (`geomint order kepler --method M`):
   * slopes 11.05 (sofroniou-spaletta-10), 14.45 (gauss-6), 15.65 (gauss-7), all with round-off
   * right below the window; the same rows measure 9.90, 11.91 and their order's round-off
   * outcome on the default e = 0.1, whose window lies higher. */
  if (out->outcome == GM_ORDER_MEASURED && fabs(out->order - (double)p) > GM_ORDER_TOLERANCE)
    for (size_t l = 0; l < out->n_levels; ++l)
      if (!(out->errors[l] >= out->window_bottom)) {
        out->outcome = GM_ORDER_NOT_SETTLED;
        break;
      }
  return GM_OK;
}
