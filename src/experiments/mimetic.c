/* Seed 003 (Palha & Gerritsma, mimetic spectral elements for Hamiltonian systems, §6): the four
 * numerical tests with MCI and MGI of degree 2 (mimetic-canonical-2, mimetic-galerkin-2), RK4,
 * explicit and symplectic Euler: each method's largest invariant error along a run, and the
 * measured orders of MCI, MGI and RK4 (state at the end, and the invariant's largest error). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/experiments.h"
#include "geomint/methods.h"

const char *const gm_mimetic_experiment_methods[GM_MIMETIC_METHODS] = {
    "mimetic-canonical-2", "mimetic-galerkin-2", "rk4", "euler", "symplectic-euler-a"};

/* seed 003 §6.1–6.4: the initial data, steps and final times of the paper's figures */
static const gm_mimetic_info infos[] = {
    {"circular", "harmonic", "q1=2", "q1", 2.0, 1.0, 1.0, 100.0, 0, 1, "q", "p", NULL,
     "|H - H0| (H = R^2/2)", 0.5, 10.0},
    {"lotka-volterra", "lotka-volterra", NULL, NULL, 0.0, 0.3, 0.3, 60.0, 0, 1, "u (prey)",
     "v (predator)", "invariant", "|V - V0|, V = ln u - u + 2 ln v - v", 0.3, 5.0},
    {"pendulum", "pendulum", "k=10", "k", 10.0, 0.4, 0.1, 20.0, 0, 1, "q", "p", NULL, "|H - H0|",
     0.2, 1.0},
    {"kepler", "kepler", "e=0.6", "e", 0.6, 0.1, 0.1, 100.0, 0, 1, "q1", "q2", NULL, "|H - H0|",
     0.1, 1.0},
};
#define N_INFOS (sizeof infos / sizeof infos[0])

const gm_mimetic_info *gm_mimetic_find(const char *name) {
  for (size_t i = 0; name != NULL && i < N_INFOS; ++i)
    if (strcmp(infos[i].name, name) == 0) return &infos[i];
  return NULL;
}

/* The monitored invariant at y: the energy, or the first invariant whose name contains
 * ex->invariant. */
static double invariant_value(const gm_mimetic_info *ex, const gm_problem *pb, const double *y) {
  if (ex->invariant == NULL) return gm_problem_energy(pb, y);
  for (size_t k = 0; k < pb->n_invariants; ++k)
    if (strstr(pb->invariants[k].name, ex->invariant) != NULL)
      return pb->invariants[k].value(pb->ctx, y);
  return NAN;
}

typedef struct trace {
  const gm_mimetic_info *ex;
  const gm_problem *pb;
  FILE *csv;
  double i0, max_error;
  size_t n;
} trace;

static int trace_observe(void *ctx, size_t step, double t, const double *y) {
  (void)step;
  trace *tr = ctx;
  double e = fabs(invariant_value(tr->ex, tr->pb, y) - tr->i0);
  if (!(e <= tr->max_error)) tr->max_error = isfinite(e) ? fmax(tr->max_error, e) : INFINITY;
  if (tr->csv != NULL) {
    fprintf(tr->csv, "%.17g", t);
    for (size_t i = 0; i < tr->n; ++i) fprintf(tr->csv, ",%.17g", y[i]);
    fprintf(tr->csv, ",%.17g\n", e);
  }
  return 0;
}

/* One run of a method into run->; writes run->csv when it is not empty. A method that does not
 * apply or stops on the way is a row with its reason, not an error; an unwritable file is. */
static gm_status run_one(const gm_mimetic_info *ex, const gm_model *model, const char *method,
                         double dt, gm_mimetic_run *run, gm_error *err) {
  const gm_problem *pb = gm_model_problem(model);
  gm_integrator *it = NULL;
  gm_error why = {{0}};
  run->method = method;
  run->dt = dt;
  run->why[0] = '\0';
  run->max_invariant_error = NAN;
  if (gm_integrator_create(gm_method_find(method), pb, &it, &why) != GM_OK) {
    run->status = -1;
    snprintf(run->why, sizeof run->why, "%s", why.message);
    return GM_OK;
  }
  const size_t n = gm_model_state_size(model);
  double t0, y0[16];
  gm_model_initial_state(model, &t0, y0);
  FILE *csv = NULL;
  if (run->csv[0] != '\0' && (csv = fopen(run->csv, "w")) == NULL) {
    gm_integrator_free(it);
    return gm_error_set(err, GM_EIO, "mimetic: cannot write %s", run->csv);
  }
  if (csv != NULL) {
    fprintf(csv, "t");
    for (size_t i = 0; i < n; ++i) fprintf(csv, ",y%zu", i + 1);
    fprintf(csv, ",invariant_error\n");
  }
  trace tr = {ex, pb, csv, invariant_value(ex, pb, y0), 0.0, n};
  gm_integrator_set_state(it, t0, y0);
  gm_integrator_add_observer(it, trace_observe, &tr, 1);
  const size_t steps = (size_t)llround(ex->t_end / dt);
  gm_status st = gm_integrator_run(it, steps, dt);
  if (st != GM_OK) snprintf(run->why, sizeof run->why, "stopped: %s", gm_integrator_errmsg(it));
  gm_integrator_free(it);
  run->status = st == GM_OK ? 0 : 1;
  run->max_invariant_error = tr.max_error;
  if (csv != NULL && (ferror(csv) | fclose(csv)) != 0)
    return gm_error_set(err, GM_EIO, "mimetic: writing %s failed", run->csv);
  return GM_OK;
}

/* least-squares slope of log y against log x over the points above round-off */
static double slope(const double *x, const double *y, size_t n) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  size_t m = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!(y[i] > 1e-13 && isfinite(y[i]))) continue;
    double a = log(x[i]), b = log(y[i]);
    sx += a;
    sy += b;
    sxx += a * a;
    sxy += a * b;
    ++m;
  }
  return m >= 2 ? ((double)m * sxy - sx * sy) / ((double)m * sxx - sx * sx) : NAN;
}

/* the state error at conv_t_end against gauss-6 (gm_order_measure) and the largest invariant
 * error over the run, for steps conv_dt0 / 2^l */
static gm_status measure_convergence(const gm_mimetic_info *ex, const gm_model *model,
                                     gm_mimetic_result *c, gm_error *err) {
  const gm_problem *pb = gm_model_problem(model);
  double t0, y0[16];
  gm_model_initial_state(model, &t0, y0);
  for (size_t k = 0; k < GM_MIMETIC_CONVERGENCE; ++k) {
    const gm_scheme sc = {gm_method_find(gm_mimetic_experiment_methods[k]), NULL, GM_SOLVER_DEFAULT, 0};
    gm_order_result r;
    gm_error e = {{0}};
    if (gm_order_measure(&sc, pb, t0, y0, t0 + ex->conv_t_end, ex->conv_dt0,
                         GM_MIMETIC_LEVELS, 2.0, gm_method_find("gauss-6"), &r, &e) != GM_OK)
      return gm_error_set(err, GM_ENOCONV, "mimetic: %s: convergence of %s: %s", ex->name,
                          gm_mimetic_experiment_methods[k], e.message);
    for (size_t l = 0; l < GM_MIMETIC_LEVELS; ++l) {
      c->dts[l] = r.dts[l];
      c->state_error[k][l] = r.errors[l];
      gm_integrator *it = NULL;
      gm_status st = gm_integrator_create(sc.method, pb, &it, err);
      if (st != GM_OK) return st;
      gm_integrator_set_state(it, t0, y0);
      double i0 = invariant_value(ex, pb, y0), worst = 0.0;
      const size_t steps = (size_t)llround(ex->conv_t_end / r.dts[l]);
      for (size_t s = 0; s < steps; ++s) {
        if (gm_integrator_step(it, r.dts[l]) != GM_OK) {
          worst = NAN;
          break;
        }
        worst = fmax(worst, fabs(invariant_value(ex, pb, gm_integrator_state(it)) - i0));
      }
      c->invariant_error[k][l] = worst;
      gm_integrator_free(it);
    }
    c->order[k] = slope(c->dts, c->state_error[k], GM_MIMETIC_LEVELS);
    c->invariant_order[k] = slope(c->dts, c->invariant_error[k], GM_MIMETIC_LEVELS);
    int kept = 1;
    for (size_t l = 0; l < GM_MIMETIC_LEVELS; ++l) kept &= c->invariant_error[k][l] <= 1e-13;
    c->invariant_kept[k] = kept;
  }
  return GM_OK;
}

static gm_status write_convergence_csv(const char *dir, const gm_mimetic_result *c,
                                       gm_error *err) {
  char path[GM_EXPERIMENT_PATH_SIZE], name[64];
  snprintf(name, sizeof name, "%s-convergence.csv", c->info->name);
  FILE *f = NULL;
  if (gm_experiment_path(path, sizeof path, dir, name) != GM_OK || (f = fopen(path, "w")) == NULL)
    return gm_error_set(err, GM_EIO, "mimetic: cannot write %s/%s", dir, name);
  fprintf(f, "dt");
  for (size_t k = 0; k < GM_MIMETIC_CONVERGENCE; ++k)
    fprintf(f, ",%s_state_error,%s_invariant_error", gm_mimetic_experiment_methods[k],
            gm_mimetic_experiment_methods[k]);
  fprintf(f, "\n");
  for (size_t l = 0; l < GM_MIMETIC_LEVELS; ++l) {
    fprintf(f, "%.17g", c->dts[l]);
    for (size_t k = 0; k < GM_MIMETIC_CONVERGENCE; ++k)
      fprintf(f, ",%.17g,%.17g", c->state_error[k][l], c->invariant_error[k][l]);
    fprintf(f, "\n");
  }
  if ((ferror(f) | fclose(f)) != 0)
    return gm_error_set(err, GM_EIO, "mimetic: writing %s failed", path);
  return GM_OK;
}

gm_status gm_experiment_mimetic(const char *name, const char *dir, gm_mimetic_result *r,
                                gm_error *err) {
  memset(r, 0, sizeof *r);
  const gm_mimetic_info *ex = gm_mimetic_find(name);
  if (ex == NULL)
    return gm_error_set(err, GM_EINVAL, "mimetic: unknown experiment '%s': circular, "
                        "lotka-volterra, pendulum or kepler", name ? name : "(null)");
  r->info = ex;
  gm_model *model = NULL;
  gm_status st = gm_model_create(ex->model, &model);
  if (st == GM_OK && ex->setting_name != NULL)
    st = gm_model_set(model, ex->setting_name, ex->setting_value);
  if (st == GM_OK) st = gm_model_build(model);
  if (st != GM_OK) {
    gm_error_set(err, st, "mimetic: the model %s: %s", ex->model,
                 model ? gm_model_errmsg(model) : gm_strerror(st));
    gm_model_free(model);
    return st;
  }
  r->state_size = gm_model_state_size(model);
  const double wall0 = gm_experiment_clock();
  /* pass 0: the phase portrait's step; pass 1: the invariant's, unless it is the same step,
   * when pass 0's runs serve both figures */
  for (size_t pass = 0; pass < 2 && st == GM_OK; ++pass) {
    const double dt = pass == 0 ? ex->dt_phase : ex->dt_invariant;
    if (pass == 1 && dt == ex->dt_phase) break;
    for (size_t k = 0; k < GM_MIMETIC_METHODS && st == GM_OK; ++k) {
      gm_mimetic_run *run = &r->runs[r->n_runs];
      if (dir != NULL) {
        char file[128];
        snprintf(file, sizeof file, "%s-%s-%g.csv", ex->name, gm_mimetic_experiment_methods[k], dt);
        if (gm_experiment_path(run->csv, sizeof run->csv, dir, file) != GM_OK) {
          st = gm_error_set(err, GM_EINVAL, "mimetic: the directory name is too long");
          break;
        }
      }
      st = run_one(ex, model, gm_mimetic_experiment_methods[k], dt, run, err);
      if (st == GM_OK) r->n_runs++;
    }
  }
  if (st == GM_OK) st = measure_convergence(ex, model, r, err);
  if (st == GM_OK) r->convergence_done = 1;
  if (st == GM_OK && dir != NULL) st = write_convergence_csv(dir, r, err);
  r->wall_s = gm_experiment_clock() - wall0;
  gm_model_free(model);
  return st;
}

/* the run of `method` at step dt in r, NULL if none */
static const gm_mimetic_run *find_run(const gm_mimetic_result *r, const char *method, double dt) {
  for (size_t i = 0; i < r->n_runs; ++i)
    if (strcmp(r->runs[i].method, method) == 0 && r->runs[i].dt == dt) return &r->runs[i];
  return NULL;
}

static gm_status run_row(const char *name, const char *dir, gm_experiment_result *out,
                         gm_error *err) {
  gm_mimetic_result *r = malloc(sizeof *r);
  if (r == NULL) return gm_error_set(err, GM_ENOMEM, "mimetic: cannot allocate the result");
  gm_status st = gm_experiment_mimetic(name, dir, r, err);
  if (st == GM_OK) {
    const double dt = r->info->dt_invariant;
    const gm_mimetic_run *mci = find_run(r, "mimetic-canonical-2", dt);
    const gm_mimetic_run *mgi = find_run(r, "mimetic-galerkin-2", dt);
    const gm_mimetic_run *rk4 = find_run(r, "rk4", dt);
    gm_experiment_add(out, "dt", dt);
    gm_experiment_add(out, "max_abs_invariant_error_mci", mci ? mci->max_invariant_error : NAN);
    gm_experiment_add(out, "max_abs_invariant_error_mgi", mgi ? mgi->max_invariant_error : NAN);
    gm_experiment_add(out, "max_abs_invariant_error_rk4", rk4 ? rk4->max_invariant_error : NAN);
    gm_experiment_add(out, "order_mci", r->order[0]);
    gm_experiment_add(out, "order_mgi", r->order[1]);
    gm_experiment_add(out, "order_rk4", r->order[2]);
    gm_experiment_add(out, "invariant_order_mci", r->invariant_order[0]);
    gm_experiment_add(out, "invariant_order_mgi", r->invariant_order[1]);
    gm_experiment_add(out, "invariant_order_rk4", r->invariant_order[2]);
    gm_experiment_add(out, "wall_s", r->wall_s);
    char file[64];
    snprintf(file, sizeof file, "%s-convergence.csv", name);
    gm_experiment_file(out, dir, file);
  }
  free(r);
  return st;
}

gm_status gm_experiment_run_mimetic_circular(const char *dir, gm_experiment_result *out,
                                             gm_error *err) {
  return run_row("circular", dir, out, err);
}
gm_status gm_experiment_run_mimetic_lotka_volterra(const char *dir, gm_experiment_result *out,
                                                   gm_error *err) {
  return run_row("lotka-volterra", dir, out, err);
}
gm_status gm_experiment_run_mimetic_pendulum(const char *dir, gm_experiment_result *out,
                                             gm_error *err) {
  return run_row("pendulum", dir, out, err);
}
gm_status gm_experiment_run_mimetic_kepler(const char *dir, gm_experiment_result *out,
                                           gm_error *err) {
  return run_row("kepler", dir, out, err);
}
