/* Seed 004 Figs 11-13 (B10): the stability of the leapfrog (LF), energy-conserving (EC) and
 * multisymplectic (MS) schemes on the sine-Gordon breather w = 0.5, [-20, 20) periodic,
 * N = 200 (dx = 0.2): LF, EC, MS at dt = dx to t = 500, EC and MS at dt = 2 dx to t = 100
 * (LF is refused there: CFL). A run stops when max |u| > 100 or the scheme fails. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/pde.h"

#define B10_L 20.0
#define B10_N 200

static const struct {
  const char *scheme;
  double ratio, t_end;
} plan[GM_B10_RUNS] = {{"lf", 1.0, 500.0}, {"ec", 1.0, 500.0}, {"ms", 1.0, 500.0},
                       {"ec", 2.0, 100.0}, {"ms", 2.0, 100.0}};

static double max_abs_u(const gm_pde *p) {
  const double *s = gm_pde_state(p);
  double m = 0.0;
  for (size_t i = 0; i < gm_pde_n(p); i++) m = fmax(m, fabs(s[3 * i]));
  return m;
}

/* the standing breather u = 4 atan((k/w) sin(wt) / cosh(kx)) at t = 0: u = 0,
 * u_t = 4k sech(kx) */
static gm_status make_solver(const char *scheme_name, double dt, gm_pde **out, gm_error *err) {
  const gm_pde_scheme *scheme = NULL;
  if (gm_pde_scheme_find(scheme_name, &scheme) != GM_OK)
    return gm_error_set(err, GM_EINVAL, "b10: no scheme named %s", scheme_name);
  const size_t n = B10_N;
  const double h = 2.0 * B10_L / (double)n, k = sqrt(1.0 - 0.25);
  double *s = calloc(3 * n, sizeof *s);
  if (s == NULL) return gm_error_set(err, GM_ENOMEM, "b10: out of memory");
  for (size_t i = 0; i < n; i++) s[3 * i + 1] = 4.0 * k / cosh(k * (-B10_L + (double)i * h));
  gm_pde_equation eq = gm_pde_sine_gordon();
  gm_pde_grid g = {n, h, -B10_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = dt;
  gm_status st = gm_pde_create(&g, &eq, scheme, &o, s, out, err);
  free(s);
  return st;
}

static gm_status b10_one(size_t i, const char *dir, gm_b10_run *r, gm_error *err) {
  const double h = 2.0 * B10_L / (double)B10_N, dt = plan[i].ratio * h;
  r->scheme = plan[i].scheme;
  r->ratio = plan[i].ratio;
  r->t_end = plan[i].t_end;
  gm_pde *p = NULL;
  gm_status st = make_solver(r->scheme, dt, &p, err);
  if (st != GM_OK) return st;
  FILE *f = NULL;
  if (dir != NULL) {
    char name[64], path[GM_EXPERIMENT_PATH_SIZE];
    snprintf(name, sizeof name, "b10-%s-%g.dat", r->scheme, r->ratio);
    if (gm_experiment_path(path, sizeof path, dir, name) != GM_OK ||
        (f = fopen(path, "w")) == NULL) {
      gm_pde_free(p);
      return gm_error_set(err, GM_EIO, "b10: cannot write '%s/%s'", dir, name);
    }
    fprintf(f, "# t max|u| relative-energy-change running-max|u| (%s, dt/dx = %g)\n", r->scheme,
            r->ratio);
  }
  const double e0 = gm_pde_energy(p);
  double emax = 0.0, run_max = 0.0;
  const size_t steps = (size_t)llround(r->t_end / dt), every = r->ratio > 1.0 ? 1 : 5;
  gm_error step_err = {{0}};
  r->outcome = GM_B10_BOUNDED;
  size_t k;
  for (k = 0; k < steps; k++) {
    if (gm_pde_advance(p, 1, &step_err) != GM_OK) {
      r->outcome = GM_B10_FAILED;
      snprintf(r->why, sizeof r->why, "%s", step_err.message);
      break;
    }
    const double m = max_abs_u(p), de = fabs(gm_pde_energy(p) - e0) / fabs(e0);
    run_max = fmax(run_max, m);
    if (f != NULL && ((k + 1) % every == 0 || m > 100.0))
      fprintf(f, "%g %.6e %.6e %.6e\n", gm_pde_time(p), m, de, run_max);
    if (m > 100.0) {
      r->outcome = GM_B10_UNBOUNDED;
      break;
    }
    emax = fmax(emax, de);
  }
  r->step = r->outcome == GM_B10_BOUNDED ? steps : k + 1;
  r->t = r->outcome == GM_B10_FAILED ? (double)(k + 1) * dt : gm_pde_time(p);
  r->max_abs_u = max_abs_u(p);
  r->max_rel_energy_error = emax;
  gm_pde_free(p);
  if (f != NULL && fclose(f) != 0)
    return gm_error_set(err, GM_EIO, "b10: cannot write into '%s'", dir);
  return GM_OK;
}

gm_status gm_experiment_b10(const char *dir, gm_b10_result *result, gm_error *err) {
  *result = (gm_b10_result){0};
  const double t0 = gm_experiment_clock();
  result->n = B10_N;
  result->h = 2.0 * B10_L / (double)B10_N;
  for (size_t i = 0; i < GM_B10_RUNS; ++i) {
    gm_status st = b10_one(i, dir, &result->runs[i], err);
    if (st != GM_OK) return st;
    result->n_runs = i + 1;
  }
  result->wall_s = gm_experiment_clock() - t0;
  return GM_OK;
}

gm_status gm_experiment_run_b10(const char *dir, gm_experiment_result *result, gm_error *err) {
  gm_b10_result r;
  gm_status st = gm_experiment_b10(dir, &r, err);
  if (st != GM_OK) return st;
  /* the time each run reached (500 / 100 when bounded) and, bounded, its energy error */
  static const char *const t_names[GM_B10_RUNS] = {"lf_1_t", "ec_1_t", "ms_1_t", "ec_2_t",
                                                   "ms_2_t"};
  static const char *const e_names[GM_B10_RUNS] = {
      "lf_1_max_rel_energy_error", "ec_1_max_rel_energy_error", "ms_1_max_rel_energy_error",
      "ec_2_max_rel_energy_error", "ms_2_max_rel_energy_error"};
  for (size_t i = 0; i < GM_B10_RUNS; ++i) {
    gm_experiment_add(result, t_names[i], r.runs[i].t);
    gm_experiment_add(result, e_names[i], r.runs[i].max_rel_energy_error);
  }
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_experiment_file(result, dir, "b10-ms-1.dat");
  gm_experiment_file(result, dir, "b10-ms-2.dat");
  return GM_OK;
}
