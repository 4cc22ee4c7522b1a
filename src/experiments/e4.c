/* Seed 000 experiment E4 (Stern 2009, §3.4.3, Figs 3.7–3.8) on the uniform grid, where the
 * asynchronous variational integrator is Yee: a 2-D rectangular cavity with PEC walls (E = 0 on
 * the boundary), random initial E, every step 1/10 of the Courant limit, run for 8 time units.
 * The thesis leaves the domain, the cell count and the energy formula open (notes §2 E4); here:
 * the unit square, N × N cells (TE: Ex, Ey on edges, Hz on faces), E uniform in [−1, 1] on every
 * interior edge from a seeded generator, and the energies of fields.h: the plain
 * ½(E·⋆_ε E + H·⋆_μ H) with E half a step behind H (bounded, oscillating) and the leapfrog form
 * the scheme conserves exactly. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/internal.h"
#include "experiments/internal.h"
#include "geomint/experiments.h"
#include "geomint/fields.h"
#include "geomint/io.h"

/* the energy series may take at most this many bytes (three doubles a step) */
#define E4_MAX_SERIES_BYTES 1e9

gm_e4_config gm_e4_defaults(void) {
  gm_e4_config c = {32, 8.0, 1, 0};
  return c;
}

/* splitmix64 (Steele, Lea & Flood, OOPSLA 2014): a small seeded generator, the same numbers
 * on every platform. */
static uint64_t splitmix64(uint64_t *state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

static double uniform_pm1(uint64_t *state) {
  return 2.0 * ((double)(splitmix64(state) >> 11) * 0x1.0p-53) - 1.0;
}

static int record(void *ctx, const gm_yee *solver) {
  gm_e4_result *r = ctx;
  if (r->n_samples > r->steps) return 0;
  gm_yee_energy e;
  if (gm_yee_get_energy(solver, &e) != GM_OK) return 1;
  r->t[r->n_samples] = gm_yee_time_h(solver);
  r->plain[r->n_samples] = e.plain;
  r->leapfrog[r->n_samples] = e.leapfrog;
  r->n_samples++;
  return 0;
}

static gm_status set_random_e(gm_yee *s, uint64_t seed) {
  gm_yee_layout L;
  gm_yee_get_layout(s, &L);
  double *v = malloc(L.size * sizeof *v);
  if (v == NULL) return GM_ENOMEM;
  uint64_t state = seed;
  gm_status st = GM_OK;
  for (int c = GM_EX; c <= GM_EY && st == GM_OK; ++c) {
    /* every entry gets a number; the solver keeps only the component's own locations and
     * zeroes tangential E on the PEC walls */
    for (size_t i = 0; i < L.size; ++i) v[i] = uniform_pm1(&state);
    st = gm_yee_set_field(s, (gm_yee_component)c, 0, v);
  }
  free(v);
  return st;
}

static gm_status write_csv(const char *path, const gm_e4_result *r, gm_error *err) {
  gm_probe_csv *w = NULL;
  const char *names[] = {"plain", "leapfrog"};
  gm_status st = gm_probe_csv_create(path, 2, names, &w, err);
  for (size_t i = 0; st == GM_OK && i < r->n_samples; ++i) {
    double row[2] = {r->plain[i], r->leapfrog[i]};
    st = gm_probe_csv_write(w, r->t[i], row);
  }
  if (st == GM_OK) st = gm_probe_csv_flush(w);
  if (st != GM_OK && w != NULL) gm_error_set(err, st, "%s", gm_probe_csv_errmsg(w));
  gm_probe_csv_free(w);
  return st;
}

gm_status gm_experiment_e4(const gm_e4_config *config, const char *dir, gm_e4_result *r,
                           gm_error *err) {
  memset(r, 0, sizeof *r);
  const size_t n = config->n;
  if (n < 2 || n > 2048)
    return gm_error_set(err, GM_EINVAL, "e4: n = %zu cells per axis is outside [2, 2048]", n);
  if (!(config->t_end > 0.0) || !isfinite(config->t_end))
    return gm_error_set(err, GM_EINVAL, "e4: the time %g is not finite and > 0", config->t_end);
  if (config->n_threads < 0)
    return gm_error_set(err, GM_EINVAL, "e4: %d threads", config->n_threads);
  gm_yee_grid grid = {GM_YEE_2D_TE, {n, n, 1}, {1.0 / (double)n, 1.0 / (double)n, 1}, {0, 0, 0}};
  gm_yee_options opt = gm_yee_defaults();
  opt.courant = 0.1; /* "each element's step is 1/10 of its CFL limit" */
  opt.n_threads = config->n_threads;
  gm_yee *s = NULL;
  gm_status st = gm_yee_create(&grid, NULL, &opt, &s, err);
  if (st != GM_OK) return st;
  r->dt = gm_yee_dt(s);
  const double steps = floor(config->t_end / r->dt * (1 + 1e-12));
  const double bytes = 3.0 * sizeof(double) * (steps + 1.0);
  if (steps < 1.0) {
    gm_yee_free(s);
    return gm_error_set(err, GM_EINVAL,
                        "e4: the time %g is shorter than one step (dt = %.6g at n = %zu)",
                        config->t_end, r->dt, n);
  }
  if (bytes > E4_MAX_SERIES_BYTES) {
    gm_yee_free(s);
    return gm_error_set(err, GM_EINVAL,
                        "e4: the time %g is %.3g steps of dt = %.6g; their energy series would "
                        "take %.3g bytes (at most %.0e)",
                        config->t_end, steps, r->dt, bytes, E4_MAX_SERIES_BYTES);
  }
  r->steps = (size_t)steps;
  r->t = malloc((r->steps + 1) * sizeof *r->t);
  r->plain = malloc((r->steps + 1) * sizeof *r->plain);
  r->leapfrog = malloc((r->steps + 1) * sizeof *r->leapfrog);
  if (r->t == NULL || r->plain == NULL || r->leapfrog == NULL)
    st = gm_error_set(err, GM_ENOMEM, "e4: cannot allocate %.3g bytes for the energy series",
                      bytes);
  if (st == GM_OK && (st = set_random_e(s, config->seed)) != GM_OK)
    gm_error_set(err, st, "e4: setting the random E: %s", gm_yee_errmsg(s));
  if (st == GM_OK && (st = gm_yee_add_observer(s, 1, record, r)) != GM_OK)
    gm_error_set(err, st, "e4: %s", gm_yee_errmsg(s));
  const double t0 = gm_experiment_clock();
  if (st == GM_OK && (st = gm_yee_advance(s, r->steps)) != GM_OK)
    gm_error_set(err, st, "e4: %s", gm_yee_errmsg(s));
  r->wall_s = gm_experiment_clock() - t0; /* the observer saw steps 0 .. steps */
  gm_yee_free(s);
  if (st == GM_OK && r->n_samples < 2)
    st = gm_error_set(err, GM_ECALLBACK, "e4: the run recorded %zu energies", r->n_samples);
  if (st != GM_OK) {
    gm_e4_result_clear(r);
    return st;
  }
  /* the plain energy's oscillation about its mean, per half of the run (bounded: the second
   * half's range is not larger than the first's), and the leapfrog energy's drift */
  double mean = 0;
  for (size_t i = 0; i < r->n_samples; ++i) mean += r->plain[i];
  mean /= (double)r->n_samples;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, drift = 0;
  for (size_t i = 0; i < r->n_samples; ++i) {
    const int half = i >= r->n_samples / 2;
    lo[half] = fmin(lo[half], r->plain[i]);
    hi[half] = fmax(hi[half], r->plain[i]);
    drift = fmax(drift, fabs(r->leapfrog[i] / r->leapfrog[0] - 1));
  }
  r->t_final = r->t[r->n_samples - 1];
  r->plain_initial = r->plain[0];
  r->plain_mean = mean;
  r->plain_range_first_half = (hi[0] - lo[0]) / mean;
  r->plain_range_second_half = (hi[1] - lo[1]) / mean;
  r->leapfrog_max_rel_drift = drift;
  if (dir != NULL) {
    char path[GM_EXPERIMENT_PATH_SIZE];
    if (gm_experiment_path(path, sizeof path, dir, "e4-energy.csv") != GM_OK)
      st = gm_error_set(err, GM_EINVAL, "e4: the directory name is too long");
    else
      st = write_csv(path, r, err);
    if (st != GM_OK) gm_e4_result_clear(r);
  }
  return st;
}

void gm_e4_result_clear(gm_e4_result *r) {
  if (r == NULL) return;
  free(r->t);
  free(r->plain);
  free(r->leapfrog);
  r->t = r->plain = r->leapfrog = NULL;
  r->n_samples = 0;
}

gm_status gm_experiment_run_e4(const char *dir, gm_experiment_result *out, gm_error *err) {
  gm_e4_config c = gm_e4_defaults();
  gm_e4_result r;
  gm_status st = gm_experiment_e4(&c, dir, &r, err);
  if (st != GM_OK) return st;
  gm_experiment_add(out, "steps", (double)r.steps);
  gm_experiment_add(out, "dt", r.dt);
  gm_experiment_add(out, "t_final", r.t_final);
  gm_experiment_add(out, "plain_initial", r.plain_initial);
  gm_experiment_add(out, "plain_mean", r.plain_mean);
  gm_experiment_add(out, "plain_range_first_half", r.plain_range_first_half);
  gm_experiment_add(out, "plain_range_second_half", r.plain_range_second_half);
  gm_experiment_add(out, "leapfrog_max_rel_drift", r.leapfrog_max_rel_drift);
  gm_experiment_add(out, "wall_s", r.wall_s);
  gm_experiment_file(out, dir, "e4-energy.csv");
  gm_e4_result_clear(&r);
  return GM_OK;
}
