/* Seed 000 experiment E1 (Stern 2009, §2.2, Fig 2.1; notes §2 E1): resonance of the impulse
 * method (r-RESPA) against the variational IMEX method on the toy problem U = q²/2,
 * W = ω²q²/2. The seed gives no initial data; q0 = 0, p0 = 1 are the notes'. h = 0.1, T = 1000,
 * the impulse method with 100 substeps of 0.001. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/experiments.h"
#include "geomint/methods.h"
#include "geomint/ode.h"
#include "geomint/oscillatory.h"
#include "geomint/problems.h"

typedef struct {
  const gm_problem *pb;
  double h0, max_error;
} energy_watch;

static int watch_energy(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  (void)t;
  energy_watch *w = ctx;
  const double e = fabs(gm_problem_energy(w->pb, y) - w->h0);
  if (!(e <= w->max_error)) w->max_error = e; /* NaN wins */
  return 0;
}

/* max |H − H0| over T = 1000, h = 0.1; a run that fails (overflow) counts as +inf. A setup
 * failure (which the fixed names and parameters make a bug) is NaN with the reason in err. */
static double resonance_error(const char *method, double omega, size_t substeps, gm_error *err) {
  gm_model *model = NULL;
  gm_status st = gm_model_create("toy-resonance", &model);
  if (st == GM_OK) st = gm_model_set(model, "omega", omega);
  if (st == GM_OK) st = gm_model_build(model);
  if (st != GM_OK) {
    gm_error_set(err, st, "resonance: the model toy-resonance at omega = %g: %s", omega,
                 model ? gm_model_errmsg(model) : gm_strerror(st));
    gm_model_free(model);
    return NAN;
  }
  gm_integrator *it = NULL;
  st = gm_integrator_create(gm_method_find(method), gm_model_problem(model), &it, err);
  double t0, y0[2];
  gm_model_initial_state(model, &t0, y0);
  if (st == GM_OK) st = gm_integrator_set_state(it, t0, y0);
  if (st == GM_OK && substeps > 0) st = gm_oscillatory_set_substeps(it, substeps);
  energy_watch w = {gm_model_problem(model), 0.5, 0.0};
  if (st == GM_OK) st = gm_integrator_add_observer(it, watch_energy, &w, 1);
  if (st != GM_OK) {
    if (it != NULL) gm_error_set(err, st, "resonance: %s: %s", method, gm_integrator_errmsg(it));
    gm_integrator_free(it);
    gm_model_free(model);
    return NAN;
  }
  st = gm_integrator_run(it, 10000, 0.1);
  gm_integrator_free(it);
  gm_model_free(model);
  return st == GM_OK && isfinite(w.max_error) ? w.max_error : INFINITY;
}

static int compare_doubles(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

gm_status gm_experiment_resonance(size_t n_points, const char *dir, gm_resonance_result *r,
                                  gm_error *err) {
  *r = (gm_resonance_result){0};
  if (n_points < 1 || n_points > GM_RESONANCE_MAX_POINTS)
    return gm_error_set(err, GM_EINVAL,
                        "resonance: %zu points is outside [1, %d] (each point is two runs of "
                        "10^4 steps, about 17 ms)",
                        n_points, GM_RESONANCE_MAX_POINTS);
  /* the uniform grid, refined within 0.005 of the integers 1..4, where the resonances of the
   * impulse method are narrower than the grid */
  static const double near[] = {-5e-3, -2e-3, -1e-3, -5e-4, -2e-4, -1e-4,
                                1e-4,  2e-4,  5e-4,  1e-3,  2e-3,  5e-3};
  const size_t n_near = sizeof near / sizeof near[0], n_total = n_points + 4 * n_near;
  double *xs = malloc(n_total * sizeof *xs);
  if (xs == NULL)
    return gm_error_set(err, GM_ENOMEM, "resonance: cannot allocate %zu points", n_total);
  for (size_t k = 0; k < n_points; ++k) xs[k] = 4.5 * (double)(k + 1) / (double)n_points;
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < n_near; ++j) xs[n_points + i * n_near + j] = (double)(i + 1) + near[j];
  qsort(xs, n_total, sizeof *xs, compare_doubles);
  FILE *f = NULL;
  char path[GM_EXPERIMENT_PATH_SIZE];
  if (dir != NULL) {
    if (gm_experiment_path(path, sizeof path, dir, "resonance.csv") != GM_OK ||
        (f = fopen(path, "w")) == NULL) {
      free(xs);
      return gm_error_set(err, GM_EIO, "resonance: cannot write %s/resonance.csv", dir);
    }
    fprintf(f, "omega_h_over_pi,omega,imex,impulse_100\n");
  }
  r->n_points = n_points;
  r->n_near = 4 * n_near;
  r->imex_min = INFINITY;
  const double t0 = gm_experiment_clock();
  gm_status st = GM_OK;
  for (size_t k = 0; k < n_total && st == GM_OK; ++k) {
    const double x = xs[k], omega = x * GM_PI / 0.1;
    if (k > 0 && x == xs[k - 1]) continue;
    const double ei = resonance_error("imex", omega, 0, err);
    const double er = resonance_error("impulse", omega, 100, err);
    if (isnan(ei) || isnan(er)) {
      st = GM_EINVAL;
      break;
    }
    r->imex_min = fmin(r->imex_min, ei);
    r->imex_max = fmax(r->imex_max, ei);
    if (er > r->impulse_max) {
      r->impulse_max = er;
      r->impulse_max_at = x;
    }
    if (isinf(er)) ++r->impulse_blowups;
    if (er > 1.0) { /* a spike: an energy error larger than H0 itself */
      ++r->impulse_spikes;
      const double integer = round(x);
      if ((r->n_spike_near == 0 || r->spike_near[r->n_spike_near - 1] != integer) &&
          r->n_spike_near < 16)
        r->spike_near[r->n_spike_near++] = integer;
    }
    if (f != NULL) fprintf(f, "%.6f,%.10g,%.6e,%.6e\n", x, omega, ei, isinf(er) ? 1e10 : er);
  }
  r->wall_s = gm_experiment_clock() - t0;
  free(xs);
  if (f != NULL && (ferror(f) | fclose(f)) != 0 && st == GM_OK)
    st = gm_error_set(err, GM_EIO, "resonance: writing %s failed", path);
  return st;
}

gm_status gm_experiment_run_resonance(const char *dir, gm_experiment_result *out,
                                      gm_error *err) {
  gm_resonance_result r;
  gm_status st = gm_experiment_resonance(900, dir, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(out, "points", (double)(r.n_points + r.n_near));
  gm_experiment_add(out, "imex_min", r.imex_min);
  gm_experiment_add(out, "imex_max", r.imex_max);
  gm_experiment_add(out, "impulse_max", r.impulse_max);
  gm_experiment_add(out, "impulse_max_at", r.impulse_max_at);
  gm_experiment_add(out, "impulse_spikes", (double)r.impulse_spikes);
  gm_experiment_add(out, "impulse_blowups", (double)r.impulse_blowups);
  gm_experiment_add(out, "wall_s", r.wall_s);
  gm_experiment_file(out, dir, "resonance.csv");
  return GM_OK;
}
