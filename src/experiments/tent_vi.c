/* Seed 001 §5.1: the multisymplectic variational integrator with bilinear tent functions on
 * sine-Gordon (gm_tentvi), from the exact breather u = 4 atan((k/w) sin wt / cosh kx) or kink
 * u = 4 atan(exp(gamma (x - ct))) at t = 0 and dt on [-20, 20); the error against the exact
 * solution and the strip energy. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/pde_spectral.h"

#define TENT_L 20.0
#define TENT_PI 3.14159265358979323846

gm_tent_vi_config gm_tent_vi_defaults(void) {
  gm_tent_vi_config c = {0, 0.5, 200, 0.1, 10.0};
  return c;
}

static double sg_V(double u, const void *c) {
  (void)c;
  return -cos(u);
}
static double sg_dV(double u, const void *c) {
  (void)c;
  return sin(u);
}
static double sg_d2V(double u, const void *c) {
  (void)c;
  return cos(u);
}

static double sg_exact(int kink, double p, double x, double t) {
  if (kink) return 4.0 * atan(exp((x - p * t) / sqrt(1.0 - p * p)));
  double k = sqrt(1.0 - p * p);
  return 4.0 * atan(k / p * sin(p * t) / cosh(k * x));
}

gm_status gm_experiment_tent_vi(const gm_tent_vi_config *c, const char *csv,
                                gm_tent_vi_result *r, gm_error *err) {
  *r = (gm_tent_vi_result){0};
  if (!(c->dt > 0.0) || !isfinite(c->dt) || !(c->t_end > 0.0) || !isfinite(c->t_end) ||
      c->t_end / c->dt > 1e9)
    return gm_error_set(err, GM_EINVAL, "tent-vi: dt %g and t_end %g must be finite, > 0, with "
                        "at most 1e9 steps", c->dt, c->t_end);
  if (!(c->param > 0.0 && c->param < 1.0))
    return gm_error_set(err, GM_EINVAL, "tent-vi: the breather frequency or kink speed %g must "
                        "lie in (0, 1)", c->param);
  if (c->n < 4 || c->n > 100000000)
    return gm_error_set(err, GM_EINVAL, "tent-vi: n = %zu must lie in [4, 1e8]", c->n);
  const double t0 = gm_experiment_clock();
  const size_t n = c->n;
  const double h = 2.0 * TENT_L / (double)n;
  double *u0 = malloc(n * sizeof *u0), *u1 = malloc(n * sizeof *u1);
  if (u0 == NULL || u1 == NULL) {
    free(u0);
    free(u1);
    return gm_error_set(err, GM_ENOMEM, "tent-vi: out of memory for %zu points", n);
  }
  for (size_t i = 0; i < n; i++) {
    u0[i] = sg_exact(c->kink, c->param, -TENT_L + (double)i * h, 0.0);
    u1[i] = sg_exact(c->kink, c->param, -TENT_L + (double)i * h, c->dt);
  }
  gm_tentvi *m = NULL;
  gm_status st = gm_tentvi_create(n, -TENT_L, h, c->kink ? 2.0 * TENT_PI : 0.0, c->dt, sg_V,
                                  sg_dV, sg_d2V, NULL, u0, u1, &m, err);
  free(u0);
  free(u1);
  if (st != GM_OK) return st;
  r->n = n;
  r->h = h;
  r->dt = c->dt;
  r->energy0 = gm_tentvi_energy(m);
  r->steps = (size_t)llround(c->t_end / c->dt);
  if (r->steps > 1 && (st = gm_tentvi_advance(m, r->steps - 1, err)) != GM_OK) {
    gm_tentvi_free(m);
    return st;
  }
  const double *u = gm_tentvi_u(m);
  r->t = gm_tentvi_time(m);
  r->energy = gm_tentvi_energy(m);
  r->max_rel_energy_error = fabs(r->energy - r->energy0) / fabs(r->energy0);
  for (size_t i = 0; i < n; i++)
    r->max_abs_error = fmax(r->max_abs_error,
                            fabs(u[i] - sg_exact(c->kink, c->param, -TENT_L + (double)i * h, r->t)));
  if (csv != NULL) {
    FILE *f = fopen(csv, "w");
    if (f == NULL) {
      gm_tentvi_free(m);
      return gm_error_set(err, GM_EIO, "cannot write '%s'", csv);
    }
    fprintf(f, "x,u,exact\n");
    for (size_t i = 0; i < n; i++) {
      double x = -TENT_L + (double)i * h;
      fprintf(f, "%.10g,%.17g,%.17g\n", x, u[i], sg_exact(c->kink, c->param, x, r->t));
    }
    if (fclose(f) != 0) {
      gm_tentvi_free(m);
      return gm_error_set(err, GM_EIO, "cannot write '%s'", csv);
    }
  }
  gm_tentvi_free(m);
  r->wall_s = gm_experiment_clock() - t0;
  return GM_OK;
}

gm_status gm_experiment_run_tent_vi(const char *dir, gm_experiment_result *result, gm_error *err) {
  gm_tent_vi_config c = gm_tent_vi_defaults();
  gm_tent_vi_result r;
  char csv[GM_EXPERIMENT_PATH_SIZE];
  gm_status st = dir ? gm_experiment_path(csv, sizeof csv, dir, "tent-vi.csv") : GM_OK;
  if (st != GM_OK) return gm_error_set(err, st, "tent-vi: the directory name is too long");
  if ((st = gm_experiment_tent_vi(&c, dir ? csv : NULL, &r, err)) != GM_OK) return st;
  gm_experiment_add(result, "steps", (double)r.steps);
  gm_experiment_add(result, "t", r.t);
  gm_experiment_add(result, "max_abs_error", r.max_abs_error);
  gm_experiment_add(result, "max_rel_energy_error", r.max_rel_energy_error);
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_experiment_file(result, dir, "tent-vi.csv");
  return GM_OK;
}
