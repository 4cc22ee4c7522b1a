/* geomint maxwell e4: seed 000 experiment E4 (Stern 2009, §3.4.3, Figs 3.7–3.8) on the uniform
 * grid, where the asynchronous variational integrator is Yee: a 2-D rectangular cavity with
 * PEC walls (E = 0 on the boundary), random initial E, every step 1/10 of the Courant limit,
 * run for 8 time units. The thesis leaves the domain, the cell count and the energy formula
 * open (notes §2 E4); here: the unit square, N × N cells (TE: Ex, Ey on edges, Hz on faces),
 * E uniform in [−1, 1] on every interior edge from a seeded generator, and the energies of
 * fields.h: the plain ½(E·⋆_ε E + H·⋆_μ H) with E half a step behind H (bounded, oscillating)
 * and the leapfrog form the scheme conserves exactly. */
#include <cJSON.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/maxwell.h"

#define COMMAND "maxwell e4"

/* splitmix64 (Steele, Lea & Flood 2014): a small seeded generator, same numbers everywhere. */
static uint64_t splitmix64(uint64_t *state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

static double uniform_pm1(uint64_t *state) {
  return 2.0 * ((double)(splitmix64(state) >> 11) * 0x1.0p-53) - 1.0;
}

typedef struct e4_series {
  size_t n, cap;
  double *t, *plain, *leapfrog;
} e4_series;

static int record(void *ctx, const gm_yee *solver) {
  e4_series *s = ctx;
  if (s->n >= s->cap) return 0;
  gm_yee_energy e;
  if (gm_yee_get_energy(solver, &e) != GM_OK) return 1;
  s->t[s->n] = gm_yee_time_h(solver);
  s->plain[s->n] = e.plain;
  s->leapfrog[s->n] = e.leapfrog;
  s->n++;
  return 0;
}

static int set_random_e(gm_yee *s, uint64_t seed) {
  gm_yee_layout L;
  gm_yee_get_layout(s, &L);
  double *v = malloc(L.size * sizeof *v);
  if (v == NULL) return -1;
  uint64_t state = seed;
  int rc = 0;
  for (int c = GM_EX; c <= GM_EY && rc == 0; ++c) {
    /* every entry gets a number; the solver keeps only the component's own locations and
     * zeroes tangential E on the PEC walls */
    for (size_t i = 0; i < L.size; ++i) v[i] = uniform_pm1(&state);
    if (gm_yee_set_field(s, (gm_yee_component)c, 0, v) != GM_OK) rc = -1;
  }
  free(v);
  return rc;
}

int mx_e4_main(int argc, char **argv) {
  size_t n = 32, seed = 1, threads = 0;
  double t_end = 8.0;
  const char *out_dir = "maxwell-output";
  int json = 0;
  cli_option options[] = {{"--n", CLI_ARG_COUNT, &n, 0},
                          {"--time", CLI_ARG_DOUBLE, &t_end, 0},
                          {"--seed", CLI_ARG_COUNT, &seed, 0},
                          {"--out", CLI_ARG_STRING, &out_dir, 0},
                          {"--json", CLI_ARG_FLAG, &json, 0},
                          {"--threads", CLI_ARG_COUNT, &threads, 0}};
  const char *positional[1];
  size_t n_pos = 0;
  int status = cli_parse(COMMAND, argc, argv, options, 6, positional, 0, &n_pos);
  if (status == CLI_HELP) {
    fputs(mx_usage(), stdout);
    return CLI_EXIT_OK;
  }
  if (status != CLI_EXIT_OK) return status;
  if (n < 2 || n > 2048) {
    cli_error(COMMAND, "--n must be in [2, 2048], got %zu", n);
    return CLI_EXIT_USAGE;
  }
  if (cli_check_positive(COMMAND, "--time", t_end) != CLI_EXIT_OK) return CLI_EXIT_USAGE;
  if ((status = mx_make_dir(COMMAND, out_dir)) != CLI_EXIT_OK) return status;

  gm_yee_grid grid = {GM_YEE_2D_TE, {n, n, 1}, {1.0 / (double)n, 1.0 / (double)n, 1}, {0, 0, 0}};
  gm_yee_options opt = gm_yee_defaults();
  opt.courant = 0.1; /* "each element's step is 1/10 of its CFL limit" */
  opt.n_threads = (int)threads;
  gm_yee *s = NULL;
  gm_error err = {{0}};
  if (gm_yee_create(&grid, NULL, &opt, &s, &err) != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    return CLI_EXIT_FAILURE;
  }
  double dt = gm_yee_dt(s);
  size_t steps = (size_t)floor(t_end / dt * (1 + 1e-12));
  e4_series e = {0, steps + 1, NULL, NULL, NULL};
  e.t = malloc((steps + 1) * sizeof *e.t);
  e.plain = malloc((steps + 1) * sizeof *e.plain);
  e.leapfrog = malloc((steps + 1) * sizeof *e.leapfrog);
  if (e.t == NULL || e.plain == NULL || e.leapfrog == NULL || set_random_e(s, seed) != 0 ||
      gm_yee_add_observer(s, 1, record, &e) != GM_OK) {
    cli_error(COMMAND, "cannot set up the run: %s", gm_yee_errmsg(s));
    status = CLI_EXIT_FAILURE;
  }
  double t0 = mx_now();
  if (status == CLI_EXIT_OK && gm_yee_advance(s, steps) != GM_OK) {
    cli_error(COMMAND, "%s", gm_yee_errmsg(s));
    status = CLI_EXIT_FAILURE;
  }
  double wall = mx_now() - t0; /* the observer saw steps 0 .. steps, the last one included */
  gm_yee_free(s);
  if (status != CLI_EXIT_OK || e.n < 2) {
    free(e.t), free(e.plain), free(e.leapfrog);
    return status != CLI_EXIT_OK ? status : CLI_EXIT_FAILURE;
  }
  /* the plain energy's oscillation about its mean, per half of the run (bounded: the second
   * half's range is not larger than the first's), and the leapfrog energy's drift */
  double mean = 0;
  for (size_t i = 0; i < e.n; ++i) mean += e.plain[i];
  mean /= (double)e.n;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY}, drift = 0;
  for (size_t i = 0; i < e.n; ++i) {
    int half = i >= e.n / 2;
    lo[half] = fmin(lo[half], e.plain[i]);
    hi[half] = fmax(hi[half], e.plain[i]);
    drift = fmax(drift, fabs(e.leapfrog[i] / e.leapfrog[0] - 1));
  }
  double range1 = (hi[0] - lo[0]) / mean, range2 = (hi[1] - lo[1]) / mean;

  char csv[4096], png[4096];
  mx_path(csv, sizeof csv, out_dir, "e4-energy.csv");
  gm_probe_csv *w = NULL;
  const char *names[] = {"plain", "leapfrog"};
  if (gm_probe_csv_create(csv, 2, names, &w, &err) != GM_OK) {
    cli_error(COMMAND, "%s", err.message);
    status = CLI_EXIT_FAILURE;
  }
  for (size_t i = 0; status == CLI_EXIT_OK && i < e.n; ++i) {
    double row[2] = {e.plain[i], e.leapfrog[i]};
    if (gm_probe_csv_write(w, e.t[i], row) != GM_OK) status = CLI_EXIT_FAILURE;
  }
  if (status == CLI_EXIT_OK && gm_probe_csv_flush(w) != GM_OK) status = CLI_EXIT_FAILURE;
  if (status != CLI_EXIT_OK && w != NULL) cli_error(COMMAND, "%s", gm_probe_csv_errmsg(w));
  gm_probe_csv_free(w);

  /* the figure: energies relative to the initial plain energy */
  int plotted = 0;
  if (status == CLI_EXIT_OK && cli_gnuplot_available()) {
    double *rp = malloc(e.n * sizeof *rp), *rl = malloc(e.n * sizeof *rl);
    if (rp != NULL && rl != NULL) {
      for (size_t i = 0; i < e.n; ++i) {
        rp[i] = e.plain[i] / e.plain[0];
        rl[i] = e.leapfrog[i] / e.plain[0];
      }
      mx_line lines[2] = {{"plain energy (E^{n-1/2}, H^n)", e.n, e.t, rp, 0},
                          {"leapfrog energy (conserved)", e.n, e.t, rl, 0}};
      char title[160];
      snprintf(title, sizeof title, "Seed 000 E4: PEC square, %zux%zu Yee cells, random E, "
               "dt = 0.1 CFL", n, n);
      mx_path(png, sizeof png, out_dir, "e4-energy.png");
      plotted = mx_plot_lines(COMMAND, png, title, "t", "energy / initial plain energy", 0,
                              lines, 2) == CLI_EXIT_OK;
    }
    free(rp), free(rl);
  }
  if (status == CLI_EXIT_OK) {
    if (json) {
      cJSON *o = cJSON_CreateObject();
      cJSON_AddNumberToObject(o, "n", (double)n);
      cJSON_AddNumberToObject(o, "dt", dt);
      cJSON_AddNumberToObject(o, "steps", (double)steps);
      cJSON_AddNumberToObject(o, "t_final", e.t[e.n - 1]);
      cJSON_AddNumberToObject(o, "seed", (double)seed);
      cJSON_AddNumberToObject(o, "plain_initial", e.plain[0]);
      cJSON_AddNumberToObject(o, "plain_mean", mean);
      cJSON_AddNumberToObject(o, "plain_range_first_half", range1);
      cJSON_AddNumberToObject(o, "plain_range_second_half", range2);
      cJSON_AddNumberToObject(o, "leapfrog_max_rel_drift", drift);
      cJSON_AddNumberToObject(o, "wall_s", wall);
      cJSON_AddStringToObject(o, "csv", csv);
      if (plotted) cJSON_AddStringToObject(o, "plot", png);
      status = cli_json_print(o);
    } else {
      printf("E4 (seed 000): PEC unit square, %zu x %zu cells (2-D TE), random E (seed %zu), "
             "dt = %.6g (0.1 of the Courant limit), %zu steps to t = %.6g (%.2f s)\n", n, n,
             seed, dt, steps, e.t[e.n - 1], wall);
      printf("  plain energy: initial %.9g, mean %.9g; range (max - min) / mean %.3e in the "
             "first half, %.3e in the second (bounded)\n", e.plain[0], mean, range1, range2);
      printf("  leapfrog energy: max relative drift %.3e (conserved to round-off)\n", drift);
      printf("  wrote %s%s%s\n", csv, plotted ? ", " : "", plotted ? png : "");
    }
  }
  free(e.t), free(e.plain), free(e.leapfrog);
  return status;
}
