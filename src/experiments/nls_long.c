/* Seed 004 §4 (NLS, eqs. 35-36): the two-soliton collision over many periods, the
 * multisymplectic Preissmann box against box-sdirk2 (the same box in space, a non-symplectic
 * order-2 SDIRK in time), with the relative errors of energy, momentum and charge against t.
 * Two solitons psi_k = a_k sech(a_k (x - x_k)) exp(i c_k x / 2), a = 1, 0.8, c = +-pi/5 (so that
 * exp(icx/2) is periodic on [-20, 20)); the pair meets every 40/(2 pi/5) = 31.8 time units. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/pde.h"

#define NLS_L 20.0
#define NLS_PI 3.14159265358979323846

static const double sol_a[2] = {1.0, 0.8}, sol_c[2] = {NLS_PI / 5.0, -NLS_PI / 5.0},
                    sol_x[2] = {-10.0, 10.0};
static const char *const scheme_names[2] = {"preissmann", "box-sdirk2"};

gm_nls_long_config gm_nls_long_defaults(void) {
  gm_nls_long_config c = {1e4, 128, 0.1, 0, NULL};
  return c;
}

static void two_soliton(double x, double *s) {
  for (int a = 0; a < 4; a++) s[a] = 0.0;
  for (int k = 0; k < 2; k++) {
    double y = x - sol_x[k]; /* the nearest periodic image */
    y -= 2.0 * NLS_L * floor((y + NLS_L) / (2.0 * NLS_L));
    double A = sol_a[k], amp = A / cosh(A * y), dam = -A * tanh(A * y) * amp;
    double th = sol_c[k] * x / 2.0, c = cos(th), sn = sin(th), w = sol_c[k] / 2.0;
    s[0] += amp * c;
    s[1] += amp * sn;
    s[2] += dam * c - amp * sn * w;
    s[3] += dam * sn + amp * c * w;
  }
}

static gm_status nls_one(const char *scheme_name, const gm_nls_long_result *r, const char *dir,
                         gm_nls_long_scheme *res, gm_error *err) {
  const gm_pde_scheme *scheme = NULL;
  if (gm_pde_scheme_find(scheme_name, &scheme) != GM_OK)
    return gm_error_set(err, GM_EINVAL, "nls-long: no scheme named %s", scheme_name);
  const size_t n = r->n, steps = r->steps, every = r->every;
  gm_pde_equation eq = gm_pde_nls();
  const double h = 2.0 * NLS_L / (double)n;
  gm_pde_grid g = {n, h, -NLS_L, {0}};
  gm_pde_options o = gm_pde_options_defaults();
  o.dt = r->dt;
  double *s0 = calloc(4 * n, sizeof *s0);
  if (s0 == NULL) return gm_error_set(err, GM_ENOMEM, "nls-long: out of memory");
  for (size_t i = 0; i < n; i++) two_soliton(-NLS_L + (double)i * h, s0 + 4 * i);
  gm_pde *p = NULL;
  gm_status st = gm_pde_create(&g, &eq, scheme, &o, s0, &p, err);
  free(s0);
  if (st != GM_OK) return st;
  FILE *f = NULL;
  if (dir != NULL) {
    char name[64], path[GM_EXPERIMENT_PATH_SIZE];
    snprintf(name, sizeof name, "nls-long-%s.dat", scheme_name);
    if (gm_experiment_path(path, sizeof path, dir, name) != GM_OK ||
        (f = fopen(path, "w")) == NULL) {
      gm_pde_free(p);
      return gm_error_set(err, GM_EIO, "nls-long: cannot write '%s/%s'", dir, name);
    }
    fprintf(f, "# %s: t/period |dE/E| |dP/P| |dN/N| (n = %zu, dt = %g)\n", scheme_name, n,
            r->dt);
  }
  const double e0 = gm_pde_cell_energy(p), p0 = gm_pde_cell_momentum(p), q0 = gm_pde_norm(p);
  memset(res, 0, sizeof *res);
  res->scheme = scheme_name;
  for (size_t k = 0; k < steps && st == GM_OK; k += every) {
    const size_t m = steps - k < every ? steps - k : every;
    if ((st = gm_pde_advance(p, m, err)) != GM_OK) {
      char why[GM_ERRMSG_SIZE];
      snprintf(why, sizeof why, "%s", err->message);
      gm_error_set(err, st, "%s: %s", scheme_name, why);
      break;
    }
    const double de = fabs(gm_pde_cell_energy(p) - e0) / fabs(e0);
    const double dp = fabs(gm_pde_cell_momentum(p) - p0) / fabs(p0);
    const double dq = fabs(gm_pde_norm(p) - q0) / fabs(q0);
    if (f != NULL) fprintf(f, "%.6f %.6e %.6e %.6e\n", gm_pde_time(p) / GM_NLS_LONG_PERIOD, de, dp, dq);
    const size_t done = k + m;
    for (int tenth = 0; tenth < 2; ++tenth)
      if (tenth == 0 ? done <= steps / 10 : done > steps - steps / 10) {
        res->energy[tenth] = fmax(res->energy[tenth], de);
        res->momentum[tenth] = fmax(res->momentum[tenth], dp);
        res->charge[tenth] = fmax(res->charge[tenth], dq);
      }
  }
  if (f != NULL && fclose(f) != 0 && st == GM_OK)
    st = gm_error_set(err, GM_EIO, "nls-long: cannot write into '%s'", dir);
  gm_pde_free(p);
  return st;
}

gm_status gm_experiment_nls_long(const gm_nls_long_config *c, const char *dir,
                                 gm_nls_long_result *r, gm_error *err) {
  *r = (gm_nls_long_result){0};
  if (!(c->dt > 0.0) || !isfinite(c->dt) || !(c->periods > 0.0) || !isfinite(c->periods) ||
      c->periods * GM_NLS_LONG_PERIOD / c->dt > 1e9)
    return gm_error_set(err, GM_EINVAL, "nls-long: dt %g and periods %g must be finite, > 0, "
                        "with at most 1e9 steps", c->dt, c->periods);
  if (c->n < 16 || c->n > 100000)
    return gm_error_set(err, GM_EINVAL, "nls-long: n must lie in 16..100000 (got %zu)", c->n);
  if (c->only != NULL && strcmp(c->only, scheme_names[0]) != 0 &&
      strcmp(c->only, scheme_names[1]) != 0)
    return gm_error_set(err, GM_EINVAL, "nls-long: only takes preissmann or box-sdirk2 (got "
                        "'%s')", c->only);
  const double t0 = gm_experiment_clock();
  r->n = c->n;
  r->dt = c->dt;
  r->periods = c->periods;
  r->steps = (size_t)llround(c->periods * GM_NLS_LONG_PERIOD / c->dt);
  if (r->steps < 10) r->steps = 10;
  r->every = c->every > 0 ? c->every : r->steps / 2000 > 0 ? r->steps / 2000 : 1;
  r->t_end = (double)r->steps * c->dt;
  for (int k = 0; k < 2; k++) {
    if (c->only != NULL && strcmp(c->only, scheme_names[k]) != 0) continue;
    gm_status st = nls_one(scheme_names[k], r, dir, &r->schemes[k], err);
    if (st != GM_OK) return st;
  }
  r->wall_s = gm_experiment_clock() - t0;
  return GM_OK;
}

gm_status gm_experiment_run_nls_long(const char *dir, gm_experiment_result *result,
                                     gm_error *err) {
  gm_nls_long_config c = gm_nls_long_defaults();
  gm_nls_long_result r;
  gm_status st = gm_experiment_nls_long(&c, dir, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(result, "steps", (double)r.steps);
  gm_experiment_add(result, "preissmann_max_rel_energy_error_last_tenth", r.schemes[0].energy[1]);
  gm_experiment_add(result, "preissmann_max_rel_momentum_error_last_tenth",
                    r.schemes[0].momentum[1]);
  gm_experiment_add(result, "preissmann_max_rel_charge_error_last_tenth", r.schemes[0].charge[1]);
  gm_experiment_add(result, "box_sdirk2_max_rel_energy_error_last_tenth", r.schemes[1].energy[1]);
  gm_experiment_add(result, "box_sdirk2_max_rel_momentum_error_last_tenth",
                    r.schemes[1].momentum[1]);
  gm_experiment_add(result, "box_sdirk2_max_rel_charge_error_last_tenth", r.schemes[1].charge[1]);
  gm_experiment_add(result, "wall_s", r.wall_s);
  gm_experiment_file(result, dir, "nls-long-preissmann.dat");
  gm_experiment_file(result, dir, "nls-long-box-sdirk2.dat");
  return GM_OK;
}
